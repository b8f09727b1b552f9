"""Tests of the sparse SPD factorisations in ``fem_rings.linalg``.

References used below:

* ``scipy.sparse.linalg.spsolve`` (SuperLU, general LU with partial pivoting) on the same
  matrix: an independent direct solve for the linear systems.
* ``scipy.linalg.eigh`` (LAPACK ``dsygvd``, dense generalized symmetric eigensolver) on the
  dense copies of K and M: the reference eigenvalues for the shift-invert Lanczos iteration.

The eigenproblems are bilinear (Q1) finite elements of the Laplacian on the unit square,
K = T⊗Mₕ + Mₕ⊗T and M = Mₕ⊗Mₕ with the 1-D stiffness T and consistent mass Mₕ, either clamped
along one edge (positive definite K) or free (K singular, one zero eigenvalue).
"""

from __future__ import annotations

import logging

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from fem_rings import linalg
from fem_rings.linalg import available_backends, factorize_spd, shift_invert_operator

BACKENDS = ["superlu", "cholmod", "cvxopt", "cholespy"]
LIBRARIES = {"cholmod": "sksparse.cholmod", "cvxopt": "cvxopt.cholmod", "cholespy": "cholespy"}


def _require(backend: str) -> None:
    """Skip a case whose library is not installed."""
    if backend in LIBRARIES:
        pytest.importorskip(LIBRARIES[backend])


def _random_spd(n: int = 300, seed: int = 7) -> sp.csc_matrix:
    """Seeded sparse SPD matrix R Rᵀ + I with about 2 % fill in R."""
    R = sp.random(n, n, density=0.02, random_state=np.random.default_rng(seed), format="csr")
    return sp.csc_matrix(R @ R.T + sp.identity(n))


def _q1_laplacian(cells: int, clamped: bool) -> tuple[sp.csc_matrix, sp.csc_matrix]:
    """Q1 stiffness and consistent mass of the unit square, optionally clamped at x = 0."""
    h = 1.0 / cells
    nodes = cells + 1
    ones = np.ones(nodes)
    T = sp.diags([-ones[1:], 2 * ones, -ones[1:]], [-1, 0, 1]).tolil() / h
    T[0, 0] = T[-1, -1] = 1.0 / h
    Mh = sp.diags([ones[1:], 4 * ones, ones[1:]], [-1, 0, 1]).tolil() * (h / 6)
    Mh[0, 0] = Mh[-1, -1] = 2 * h / 6
    K = sp.kron(T, Mh) + sp.kron(Mh, T)
    M = sp.kron(Mh, Mh)
    if clamped:
        free = np.arange(nodes * nodes)[nodes:]  # the first block row is the edge x = 0
        K, M = K.tocsr()[free][:, free], M.tocsr()[free][:, free]
    return sp.csc_matrix(K), sp.csc_matrix(M)


@pytest.fixture
def fresh_warning(monkeypatch):
    """Pretend scikit-sparse, cvxopt and cholespy are absent and the fallback warning is unsaid."""
    monkeypatch.setattr(linalg, "_import_cholmod", lambda: None)
    monkeypatch.setattr(linalg, "_import_cvxopt", lambda: None)
    monkeypatch.setattr(linalg, "_import_cholespy", lambda: None)
    monkeypatch.setattr(linalg, "_fallback_warned", False)
    monkeypatch.delenv("FLEXBEARING_SPARSE_SOLVER", raising=False)


@pytest.mark.parametrize("backend", BACKENDS)
def test_solve_matches_spsolve(backend):
    _require(backend)
    A = _random_spd()
    rng = np.random.default_rng(1)
    b = rng.standard_normal(A.shape[0])
    B = rng.standard_normal((A.shape[0], 4))
    factor = factorize_spd(A, backend=backend)
    assert factor.backend == backend and factor.n == A.shape[0]
    x = factor.solve(b)
    X = factor.solve(B)
    assert x.shape == b.shape and X.shape == B.shape
    x_ref = spla.spsolve(A, b)
    X_ref = spla.spsolve(A, B)
    assert np.linalg.norm(x - x_ref) <= 1e-10 * np.linalg.norm(x_ref)
    assert np.linalg.norm(X - X_ref) <= 1e-10 * np.linalg.norm(X_ref)


@pytest.mark.parametrize("backend", BACKENDS)
def test_shift_invert_lowest_eigenvalues_clamped(backend):
    _require(backend)
    K, M = _q1_laplacian(cells=12, clamped=True)
    reference = scipy.linalg.eigh(K.toarray(), M.toarray(), eigvals_only=True)[:6]
    op, factor = shift_invert_operator(K, M, sigma=-1.0, backend=backend)
    assert factor.backend == backend
    found = spla.eigsh(K, k=6, M=M, sigma=-1.0, OPinv=op, mode="normal", return_eigenvectors=False)
    np.testing.assert_allclose(np.sort(found), reference, rtol=1e-9)


@pytest.mark.parametrize("backend", BACKENDS)
def test_shift_invert_free_free_needs_negative_shift(backend):
    _require(backend)
    K, M = _q1_laplacian(cells=10, clamped=False)
    reference = scipy.linalg.eigh(K.toarray(), M.toarray(), eigvals_only=True)[:5]
    op, _ = shift_invert_operator(K, M, sigma=-5.0, backend=backend)
    found = np.sort(spla.eigsh(K, k=5, M=M, sigma=-5.0, OPinv=op, return_eigenvectors=False))
    assert abs(found[0]) <= 1e-9 * reference[1]  # rigid-body mode, eigenvalue 0
    np.testing.assert_allclose(found[1:], reference[1:], rtol=1e-9)


@pytest.mark.parametrize("backend", ["cholmod", "cvxopt", "cholespy"])
def test_cholesky_not_positive_definite_message(backend):
    _require(backend)
    K, M = _q1_laplacian(cells=8, clamped=True)
    with pytest.raises(np.linalg.LinAlgError, match="not positive definite.*negative shift"):
        factorize_spd(K - 100.0 * M, backend=backend)  # above the lowest eigenvalue ≈ 24.7
    with pytest.raises(np.linalg.LinAlgError, match="sigma = 100.*not positive definite"):
        shift_invert_operator(K, M, sigma=100.0, backend=backend)


def test_superlu_singular_matrix_is_linalg_error():
    A = sp.csc_matrix(sp.diags([1.0, 2.0, 0.0, 3.0]))
    with pytest.raises(np.linalg.LinAlgError, match="singular"):
        factorize_spd(A, backend="superlu")


def test_rejects_non_symmetric_and_bad_rhs():
    A = _random_spd(n=50)
    with pytest.raises(ValueError, match="not symmetric"):
        factorize_spd(A + sp.csc_matrix(([1.0], ([0], [1])), shape=A.shape), backend="superlu")
    with pytest.raises(ValueError, match="backend"):
        factorize_spd(A, backend="umfpack")
    with pytest.raises(ValueError, match="shape"):
        factorize_spd(A, backend="superlu").solve(np.ones(49))


def test_fallback_warns_once(fresh_warning, caplog):
    A = _random_spd(n=40)
    with caplog.at_level(logging.WARNING, logger="fem_rings.linalg"):
        first = factorize_spd(A)
        second = factorize_spd(A)
    assert first.backend == second.backend == "superlu"
    warnings = [r for r in caplog.records if r.levelno == logging.WARNING]
    assert len(warnings) == 1
    assert "pip install cholespy" in warnings[0].getMessage()
    assert 'pip install "scikit-sparse<0.5"' in warnings[0].getMessage()
    assert "libsuitesparse-dev" in warnings[0].getMessage()
    assert available_backends() == ("superlu",)


def test_cholmod_requested_but_missing(fresh_warning):
    with pytest.raises(ImportError, match=r"scikit-sparse<0\.5.*libsuitesparse-dev"):
        factorize_spd(_random_spd(n=20), backend="cholmod")
    with pytest.raises(ImportError, match="cholespy is missing.*pip install cholespy"):
        factorize_spd(_random_spd(n=20), backend="cholespy")
    with pytest.raises(ImportError, match="cvxopt is missing.*pip install cvxopt"):
        factorize_spd(_random_spd(n=20), backend="cvxopt")
