"""Craig–Bampton reduction of a ring model into a modal body, with raceway load-mode augmentation.

Interfaces (a bolted face, a support patch) are condensed to one 6-DOF master node each, by a
rigid multipoint constraint (RBE2-like: every slave node s follows u_s = t + θ × (x_s − c), so the
FE displacement is u = T q with q = (retained node DOFs, master DOFs)) or by an averaging one
(RBE3-like: the master follows the least-squares rigid fit of the patch, q_m = C u, imposed with
Lagrange multipliers on a factor of K + α CᵀC, which equals K on the constraint set). With B the
master DOFs and I the rest (Craig & Bampton, AIAA J. 6(7), 1968):

    fixed-interface modes   (K_II − ω² M_II) φ = 0,        lowest n_modes
    constraint modes        Ψ = −K_II⁻¹ K_IB               (interfaces that stay free)
    augmentation            U = K_II⁻¹ f_I                 (raceway line loads cos nθ, sin nθ)

all from one factorisation of K_II. A grounded interface has its master held (q_B = 0): its
constraint modes are not needed. A body without interfaces is reduced with free–free modes; its
static load shapes use inertia relief (the load made self-equilibrated against the rigid-body
inertia forces, solved with K − σM, σ < 0, then cleared of rigid content).

The basis V = [Φ_I, Ψ, U] is M-orthonormalised block by block in that order, twice (what a later
block adds to the earlier ones below 1e-8 of its Gram scale is dropped as dependent), and the reduced
eigenproblem (VᵀKV) x = ω² (VᵀMV) x gives the modal form: mass-normalised modes with their
frequencies. For a floating body the basis is first cleared of the six rigid motions (M-orthogonal
projection), since the reference frame carries them; its free–free modes are computed
deflated of them (:mod:`fem_rings.modal_basis`), so a soft body keeps all its requested elastic
modes. Start vectors and degenerate pairs are fixed, so a rebuild gives the same body bit for bit.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator

from fem_rings.linalg import factorize_spd, shift_invert_operator
from fem_rings.modal_basis import (body_length_m, canonical_modes, deflated_eigsh, m_orthonormal,
                                   mass_centre_m, rigid_body_fields, unheld_rigid_combinations)
from fem_rings.model import FEModel
from fem_rings.solve import solver_threads
from foundation.progress import phase

from .body import ReducedBody

__all__ = ["Interface", "reduce_model", "rbe2_transform", "averaging_constraints"]

log = logging.getLogger(__name__)

#: right-hand sides solved together: a block is one step of the progress bar of the constraint
#: modes and load shapes. Each column's solution is the same whatever the blocking up to the last
#: digits (CHOLMOD's blocked triangular solves, ~1e-14 relative); 24 columns cost no more than
#: one block of all (99.5k-DOF race, 192 columns: 3.70 s against 3.82 s, noise ±5 %)
RHS_BLOCK = 24

#: a basis direction whose Gram eigenvalue, after clearing it of the earlier blocks, is below this
#: fraction of the unit M-norm its vectors had is dropped as dependent (a new part of 1e-4 in
#: norm or less: nothing the others do not carry, and kept it would cost orthogonality ~ε/1e-8)
DEPENDENCE_RTOL = 1e-8


class InterfaceError(ValueError):
    """An interface that cannot be built on the mesh: no nodes, nodes on one line, or nodes shared
    with another interface (a support patch too small or too large for the mesh)."""


@dataclass(frozen=True)
class Interface:
    """A patch of nodes condensed to one 6-DOF master node.

    Parameters
    ----------
    name : str
    nodes : (k,) int
        Slave nodes of the FE model.
    master_m : (3,) float or None
        Master point, m; default the centroid of the slave nodes.
    grounded : bool
        True: the master is fixed (bolted to a rigid housing). False: its 6 DOFs stay boundary
        DOFs of the reduced body (constraint modes kept).
    kind : {"rigid", "averaging"}
        ``"rigid"`` (RBE2-like): the patch moves as a rigid body with the master.
        ``"averaging"`` (RBE3-like): the master moves with the least-squares rigid fit of the
        patch, q_m = (GᵀG)⁻¹Gᵀ u_s (G the rigid-motion matrix of the slave positions about the
        master, equal weights); the patch keeps its own deformation and adds no stiffness.
    """

    name: str
    nodes: np.ndarray
    master_m: np.ndarray | None = None
    grounded: bool = True
    kind: str = "rigid"

    def __post_init__(self) -> None:
        if len(self.nodes) == 0:
            raise InterfaceError(f"interface {self.name!r}: node set is empty")
        if self.kind not in ("rigid", "averaging"):
            raise ValueError(f"interface {self.name!r}: kind must be 'rigid' or 'averaging', got {self.kind!r}")

    def master_point(self, nodes_m: np.ndarray) -> np.ndarray:
        return np.mean(nodes_m[self.nodes], axis=0) if self.master_m is None else np.asarray(self.master_m, float)

    def rigid_motion_matrix(self, nodes_m: np.ndarray) -> np.ndarray:
        """G (3k, 6): slave displacements of a master translation t and small rotation θ,
        u_s = t + θ × (x_s − c); rows interleaved per slave node. Checks the patch is not a line."""
        d = nodes_m[self.nodes] - self.master_point(nodes_m)
        G = np.zeros((len(self.nodes), 3, 6))
        G[:, :, :3] = np.eye(3)
        for a, e in enumerate(np.eye(3)):
            G[:, :, 3 + a] = np.cross(e, d)
        sv = np.linalg.svd(G[:, :, 3:].reshape(-1, 3), compute_uv=False)
        if sv[-1] <= 1e-8 * max(sv[0], 1e-300):
            raise InterfaceError(f"interface {self.name!r}: its {len(self.nodes)} nodes lie on one line, so a "
                             "rotation about that line moves none of them; widen the patch")
        return G.reshape(-1, 6)


def rbe2_transform(model: FEModel, interfaces) -> tuple[sp.csr_matrix, np.ndarray, np.ndarray]:
    """u = T q for the rigid interfaces (averaging ones are ignored here).

    Returns
    -------
    T : (3N, n_q) sparse
        Columns: the 3 DOFs of every retained (non-slave) node, then 6 DOFs per rigid interface
        (translation x, y, z and rotation about x, y, z of the master).
    retained : (n_r,) int
        Retained nodes, in the order of their q-columns.
    master_cols : (6 · n_rigid,) int
        q-columns of the master DOFs.
    """
    rigid = [i for i in interfaces if i.kind == "rigid"]
    n = model.ring.n_nodes
    slave = np.zeros(n, dtype=bool)
    for itf in interfaces:
        if slave[itf.nodes].any():
            raise InterfaceError(f"interface {itf.name!r} shares nodes with another interface")
        slave[itf.nodes] = itf.kind == "rigid"
    retained = np.flatnonzero(~slave)
    rows = [(3 * retained[:, None] + np.arange(3)).ravel()]
    cols = [np.arange(3 * len(retained))]
    vals = [np.ones(3 * len(retained))]
    col0 = 3 * len(retained)
    for j, itf in enumerate(rigid):
        G = itf.rigid_motion_matrix(model.nodes_m)            # (3k, 6)
        r = (3 * np.asarray(itf.nodes)[:, None] + np.arange(3)).ravel()
        rows.append(np.repeat(r, 6))
        cols.append(np.tile(col0 + 6 * j + np.arange(6), len(r)))
        vals.append(G.ravel())
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(3 * n, col0 + 6 * len(rigid)))
    return T, retained, np.arange(col0, col0 + 6 * len(rigid))


def averaging_constraints(model: FEModel, interfaces, retained: np.ndarray) -> tuple[sp.csr_matrix, np.ndarray]:
    """C (6 n_avg, 3 n_r) with q_m = C q for the averaging interfaces, and which rows are grounded.

    q are the retained-node DOFs (the first 3 n_r columns of :func:`rbe2_transform`).
    """
    avg = [i for i in interfaces if i.kind == "averaging"]
    pos = np.full(model.ring.n_nodes, -1)
    pos[retained] = np.arange(len(retained))
    rows, cols, vals, grounded = [], [], [], []
    for j, itf in enumerate(avg):
        G = itf.rigid_motion_matrix(model.nodes_m)
        A = np.linalg.solve(G.T @ G, G.T)                      # (6, 3k) least-squares rigid fit
        c = (3 * pos[np.asarray(itf.nodes)][:, None] + np.arange(3)).ravel()
        rows.append(np.repeat(6 * j + np.arange(6), len(c)))
        cols.append(np.tile(c, 6))
        vals.append(A.ravel())
        grounded += [itf.grounded] * 6
    if not avg:
        return sp.csr_matrix((0, 3 * len(retained))), np.zeros(0, dtype=bool)
    C = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(6 * len(avg), 3 * len(retained)))
    return C, np.asarray(grounded)


class _ConstrainedSolver:
    """Solutions of K u + Cᵀλ = f, C u = g with one Cholesky factor of K̂ = K + α CᵀC.

    K̂ equals K on the constraint set (CᵀC u is in the range of Cᵀ, absorbed by λ), so the
    solutions are exact; K̂ is positive definite when the constraints hold the rigid motion that
    K leaves free. The 6r × 6r Schur complement S = C K̂⁻¹ Cᵀ is dense and small.
    """

    def __init__(self, K, C, backend: str) -> None:
        self.C = C.tocsr()
        if C.shape[0]:
            # scale the added term like K's diagonal (conditioning only; the solutions do not depend on it)
            alpha = float(np.mean(K.diagonal())) / float(np.mean(np.asarray(C.multiply(C).sum(axis=1))))
            K = K + alpha * (C.T @ C)
        self.factor = factorize_spd(K.tocsc(), backend=backend)
        self.KinvCt = (solve_in_blocks(self.factor.solve, C.T.toarray(), "averaging-interface solves")
                       if C.shape[0] else np.zeros((K.shape[0], 0)))
        self.S = self.C @ self.KinvCt

    def solve(self, f, g=None):
        """u with C u = g (default 0)."""
        u = self.factor.solve(f)
        if not self.C.shape[0]:
            return u
        r = self.C @ u - (0.0 if g is None else g)
        return u - self.KinvCt @ np.linalg.solve(self.S, r)


def solve_in_blocks(solve, B: np.ndarray, label: str) -> np.ndarray:
    """``solve(B)`` column block by column block (:data:`RHS_BLOCK` wide), as a phase with a total.

    Parameters
    ----------
    solve : callable
        (n, k) right-hand sides → (n, k) solutions, column by column independent.
    B : (n, k) float64
    label : str
        Phase label (:func:`foundation.progress.phase`).
    """
    out = np.empty((B.shape[0], B.shape[1]))
    starts = range(0, B.shape[1], RHS_BLOCK)
    with phase(label, total=len(starts)) as p:
        for j in starts:
            out[:, j:j + RHS_BLOCK] = solve(B[:, j:j + RHS_BLOCK])
            p.advance()
    return out


def _orthonormal_extension(Mq, Q, B, rel_tol: float = DEPENDENCE_RTOL):
    """(n, m) M-orthonormal basis of span(B) beyond span(Q), nearly dependent directions dropped.

    The columns of B are scaled to unit M-norm and cleared of Q (Q M-orthonormal); then the Gram
    matrix G = BᵀMB is diagonalised and the directions with eigenvalue ≤ ``rel_tol`` (of the unit
    norm the columns had: a direction that lay in span(Q) or in the span of the others is left
    with nothing) are dropped. Everything is done twice: the second pass removes the loss of
    orthogonality of the first, which grows like ε / λ_min ("twice is enough": Parlett, The
    Symmetric Eigenvalue Problem, SIAM 1998, §6.9). Returns the basis and the number dropped.
    """
    B = B / np.sqrt(np.einsum("ik,ik->k", B, Mq @ B))
    dropped = 0
    for _ in range(2):
        if Q.shape[1]:
            B = B - Q @ ((Mq @ Q).T @ B)
        G = B.T @ (Mq @ B)
        lam, X = np.linalg.eigh(0.5 * (G + G.T))
        keep = lam > rel_tol
        dropped += int((~keep).sum())
        B = B @ (X[:, keep] / np.sqrt(lam[keep]))
    return B, dropped


def _modal_form(Kq, Mq, blocks, rigid_q=None):
    """Mass-normalised modes and ω² of K on the span of the basis blocks (n, k_i).

    The blocks are M-orthonormalised in order (:func:`_orthonormal_extension`), so the first
    (the normal modes) is kept whole and later ones (constraint modes, load shapes) only add what
    is new. ``rigid_q`` (n, r) M-orthonormal: rigid motions the span is cleared of (a floating
    body's reference frame carries them).
    """
    Q = np.zeros((Kq.shape[0], 0)) if rigid_q is None else rigid_q
    n_rigid, dropped = Q.shape[1], 0
    for B in blocks:
        if B.shape[1]:
            E, d = _orthonormal_extension(Mq, Q, B)
            Q, dropped = np.hstack((Q, E)), dropped + d
    W = Q[:, n_rigid:]
    Kr = W.T @ (Kq @ W)
    w2, X = sla.eigh(0.5 * (Kr + Kr.T))
    w2, shapes = canonical_modes(w2, W @ X)
    return shapes, w2, dropped


def rigid_fields_q(model: FEModel, interfaces, retained: np.ndarray) -> np.ndarray:
    """(n_q, 6) rigid motions in the reduced coordinates q of :func:`rbe2_transform` (T R_q = R).

    Rigid fields about the centre of mass: retained nodes take their nodal values, the master
    of a rigid interface at p takes t = v + θ × (p − c), θ the field's rotation.
    """
    c = mass_centre_m(model.M, model.nodes_m)
    R = rigid_body_fields(model.nodes_m, c).reshape(-1, 3, 6)
    rows = [R[retained].reshape(-1, 6)]
    for itf in (i for i in interfaces if i.kind == "rigid"):
        master = np.zeros((6, 6))
        master[:3] = rigid_body_fields(itf.master_point(model.nodes_m)[None, :], c)
        master[3:, 3:] = np.eye(3)
        rows.append(master)
    return np.vstack(rows)


def _load_columns(model: FEModel, T, shapes) -> np.ndarray:
    """(n_q, k) consistent load vectors of load shapes (:mod:`.augmentation`) in the reduced coordinates."""
    if not shapes:
        return np.zeros((T.shape[1], 0))
    return np.column_stack([T.T @ a.load_vectors(model, model.ring.spec.full_circle) for a in shapes])


def _block(A: sp.csr_matrix, index: np.ndarray) -> sp.csc_matrix:
    """A[index][:, index] in CSC (without the intermediate copies when ``index`` is every row)."""
    if len(index) == A.shape[0] and np.array_equal(index, np.arange(A.shape[0])):
        return A.tocsc()
    return A[index][:, index].tocsc()


def reduce_model(
    model: FEModel,
    n_modes: int,
    interfaces=(),
    augmentation=(),
    *,
    floating: bool | None = None,
    damping_ratio: float | np.ndarray = 0.0,
    name: str | None = None,
    backend: str = "auto",
    probes=(),
) -> ReducedBody:
    """Reduce an FE ring model to a modal body.

    Parameters
    ----------
    model : FEModel
    n_modes : int
        Fixed-interface (or, without interfaces, free–free elastic) normal modes to compute.
    interfaces : sequence of Interface
        Condensed patches; grounded ones are held, the others keep constraint modes.
    augmentation : sequence of load shapes (:mod:`.augmentation`)
        Raceway load shapes added to the basis.
    floating : bool, optional
        Remove rigid-body modes (the reference frame carries rigid motion). Default: True when
        no interface is grounded.
    damping_ratio : float or (m,) array
        Modal damping ratio of every kept mode.
    probes : sequence of load shapes (:mod:`.augmentation`)
        Loads whose static response is measured but not added: the body's metadata gets
        ``probe_compliance_m_per_N``, the (k, k) compliance FᵀK⁻¹F of the k probe loads on the
        elastic motion (inertia relief on a free floating body; with every interface grounded, the
        motion of the held body), and ``residual_compliance_m_per_N``, the part of it the basis does
        not hold (:func:`residual_compliance`). Free floating bodies, or bodies held at all their
        interfaces.
    """
    interfaces = tuple(interfaces)
    augmentation = tuple(augmentation)
    grounded = any(i.grounded for i in interfaces)
    floating = (not grounded) if floating is None else bool(floating)
    if floating and grounded:
        raise ValueError("a floating body cannot have grounded interfaces")
    T, retained, master_cols = rbe2_transform(model, interfaces)
    if len(master_cols) == 0 and T.shape[0] == T.shape[1]:  # T = I: no copies of the (large) K and M
        Kq, Mq = model.K.tocsr(), model.M.tocsr()
    else:
        Kq = (T.T @ model.K @ T).tocsr()
        Mq = (T.T @ model.M @ T).tocsr()
    nq = Kq.shape[0]
    rigid_itf = [i for i in interfaces if i.kind == "rigid"]
    held = np.concatenate([master_cols[6 * j: 6 * j + 6] for j, itf in enumerate(rigid_itf) if itf.grounded]
                          or [np.zeros(0, dtype=np.int64)])
    C_avg, avg_grounded = averaging_constraints(model, interfaces, retained)
    boundary = np.setdiff1d(master_cols, held)
    interior = np.setdiff1d(np.arange(nq), master_cols)
    KII, MII = (_block(A, interior) for A in (Kq, Mq))
    loads_q, probe_q = (_load_columns(model, T, shapes) for shapes in (augmentation, probes))
    free_body = len(master_cols) == 0 and C_avg.shape[0] == 0
    all_held = not floating and len(master_cols) == len(held) and bool(np.all(avg_grounded))
    if probe_q.shape[1] and not ((free_body and floating) or (all_held and not free_body)):
        raise ValueError("residual-compliance probes are measured on free floating bodies or on bodies held at "
                         "all their interfaces")
    probe_compliance, probe_shift = None, 0.0
    Rq = rigid_fields_q(model, interfaces, retained)
    held_rigid = np.vstack((Rq[held], C_avg[np.flatnonzero(avg_grounded)] @ Rq[interior]))
    length_m = body_length_m(model.nodes_m, mass_centre_m(model.M, model.nodes_m))
    n_free_rigid = unheld_rigid_combinations(held_rigid, length_m).shape[1]
    if not floating and n_free_rigid:
        raise ValueError(f"the grounded interfaces leave {n_free_rigid} rigid-body motion(s) of the body free; "
                         "ground more of them (or reduce it as floating)")
    interior_blocks, boundary_blocks = [], []     # q-rows: interior DOFs, free master DOFs
    with solver_threads():
        rigid_q = m_orthonormal(Rq, Mq) if floating else None
        if free_body:
            # free body (q = u): free–free elastic modes, deflated of the rigid motions, and
            # inertia-relief load shapes from one factor of K − σM
            sigma = -(2.0 * math.pi) ** 2
            op, factor = shift_invert_operator(KII, MII, sigma, backend=backend)
            interior_blocks.append(deflated_eigsh(KII, MII, int(n_modes), sigma, op, rigid_q)[1])
            MR = MII @ rigid_q
            if loads_q.shape[1]:
                U = solve_in_blocks(factor.solve, loads_q - MR @ (rigid_q.T @ loads_q), "load shapes")
                interior_blocks.append(U - rigid_q @ (MR.T @ U))
            if probe_q.shape[1]:
                U = factor.solve(probe_q - MR @ (rigid_q.T @ probe_q))
                probe_compliance, probe_shift = probe_q.T @ (U - rigid_q @ (MR.T @ U)), sigma
        else:
            # interior rows: retained-node DOFs (rigid-interface masters excluded), which are also
            # the first columns of q, so the averaging constraints apply to them directly
            C = C_avg[:, :len(interior)]
            solver = _ConstrainedSolver(KII, C, backend)
            op = LinearOperator(KII.shape, matvec=solver.solve, dtype=float)
            interior_blocks.append(deflated_eigsh(KII, MII, int(n_modes), 0.0, op)[1])
            if len(boundary):
                interior_blocks.append(-solve_in_blocks(solver.solve, Kq[interior][:, boundary].toarray(),
                                                        "constraint modes"))
                boundary_blocks.append((len(interior_blocks) - 1, np.eye(len(boundary))))
            free_avg = np.flatnonzero(~avg_grounded)
            if len(free_avg):
                # constraint modes of the averaging masters: least strain energy with C u = e_j
                interior_blocks.append(solver.KinvCt @ np.linalg.solve(solver.S, np.eye(C.shape[0])[:, free_avg]))
            if loads_q.shape[1]:
                interior_blocks.append(solve_in_blocks(solver.solve, loads_q[interior], "load shapes"))
            if probe_q.shape[1]:  # every master held: the probe loads on the interior do all the work
                probe_compliance = probe_q[interior].T @ solve_in_blocks(solver.solve, probe_q[interior], "probes")
        blocks = []
        for k, blk in enumerate(interior_blocks):
            V = np.zeros((nq, blk.shape[1]))
            V[interior] = blk
            for j, eye in boundary_blocks:
                if j == k:
                    V[boundary] = eye
            blocks.append(V)
        # a floating body's reference frame carries its rigid motion: the modes are cleared of it
        with phase(f"orthonormalising the basis ({sum(b.shape[1] for b in blocks)} vectors)"):
            Vq, w2, dropped = _modal_form(Kq, Mq, blocks, rigid_q)
    metadata = {}
    if probe_compliance is not None:
        metadata["residual_compliance_m_per_N"] = residual_compliance(probe_compliance, Vq, w2, probe_q,
                                                                      probe_shift).tolist()
        metadata["probe_compliance_m_per_N"] = (0.5 * (probe_compliance + probe_compliance.T)).tolist()
    shapes = np.asarray(T @ Vq)
    freqs = np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * math.pi)
    zeta = np.broadcast_to(np.asarray(damping_ratio, dtype=float), freqs.shape).copy()
    log.info("reduced %s: %d modes (%d normal, %d augmentation, %d dropped as dependent), %.4g–%.4g Hz",
             model.ring.profile.name, len(freqs), int(n_modes), loads_q.shape[1], dropped,
             freqs[0] if len(freqs) else 0, freqs[-1] if len(freqs) else 0)
    return ReducedBody(
        name=name or model.ring.profile.name,
        nodes_m=model.nodes_m.copy(),
        shapes=shapes,
        frequencies_Hz=freqs,
        damping_ratio=zeta,
        floating=floating,
        mesh_kind=model.ring.spec.element,
        mesh_doflocs=model.mesh.doflocs.copy(),
        mesh_t=model.mesh.t.copy(),
        metadata={"n_normal_modes": int(n_modes), "n_augmentation_vectors": int(loads_q.shape[1]),
                  "interfaces": [i.name for i in interfaces], "grounded": grounded, **metadata},
    )


def residual_compliance(full_compliance, shapes, omega2, loads, sigma: float = 0.0) -> np.ndarray:
    """The static compliance of ``loads`` that a modal basis does not hold (residual flexibility).

    Parameters
    ----------
    full_compliance : (k, k)
        Fᵀ(K − σM)⁻¹F of the loads F on the body's elastic motions (inertia relief on a floating body).
    shapes : (n, m)
        M-orthonormal basis with ``shapes``ᵀ K ``shapes`` = diag(``omega2``), cleared of rigid motion.
    omega2 : (m,)
    loads : (n, k)
    sigma : float
        The shift of the factorisation that gave ``full_compliance``.

    The Ritz (Galerkin) compliance on the basis is Σ_j (φ_jᵀF)ᵀ(φ_jᵀF) / (ω_j² − σ), a lower bound of
    the full one (Rayleigh–Ritz: the basis holds part of the static response); the difference is
    the residual flexibility of the truncation (Craig & Kurdila, Fundamentals of Structural
    Dynamics, 2nd ed. 2006, §17.4), positive semi-definite up to round-off.
    """
    P = shapes.T @ loads
    modal = P.T @ (P / (np.asarray(omega2, float) - sigma)[:, None])
    R = np.asarray(full_compliance, float) - modal
    return 0.5 * (R + R.T)
