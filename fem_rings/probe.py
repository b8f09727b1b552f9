"""Evaluate finite-element fields at arbitrary points of a curved quadratic mesh.

scikit-fem's ``probes`` locates points through the straight-sided mesh and fails for points on a
curved boundary (a raceway point lies outside the chord of its element by the sag h²/8R). Here
candidate elements are the nearest by centroid (k-d tree); the isoparametric map is inverted by
Newton's method in each candidate and the element whose reference coordinates lie inside (or least
outside) the reference cell is taken. The result is the sparse interpolation matrix P with
u(x_k) = Σ_j P[k, j] u_j; its transpose turns point forces into consistent nodal forces
(work-consistent: F_nodal = Pᵀ f).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import skfem
from scipy.spatial import cKDTree

__all__ = ["locate", "probe_matrix", "vector_probe_matrix", "gradient_probe_matrices"]


def _outside(mesh: skfem.Mesh, X: np.ndarray) -> np.ndarray:
    """How far reference points (3, n) lie outside the reference cell (0 inside)."""
    if isinstance(mesh, skfem.MeshTet1):
        return np.maximum(0.0, np.maximum(-X.min(axis=0), X.sum(axis=0) - 1.0))
    return np.maximum(0.0, np.maximum(-X, X - 1.0).max(axis=0))


def _newton(mapping, x: np.ndarray, cells: np.ndarray, iters: int = 25) -> np.ndarray:
    X = np.full((3, x.shape[1], 1), 0.25)
    xx = x[:, :, None]
    for _ in range(iters):
        F = mapping.F(X, cells)
        dX = np.einsum("ijkl,jkl->ikl", mapping.invDF(X, cells), xx - F)
        X = np.clip(X + dX, -1.0, 2.0)  # keep the polynomial map in its sane range
        if np.abs(dX).max() < 1e-13:
            break
    return X[:, :, 0]


def locate(basis: skfem.CellBasis, points_m: np.ndarray, n_candidates: int = 12, tol: float = 0.02):
    """Element and reference coordinates of each point.

    Parameters
    ----------
    basis : skfem.CellBasis
        Any basis on the mesh (its isoparametric mapping is used).
    points_m : (n, 3) float64, m
    n_candidates : int
        Nearest elements (by centroid) tried per point first (then 8× and 64× as many for the
        points that none of them holds).
    tol : float
        Accepted distance outside the reference cell (reference units): points on the exact
        curved surface may lie just outside the quadratic approximation of it.

    Returns
    -------
    cells : (n,) int
    X : (3, n) float64
        Reference coordinates.

    Raises
    ------
    ValueError
        When a point lies outside the mesh.
    """
    mesh = basis.mesh
    x = np.ascontiguousarray(np.atleast_2d(points_m).T)
    centroids = mesh.p[:, mesh.t].mean(axis=1).T
    tree = cKDTree(centroids)
    best_cell = np.zeros(x.shape[1], dtype=np.int64)
    best_X = np.zeros_like(x)
    best_out = np.full(x.shape[1], np.inf)
    scale = np.maximum(1.0, np.abs(x).max(axis=0))
    # per point: candidates in order of distance, stop at the first that contains it, else keep
    # the least-outside one (a point on the curved surface may sit just outside every element);
    # the result of a point does not depend on the other points located with it. Where small
    # elements crowd (a bolt hole beside a groove) the containing element can lie beyond the
    # first candidates: the points not yet inside are tried on 8× and 64× as many.
    done = 0
    for k in (n_candidates, 8 * n_candidates, 64 * n_candidates):
        k = min(k, centroids.shape[0])
        left = np.flatnonzero(best_out > 1e-6)
        if not len(left) or k <= done:
            break
        _, cand = tree.query(x[:, left].T, k=k)
        cand = cand.reshape(len(left), k)
        for j in range(done, k):
            todo = np.flatnonzero(best_out[left] > 1e-6)   # 1e-6 of an element: inside for every purpose
            if not len(todo):
                break
            pts, cells = left[todo], cand[todo, j]
            xt = x[:, pts]
            X = _newton(basis.mapping, xt, cells)
            err = np.linalg.norm(basis.mapping.F(X[:, :, None], cells)[:, :, 0] - xt, axis=0)
            out = _outside(mesh, X) + np.where(err < 1e-9 * scale[pts], 0.0, np.inf)
            better = out < best_out[pts]
            idx = pts[better]
            best_cell[idx], best_X[:, idx], best_out[idx] = cells[better], X[:, better], out[better]
        if not (best_out > tol).any():
            break
        done = k
    bad = np.flatnonzero(best_out > tol)
    if len(bad):
        p = x[:, bad[0]]
        raise ValueError(f"{len(bad)} point(s) lie outside the mesh, first at ({p[0]:.6g}, {p[1]:.6g}, {p[2]:.6g}) m")
    return best_cell, best_X


def probe_matrix(basis: skfem.CellBasis, points_m: np.ndarray) -> sp.csr_matrix:
    """Scalar interpolation matrix (n_points, N): values at the points from nodal values."""
    cells, X = locate(basis, points_m)
    pts = X[:, :, None]
    phis = np.array([np.asarray(basis.elem.gbasis(basis.mapping, pts, a, tind=cells)[0])[:, 0]
                     for a in range(basis.Nbfun)])  # (nloc, n)
    n = X.shape[1]
    rows = np.tile(np.arange(n), basis.Nbfun)
    cols = basis.element_dofs[:, cells].ravel()
    return sp.coo_matrix((phis.ravel(), (rows, cols)), shape=(n, basis.N)).tocsr()


def vector_probe_matrix(basis: skfem.CellBasis, points_m: np.ndarray) -> sp.csr_matrix:
    """Interleaved vector interpolation (3 n_points, 3 N): u(x_k)_i = row 3k+i."""
    return sp.kron(probe_matrix(basis, points_m), sp.identity(3, format="csr"), format="csr")


def gradient_probe_matrices(basis: skfem.CellBasis, points_m: np.ndarray) -> list[sp.csr_matrix]:
    """Matrices G_i (n_points, N) with ∂f/∂x_i at the points = G_i @ nodal values of a scalar f."""
    cells, X = locate(basis, points_m)
    pts = X[:, :, None]
    grads = np.array([np.asarray(basis.elem.gbasis(basis.mapping, pts, a, tind=cells)[0].grad)[:, :, 0]
                      for a in range(basis.Nbfun)])  # (nloc, 3, n)
    n = X.shape[1]
    rows = np.tile(np.arange(n), basis.Nbfun)
    cols = basis.element_dofs[:, cells].ravel()
    return [sp.coo_matrix((grads[:, i, :].ravel(), (rows, cols)), shape=(n, basis.N)).tocsr() for i in range(3)]
