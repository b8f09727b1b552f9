"""Craig–Bampton reduction of a ring model into a modal body, with raceway load-mode augmentation.

Interfaces (a bolted face, a support patch) are condensed to one 6-DOF master node each by a
rigid multipoint constraint (RBE2): every slave node s follows u_s = t + θ × (x_s − c), so the
FE displacement is u = T q with q = (retained node DOFs, master DOFs). With B the master DOFs and I
the rest (Craig & Bampton, AIAA J. 6(7), 1968):

    fixed-interface modes   (K_II − ω² M_II) φ = 0,        lowest n_modes
    constraint modes        Ψ = −K_II⁻¹ K_IB               (interfaces that stay free)
    augmentation            U = K_II⁻¹ f_I                 (raceway line loads cos nθ, sin nθ)

all from one factorisation of K_II. A grounded interface has its master held (q_B = 0): its
constraint modes are not needed. A body without interfaces is reduced with free–free modes; its
static load shapes use inertia relief (the load made self-equilibrated against the rigid-body
inertia forces, solved with K − σM, σ < 0, then cleared of rigid content).

The basis V = [Φ_I, Ψ, U] is M-orthonormalised (near-dependent vectors dropped) and the reduced
eigenproblem (VᵀKV) x = ω² (VᵀMV) x gives the modal form: mass-normalised modes with their
frequencies. For a floating body the zero-frequency (rigid-body) modes are removed, since the
reference frame carries the rigid motion (DESIGN §4).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, eigsh

from fem_rings.linalg import factorize_spd, shift_invert_operator
from fem_rings.model import FEModel
from fem_rings.nodesets import RacewayCurve
from fem_rings.solve import line_load_operator, rigid_body_fields, solver_threads

from .body import ReducedBody

__all__ = ["Interface", "Augmentation", "reduce_model", "rbe2_transform"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Interface:
    """A patch of nodes condensed to one 6-DOF master node (rigid, RBE2-like).

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
    """

    name: str
    nodes: np.ndarray
    master_m: np.ndarray | None = None
    grounded: bool = True

    def __post_init__(self) -> None:
        if len(self.nodes) == 0:
            raise ValueError(f"interface {self.name!r}: node set is empty")


@dataclass(frozen=True)
class Augmentation:
    """Static load shapes of unit raceway line loads q(θ) = cos nθ, sin nθ (N/m), n = 0…n_max.

    Parameters
    ----------
    curve : RacewayCurve
        Raceway points (from :func:`fem_rings.nodesets.raceway_curve`).
    directions : tuple of str
        Load directions in the section: ``"normal"`` (into the raceway surface, i.e. along the
        contact line for a groove at its contact point), ``"axial"``, ``"radial"``.
    n_max : int
        Highest circumferential harmonic.
    """

    curve: RacewayCurve
    directions: tuple = ("normal",)
    n_max: int = 8

    def __post_init__(self) -> None:
        bad = set(self.directions) - {"normal", "axial", "radial"}
        if bad:
            raise ValueError(f"augmentation directions must be 'normal', 'axial' or 'radial', got {sorted(bad)}")
        if int(self.n_max) < 0:
            raise ValueError(f"augmentation n_max must be ≥ 0, got {self.n_max}")

    def load_vectors(self, model: FEModel, full_circle: bool) -> np.ndarray:
        """Consistent nodal force vectors (3N, k) of all harmonics and directions."""
        c = self.curve
        th = c.theta_rad
        radial = np.column_stack((np.cos(th), np.sin(th), np.zeros_like(th)))
        axial = np.tile([0.0, 0.0, 1.0], (len(th), 1))
        dirs = {"radial": radial, "axial": axial,
                "normal": -(c.normal_rz[0] * radial + c.normal_rz[1] * axial)}
        load = line_load_operator(model, c.points_m, closed=full_circle)
        out = []
        for name in self.directions:
            d = dirs[name]
            for n in range(int(self.n_max) + 1):
                for trig in ((np.cos,) if n == 0 else (np.cos, np.sin)):
                    out.append(load(trig(n * th)[:, None] * d))
        return np.column_stack(out)


def rbe2_transform(model: FEModel, interfaces) -> tuple[sp.csr_matrix, np.ndarray, np.ndarray]:
    """u = T q for rigid interfaces.

    Returns
    -------
    T : (3N, n_q) sparse
        Columns: the 3 DOFs of every retained (non-slave) node, then 6 DOFs per interface
        (translation x, y, z and rotation about x, y, z of the master).
    retained : (n_r,) int
        Retained nodes, in the order of their q-columns.
    master_cols : (6 · n_interfaces,) int
        q-columns of the master DOFs.
    """
    n = model.ring.n_nodes
    slave = np.zeros(n, dtype=bool)
    for itf in interfaces:
        if slave[itf.nodes].any():
            raise ValueError(f"interface {itf.name!r} shares nodes with another interface")
        slave[itf.nodes] = True
    retained = np.flatnonzero(~slave)
    rows = [(3 * retained[:, None] + np.arange(3)).ravel()]
    cols = [np.arange(3 * len(retained))]
    vals = [np.ones(3 * len(retained))]
    x = model.nodes_m
    col0 = 3 * len(retained)
    for j, itf in enumerate(interfaces):
        c = np.mean(x[itf.nodes], axis=0) if itf.master_m is None else np.asarray(itf.master_m, float)
        d = x[itf.nodes] - c                      # (k, 3)
        rot = np.stack([np.cross(e, d).ravel() for e in np.eye(3)], axis=1)
        sv = np.linalg.svd(rot, compute_uv=False)
        if sv[-1] <= 1e-8 * max(sv[0], 1e-300):
            raise ValueError(f"interface {itf.name!r}: its {len(itf.nodes)} nodes lie on one line, so a "
                             "rotation about that line moves none of them; widen the patch")
        base = col0 + 6 * j
        for i in range(3):
            r = 3 * np.asarray(itf.nodes) + i
            rows.append(r)
            cols.append(np.full(len(r), base + i))
            vals.append(np.ones(len(r)))
            # rotation about axis a: u = e_a × d
            for a in range(3):
                e = np.zeros(3)
                e[a] = 1.0
                coef = np.cross(e, d)[:, i]
                rows.append(r)
                cols.append(np.full(len(r), base + 3 + a))
                vals.append(coef)
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(3 * n, col0 + 6 * len(interfaces)))
    return T, retained, np.arange(col0, col0 + 6 * len(interfaces))


def _orthonormal_modal_form(Kq, Mq, V, rel_tol: float = 1e-10):
    """M-orthonormalise V (dropping near-dependent columns) and diagonalise K on its span."""
    V = V / np.sqrt(np.einsum("ik,ik->k", V, Mq @ V))   # unit M-norm columns: modes and statics alike
    Mr = V.T @ (Mq @ V)
    Mr = 0.5 * (Mr + Mr.T)
    lam, Q = np.linalg.eigh(Mr)
    keep = lam > rel_tol * lam.max()
    W = Q[:, keep] / np.sqrt(lam[keep])
    Kr = W.T @ (V.T @ (Kq @ V)) @ W
    w2, X = sla.eigh(0.5 * (Kr + Kr.T))
    return V @ (W @ X), w2, int((~keep).sum())


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
) -> ReducedBody:
    """Reduce an FE ring model to a modal body.

    Parameters
    ----------
    model : FEModel
    n_modes : int
        Fixed-interface (or, without interfaces, free–free elastic) normal modes to compute.
    interfaces : sequence of Interface
        Condensed patches; grounded ones are held, the others keep constraint modes.
    augmentation : sequence of Augmentation
        Raceway load shapes added to the basis.
    floating : bool, optional
        Remove rigid-body modes (the reference frame carries rigid motion). Default: True when
        no interface is grounded.
    damping_ratio : float or (m,) array
        Modal damping ratio of every kept mode.
    """
    interfaces = tuple(interfaces)
    augmentation = tuple(augmentation)
    grounded = any(i.grounded for i in interfaces)
    floating = (not grounded) if floating is None else bool(floating)
    if floating and grounded:
        raise ValueError("a floating body cannot have grounded interfaces")
    T, _, master_cols = rbe2_transform(model, interfaces)
    Kq = (T.T @ model.K @ T).tocsr()
    Mq = (T.T @ model.M @ T).tocsr()
    nq = Kq.shape[0]
    held = np.concatenate([master_cols[6 * j: 6 * j + 6] for j, itf in enumerate(interfaces) if itf.grounded]
                          or [np.zeros(0, dtype=np.int64)])
    boundary = np.setdiff1d(master_cols, held)
    interior = np.setdiff1d(np.arange(nq), master_cols)
    KII = Kq[interior][:, interior].tocsc()
    MII = Mq[interior][:, interior].tocsc()
    loads_q = np.column_stack([T.T @ a.load_vectors(model, model.ring.spec.full_circle) for a in augmentation]) \
        if augmentation else np.zeros((nq, 0))
    interior_blocks, boundary_blocks = [], []     # q-rows: interior DOFs, free master DOFs
    with solver_threads():
        if len(master_cols) == 0:
            # free body: free–free modes and inertia-relief load shapes from one factor of K − σM
            sigma = -(2.0 * math.pi) ** 2
            op, factor = shift_invert_operator(KII, MII, sigma, backend=backend)
            _, phi = eigsh(KII, k=int(n_modes) + 6, M=MII, sigma=sigma, OPinv=op, which="LM")
            interior_blocks.append(phi)
            if loads_q.shape[1]:
                R = rigid_body_fields(model.nodes_m)            # no interfaces: q = u
                MR = MII @ R
                f = loads_q - MR @ np.linalg.solve(R.T @ MR, R.T @ loads_q)
                U = factor.solve(f)
                interior_blocks.append(U - R @ np.linalg.solve(R.T @ MR, MR.T @ U))
        else:
            factor = factorize_spd(KII, backend=backend)
            op = LinearOperator(KII.shape, matvec=factor.solve, dtype=float)
            _, phi = eigsh(KII, k=int(n_modes), M=MII, sigma=0.0, OPinv=op, which="LM")
            interior_blocks.append(phi)
            if len(boundary):
                interior_blocks.append(-factor.solve(Kq[interior][:, boundary].toarray()))
                boundary_blocks.append((len(interior_blocks) - 1, np.eye(len(boundary))))
            if loads_q.shape[1]:
                interior_blocks.append(factor.solve(loads_q[interior]))
    widths = [blk.shape[1] for blk in interior_blocks]
    starts = np.concatenate(([0], np.cumsum(widths)))
    V = np.zeros((nq, int(starts[-1])))
    for k, blk in enumerate(interior_blocks):
        V[interior, starts[k]:starts[k + 1]] = blk
    for k, eye in boundary_blocks:
        V[boundary, starts[k]:starts[k + 1]] = eye
    Vq, w2, dropped = _orthonormal_modal_form(Kq, Mq, V)
    scale = float(np.max(Kq.diagonal() / np.maximum(Mq.diagonal(), 1e-300)))
    rigid = w2 < 1e-10 * scale
    if floating:
        Vq, w2 = Vq[:, ~rigid], w2[~rigid]
    elif rigid.any():
        raise ValueError(f"{int(rigid.sum())} zero-frequency mode(s) in a grounded body: the grounded "
                         "interfaces do not hold it")
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
                  "interfaces": [i.name for i in interfaces], "grounded": grounded},
    )
