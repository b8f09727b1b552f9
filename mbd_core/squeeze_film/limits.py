"""The short- and long-damper limits of the squeeze film, for any journal velocity.

Both limits make Reynolds' equation (:mod:`.reynolds_grid`) one-dimensional, so the force is one
integral over θ (Vance, Rotordynamics of Turbomachinery, 1988, §6; San Andrés, Modern Lubrication
Theory, ch. 8). With ∂h/∂t = −(ė cos θ + e φ̇ sin θ) and h = c(1 − ε cos θ):

- **Short damper** (L/D → 0, circumferential flow neglected): ∂/∂z(h³ ∂p/∂z) = 12 μ ∂h/∂t gives
  p = (6 μ/h³)(∂h/∂t)(z² − L²/4), and over the land ∫p dz = −μ L³ (∂h/∂t)/h³.
- **Long damper** (L/D → ∞, axial flow neglected): (1/R²) d/dθ(h³ dp/dθ) = 12 μ ∂h/∂t integrates
  to h³ dp/dθ = 12 μ R² (−ė sin θ + e φ̇ cos θ + C), C from periodicity of p; the additive
  constant of p from Σ h³ p = 0 around the land, which is where the pressure of an open-ended
  land tends far from its ends (the θ-mean of the axial flux vanishes). ∫p dz = L·p.

Cavitation as in the grid solver (``gumbel``: negative pressures dropped). For the centred circular
orbit (ė = 0, e φ̇ = ε c ω) and the π-film these give the classical closed forms
(:func:`short_circular_orbit_force_N`, :func:`long_circular_orbit_force_N`):

    short:  F_r = −μ R L³ ω ε/c² · 2ε/(1 − ε²)²,          F_t = −μ R L³ ω ε/c² · π/(2(1 − ε²)^{3/2})
    long:   F_r = −24 μ R³ L ω ε²/(c² (2 + ε²)(1 − ε²)),   F_t = −12 π μ R³ L ω ε/(c² (2 + ε²)(1 − ε²)^{1/2})

(Vance 1988, Table 6-1; San Andrés, ch. 8, eqs. for the π-film).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import cumulative_trapezoid

from .reynolds_grid import SqueezeFilmDamper

__all__ = ["LIMITS", "limit_force_N", "short_circular_orbit_force_N", "long_circular_orbit_force_N"]

#: the closed-form limits a damper's force can be taken from
LIMITS = ("short", "long")
#: points around the land of the θ integrals (the integrands are smooth; the clipping kink is O(Δθ²))
N_THETA = 2048


def _line_pressure(damper: SqueezeFilmDamper, limit: str, eps: float, vr: float, vt: float, th: np.ndarray):
    """∫ p dz over the land at each θ, Pa·m (module docstring)."""
    c, R, L, mu = damper.clearance_m, damper.radius_m, damper.length_m, damper.viscosity_Pa_s
    h = c * (1.0 - eps * np.cos(th))
    if limit == "short":
        return mu * L**3 * (vr * np.cos(th) + vt * np.sin(th)) / h**3
    g = -vr * np.sin(th) + vt * np.cos(th)
    C = -np.sum(g / h**3) / np.sum(1.0 / h**3)
    dp = 12.0 * mu * R**2 * (g + C) / h**3
    closed = np.append(th, 2.0 * math.pi)
    p = cumulative_trapezoid(np.append(dp, dp[0]), closed, initial=0.0)[:-1]
    p -= np.sum(h**3 * p) / np.sum(h**3)
    return L * p


def limit_force_N(damper: SqueezeFilmDamper, limit: str, eccentricity_ratio: float, radial_velocity_m_s: float,
                  tangential_velocity_m_s: float) -> tuple[float, float]:
    """(F_r, F_t) of the film on the journal in the ``"short"`` or ``"long"`` limit, N (arguments as
    :func:`.reynolds_grid.film_force_N`)."""
    if limit not in LIMITS:
        raise ValueError(f"limit must be one of {', '.join(LIMITS)}, got {limit!r}")
    eps = float(eccentricity_ratio)
    if not 0.0 <= eps < 1.0:
        raise ValueError(f"eccentricity ratio must lie in [0, 1), got {eps!r}")
    th = np.arange(N_THETA) * (2.0 * math.pi / N_THETA)
    line = _line_pressure(damper, limit, eps, radial_velocity_m_s, tangential_velocity_m_s, th)
    if damper.cavitation == "gumbel":
        line = np.maximum(line, 0.0)
    s = -damper.radius_m * 2.0 * math.pi / N_THETA
    return s * float(line @ np.cos(th)), s * float(line @ np.sin(th))


def short_circular_orbit_force_N(damper: SqueezeFilmDamper, eccentricity_ratio: float,
                                 whirl_rad_s: float) -> tuple[float, float]:
    """(F_r, F_t) of a short π-film damper on a centred circular orbit of radius ε c at whirl ω, N."""
    eps, w = float(eccentricity_ratio), float(whirl_rad_s)
    s = damper.viscosity_Pa_s * damper.radius_m * damper.length_m**3 * w * eps / damper.clearance_m**2
    return -s * 2.0 * eps / (1.0 - eps**2) ** 2, -s * math.pi / (2.0 * (1.0 - eps**2) ** 1.5)


def long_circular_orbit_force_N(damper: SqueezeFilmDamper, eccentricity_ratio: float,
                                whirl_rad_s: float) -> tuple[float, float]:
    """(F_r, F_t) of a long π-film damper on a centred circular orbit of radius ε c at whirl ω, N."""
    eps, w = float(eccentricity_ratio), float(whirl_rad_s)
    s = damper.viscosity_Pa_s * damper.radius_m**3 * damper.length_m * w / damper.clearance_m**2
    d = (2.0 + eps**2)
    return -24.0 * s * eps**2 / (d * (1.0 - eps**2)), -12.0 * math.pi * s * eps / (d * math.sqrt(1.0 - eps**2))
