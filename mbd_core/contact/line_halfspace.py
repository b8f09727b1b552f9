"""Slices of a roller–raceway line contact coupled through the elastic half-space (edge stresses).

The ISO/TS 16281 slices (:mod:`mbd_core.contact.line`) carry each its own load from its own
approach: a straight roller then loads evenly up to its ends. On a real roller the material
around a slice sinks with its neighbours' load, and where the roller ends the raceway is pressed
by one side only: the pressure rises at the ends (edge stress). Coupling the slices through the
influence coefficients of the elastic half-space gives that rise, as the Alternative Slicing
Technique of Teutsch & Sauer does (J. Tribol. 126 (2004) 436–442); the formulation below is the
plain half-space one.

Model
-----
The effective length L along x is cut into n slices of width w = L/n, centres x_k. Slice k
carries the load q_k with a Hertz pressure across the rolling direction y,

    p_k(y) = p0_k·sqrt(1 − y²/b_k²),   p0_k = 2 q_k / (π b_k w),

uniform along x over its width, with the plane-strain Hertz half-width of its load per length,
b_k = sqrt(8 (q_k/w) R / (π E')) (Johnson, *Contact Mechanics* (1985), eq. 4.45; R the effective
radius across, E' = 2/((1−ν1²)/E1 + (1−ν2²)/E2)). The two bodies' surfaces approach at (x, y) by

    u(x, y) = 2/(π E') ∫∫ p(x', y') / sqrt((x−x')² + (y−y')²) dx' dy'

(Boussinesq, Johnson eq. 3.20 summed over both bodies). On the centre line y = 0 of slice i,

    u_i = Σ_j A_ij q_j,   A_ij = 4/(π² E' w) · I(|i − j|, b_j / w),
    I(m, β) = ∫_{−1}^{1} sqrt(1 − t²) [asinh((m + ½)/(β|t|)) − asinh((m − ½)/(β|t|))] dt,

the x' integral taken in closed form. Contact: u_i = e_i on loaded slices and q_i = 0 where
u_i ≥ e_i, with e_i = δ − g_i the interference of the rigid surfaces (δ the approach of the
roller's centre section, g_i the gap: profile drop, tilt). A is solved by an active set; b_k
follows q_k by fixed-point iteration (A depends on b only through a logarithm; 14–30 passes to 1e-10).

I(m, β) is integrated with t = sin φ (removing the square root at the strip's border) and
Gauss–Legendre on intervals graded geometrically towards φ = 0, where the self term (m = 0) is
log-singular and the near strips vary on the scale w/b; once per slice count on a grid of ln β,
which a cubic spline then interpolates for every pass of the fixed point (:func:`influence_table`).

Units: SI (m, N, Pa).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.interpolate import CubicSpline

from foundation.validation import check_positive

__all__ = [
    "strip_influence",
    "influence_matrix",
    "influence_table",
    "CoupledSlices",
    "coupled_slice_loads",
    "coupled_slices_under_load",
]

#: Gauss–Legendre points per interval and number of geometrically graded intervals in φ.
_GAUSS_POINTS = 8
_GRADED_INTERVALS = 48


@lru_cache(maxsize=1)
def _phi_rule():
    """Nodes φ in (0, π/2) and weights of ∫_0^{π/2} f(φ) dφ, graded towards φ = 0 (read-only)."""
    x, w = np.polynomial.legendre.leggauss(_GAUSS_POINTS)
    edges = 0.5 * math.pi * np.concatenate(([0.0], 2.0 ** -np.arange(_GRADED_INTERVALS - 1, -1, -1.0)))
    lo, hi = edges[:-1, None], edges[1:, None]
    nodes = (0.5 * (hi - lo) * (x + 1.0) + lo).ravel()
    weights = (0.5 * (hi - lo) * w).ravel()
    nodes.flags.writeable = False
    weights.flags.writeable = False
    return nodes, weights


def strip_influence(m, beta):
    """I(m, β) of the module docstring: the dimensionless centre-line influence of a Hertz strip.

    ``m`` is the distance between the two slices' centres in slice widths (0 for the slice on
    itself), ``beta`` the loaded slice's half-width over the slice width, b/w > 0. Both broadcast.
    """
    phi, weight = _phi_rule()
    m = np.abs(np.asarray(m, dtype=float))[..., None]
    beta = np.asarray(beta, dtype=float)[..., None]
    y = beta * np.sin(phi)  # b|t| / w
    f = np.arcsinh((m + 0.5) / y) - np.arcsinh((m - 0.5) / y)
    # ∫_{−1}^{1} sqrt(1 − t²) F dt = 2 ∫_0^{π/2} cos² φ F(sin φ) dφ (F even in t)
    return 2.0 * np.sum(weight * np.cos(phi) ** 2 * f, axis=-1)


#: range and points of the table of I(m, β) over ln β (cubic spline; :func:`influence_table`)
_TABLE_BETA = (1e-4, 1e4)
_TABLE_POINTS = 321


@lru_cache(maxsize=16)
def influence_table(n_slices: int) -> CubicSpline:
    """I(m, β) for m = 0 … n−1 as a cubic spline in ln β over [1e-4, 1e4] (β clamped to it), so that
    the fixed point rebuilds A by interpolation instead of quadrature (to 1e-7 relative, tests)."""
    log_beta = np.linspace(math.log(_TABLE_BETA[0]), math.log(_TABLE_BETA[1]), _TABLE_POINTS)
    values = np.stack([strip_influence(m, np.exp(log_beta)) for m in range(n_slices)])
    return CubicSpline(log_beta, values, axis=1)


def influence_matrix(n_slices: int, half_width_over_width, E_eff_Pa: float, width_m: float) -> np.ndarray:
    """A (n, n) m/N: the approach on slice i's centre line per newton on slice j.

    ``half_width_over_width`` (n,) is b_j / w of each loaded slice (column j).
    """
    beta = np.clip(np.asarray(half_width_over_width, dtype=float), *_TABLE_BETA)
    table = influence_table(n_slices)(np.log(beta))          # (m, j): I(m, β_j)
    idx = np.arange(n_slices)
    dist = np.abs(idx[:, None] - idx[None, :])
    return 4.0 / (math.pi**2 * E_eff_Pa * width_m) * table[dist, idx[None, :]]


@dataclass(frozen=True)
class CoupledSlices:
    """Loads of the coupled slices of one line contact.

    Attributes
    ----------
    load_N : (n,) slice loads q_k, N.
    half_width_m : (n,) Hertz half-widths b_k across the rolling direction, m (0 where unloaded).
    peak_pressure_Pa : (n,) p0_k = 2 q_k/(π b_k w), Pa.
    iterations : int, fixed-point passes on the half-widths.
    """

    load_N: np.ndarray
    half_width_m: np.ndarray
    peak_pressure_Pa: np.ndarray
    iterations: int

    @property
    def total_load_N(self) -> float:
        return float(np.sum(self.load_N))


def _half_width_m(load_N, width_m, effective_radius_m, E_eff_Pa):
    return np.sqrt(8.0 * np.maximum(load_N, 0.0) / width_m * effective_radius_m / (math.pi * E_eff_Pa))


def _active_set_solve(A: np.ndarray, gap_m: np.ndarray, approach_m: float | None, total_load_N: float | None):
    """q ≥ 0 with (A q)_i = δ − g_i where q_i > 0 and (A q)_i ≥ δ − g_i elsewhere; δ given, or the
    unknown that makes Σ q = ``total_load_N`` (then bordered by that row). Returns (q, δ)."""
    n = gap_m.size
    fixed = total_load_N is None
    active = (approach_m - gap_m > 0.0) if fixed else np.ones(n, dtype=bool)
    q = np.zeros(n)
    delta = approach_m
    for _ in range(4 * n + 10):
        q[:] = 0.0
        idx = np.flatnonzero(active)
        if fixed:
            q[idx] = np.linalg.solve(A[np.ix_(idx, idx)], delta - gap_m[idx]) if idx.size else 0.0
        else:
            m = idx.size
            K = np.zeros((m + 1, m + 1))
            K[:m, :m] = A[np.ix_(idx, idx)]
            K[:m, m] = -1.0
            K[m, :m] = 1.0
            sol = np.linalg.solve(K, np.concatenate((-gap_m[idx], [total_load_N])))
            q[idx], delta = sol[:m], float(sol[m])
        negative = active & (q < 0.0)
        if negative.any():
            active &= ~negative
            continue
        e = delta - gap_m
        penetrating = ~active & (A @ q - e < -1e-12 * np.max(np.abs(e)))
        if not penetrating.any():
            return np.maximum(q, 0.0), delta
        active |= penetrating
    raise RuntimeError("coupled slices: the active set did not settle")


def _coupled(gap_m, length_m, effective_radius_m, E_eff_Pa, approach_m, total_load_N, rtol, max_iter):
    """Fixed point on the half-widths around the active-set solve (module docstring)."""
    n = gap_m.size
    width = length_m / n
    q = np.zeros(n)
    beta = np.full(n, 1.0)  # first pass with b = w everywhere; A depends on b only logarithmically
    for it in range(1, max_iter + 1):
        A = influence_matrix(n, beta, E_eff_Pa, width)
        q_new, delta = _active_set_solve(A, gap_m, approach_m, total_load_N)
        change = np.max(np.abs(q_new - q))
        q = q_new
        beta = np.maximum(_half_width_m(q, width, effective_radius_m, E_eff_Pa) / width, 1e-6)
        if change <= rtol * max(np.max(q), 1e-300):
            break
    else:
        raise RuntimeError(f"coupled slices: half-widths did not settle in {max_iter} passes")
    b = _half_width_m(q, width, effective_radius_m, E_eff_Pa)
    with np.errstate(invalid="ignore", divide="ignore"):
        p0 = np.where(q > 0.0, 2.0 * q / (math.pi * np.where(b > 0, b, 1.0) * width), 0.0)
    return CoupledSlices(q, b, p0, it), delta


def _check_slices(name, values) -> np.ndarray:
    v = np.asarray(values, dtype=float)
    if v.ndim != 1 or v.size < 1 or not np.all(np.isfinite(v)):
        raise ValueError(f"{name} must be a finite 1-D array with one value per slice")
    return v


def coupled_slice_loads(interference_m, length_m: float, effective_radius_m: float, E_eff_Pa: float,
                        *, rtol: float = 1e-10, max_iter: int = 60) -> CoupledSlices:
    """Slice loads of a line contact coupled through the half-space, for given rigid interference.

    Parameters
    ----------
    interference_m : (n,) array
        e_k = δ − g_k at each slice centre, m (positive where the rigid profiles overlap).
    length_m : float
        Effective contact length L, m (slices of width L/n).
    effective_radius_m : float
        R across the rolling direction (1/R = 1/R1 + 1/R2), m.
    E_eff_Pa : float
        E' = 2/((1−ν1²)/E1 + (1−ν2²)/E2), Pa.
    """
    check_positive(length_m=length_m, effective_radius_m=effective_radius_m, E_eff_Pa=E_eff_Pa)
    e = _check_slices("interference_m", interference_m)
    if np.max(e) <= 0.0:
        zero = np.zeros(e.size)
        return CoupledSlices(zero, zero.copy(), zero.copy(), 0)
    return _coupled(-e, length_m, effective_radius_m, E_eff_Pa, 0.0, None, rtol, max_iter)[0]


def coupled_slices_under_load(total_load_N: float, gap_m, length_m: float, effective_radius_m: float,
                              E_eff_Pa: float, *, rtol: float = 1e-10, max_iter: int = 60) -> tuple[CoupledSlices, float]:
    """Coupled slice loads for a given total load, and the approach δ (m) that carries it (e_k = δ − g_k).

    ``gap_m`` (n,) is the gap of each slice centre when the roller just touches (profile drop,
    tilt; its minimum is the first point to touch), m. The approach is an unknown of the same
    fixed point (the load balance borders the active-set system).
    """
    check_positive(total_load_N=total_load_N, length_m=length_m, effective_radius_m=effective_radius_m,
                   E_eff_Pa=E_eff_Pa)
    g = _check_slices("gap_m", gap_m)
    g = g - np.min(g)
    return _coupled(g, length_m, effective_radius_m, E_eff_Pa, None, total_load_N, rtol, max_iter)
