"""Independent reference: frictionless contact of two elastic bodies on a grid of the half-space.

The contact plane is cut into rectangular cells with uniform pressure each. The approach of the
two surfaces at a cell centre per unit pressure on another cell is Love's closed form for a
uniformly loaded rectangle (Johnson, *Contact Mechanics*, 1985, eq. 3.25), summed over both
bodies: u = 2/(π E') ∫∫ dx'dy' / ρ, with the double antiderivative

    F(X, Y) = X·ln(Y + ρ) + Y·ln(X + ρ),   ρ = sqrt(X² + Y²),   ∂²F/∂X∂Y = 1/ρ.

Contact with a rigid approach δ and an initial gap h(x, y): p ≥ 0, A p ≥ δ − h with equality
where p > 0. That is the minimum of ½ pᵀA p − pᵀ(δ − h) over p ≥ 0 (A symmetric positive
definite), solved here with scipy's L-BFGS-B to a tight gradient tolerance. Plain numpy/scipy;
no library code.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize

__all__ = ["rectangle_influence", "grid_contact"]


def _log_x_plus_rho(X, Y):
    """ln(X + sqrt(X² + Y²)) without cancellation for X < 0 (there X + ρ = Y²/(ρ − X))."""
    rho = np.hypot(X, Y)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(X >= 0.0, np.log(X + rho), np.log(Y * Y) - np.log(rho - X))


def _antiderivative(X, Y):
    with np.errstate(invalid="ignore"):
        a = np.where(X == 0.0, 0.0, X * _log_x_plus_rho(Y, X))
        b = np.where(Y == 0.0, 0.0, Y * _log_x_plus_rho(X, Y))
    return a + b


def rectangle_influence(x, y, x1, x2, y1, y2):
    """∫_{x1}^{x2} ∫_{y1}^{y2} dx'dy' / sqrt((x − x')² + (y − y')²) (broadcasting), m."""
    return (_antiderivative(x - x1, y - y1) - _antiderivative(x - x1, y - y2)
            - _antiderivative(x - x2, y - y1) + _antiderivative(x - x2, y - y2))


def grid_contact(x_edges, y_edges, gap_m, approach_m, E_eff_Pa):
    """Cell pressures (nx, ny) Pa of the contact on the grid with the given cell edges.

    ``gap_m`` (nx, ny) is the initial gap at the cell centres, m; ``approach_m`` the rigid
    approach, m.
    """
    xc = 0.5 * (x_edges[1:] + x_edges[:-1])
    yc = 0.5 * (y_edges[1:] + y_edges[:-1])
    X, Y = np.meshgrid(xc, yc, indexing="ij")
    X1, Y1 = np.meshgrid(x_edges[:-1], y_edges[:-1], indexing="ij")
    X2, Y2 = np.meshgrid(x_edges[1:], y_edges[1:], indexing="ij")
    A = 2.0 / (math.pi * E_eff_Pa) * rectangle_influence(
        X.ravel()[:, None], Y.ravel()[:, None], X1.ravel()[None, :], X2.ravel()[None, :],
        Y1.ravel()[None, :], Y2.ravel()[None, :])
    A = 0.5 * (A + A.T)  # equal cells: symmetric up to rounding
    rhs = approach_m - np.asarray(gap_m, dtype=float).ravel()
    scale = float(np.max(rhs)) / float(np.max(np.diag(A)))  # pressure scale

    def energy(p_scaled):
        p = p_scaled * scale
        Ap = A @ p
        return (0.5 * p @ Ap - p @ rhs) / (scale * np.max(rhs)), (Ap - rhs) / np.max(rhs)

    p0 = np.where(rhs > 0.0, scale, 0.0)
    res = minimize(energy, p0, jac=True, method="L-BFGS-B", bounds=[(0.0, None)] * rhs.size,
                   options={"maxiter": 20000, "maxcor": 30, "ftol": 1e-15, "gtol": 1e-11})
    return (res.x * scale).reshape(X.shape)
