"""Sparse factorisations of symmetric positive definite matrices for the ring models.

The stiffness matrices of the 3-D ring models (about 10⁵ degrees of freedom, quadratic
tetrahedra) are solved many times: static condensation, Craig–Bampton constraint modes and the
shift-invert Lanczos iteration of the modal analysis. A sparse Cholesky factorisation with
CHOLMOD (SuiteSparse, through scikit-sparse) is several times faster and leaner than SciPy's
SuperLU for these matrices, and ``scipy.sparse.linalg.eigsh(..., sigma=...)`` uses SuperLU
internally. This module factorises once with the best available backend and exposes the
factor as a solver and as the ``OPinv`` operator of ``eigsh``.

Backends
--------
``"cholmod"``
    ``sksparse.cholmod.cholesky``, supernodal LLᵀ (which stops on a matrix that is not
    positive definite; the simplicial LDLᵀ does not) with CHOLMOD's default ordering (AMD, and
    METIS when AMD fills in too much). Install with
    ``apt-get install libsuitesparse-dev libopenblas0-pthread`` and
    ``pip install "scikit-sparse<0.5"`` (the 0.5 series needs SuiteSparse ≥ 7, which Debian 12
    does not ship). Without OpenBLAS, CHOLMOD's supernodal factorisation runs on the reference
    BLAS and loses most of its speed.
``"superlu"``
    ``scipy.sparse.linalg.splu`` in symmetric mode: minimum-degree ordering of A + Aᵀ, diagonal
    pivots (``diag_pivot_thresh=0``), which for a symmetric positive definite matrix amounts to
    a Cholesky factorisation stored as LU. It does not test definiteness: a nonsingular
    indefinite matrix is factorised and solved without error (CHOLMOD refuses it).

``"auto"`` uses CHOLMOD when scikit-sparse imports and falls back to SuperLU with a single
``logging`` warning per process.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = [
    "SparseFactor",
    "available_backends",
    "factorize_spd",
    "shift_invert_operator",
]

log = logging.getLogger(__name__)

CHOLMOD = "cholmod"
SUPERLU = "superlu"
BACKENDS = (CHOLMOD, SUPERLU)

INSTALL_HINT = (
    'install scikit-sparse for CHOLMOD: pip install "scikit-sparse<0.5" '
    "(needs the system packages libsuitesparse-dev and libopenblas0-pthread: "
    "apt-get install libsuitesparse-dev libopenblas0-pthread)"
)
NOT_PD_HINT = "is the model free of supports? use a negative shift"

#: relative tolerance of the symmetry check, max|A − Aᵀ| ≤ tol · max|A|
SYMMETRY_RTOL = 1e-10

_fallback_warned = False


@dataclass(frozen=True)
class SparseFactor:
    """Factorisation of a symmetric positive definite sparse matrix A.

    Parameters
    ----------
    n : int
        Order of A.
    backend : {"cholmod", "superlu"}
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
        x = self._solve(np.asarray(b, dtype=np.float64))
        return np.asarray(x).reshape(b.shape)


def _import_cholmod():
    """Return ``sksparse.cholmod``, or ``None`` when scikit-sparse is not importable."""
    try:
        from sksparse import cholmod
    except ImportError:
        return None
    return cholmod


def available_backends() -> tuple[str, ...]:
    """Backends that can factorise in this process.

    Returns
    -------
    tuple of str
        ``("cholmod", "superlu")`` when scikit-sparse imports, else ``("superlu",)``.
    """
    if _import_cholmod() is None:
        return (SUPERLU,)
    return BACKENDS


def _warn_fallback_once() -> None:
    """Log, once per process, that SuperLU stands in for CHOLMOD."""
    global _fallback_warned
    if _fallback_warned:
        return
    _fallback_warned = True
    log.warning(
        "scikit-sparse (CHOLMOD) is not available: sparse factorisations use SciPy's SuperLU, "
        "which is several times slower and needs more memory on 3-D ring models; %s",
        INSTALL_HINT,
    )


def _resolve_backend(backend: str) -> str:
    """Map "auto"/"cholmod"/"superlu" to a backend that can run here.

    Raises
    ------
    ValueError
        For an unknown backend name.
    ImportError
        If "cholmod" is asked for and scikit-sparse does not import.
    """
    if backend not in ("auto", *BACKENDS):
        raise ValueError(f"backend must be 'auto', 'cholmod' or 'superlu', got {backend!r}")
    if backend == SUPERLU:
        return SUPERLU
    if _import_cholmod() is not None:
        return CHOLMOD
    if backend == CHOLMOD:
        raise ImportError(f"backend 'cholmod' requested but scikit-sparse is missing: {INSTALL_HINT}")
    _warn_fallback_once()
    return SUPERLU


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


def factorize_spd(A: Any, backend: str = "auto") -> SparseFactor:
    """Factorise a symmetric positive definite sparse matrix once for repeated solves.

    Parameters
    ----------
    A : sparse matrix or array, shape (n, n)
        Symmetric positive definite matrix (converted to float64 CSC).
    backend : {"auto", "cholmod", "superlu"}
        "auto" takes CHOLMOD when scikit-sparse imports, else SuperLU with a one-time
        warning naming the package to install.

    Returns
    -------
    SparseFactor
        Factor with ``solve``, ``backend`` and ``n``.

    Raises
    ------
    ImportError
        If ``backend="cholmod"`` and scikit-sparse is not installed.
    numpy.linalg.LinAlgError
        If CHOLMOD finds A not positive definite, or SuperLU finds it singular.
    ValueError
        For an unknown backend or a non-square or non-symmetric A.
    """
    chosen = _resolve_backend(backend)
    A = _as_symmetric_csc(A)
    if chosen == CHOLMOD:
        return _factor_cholmod(A)
    return _factor_superlu(A)


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
    backend : {"auto", "cholmod", "superlu"}
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
