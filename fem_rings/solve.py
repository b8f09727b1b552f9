"""Static and modal solves of a ring model, and the loads they take.

Supports are Dirichlet conditions on node sets (eliminated: only the free DOFs enter the
factorisation). Loads are consistent nodal force vectors built from surface tractions
(:func:`surface_load`), forces at points (:func:`point_load`, through the interpolation transpose)
or force per unit length along a curve (:func:`line_load`).

Modal analysis solves K φ = ω² M φ for the lowest modes with ``eigsh`` in shift-invert mode; the
operator (K − σM)⁻¹ is one sparse Cholesky factorisation (CHOLMOD when installed,
:mod:`fem_rings.linalg`). A free model uses σ < 0 so that K − σM is positive definite despite the
rigid-body modes. These are the rigid motions the supports leave free (six for a free body), taken
directly from the rigid fields; the elastic modes are computed M-orthogonal to them, from a fixed
start vector and with degenerate pairs in a canonical basis (:mod:`fem_rings.modal_basis`).
"""

from __future__ import annotations

import logging
import math
import os
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import skfem
from threadpoolctl import threadpool_limits

from .linalg import available_backends, factorize_spd, shift_invert_operator
from .modal_basis import (body_length_m, deflated_eigsh, m_orthonormal, mass_centre_m, rigid_body_fields,
                          unheld_rigid_combinations)
from .model import FEModel, vector_dofs
from .probe import vector_probe_matrix

__all__ = [
    "solver_threads",
    "Support",
    "StaticResult",
    "Modes",
    "fixed_dofs",
    "static_solve",
    "modal_analysis",
    "rigid_body_fields",
    "surface_load",
    "point_load",
    "line_load",
    "line_load_operator",
    "support_reaction_N",
    "classify_ring_mode",
]

log = logging.getLogger(__name__)

#: an elastic eigenvalue below this fraction of max(K_ii/M_ii) is zero to round-off: a mechanism
MECHANISM_RTOL = 1e-14


@contextmanager
def solver_threads():
    """Limit BLAS/OpenMP pools to ``$FLEXBEARING_SOLVER_THREADS`` threads (default 1) while solving.

    numpy, scipy and CHOLMOD each bring an OpenBLAS thread pool; on a 2-core machine they spin
    against each other during the many single-vector solves of the eigensolver (seen: 30 modes of
    a 32k-DOF ring in 15 s with the default pools, 1.9 s with one thread; a 211k-DOF
    factorisation 11.4 s vs 6.8 s).
    """
    n = int(os.environ.get("FLEXBEARING_SOLVER_THREADS", "1"))
    # threadpoolctl limits only the pools already loaded: load the sparse backends' BLAS first, or a
    # factorisation that imports its backend inside the block runs on all threads the first time
    # (and rounds differently from every later one: the reductions would depend on what ran before)
    available_backends()
    with threadpool_limits(limits=n):
        yield


@dataclass(frozen=True)
class Support:
    """Zero displacement of the given components at a node set.

    Parameters
    ----------
    nodes : (k,) int
        Node indices (e.g. ``model.node_set("bolt_face")``).
    components : tuple of int
        Displacement components held: 0 = x, 1 = y, 2 = z.
    name : str
        Label used in messages.
    """

    nodes: np.ndarray
    components: tuple = (0, 1, 2)
    name: str = "support"

    def __post_init__(self) -> None:
        if len(self.nodes) == 0:
            raise ValueError(f"support {self.name!r}: node set is empty")
        if not set(self.components) <= {0, 1, 2} or not self.components:
            raise ValueError(f"support {self.name!r}: components must be a non-empty subset of (0, 1, 2)")


def fixed_dofs(supports) -> np.ndarray:
    """Sorted unique vector DOFs held by the supports."""
    if not supports:
        return np.zeros(0, dtype=np.int64)
    return np.unique(np.concatenate([vector_dofs(s.nodes, s.components) for s in supports]))


def _free(n: int, fixed: np.ndarray) -> np.ndarray:
    mask = np.ones(n, dtype=bool)
    mask[fixed] = False
    return np.flatnonzero(mask)


@dataclass(frozen=True)
class StaticResult:
    """Displacement (n_nodes, 3) m and support reactions (3N,) N of a static solve."""

    displacement_m: np.ndarray
    reaction_N: np.ndarray
    backend: str

    @property
    def u(self) -> np.ndarray:
        """Interleaved displacement vector (3N,), m."""
        return self.displacement_m.ravel()


def static_solve(model: FEModel, force_N: np.ndarray, supports, backend: str = "auto") -> StaticResult:
    """Solve K u = f with the supports' DOFs held at zero.

    Parameters
    ----------
    force_N : (3N,) float64, N
        Consistent nodal forces (interleaved).
    supports : sequence of Support
        Must suppress all rigid-body motion, else the factorisation reports a singular matrix.
    """
    f = np.asarray(force_N, dtype=float)
    if f.shape != (model.n_dofs,):
        raise ValueError(f"force_N must have shape ({model.n_dofs},), got {f.shape}")
    if not np.isfinite(f).all():
        raise ValueError("force_N contains non-finite values")
    fixed = fixed_dofs(supports)
    if len(fixed) == 0:
        raise ValueError("static_solve needs supports: a free body has no static solution under a general load")
    free = _free(model.n_dofs, fixed)
    Kff = model.K[free][:, free].tocsc()
    u = np.zeros(model.n_dofs)
    with solver_threads():
        factor = factorize_spd(Kff, backend=backend)
        u[free] = factor.solve(f[free])
    reaction = model.K @ u - f
    reaction[free] = 0.0
    return StaticResult(u.reshape(-1, 3), reaction, factor.backend)


@dataclass(frozen=True)
class Modes:
    """Natural modes of a (free or supported) model.

    Attributes
    ----------
    frequencies_Hz : (k,) float64
        Ascending; rigid-body modes (numerically ~0) included.
    shapes : (3N, k) float64
        Mass-normalised mode shapes (φᵀ M φ = 1), zero at held DOFs.
    rigid : (k,) bool
        Rigid-body modes: the first ``n_rigid`` modes, an M-orthonormal basis of the rigid
        motions the supports leave free (6 for a free body, 0 when held); the elastic modes
        are computed M-orthogonal to them (:mod:`fem_rings.modal_basis`).
    backend : str
        Factorisation used.
    """

    frequencies_Hz: np.ndarray
    shapes: np.ndarray
    rigid: np.ndarray
    backend: str

    @property
    def n_rigid(self) -> int:
        return int(self.rigid.sum())

    @property
    def elastic_frequencies_Hz(self) -> np.ndarray:
        return self.frequencies_Hz[~self.rigid]


def modal_analysis(
    model: FEModel,
    n_modes: int,
    supports=(),
    shift_Hz: float | None = None,
    backend: str = "auto",
) -> Modes:
    """Lowest natural modes, free–free (no supports) or constrained.

    Parameters
    ----------
    n_modes : int
        Number of modes wanted, rigid-body modes included.
    supports : sequence of Support
        Held DOFs; empty for a free–free model.
    shift_Hz : float, optional
        Shift σ = −(2π shift_Hz)² (negative: K − σM stays positive definite for a free model).
        Default 1 Hz.
    """
    if int(n_modes) < 1:
        raise ValueError(f"n_modes must be ≥ 1, got {n_modes}")
    fixed = fixed_dofs(supports)
    free = _free(model.n_dofs, fixed)
    if n_modes >= len(free):
        raise ValueError(f"n_modes ({n_modes}) must be below the number of free DOFs ({len(free)})")
    K = model.K[free][:, free].tocsc()
    M = model.M[free][:, free].tocsc()
    sigma = -(2.0 * math.pi * (1.0 if shift_Hz is None else shift_Hz)) ** 2
    with solver_threads():
        rigid_m = free_rigid_modes(model, fixed, free, M)
        n_rigid = min(rigid_m.shape[1], int(n_modes))
        rigid_m = rigid_m[:, :n_rigid]
        lam_rigid = np.clip(np.einsum("ik,ik->k", rigid_m, K @ rigid_m), 0.0, None)
        op, factor = shift_invert_operator(K, M, sigma, backend=backend)
        if int(n_modes) > n_rigid:
            lam, vec = deflated_eigsh(K, M, int(n_modes) - n_rigid, sigma, op, rigid_m)
        else:
            lam, vec = np.zeros(0), np.zeros((len(free), 0))
    lam = np.concatenate((lam_rigid, lam))
    shapes = np.zeros((model.n_dofs, len(lam)))
    shapes[free] = np.column_stack((rigid_m, vec))
    freq = np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * math.pi)
    rigid = np.arange(len(lam)) < n_rigid
    if len(fixed) and n_rigid:
        log.warning("model %s: the supports leave %d rigid-body motion(s) free", model.ring.profile.name, n_rigid)
    scale = float(np.max(K.diagonal() / M.diagonal()))
    if len(vec.T) and lam[n_rigid] < MECHANISM_RTOL * scale:
        log.warning("model %s: elastic mode at %.3g Hz, a zero-energy mechanism (a loose part?)",
                    model.ring.profile.name, freq[n_rigid])
    log.info("modes of %s: %d rigid-body, first elastic %.4g Hz", model.ring.profile.name, n_rigid,
             freq[n_rigid] if len(freq) > n_rigid else float("nan"))
    return Modes(freq, shapes, rigid, factor.backend)


def free_rigid_modes(model: FEModel, fixed: np.ndarray, free: np.ndarray, M_free) -> np.ndarray:
    """(n_free, r) M-orthonormal rigid motions that the held DOFs leave free, at the free DOFs.

    The six rigid fields about the centre of mass are combined into those that vanish at every
    held DOF (r = 6 for a free body, fewer under supports, 0 when clamped).
    """
    c = mass_centre_m(model.M, model.nodes_m)
    R = rigid_body_fields(model.nodes_m, c)
    N = unheld_rigid_combinations(R[fixed], body_length_m(model.nodes_m, c))
    return m_orthonormal(R[free] @ N, M_free)


def classify_ring_mode(nodes_m: np.ndarray, shape: np.ndarray, max_wave: int = 8) -> tuple[str, int]:
    """Family and circumferential wave number of a ring mode about the z axis.

    Returns ``("out", n)`` when axial motion dominates (out-of-plane bending/torsion), else
    ``("in", n)``; n is the dominant harmonic cos(nθ), sin(nθ) of the axial (out) or radial (in)
    displacement over the nodes.
    """
    u = np.asarray(shape).reshape(-1, 3)
    th = np.arctan2(nodes_m[:, 1], nodes_m[:, 0])
    ur = u[:, 0] * np.cos(th) + u[:, 1] * np.sin(th)
    axial = np.sum(u[:, 2] ** 2) > 0.5 * np.sum(u**2)
    w = u[:, 2] if axial else ur
    amp = [np.hypot(np.mean(w * np.cos(n * th)), np.mean(w * np.sin(n * th))) for n in range(max_wave + 1)]
    return ("out" if axial else "in"), int(np.argmax(amp))


# -- loads ------------------------------------------------------------------------------------

def surface_load(model: FEModel, facets: np.ndarray, traction_Pa, intorder: int | None = None) -> np.ndarray:
    """Consistent nodal forces (3N,) N of a traction on boundary facets.

    f_a = ∫ N_a t dA over the facets, integrated on each facet as a face of its element: the
    facet's quadrature points are placed on that face of the reference element directly (the
    face is a plane of the reference cube or tetrahedron, so the map is affine and exact), and
    dA = |(DF e₁) × (DF e₂)| dX with DF the element's isoparametric Jacobian and e₁, e₂ the face's
    edge vectors in reference coordinates. No inverse mapping is needed: scikit-fem's
    ``FacetBasis`` locates the points by a Newton iteration on x = F(X) that fails to converge
    on strongly curved quadratic facets (a round section of a few elements).

    Parameters
    ----------
    facets : (k,) int
        Facet indices (e.g. ``model.ring.facet_sets["top"]``).
    traction_Pa : (3,) array or callable
        Constant traction vector, Pa, or ``f(x) -> (3, ...)`` of the physical coordinates
        ``x`` (3, n_facets, n_qp).
    intorder : int, optional
        Quadrature order on the facets (default the model's stiffness order).
    """
    facets = np.asarray(facets, dtype=np.int64)
    if len(facets) == 0:
        raise ValueError("surface_load: the facet set is empty")
    if not callable(traction_Pa):
        t_const = np.asarray(traction_Pa, dtype=float)
        if t_const.shape != (3,):
            raise ValueError(f"traction_Pa must be a 3-vector, got shape {t_const.shape}")
    mesh = model.mesh
    elem = mesh.elem()
    dofs, phi, x, dA = _facet_quadrature(mesh, elem, facets, intorder or model.intorder[0])
    if callable(traction_Pa):
        t = np.asarray(traction_Pa(x), dtype=float)
    else:
        t = np.broadcast_to(t_const[:, None, None], x.shape)
    # (n_local, n_facets, 3): ∫ N_a t_c dA on each facet
    local = np.einsum("afq,cfq,fq->afc", phi, t, dA)
    rows = 3 * dofs[:, :, None] + np.arange(3)
    return np.bincount(rows.ravel(), weights=local.ravel(), minlength=model.n_dofs)


def _facet_quadrature(mesh, elem, facets: np.ndarray, intorder: int):
    """Shape functions, points and area weights of a quadrature on boundary facets.

    Returns ``dofs`` (n_local, k) node indices of each facet's element, ``phi`` (n_local, k, n_qp)
    shape-function values, ``x`` (3, k, n_qp) m points and ``dA`` (k, n_qp) m² weights.
    """
    tind = mesh.f2t[0, facets]
    local_face = np.argmax(mesh.t2f[:, tind] == facets[None, :], axis=0)
    if not np.array_equal(mesh.t2f[local_face, tind], facets):
        raise ValueError("surface_load: some facets are not faces of their elements (not mesh facets?)")
    faces = np.asarray(elem.refdom.facets)[local_face]         # (k, corners) local vertices
    corners = elem.refdom.p[:, faces]                            # (3, k, corners) reference coordinates
    X, W = skfem.quadrature.get_quadrature(mesh.brefdom, int(intorder))
    p0 = corners[:, :, 0]
    # quadrilateral faces are listed cyclically: the edges from corner 0 go to corners 1 and 3
    e1 = corners[:, :, 1] - p0
    e2 = corners[:, :, 3 if faces.shape[1] == 4 else 2] - p0
    Y = p0[:, :, None] + e1[:, :, None] * X[0] + e2[:, :, None] * X[1]
    dofs = mesh.dofs.element_dofs[:, tind]
    nodes = mesh.doflocs
    phi = np.empty((dofs.shape[0],) + Y.shape[1:])
    x = np.zeros(Y.shape)
    DF = np.zeros((3, 3) + Y.shape[1:])
    for a in range(dofs.shape[0]):
        phi[a], dphi = elem.lbasis(Y, a)
        xa = nodes[:, dofs[a]][:, :, None]                       # (3, k, 1)
        x += xa * phi[a]
        DF += xa[:, None] * dphi[None]
    t1 = np.einsum("ijfq,jf->ifq", DF, e1)
    t2 = np.einsum("ijfq,jf->ifq", DF, e2)
    dA = np.linalg.norm(np.cross(t1, t2, axis=0), axis=0) * W
    return dofs, phi, x, dA


def point_load(model: FEModel, points_m: np.ndarray, forces_N: np.ndarray) -> np.ndarray:
    """Consistent nodal forces (3N,) N of concentrated forces at points (Pᵀ f).

    Parameters
    ----------
    points_m : (n, 3) float64, m
    forces_N : (n, 3) float64, N
    """
    pts = np.atleast_2d(points_m)
    f = np.atleast_2d(np.asarray(forces_N, dtype=float))
    if f.shape != pts.shape:
        raise ValueError(f"forces_N must have the shape of points_m {pts.shape}, got {f.shape}")
    P = vector_probe_matrix(model.basis(2), pts)
    return P.T @ f.ravel()


def line_load_operator(model: FEModel, curve_m: np.ndarray, closed: bool = True, n_sub: int = 8):
    """A function q ↦ consistent nodal forces (3N,) for force-per-length values q (n, 3) N/m at the
    polyline points ``curve_m`` (n, 3) (linear in between, ``n_sub`` Gauss points per piece).

    The points are located once, so many load cases on one curve (e.g. load harmonics) cost one
    location. For a circle pass enough points that the chords follow it (the resultant uses the
    chord lengths).
    """
    c = np.asarray(curve_m, dtype=float)
    n = len(c)
    i0 = np.arange(n) if closed else np.arange(n - 1)
    i1 = (i0 + 1) % n
    s, w = np.polynomial.legendre.leggauss(n_sub)
    s, w = 0.5 * (s + 1.0), 0.5 * w
    L = np.linalg.norm(c[i1] - c[i0], axis=1)
    pts = (c[i0][:, None, :] + s[None, :, None] * (c[i1] - c[i0])[:, None, :]).reshape(-1, 3)
    wq = (L[:, None] * w[None, :]).ravel()                      # quadrature weight of each point, m
    # value at a quadrature point = (1 − s) q[i0] + s q[i1]
    rows = np.repeat(np.arange(len(pts)), 2)
    cols = np.stack([np.repeat(i0, n_sub), np.repeat(i1, n_sub)], axis=1).ravel()
    vals = np.stack([np.tile(1.0 - s, len(i0)), np.tile(s, len(i0))], axis=1).ravel()
    A = sp.csr_matrix((vals, (rows, cols)), shape=(len(pts), n))
    PT = vector_probe_matrix(model.basis(2), pts).T.tocsr()

    def apply(force_per_length_N_m) -> np.ndarray:
        q = np.broadcast_to(np.asarray(force_per_length_N_m, dtype=float), c.shape)
        return PT @ ((A @ q) * wq[:, None]).ravel()

    return apply


def line_load(model: FEModel, curve_m: np.ndarray, force_per_length_N_m, closed: bool = True,
              n_sub: int = 8) -> np.ndarray:
    """Consistent nodal forces (3N,) N of a force per unit length along a polyline on or in the body.

    ``force_per_length_N_m`` is a (3,) vector or (n, 3) values at the polyline points ``curve_m``
    (n, 3), linear in between; see :func:`line_load_operator`.
    """
    return line_load_operator(model, curve_m, closed, n_sub)(force_per_length_N_m)


def support_reaction_N(result: StaticResult, supports) -> np.ndarray:
    """Total reaction force (3,) N over the supports."""
    return result.reaction_N.reshape(-1, 3)[np.unique(np.concatenate([s.nodes for s in supports]))].sum(axis=0)

