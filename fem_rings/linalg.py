"""Sparse factorisations of symmetric positive definite matrices for the ring models.

The stiffness matrices of the 3-D ring models (about 10⁵ degrees of freedom, quadratic
tetrahedra and hexahedra) are solved many times: static condensation, Craig–Bampton constraint
modes and the shift-invert Lanczos iteration of the modal analysis. CHOLMOD's supernodal
Cholesky factorisation (SuiteSparse) is several times faster and leaner than SciPy's SuperLU for
these matrices, and ``scipy.sparse.linalg.eigsh(..., sigma=...)`` uses SuperLU internally. This
module factorises once with the best available backend and exposes the factor as a solver and
as the ``OPinv`` operator of ``eigsh``.

Backends
--------
``"cholmod"``
    ``sksparse.cholmod.cholesky`` (the ``fast`` extra), supernodal LLᵀ (which stops on a matrix
    that is not positive definite; the simplicial LDLᵀ does not) with CHOLMOD's default ordering
    (AMD, and METIS when AMD fills in too much). Install with
    ``apt-get install libsuitesparse-dev libopenblas0-pthread`` and
    ``pip install "scikit-sparse<0.5"`` (the 0.5 series needs SuiteSparse ≥ 7, which Debian 12
    does not ship). Without OpenBLAS, CHOLMOD's supernodal factorisation runs on the reference
    BLAS and loses most of its speed.
``"cvxopt"``
    ``cvxopt.cholmod`` (optional, ``pip install cvxopt``): a wheel that bundles CHOLMOD with
    OpenBLAS, so no system package is needed, and runs CHOLMOD's supernodal LLᵀ like
    ``"cholmod"`` (it stops on a matrix that is not positive definite). The matrix is copied
    into cvxopt's own sparse type (lower triangle) and each solve into its dense type.
``"cholespy"``
    ``cholespy.CholeskySolverD``, a normal dependency: a wheel that bundles CHOLMOD, so no system
    package is needed. Its CHOLMOD runs the simplicial LLᵀ factorisation (nested-dissection
    ordering), which stops on a matrix that is not positive definite (CHOLMOD also prints a
    warning on stderr then). On the 152k-DOF hex27 ring (``benchmarks/bench_solvers.py``) it
    factorises 5× slower than the supernodal one and 1.7× slower than SuperLU, but needs less
    memory than SuperLU and solves many right-hand sides faster. It reads the lower triangle only.

The factors of the two wheels are checked by one probe solve each (normwise backward error,
:func:`backward_error`); under "auto" a factor that fails it is replaced by SuperLU with a
warning.
``"superlu"``
    ``scipy.sparse.linalg.splu`` in symmetric mode: minimum-degree ordering of A + Aᵀ, diagonal
    pivots (``diag_pivot_thresh=0``), which for a symmetric positive definite matrix amounts to
    a Cholesky factorisation stored as LU. It does not test definiteness: a nonsingular
    indefinite matrix is factorised and solved without error (CHOLMOD refuses it).

``"auto"`` takes the first of cholmod → cvxopt → cholespy → superlu that imports, SuperLU with a
single ``logging`` warning per process. The environment variable ``FLEXBEARING_SPARSE_SOLVER``
(``auto`` or a backend name) replaces ``"auto"``; a backend passed
explicitly wins over it. Every factorisation logs its backend, size and time at INFO level.
"""

from __future__ import annotations

import logging
import os
import time
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from foundation.progress import phase

__all__ = [
    "SparseFactor",
    "available_backends",
    "backward_error",
    "factorize_spd",
    "shift_invert_operator",
]

log = logging.getLogger(__name__)

CHOLMOD = "cholmod"
CVXOPT = "cvxopt"
CHOLESPY = "cholespy"
SUPERLU = "superlu"
#: all backends, in the order in which "auto" tries them
BACKENDS = (CHOLMOD, CVXOPT, CHOLESPY, SUPERLU)
#: environment variable that replaces backend="auto"
BACKEND_ENV = "FLEXBEARING_SPARSE_SOLVER"

INSTALL_HINT = (
    'install scikit-sparse for CHOLMOD: pip install "scikit-sparse<0.5" '
    "(needs the system packages libsuitesparse-dev and libopenblas0-pthread: "
    "apt-get install libsuitesparse-dev libopenblas0-pthread)"
)
CHOLESPY_HINT = "install cholespy (a dependency of flexbearing, a wheel that bundles CHOLMOD): pip install cholespy"
CVXOPT_HINT = "install cvxopt (a wheel that bundles CHOLMOD and OpenBLAS): pip install cvxopt"
NOT_PD_HINT = "is the model free of supports? use a negative shift"

#: relative tolerance of the symmetry check, max|A − Aᵀ| ≤ tol · max|A|
SYMMETRY_RTOL = 1e-10
#: largest normwise backward error accepted from the probe solve of a cvxopt or cholespy factor; a
#: Cholesky solve is backward stable, a small multiple of ε ≈ 1.1e-16 (Higham 2002, Thm 10.4)
PROBE_MAX_BACKWARD_ERROR = 1e-8

_fallback_warned = False


@dataclass(frozen=True)
class SparseFactor:
    """Factorisation of a symmetric positive definite sparse matrix A.

    Parameters
    ----------
    n : int
        Order of A.
    backend : {"cholmod", "cvxopt", "cholespy", "superlu"}
        Library that holds the factor.
    _solve : callable
        Backend solve for real right-hand sides of shape (n,) or (n, k).
    """

    n: int
    backend: str
    _solve: Callable[[np.ndarray], np.ndarray] = field(repr=False, compare=False)

    def solve(self, b: Any) -> np.ndarray:
        """Solve A x = b.

        Parameters
        ----------
        b : array_like, shape (n,) or (n, k)
            Right-hand side(s); complex values are solved as real and imaginary parts.

        Returns
        -------
        numpy.ndarray
            x, same shape as ``b``.

        Raises
        ------
        ValueError
            If ``b`` does not have n rows or has more than two dimensions.
        """
        b = np.asarray(b)
        if b.ndim not in (1, 2) or b.shape[0] != self.n:
            raise ValueError(f"b must have shape ({self.n},) or ({self.n}, k), got {b.shape}")
        if np.iscomplexobj(b):
            return self._solve_real(b.real) + 1j * self._solve_real(b.imag)
        return self._solve_real(b)

    def _solve_real(self, b: np.ndarray) -> np.ndarray:
        """Solve for a real right-hand side, returned with the shape of ``b``."""
        if b.size == 0:
            return np.zeros(b.shape)
        x = self._solve(np.asarray(b, dtype=np.float64))
        return np.asarray(x).reshape(b.shape)


def _import_cholmod():
    """Return ``sksparse.cholmod``, or ``None`` when scikit-sparse is not importable."""
    try:
        from sksparse import cholmod
    except ImportError:
        return None
    return cholmod


def _import_cholespy():
    """Return the ``cholespy`` module, or ``None`` when it is not importable."""
    try:
        import cholespy
    except ImportError:
        return None
    return cholespy


def _import_cvxopt():
    """Return ``(cvxopt, cvxopt.cholmod)``, or ``None`` when cvxopt is not importable."""
    try:
        import cvxopt
        from cvxopt import cholmod
    except ImportError:
        return None
    return cvxopt, cholmod


def _importable(backend: str) -> bool:
    """True when the library of ``backend`` imports (SuperLU always does)."""
    importer = {CHOLMOD: _import_cholmod, CVXOPT: _import_cvxopt, CHOLESPY: _import_cholespy}.get(backend)
    return importer is None or importer() is not None


def available_backends() -> tuple[str, ...]:
    """Backends that can factorise in this process, in the order "auto" tries them.

    Returns
    -------
    tuple of str
        A subsequence of ``("cholmod", "cvxopt", "cholespy", "superlu")``; "superlu" is always there.
    """
    return tuple(b for b in BACKENDS if _importable(b))


def _warn_fallback_once() -> None:
    """Log, once per process, that SuperLU stands in for CHOLMOD."""
    global _fallback_warned
    if _fallback_warned:
        return
    _fallback_warned = True
    log.warning(
        "no CHOLMOD (scikit-sparse, cvxopt or cholespy) is available: sparse factorisations use "
        "SciPy's SuperLU, which needs more memory on 3-D ring models and is several times slower "
        "than a supernodal CHOLMOD; %s; or %s",
        CHOLESPY_HINT,
        INSTALL_HINT,
    )


def _requested_backend(backend: str) -> str:
    """Validate ``backend`` and replace "auto" by ``$FLEXBEARING_SPARSE_SOLVER`` when that is set.

    Raises
    ------
    ValueError
        For an unknown backend name, in the argument or in the environment variable.
    """
    if backend not in ("auto", *BACKENDS):
        raise ValueError(f"backend must be 'auto', {', '.join(repr(b) for b in BACKENDS)}, got {backend!r}")
    if backend != "auto":
        return backend
    value = os.environ.get(BACKEND_ENV, "").strip().lower()
    if value in ("", "auto"):
        return "auto"
    if value not in BACKENDS:
        raise ValueError(f"{BACKEND_ENV} must be one of auto, {', '.join(BACKENDS)}; got {value!r}")
    return value


def _resolve_backend(requested: str) -> str:
    """Map a requested backend ("auto" or a name) to one that can run here.

    Raises
    ------
    ImportError
        If "cholmod", "cvxopt" or "cholespy" is asked for and its library does not import.
    """
    if requested == "auto":
        chosen = next(b for b in BACKENDS if _importable(b))
        if chosen == SUPERLU:
            _warn_fallback_once()
        return chosen
    if not _importable(requested):
        library, hint = {CHOLMOD: ("scikit-sparse", INSTALL_HINT), CVXOPT: ("cvxopt", CVXOPT_HINT),
                         CHOLESPY: ("cholespy", CHOLESPY_HINT)}[requested]
        raise ImportError(f"backend {requested!r} requested but {library} is missing: {hint}")
    return requested


def _as_symmetric_csc(A: Any) -> sp.csc_matrix:
    """Return A as a float64 CSC matrix after checking that it is square and symmetric.

    Raises
    ------
    ValueError
        If A is not square or max|A − Aᵀ| exceeds ``SYMMETRY_RTOL`` · max|A|.
    """
    A = sp.csc_matrix(A, dtype=np.float64)
    if A.shape[0] != A.shape[1]:
        raise ValueError(f"matrix must be square, got shape {A.shape}")
    scale = np.abs(A.data).max(initial=0.0)
    asym = np.abs((A - A.T).data).max(initial=0.0)
    if asym > SYMMETRY_RTOL * scale:
        raise ValueError(f"matrix is not symmetric: max|A - A.T| = {asym:.3g}, max|A| = {scale:.3g}")
    A.sort_indices()
    return A


def backward_error(A: sp.spmatrix, x: np.ndarray, b: np.ndarray) -> float:
    """Normwise backward error of an approximate solution of A x = b, in the ∞-norm.

    η = ‖b − A x‖ / (‖A‖ ‖x‖ + ‖b‖), the smallest relative perturbation of A and b for which x
    is an exact solution (Rigal & Gaches 1967; N. J. Higham, *Accuracy and Stability of
    Numerical Algorithms*, 2nd ed., SIAM 2002, Thm 7.1).

    Parameters
    ----------
    A : sparse matrix, shape (n, n)
    x, b : (n,) float64

    Returns
    -------
    float
        η (0 for b = 0 and x = 0).
    """
    norm_A = float(np.asarray(abs(A).sum(axis=1)).max(initial=0.0))
    scale = norm_A * np.abs(x).max(initial=0.0) + np.abs(b).max(initial=0.0)
    residual = np.abs(b - A @ x).max(initial=0.0)
    return float(residual / scale) if scale > 0 else 0.0


def _factor_cholmod(A: sp.csc_matrix) -> SparseFactor:
    """Cholesky factorisation with CHOLMOD; not positive definite becomes LinAlgError."""
    cholmod = _import_cholmod()
    try:
        # supernodal LLᵀ always: CHOLMOD's simplicial mode (chosen by "auto" for small or very
        # sparse factors) computes LDLᵀ and accepts indefinite matrices without an error
        factor = cholmod.cholesky(A, mode="supernodal")
    except cholmod.CholmodNotPositiveDefiniteError as err:
        column = getattr(err, "column", None)
        where = f" (CHOLMOD: not positive at column {column})" if column is not None else ""
        raise np.linalg.LinAlgError(f"matrix is not positive definite{where}; {NOT_PD_HINT}") from err
    return SparseFactor(n=A.shape[0], backend=CHOLMOD, _solve=factor.solve_A)


class _ProbeFailed(RuntimeError):
    """A factor whose probe solve has a backward error above the bound (or that cannot be made)."""


def _probed(A: sp.csc_matrix, factor: SparseFactor) -> SparseFactor:
    """Return ``factor`` after one probe solve with a seeded random solution; else _ProbeFailed."""
    b = A @ np.random.default_rng(0).standard_normal(A.shape[0])
    eta = backward_error(A, factor.solve(b), b)
    if not eta <= PROBE_MAX_BACKWARD_ERROR:   # also catches NaN
        raise _ProbeFailed(f"probe solve has backward error {eta:.3g} > {PROBE_MAX_BACKWARD_ERROR:g}")
    log.debug("%s probe solve: backward error %.3g", factor.backend, eta)
    return factor


def _factor_cvxopt(A: sp.csc_matrix) -> SparseFactor:
    """Supernodal Cholesky with cvxopt's CHOLMOD, checked by one probe solve.

    Raises
    ------
    numpy.linalg.LinAlgError
        If CHOLMOD finds A not positive definite.
    _ProbeFailed
        If the probe solve's backward error exceeds ``PROBE_MAX_BACKWARD_ERROR``.
    """
    cvxopt, cholmod = _import_cvxopt()
    n = A.shape[0]
    lower = sp.tril(A, format="coo")
    S = cvxopt.spmatrix(cvxopt.matrix(lower.data), cvxopt.matrix(lower.row.astype(np.int64)),
                        cvxopt.matrix(lower.col.astype(np.int64)), (n, n))
    del lower
    cholmod.options["supernodal"] = 2   # supernodal always (cvxopt's default)
    try:
        F = cholmod.symbolic(S, uplo="L")
        cholmod.numeric(S, F)
    except ArithmeticError as err:
        raise np.linalg.LinAlgError(f"matrix is not positive definite (cvxopt: {err}); {NOT_PD_HINT}") from err
    del S

    def solve(b: np.ndarray) -> np.ndarray:
        B = cvxopt.matrix(np.asfortranarray(b, dtype=np.float64))   # a copy, overwritten by x
        cholmod.solve(F, B)
        return np.array(B)

    return _probed(A, SparseFactor(n=n, backend=CVXOPT, _solve=solve))


def _factor_cholespy(A: sp.csc_matrix) -> SparseFactor:
    """Cholesky factorisation with cholespy's CHOLMOD, checked by one probe solve.

    Raises
    ------
    numpy.linalg.LinAlgError
        If CHOLMOD finds A not positive definite.
    _ProbeFailed
        If the probe solve's backward error exceeds ``PROBE_MAX_BACKWARD_ERROR``, or A has more
        nonzeros than cholespy's 32-bit indices can address.
    """
    cholespy = _import_cholespy()
    n = A.shape[0]
    # CHOLMOD reads the lower triangle only (stype −1); passed as CSR so that cholespy converts
    # it into arrays of its own (given CSC, it sorts and reallocates the caller's arrays in place)
    lower = sp.tril(A, format="csr")
    if lower.nnz > np.iinfo(np.int32).max:
        raise _ProbeFailed(f"{lower.nnz} nonzeros in the lower triangle exceed cholespy's 32-bit indices")
    try:
        solver = cholespy.CholeskySolverD(
            n,
            lower.indptr.astype(np.int32, copy=False),
            lower.indices.astype(np.int32, copy=False),
            np.ascontiguousarray(lower.data),
            cholespy.MatrixType.CSR,
        )
    except ValueError as err:
        if "positive definite" not in str(err):
            raise
        raise np.linalg.LinAlgError(f"matrix is not positive definite (cholespy: {err}); {NOT_PD_HINT}") from err
    del lower

    def solve(b: np.ndarray) -> np.ndarray:
        b = np.ascontiguousarray(b, dtype=np.float64)   # cholespy takes C-ordered float64 only
        x = np.empty_like(b)
        solver.solve(b, x)
        return x

    return _probed(A, SparseFactor(n=n, backend=CHOLESPY, _solve=solve))


def _factor_superlu(A: sp.csc_matrix) -> SparseFactor:
    """Symmetric-mode SuperLU factorisation; a singular matrix becomes LinAlgError."""
    # measured on P2 elasticity blocks: 70k DOF 158 s (this setting) vs 233 s (same ordering,
    # partial pivoting); 161k DOF slender bar 18 s vs 18 s, COLAMD (SciPy's default) 61 s
    try:
        lu = spla.splu(
            A,
            permc_spec="MMD_AT_PLUS_A",
            diag_pivot_thresh=0.0,
            options={"SymmetricMode": True},
        )
    except RuntimeError as err:
        raise np.linalg.LinAlgError(f"matrix is singular (SuperLU: {err}); {NOT_PD_HINT}") from err
    return SparseFactor(n=A.shape[0], backend=SUPERLU, _solve=lu.solve)


def _factor_with(chosen: str, A: sp.csc_matrix, requested: str) -> SparseFactor:
    """Factorise with the chosen backend; a failed probe under "auto" falls back to SuperLU."""
    if chosen == CHOLMOD:
        return _factor_cholmod(A)
    if chosen == SUPERLU:
        return _factor_superlu(A)
    try:
        return _factor_cvxopt(A) if chosen == CVXOPT else _factor_cholespy(A)
    except _ProbeFailed as err:
        if requested != "auto":
            raise np.linalg.LinAlgError(f"{chosen} factor rejected: {err}") from err
        log.warning("%s factor rejected (%s); this matrix is factorised with SciPy's SuperLU instead", chosen, err)
        return _factor_superlu(A)


def factorize_spd(A: Any, backend: str = "auto") -> SparseFactor:
    """Factorise a symmetric positive definite sparse matrix once for repeated solves.

    Parameters
    ----------
    A : sparse matrix or array, shape (n, n)
        Symmetric positive definite matrix (converted to float64 CSC).
    backend : {"auto", "cholmod", "cvxopt", "cholespy", "superlu"}
        "auto" takes ``$FLEXBEARING_SPARSE_SOLVER`` when set, else the first of cholmod →
        cvxopt → cholespy → superlu that imports (SuperLU with a one-time warning naming the packages
        to install).

    Returns
    -------
    SparseFactor
        Factor with ``solve``, ``backend`` and ``n``.

    Raises
    ------
    ImportError
        If ``backend`` names a library that is not installed.
    numpy.linalg.LinAlgError
        If CHOLMOD (any of the three backends) finds A not positive definite, SuperLU finds it
        singular, or an explicitly requested cvxopt or cholespy factor fails its probe solve.
    ValueError
        For an unknown backend (argument or environment variable) or a non-square or
        non-symmetric A.
    """
    requested = _requested_backend(backend)
    chosen = _resolve_backend(requested)
    A = _as_symmetric_csc(A)
    t0 = time.perf_counter()
    with phase(f"factorising ({A.shape[0]} DOF, {A.nnz} nonzeros, {chosen})") as shown:
        factor = _factor_with(chosen, A, requested)
        if factor.backend != chosen:
            shown.note(f"done by {factor.backend}")
    log.info("sparse factorisation (%s): n = %d, %d nonzeros, %.2f s",
             factor.backend, A.shape[0], A.nnz, time.perf_counter() - t0)
    return factor


def shift_invert_operator(
    K: Any, M: Any, sigma: float, backend: str = "auto"
) -> tuple[spla.LinearOperator, SparseFactor]:
    """Operator (K − σM)⁻¹ for the shift-invert mode of ``scipy.sparse.linalg.eigsh``.

    Use as ``eigsh(K, k, M=M, sigma=sigma, OPinv=op, mode="normal")``; ``eigsh`` then
    factorises nothing itself. K − σM is positive definite when σ lies below the lowest
    eigenvalue, e.g. any σ < 0 for a supported model and a negative σ for a free–free model,
    whose rigid-body modes have eigenvalue 0.

    Parameters
    ----------
    K, M : sparse matrix, shape (n, n)
        Symmetric stiffness (positive semi-definite) and mass (positive definite) matrices.
    sigma : float
        Shift σ in the units of the eigenvalue (ω² in rad²/s² for K, M in SI units).
    backend : {"auto", "cholmod", "cvxopt", "cholespy", "superlu"}
        As for :func:`factorize_spd`.

    Returns
    -------
    op : scipy.sparse.linalg.LinearOperator
        x ↦ (K − σM)⁻¹ x, for vectors and (n, k) blocks.
    factor : SparseFactor
        The single factorisation behind ``op``.

    Raises
    ------
    ValueError
        If K and M differ in shape or σ is not finite.
    numpy.linalg.LinAlgError
        If K − σM is not positive definite (σ at or above the lowest eigenvalue).
    """
    if K.shape != M.shape:
        raise ValueError(f"K and M must have the same shape, got {K.shape} and {M.shape}")
    if not np.isfinite(sigma):
        raise ValueError(f"sigma must be finite, got {sigma!r}")
    try:
        factor = factorize_spd(sp.csc_matrix(K) - sigma * sp.csc_matrix(M), backend=backend)
    except np.linalg.LinAlgError as err:
        raise np.linalg.LinAlgError(
            f"K - sigma*M with sigma = {sigma:g} cannot be factorised: {err}; "
            "sigma must lie below the lowest eigenvalue"
        ) from err
    op = spla.LinearOperator(
        shape=K.shape, matvec=factor.solve, matmat=factor.solve, dtype=np.float64
    )
    return op, factor
