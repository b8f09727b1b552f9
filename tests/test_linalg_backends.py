"""Backend choice of ``fem_rings.linalg``: the CHOLMOD wheels (cvxopt, cholespy), the order
cholmod → cvxopt → cholespy → superlu, the ``FLEXBEARING_SPARSE_SOLVER`` override and the probe
check.

References used below:

* ``scipy.linalg.cho_factor``/``cho_solve`` (LAPACK ``dpotrf``/``dpotrs``, dense Cholesky) and
  ``scipy.sparse.linalg.spsolve`` (SuperLU with partial pivoting): independent direct solves.
  The forward error of a backward-stable solve is bounded by about κ(A)·η (Higham, *Accuracy
  and Stability of Numerical Algorithms*, 2nd ed., SIAM 2002, §7.1), so solutions are compared
  in the 1-norm with the tolerance 100·κ₁(A)·ε, κ₁ estimated by LAPACK ``dpocon``.
* The normwise backward error η = ‖b − Ax‖∞ / (‖A‖∞‖x‖∞ + ‖b‖∞) (Rigal & Gaches 1967; Higham
  Thm 7.1), written out densely in the test.

The project matrix is K + 4π²·100·M (the shift-invert matrix K − σM at σ = −(2π·10 Hz)²) of a
90° sector of the Ø1 m slewing-ring bottom race, 10-node tetrahedra of 0.1 m, 3381 DOF.
"""

from __future__ import annotations

import logging
import math
import sys
import types

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from fem_rings import MeshSpec, build_model, linalg
from fem_rings.linalg import available_backends, backward_error, factorize_spd
from fem_rings.sections import slewing_bottom_race
from foundation.materials import ElasticMaterial

EPS = np.finfo(float).eps
SIGMA = -(2.0 * math.pi * 10.0) ** 2


@pytest.fixture(autouse=True)
def no_env_override(monkeypatch):
    """Each test starts without ``$FLEXBEARING_SPARSE_SOLVER`` and with the fallback warning unsaid."""
    monkeypatch.delenv("FLEXBEARING_SPARSE_SOLVER", raising=False)
    monkeypatch.setattr(linalg, "_fallback_warned", False)


@pytest.fixture(scope="module")
def ring_matrix() -> sp.csc_matrix:
    model = build_model(slewing_bottom_race(1.0), MeshSpec(0.1, "tet10", sector_deg=90.0),
                        ElasticMaterial("steel", 200e9, 0.3, 7850.0), use_cache=False)
    return sp.csc_matrix(model.K - SIGMA * model.M)


def _random_spd(n: int = 300, seed: int = 3) -> sp.csc_matrix:
    """Seeded sparse SPD matrix R Rᵀ + I with about 2 % fill in R."""
    R = sp.random(n, n, density=0.02, random_state=np.random.default_rng(seed), format="csr")
    return sp.csc_matrix(R @ R.T + sp.identity(n))


def _hide(monkeypatch, *modules: str) -> None:
    """Make ``import <module>`` raise ImportError (a ``None`` entry in ``sys.modules``)."""
    for name in modules:
        monkeypatch.setitem(sys.modules, name, None)


def _fake_sksparse(monkeypatch) -> None:
    """Install a stand-in ``sksparse.cholmod`` whose factor solves with SciPy's spsolve."""
    cholmod = types.ModuleType("sksparse.cholmod")

    class CholmodNotPositiveDefiniteError(Exception):
        pass

    def cholesky(A, mode="auto"):
        return types.SimpleNamespace(solve_A=lambda b: spla.spsolve(A, b))

    cholmod.CholmodNotPositiveDefiniteError = CholmodNotPositiveDefiniteError
    cholmod.cholesky = cholesky
    package = types.ModuleType("sksparse")
    package.cholmod = cholmod
    monkeypatch.setitem(sys.modules, "sksparse", package)
    monkeypatch.setitem(sys.modules, "sksparse.cholmod", cholmod)


def _broken_cholespy(monkeypatch) -> None:
    """Install a stand-in ``cholespy`` whose factor returns x = b (a silently wrong solve)."""
    module = types.ModuleType("cholespy")

    class CholeskySolverD:
        def __init__(self, n, ii, jj, x, kind):
            self.n = n

        def solve(self, b, x):
            x[...] = b

    module.CholeskySolverD = CholeskySolverD
    module.MatrixType = types.SimpleNamespace(CSC=0, CSR=1, COO=2)
    monkeypatch.setitem(sys.modules, "cholespy", module)


def _dense_reference(A: sp.spmatrix, b: np.ndarray) -> tuple[np.ndarray, float]:
    """Dense Cholesky solution (LAPACK) and the forward-error tolerance 100·κ₁(A)·ε.

    κ₁ = ‖A‖₁‖A⁻¹‖₁ with ‖A⁻¹‖₁ from LAPACK's estimator ``dpocon`` on the dense factor.
    """
    dense = A.toarray()
    c, lower = scipy.linalg.cho_factor(dense)
    norm_1 = np.abs(dense).sum(axis=0).max()
    rcond, info = scipy.linalg.lapack.dpocon(c, norm_1, uplo="L" if lower else "U")
    assert info == 0
    return scipy.linalg.cho_solve((c, lower), b), 100.0 * EPS / rcond


WHEELS = {"cvxopt": "cvxopt.cholmod", "cholespy": "cholespy"}


# --- the wheels against references ------------------------------------------------------------

@pytest.mark.parametrize("backend", sorted(WHEELS))
def test_wheel_ring_matrix_matches_dense_and_superlu(ring_matrix, backend):
    pytest.importorskip(WHEELS[backend])
    A = ring_matrix
    B = np.random.default_rng(5).standard_normal((A.shape[0], 3))
    X_ref, rtol = _dense_reference(A, B)
    assert rtol < 1e-3  # the comparison below is meaningful
    X = factorize_spd(A, backend=backend).solve(B)
    X_lu = factorize_spd(A, backend="superlu").solve(B)
    for k in range(B.shape[1]):
        scale = np.abs(X_ref[:, k]).sum()
        assert np.abs(X[:, k] - X_ref[:, k]).sum() <= rtol * scale
        assert np.abs(X[:, k] - X_lu[:, k]).sum() <= rtol * scale
    for k in range(B.shape[1]):  # Cholesky is backward stable: η a small multiple of ε
        assert backward_error(A, X[:, k], B[:, k]) <= 100 * EPS


@pytest.mark.parametrize("backend", sorted(WHEELS))
def test_wheel_random_spd_matches_dense(backend):
    pytest.importorskip(WHEELS[backend])
    A = _random_spd()
    b = np.random.default_rng(6).standard_normal(A.shape[0])
    x_ref, rtol = _dense_reference(A, b)
    x = factorize_spd(A, backend=backend).solve(b)
    assert np.abs(x - x_ref).sum() <= rtol * np.abs(x_ref).sum()


@pytest.mark.parametrize("backend", sorted(WHEELS))
def test_wheel_block_solve_equals_column_solves(backend):
    """One (n, k) solve gives the k single-vector solves, whatever the layout and dtype of b."""
    pytest.importorskip(WHEELS[backend])
    A = _random_spd(n=200)
    factor = factorize_spd(A, backend=backend)
    B = np.random.default_rng(7).standard_normal((200, 5))
    X = factor.solve(B)
    assert X.shape == (200, 5)
    columns = np.column_stack([factor.solve(B[:, k]) for k in range(5)])
    np.testing.assert_allclose(X, columns, rtol=1e-13, atol=0)
    X_ref = spla.spsolve(A, B)
    assert np.linalg.norm(X - X_ref) <= 1e-10 * np.linalg.norm(X_ref)
    # layouts that cholespy itself refuses (Fortran order, strided views, float32, complex)
    np.testing.assert_allclose(factor.solve(np.asfortranarray(B)), X, rtol=1e-13, atol=0)
    np.testing.assert_allclose(factor.solve(B[:, ::2]), X[:, ::2], rtol=1e-13, atol=0)
    assert factor.solve(B[:, :1]).shape == (200, 1)
    assert factor.solve(np.zeros((200, 0))).shape == (200, 0)
    b32 = B[:, 0].astype(np.float32)
    np.testing.assert_allclose(factor.solve(b32), spla.spsolve(A, b32.astype(float)), rtol=1e-10)
    Z = factor.solve(B[:, 0] + 1j * B[:, 1])
    np.testing.assert_allclose(Z, X[:, 0] + 1j * X[:, 1], rtol=1e-13, atol=0)


def test_backward_error_formula():
    A = _random_spd(n=60)
    b = np.random.default_rng(8).standard_normal(60)
    x = spla.spsolve(A, b) + 1e-3
    dense = A.toarray()
    expected = np.abs(b - dense @ x).max() / (np.abs(dense).sum(axis=1).max() * np.abs(x).max() + np.abs(b).max())
    assert backward_error(A, x, b) == pytest.approx(expected, rel=1e-12)


# --- order cholmod → cvxopt → cholespy → superlu, by hiding imports ----------------------------

def test_cvxopt_comes_before_cholespy(monkeypatch):
    pytest.importorskip("cvxopt.cholmod")
    _hide(monkeypatch, "sksparse", "sksparse.cholmod")
    assert available_backends()[0] == "cvxopt"
    assert factorize_spd(_random_spd(n=50)).backend == "cvxopt"


def test_cholespy_is_chosen_without_scikit_sparse(monkeypatch, caplog):
    pytest.importorskip("cholespy")
    _hide(monkeypatch, "sksparse", "sksparse.cholmod", "cvxopt", "cvxopt.cholmod")
    assert available_backends() == ("cholespy", "superlu")
    with caplog.at_level(logging.INFO, logger="fem_rings.linalg"):
        factor = factorize_spd(_random_spd(n=50))
    assert factor.backend == "cholespy"
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]
    assert any("(cholespy)" in r.getMessage() for r in caplog.records)  # the backend is logged


def test_scikit_sparse_comes_first(monkeypatch):
    _fake_sksparse(monkeypatch)
    assert available_backends()[0] == "cholmod"
    assert factorize_spd(_random_spd(n=50)).backend == "cholmod"


def test_superlu_last_with_warning(monkeypatch, caplog):
    _hide(monkeypatch, "sksparse", "sksparse.cholmod", "cvxopt", "cvxopt.cholmod", "cholespy")
    assert available_backends() == ("superlu",)
    with caplog.at_level(logging.WARNING, logger="fem_rings.linalg"):
        assert factorize_spd(_random_spd(n=50)).backend == "superlu"
    assert any("pip install cholespy" in r.getMessage() for r in caplog.records)


# --- FLEXBEARING_SPARSE_SOLVER -----------------------------------------------------------------

@pytest.mark.parametrize("name", ["superlu", "cholespy", "SuperLU "])
def test_environment_override(monkeypatch, name):
    pytest.importorskip("cholespy")
    _fake_sksparse(monkeypatch)  # "auto" would take it
    monkeypatch.setenv("FLEXBEARING_SPARSE_SOLVER", name)
    A = _random_spd(n=80)
    factor = factorize_spd(A)
    assert factor.backend == name.strip().lower()
    b = np.ones(80)
    x_ref = spla.spsolve(A, b)
    assert np.linalg.norm(factor.solve(b) - x_ref) <= 1e-10 * np.linalg.norm(x_ref)
    assert factorize_spd(A, backend="cholmod").backend == "cholmod"  # an explicit backend wins


def test_environment_override_errors(monkeypatch):
    monkeypatch.setenv("FLEXBEARING_SPARSE_SOLVER", "pardiso")
    with pytest.raises(ValueError, match="FLEXBEARING_SPARSE_SOLVER must be one of auto, cholmod, cvxopt, cholespy"):
        factorize_spd(_random_spd(n=20))
    _hide(monkeypatch, "cholespy")
    monkeypatch.setenv("FLEXBEARING_SPARSE_SOLVER", "cholespy")
    with pytest.raises(ImportError, match="pip install cholespy"):
        factorize_spd(_random_spd(n=20))


# --- a factor that fails its probe solve ------------------------------------------------------

def test_failed_probe_falls_back_to_superlu(monkeypatch, caplog):
    _hide(monkeypatch, "sksparse", "sksparse.cholmod", "cvxopt", "cvxopt.cholmod")
    _broken_cholespy(monkeypatch)
    A = _random_spd(n=100)
    with caplog.at_level(logging.WARNING, logger="fem_rings.linalg"):
        factor = factorize_spd(A)
    assert factor.backend == "superlu"
    messages = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert len(messages) == 1 and "cholespy factor rejected" in messages[0] and "backward error" in messages[0]
    b = np.random.default_rng(9).standard_normal(100)
    x_ref = spla.spsolve(A, b)
    assert np.linalg.norm(factor.solve(b) - x_ref) <= 1e-10 * np.linalg.norm(x_ref)
    with pytest.raises(np.linalg.LinAlgError, match="cholespy factor rejected.*backward error"):
        factorize_spd(A, backend="cholespy")  # asked for by name: no silent substitute
