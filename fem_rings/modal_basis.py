"""Rigid-body fields, deflated Lanczos and a canonical, reproducible basis of natural modes.

Rigid-body modes are identified by what they are — a combination of the six rigid fields
(three translations, three small rotations) that the supports leave free — not by a frequency
threshold: on a fine quadratic mesh max(K_ii/M_ii) is so large that any fixed fraction of it can
reach the first bending modes of a soft part (a cage's two-wave pair at 16 Hz).

The elastic modes are then computed in the M-orthogonal complement of that rigid space
(deflation): with P = I − R Rᵀ M (R M-orthonormal), the shift-invert operator
P (K − σM)⁻¹ M has the same elastic eigenpairs as (K − σM)⁻¹ M and maps the rigid fields, which
satisfy K R = 0, to zero, so ARPACK never returns them (Saad, Numerical Methods for Large
Eigenvalue Problems, 2nd ed., SIAM 2011, §4.2, deflation; K R = 0 holds to round-off because
isoparametric elements reproduce every linear displacement field exactly).

Reproducibility: ``eigsh`` starts from a fixed vector of a seeded generator instead of ARPACK's
random one, and each cluster of (numerically) equal frequencies is rotated into a canonical basis,
so that degenerate pairs of a ring come out the same in every build.
"""

from __future__ import annotations

import logging

import numpy as np
import scipy.linalg as sla
from scipy.sparse.linalg import LinearOperator, eigsh

from foundation.progress import phase

__all__ = [
    "START_SEED",
    "CLUSTER_RTOL",
    "rigid_body_fields",
    "mass_centre_m",
    "unheld_rigid_combinations",
    "body_length_m",
    "m_orthonormal",
    "start_vector",
    "canonical_modes",
    "deflated_eigsh",
]

log = logging.getLogger(__name__)

#: seed of the fixed start vector and of the probe vectors of the canonical basis
START_SEED = 18_2026

#: modes whose frequencies differ by less than this fraction form one (degenerate) cluster;
#: a revolved ring's n-wave pairs agree to about 1e-11, a tetrahedral cage's split pairs differ
#: by 1e-5 and more, and ARPACK resolves those individually (eigenvector error ~ tol / gap)
CLUSTER_RTOL = 1e-8

#: singular values of the held rigid fields below this fraction of the largest count as zero
RANK_RTOL = 1e-8


def rigid_body_fields(nodes_m: np.ndarray, center_m=None) -> np.ndarray:
    """(3N, 6) rigid fields at the nodes: translations x, y, z and small rotations about x, y, z.

    Parameters
    ----------
    nodes_m : (N, 3) float64, m
    center_m : (3,) float64, m, optional
        Centre of the rotations (default the origin); u = e_k × (x − c).
    """
    x = np.asarray(nodes_m, dtype=float)
    if center_m is not None:
        x = x - np.asarray(center_m, dtype=float)
    R = np.zeros((len(x), 3, 6))
    for i in range(3):
        R[:, i, i] = 1.0
    for k, e in enumerate(np.eye(3)):
        R[:, :, 3 + k] = np.cross(e, x)
    return R.reshape(3 * len(x), 6)


def mass_centre_m(M, nodes_m: np.ndarray) -> np.ndarray:
    """Centre of mass (3,) m of a consistent mass matrix M (3N × 3N, interleaved DOFs).

    c_i = (t_iᵀ M p_i) / (t_iᵀ M t_i), t_i the unit translation along i and p_i the field whose
    i-component is the coordinate x_i (the first moment of mass over the mass).
    """
    x = np.asarray(nodes_m, dtype=float)
    c = np.zeros(3)
    for i in range(3):
        t = np.zeros(x.shape)
        t[:, i] = 1.0
        p = np.zeros(x.shape)
        p[:, i] = x[:, i]
        Mt = M @ t.ravel()
        c[i] = float(Mt @ p.ravel()) / float(Mt @ t.ravel())
    return c


def unheld_rigid_combinations(R_held: np.ndarray, length_m: float) -> np.ndarray:
    """(6, r) combinations of the rigid fields that vanish on the held DOFs.

    Parameters
    ----------
    R_held : (k, 6) float64
        Values of the rigid fields (translations, then rotations about a central point) at the
        held DOFs, or any linear constraint rows applied to them.
    length_m : float
        Size of the body (e.g. the RMS distance of its nodes from the centre): a rotation
        moves its nodes by about this much, so the columns are compared on one scale.

    Returns
    -------
    (6, r) float64
        A basis of the null space of ``R_held``; r = 6 for a free body, 0 when the constraints
        hold every rigid motion.
    """
    R_held = np.asarray(R_held, dtype=float)
    scale = np.array([1.0, 1.0, 1.0, length_m, length_m, length_m])
    if R_held.shape[0] == 0:
        return np.diag(1.0 / scale)
    _, s, vt = np.linalg.svd(R_held / scale, full_matrices=True)
    rank = int(np.sum(s > RANK_RTOL * s[0])) if s[0] > 0 else 0
    return vt[rank:].T / scale[:, None]


def body_length_m(nodes_m: np.ndarray, center_m: np.ndarray) -> float:
    """RMS distance of the nodes from ``center_m``, m (the scale of a rotation's displacements)."""
    return float(np.sqrt(np.mean(np.sum((np.asarray(nodes_m) - center_m) ** 2, axis=1))))


def m_orthonormal(R: np.ndarray, M) -> np.ndarray:
    """M-orthonormal basis of the columns of R, in their order (Gram–Schmidt by Cholesky)."""
    if R.shape[1] == 0:
        return R
    G = R.T @ (M @ R)
    L = np.linalg.cholesky(0.5 * (G + G.T))
    return sla.solve_triangular(L, R.T, lower=True).T


def start_vector(n: int) -> np.ndarray:
    """Fixed start vector (n,) for ARPACK: standard normal values of a seeded generator."""
    return np.random.default_rng(START_SEED).standard_normal(n)


def _probes(n: int, m: int) -> np.ndarray:
    """(n, m) fixed probe vectors that define the canonical basis of a cluster of m modes."""
    return np.random.default_rng([START_SEED, n, m]).standard_normal((n, m))


def canonical_modes(lam: np.ndarray, vec: np.ndarray, rtol: float = CLUSTER_RTOL) -> tuple[np.ndarray, np.ndarray]:
    """Sort modes by eigenvalue and put every cluster of equal eigenvalues into a canonical basis.

    A cluster is a run of modes whose frequencies (√λ) differ by less than ``rtol`` of the
    largest. Its shapes Φ (orthonormal in some inner product) are rotated by the orthogonal Q
    that makes Gᵀ Φ Q lower triangular with a positive diagonal, G fixed probe vectors: QR of
    (GᵀΦ)ᵀ = Q R gives GᵀΦ Q = Rᵀ. The result depends only on the cluster's subspace, not on the
    basis the eigensolver happened to return; a single mode gets the sign that makes gᵀφ > 0.

    Parameters
    ----------
    lam : (k,) float64
        Eigenvalues ω², rad²/s².
    vec : (n, k) float64
        Mode shapes.
    """
    order = np.argsort(lam, kind="stable")
    lam, vec = np.asarray(lam)[order], np.array(vec[:, order])
    f = np.sqrt(np.clip(lam, 0.0, None))
    start = 0
    for i in range(1, len(lam) + 1):
        if i < len(lam) and f[i] - f[i - 1] <= rtol * max(abs(f[i]), 1e-300):
            continue
        m = i - start
        block = vec[:, start:i]
        A = _probes(vec.shape[0], m).T @ block
        Q, Rt = np.linalg.qr(A.T)
        sign = np.where(np.diag(Rt) < 0.0, -1.0, 1.0)
        vec[:, start:i] = block @ (Q * sign)
        if m > 1:
            lam[start:i] = np.mean(lam[start:i])
        start = i
    return lam, vec


def deflated_eigsh(K, M, k: int, sigma: float, opinv, rigid_m: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Lowest k eigenpairs of K φ = λ M φ M-orthogonal to ``rigid_m``, reproducibly.

    Parameters
    ----------
    K, M : sparse (n, n)
    k : int
        Number of (elastic) modes.
    sigma : float
        Shift; ``opinv`` applies (K − σM)⁻¹.
    opinv : LinearOperator
    rigid_m : (n, r) float64, optional
        M-orthonormal rigid fields to deflate (K R = 0).

    Returns
    -------
    lam : (k,) float64, rad²/s², ascending
    vec : (n, k) float64, M-normalised, M-orthogonal to ``rigid_m``, canonical within clusters
    """
    n = K.shape[0]
    v0 = start_vector(n)
    if rigid_m is not None and rigid_m.shape[1]:
        MR = np.asarray(M @ rigid_m)

        def project(x):
            return x - rigid_m @ (MR.T @ x)

        op = LinearOperator((n, n), matvec=lambda b: project(opinv.matvec(b)), dtype=float)
        v0 = project(v0)
    else:
        project, op = (lambda x: x), opinv
    with phase(f"eigen solve: {int(k)} modes of {n} DOF") as shown:
        solves = [0]

        def counted(b):
            solves[0] += 1
            shown.note(f"{solves[0]} solves")
            return op.matvec(b)

        lam, vec = eigsh(K, k=int(k), M=M, sigma=sigma, OPinv=LinearOperator((n, n), matvec=counted, dtype=float),
                         which="LM", v0=v0)
    vec = project(vec)
    vec /= np.sqrt(np.einsum("ik,ik->k", vec, M @ vec))
    return canonical_modes(lam, vec)
