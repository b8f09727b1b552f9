"""Globally convergent solution of the rigid-ring equilibrium: minimise the potential energy.

The equilibrium of the moving ring is the minimum of its potential

    Π(q) = Σ_i E_i(q) − f·q,    E_i = K_i·δ_i^(n+1)/(n+1) for δ_i > 0, else 0,

whose gradient is −(reaction + f) = −R and whose Hessian is −J, J the Jacobian of the reaction.
Each E_i is a convex non-decreasing function of an approach that is convex in q (|s_i| − A of a
ball, an affine approach of a roller slice), so Π is convex: Newton steps regularised where
elements have lost contact (Levenberg–Marquardt, H + μ·D positive definite) are descent
directions of Π, and a backtracking line search with sufficient decrease of Π converges from any
start to the equilibrium whenever it exists (Nocedal & Wright, *Numerical Optimization*, 2nd ed.,
2006, Thm. 3.2 and §10.3). A residual norm as merit function has no such property: where every
element is out of contact R = −f is constant and its norm has no descent direction.

The start closes the clearances: along the linear-spring estimate y_lin (a descent direction of Π
at q = 0) the 1-D minimum of Π(t·y_lin) is the root of the increasing dΠ/dt = −R(t·y_lin)·y_lin,
bracketed by doubling t and found by Brent's method.

Unknowns and residuals are scaled (moments and rotations by the largest pitch radius) by the
caller; ``evaluate(y, jacobian)`` returns an :class:`Evaluation` of the scaled problem.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.linalg import LinAlgError, cho_factor, cho_solve
from scipy.optimize import brentq

__all__ = ["Evaluation", "safe_norm", "ray_start", "minimise_potential"]

log = logging.getLogger(__name__)

#: Sufficient-decrease (Armijo) constant of the line search.
ARMIJO = 1e-4
#: Largest Levenberg–Marquardt factor before the solve gives up.
MU_MAX = 1e12


@dataclass(frozen=True)
class Evaluation:
    """The scaled problem at one point.

    Attributes
    ----------
    R : (m,) scaled residual (reaction + load), −∇Π
    J : (m, m) dR/dy, or None
    energy : float
        Π, J (unscaled; its gradient in the scaled unknowns is −R).
    tolerance : float
        |R| below which the point is an equilibrium (relative tolerance times the force scale
        plus the rounding level of the element approaches).
    """

    R: np.ndarray
    J: np.ndarray | None
    energy: float
    tolerance: float


def safe_norm(v: np.ndarray) -> float:
    """Euclidean norm without overflow or underflow of the squares (inf or nan pass through)."""
    v = np.asarray(v, dtype=float)
    if v.size == 0:
        return 0.0
    m = float(np.max(np.abs(v)))
    if m == 0.0 or not math.isfinite(m):
        return m
    return m * math.sqrt(float(np.sum((v / m) ** 2)))


def ray_start(evaluate: Callable[[np.ndarray, bool], Evaluation], direction: np.ndarray, free: np.ndarray,
              max_doublings: int = 200) -> np.ndarray:
    """A start on the ray t·direction, t ≥ 0, at or past the minimum of Π along it.

    dΠ/dt = −R(t·d)·d is non-decreasing (Π convex). If it is ≥ 0 at t = 1 (the linear estimate is
    past the minimum, the usual case without clearance) the estimate is returned; otherwise (a
    clearance still open there) the root is bracketed by doubling t and found by Brent's method to
    1e-3 relative, enough for a start. 0 if the direction does not descend.
    """
    d = np.where(np.isin(np.arange(direction.size), free), direction, 0.0)

    def slope(t: float) -> float:
        return -float(evaluate(t * d, False).R[free] @ d[free])

    if not slope(0.0) < 0.0:
        return np.zeros_like(d)
    if slope(1.0) >= 0.0:
        return d  # the estimate itself is past the minimum on the ray: Newton takes it from there
    t_lo, t_hi = 1.0, 2.0
    for _ in range(max_doublings):
        s = slope(t_hi)
        if not math.isfinite(s):
            return t_lo * d
        if s >= 0.0:
            break
        t_lo, t_hi = t_hi, 2.0 * t_hi
    else:
        return t_lo * d  # the rows give nothing along this ray: let the minimisation look elsewhere
    t = brentq(slope, t_lo, t_hi, xtol=1e-300, rtol=1e-3)
    return t * d


def _regularised_step(H: np.ndarray, g: np.ndarray, D: np.ndarray, mu: float) -> tuple[np.ndarray, float]:
    """p = (H + μ·diag(D))⁻¹ g, μ raised until the matrix is positive definite and well conditioned."""
    while True:
        A = H + mu * np.diag(D)
        try:
            c = cho_factor(A)
            p = cho_solve(c, g)
            # a Cholesky of a nearly singular matrix succeeds with a meaningless step
            if np.all(np.isfinite(p)) and np.min(np.abs(np.diag(c[0]))) ** 2 > 1e-14 * np.max(np.abs(np.diag(A))):
                return p, mu
        except (LinAlgError, ValueError):
            pass
        mu = max(10.0 * mu, 1e-10)
        if mu > MU_MAX:
            return np.zeros_like(g), mu


def _line_search(evaluate, y, p, free, ev0: Evaluation, norm0: float):
    """Backtracking on Π with sufficient decrease; a decrease of |R| is also accepted (Π differences
    drown in rounding near the solution). Returns (step length, evaluation) or (0, None)."""
    slope = float(ev0.R[free] @ p)  # −dΠ/dλ at λ = 0, > 0 for a descent direction
    lam = 1.0
    while lam > 1e-14:
        y_try = y.copy()
        y_try[free] += lam * p
        ev = evaluate(y_try, True)
        if math.isfinite(ev.energy) and np.all(np.isfinite(ev.R)):
            if ev.energy <= ev0.energy - ARMIJO * lam * slope:
                return lam, ev, y_try
            if safe_norm(ev.R[free]) < (1.0 - ARMIJO * lam) * norm0:
                return lam, ev, y_try
            # minimum of the quadratic through Π(0), Π'(0) and Π(λ), kept within [0.1λ, 0.5λ]
            excess = ev.energy - ev0.energy + slope * lam
            shrink = 0.5 if excess <= 0.0 else min(0.5, max(0.1, 0.5 * slope * lam / excess))
        else:
            shrink = 0.1
        lam *= shrink
    return 0.0, None, y


def minimise_potential(evaluate: Callable[[np.ndarray, bool], Evaluation], y: np.ndarray, free: np.ndarray,
                       max_iterations: int, regularisation: np.ndarray):
    """Newton–Levenberg–Marquardt minimisation of Π over the ``free`` unknowns (module docstring).

    Parameters
    ----------
    evaluate : callable (y, jacobian) -> Evaluation
    y : (m,) scaled start
    free : (k,) int indices of the unknowns solved for; the others are held
    max_iterations : int
    regularisation : (k,) positive diagonal D of the Levenberg–Marquardt term μ·D (a stiffness
        scale of each free unknown)

    Returns
    -------
    y, Evaluation at y, |R_free|, iterations — converged when |R_free| ≤ Evaluation.tolerance.
    """
    y = np.array(y, dtype=float)
    ev = evaluate(y, True)
    mu, it = 0.0, 0
    while it < max_iterations:
        norm = safe_norm(ev.R[free])
        if not math.isfinite(norm) or not math.isfinite(ev.energy) or norm <= ev.tolerance:
            break
        it += 1
        H = -ev.J[np.ix_(free, free)]
        p, mu = _regularised_step(0.5 * (H + H.T), ev.R[free], regularisation, mu)
        if mu > MU_MAX:
            break
        lam, ev_new, y_new = _line_search(evaluate, y, p, free, ev, norm)
        if ev_new is None:
            mu = max(100.0 * mu, 1e-6)  # no descent along this step: lean towards steepest descent
            if mu > MU_MAX:
                break
            continue
        y, ev = y_new, ev_new
        mu = 0.0 if lam == 1.0 and mu < 1e-9 else (0.1 * mu if lam == 1.0 else max(10.0 * mu, 1e-10))
        log.debug("iteration %d: |residual| = %.3e (step %.3g, mu %.1e)", it, safe_norm(ev.R[free]), lam, mu)
    return y, ev, safe_norm(ev.R[free]), it
