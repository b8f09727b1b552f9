"""Film and rolling loss of a lubricated line contact from its inlet (Ertel–Grubin).

The contact is a Hertz line contact of half-width b (plane strain, E' = 2/((1 − ν1²)/E1 + (1 − ν2²)/E2),
b = √(8·w·R/(π·E')), w the load per unit length); outside it the gap is the Hertz one,

    h(x) = h_c + (b²/2R)·g(ξ),   g(ξ) = ξ·√(ξ² − 1) − ln(ξ + √(ξ² − 1)),   ξ = |x|/b ≥ 1

(the surface displacement of the elliptical pressure, Johnson, Contact Mechanics, §4.3 and §7.2). In the
inlet the oil obeys Reynolds' equation for pure rolling at the mean surface speed u (both surfaces move
at u relative to the contact) with Barus' viscosity η = η0·exp(α·p). With the reduced pressure
q = (1 − exp(−α·p))/α,

    dq/dx = 12·η0·u·(h − h_c)/h³,

and Grubin's condition — the pressure is as large as Hertz's at the edge of the flat zone, so q reaches
1/α there — fixes h_c: 12·η0·u·α·b·(2R/b²)²·I(H) = 1, I(H) = ∫₁^∞ g/(H + g)³ dξ, H = 2R·h_c/b².
(Grubin 1949; the closed form he fitted to the same integral, H_c = 1.95·(G·U)^(8/11)·W^(−1/11), is
checked in the tests.)

The oil that the pressure drives back out of the inlet is where rolling loses energy: the Poiseuille
dissipation per unit length P/l = ∫ h³/(12η)·(dp/dx)² dx = u·∫ (h − h_c)·dp/dx dx over the inlet (the
Couette part of pure rolling dissipates nothing; in the Hertz zone h = h_c and the flow is Couette
only). The rolling resistance is F_R = P/u. The outlet and its cavitation are left out (as in Grubin's
model); the formulas are isothermal.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.integrate import cumulative_trapezoid
from scipy.optimize import brentq

from foundation.validation import check_positive

__all__ = ["InletFilm", "hertz_gap", "grubin_line_contact"]

# the inlet is integrated from ξ = 1 to this many half-widths upstream; beyond it the film integrand
# falls like ξ⁻⁴ (its share below 1e-7) and the loss integrand like 1/g ≈ ξ⁻², whose tail 1/ξ is added
_XI_FAR = 400.0


@dataclass(frozen=True)
class InletFilm:
    """Central film (m), rolling resistance per unit length (N/m), Hertz half-width (m) and the
    dimensionless film H = 2R·h_c/b² of a line contact (module docstring)."""

    central_film_m: float
    rolling_force_per_length_N_m: float
    half_width_m: float
    H: float


def hertz_gap(xi):
    """g(ξ) = ξ·√(ξ² − 1) − ln(ξ + √(ξ² − 1)) for ξ ≥ 1: the Hertz gap outside a line contact in units
    of b²/(2R)."""
    xi = np.asarray(xi, dtype=float)
    root = np.sqrt(np.maximum(xi * xi - 1.0, 0.0))
    return xi * root - np.log(xi + root)


@lru_cache(maxsize=1)
def _grid() -> tuple[np.ndarray, np.ndarray]:
    # ξ − 1 = s² spaced geometrically: g ∝ s³ near the edge, and the integrands stay smooth in s
    s = np.concatenate(([0.0], np.geomspace(1e-5, math.sqrt(_XI_FAR - 1.0), 6000)))
    xi = 1.0 + s * s
    return xi, hertz_gap(xi)


def _inlet_integrals(H: float) -> tuple[float, float]:
    """I(H) = ∫ g/(H + g)³ dξ and J(H) = ∫ g²/((H + g)³·(1 − A(ξ))) dξ with A(ξ) the share of I
    that lies upstream of ξ (so 1 − A = α·q: how far the reduced pressure is from 1/α)."""
    xi, g = _grid()
    f = g / (H + g) ** 3
    # integrate from far upstream towards the contact edge
    upstream = cumulative_trapezoid(f[::-1], xi[::-1] * -1.0, initial=0.0)[::-1]  # ∫_ξ^far f
    total = upstream[0]
    remaining = 1.0 - upstream / total  # 1 − α·q(ξ): 0 at the edge, 1 far upstream
    with np.errstate(divide="ignore", invalid="ignore"):
        j = np.where(remaining > 0.0, g * g / (H + g) ** 3 / remaining, 0.0)
    return float(total), float(np.trapezoid(j, xi) + 1.0 / xi[-1])


def grubin_line_contact(load_per_length_N_m: float, mean_speed_m_s: float, Rx_m: float, E_eff_Pa: float,
                        eta0_Pa_s: float, alpha_Pa_inv: float) -> InletFilm:
    """Central film and rolling resistance of a rolling line contact (module docstring); the load
    ``load_per_length_N_m`` (N/m), the mean surface speed u = (u1 + u2)/2 relative to the contact."""
    check_positive("inlet film", load_per_length_N_m=load_per_length_N_m, mean_speed_m_s=mean_speed_m_s, Rx_m=Rx_m,
                   E_eff_Pa=E_eff_Pa, eta0_Pa_s=eta0_Pa_s, alpha_Pa_inv=alpha_Pa_inv)
    b = math.sqrt(8.0 * load_per_length_N_m * Rx_m / (math.pi * E_eff_Pa))
    scale = 12.0 * eta0_Pa_s * mean_speed_m_s * alpha_Pa_inv * b * (2.0 * Rx_m / b**2) ** 2
    # I(H) falls monotonically from ∞ (H → 0) to 0: bracket its root
    lo, hi = 1e-12, 1e6
    H = brentq(lambda x: math.log(_inlet_integrals(x)[0] * scale), lo, hi, xtol=1e-14, rtol=1e-10)
    _, J = _inlet_integrals(H)
    # P/l = u ∫ (h − h_c)·dp/dx dx, dp/dx = (dq/dx)/(α·q̄) with α·q̄ = 1 − A: in units of ξ
    force = 12.0 * eta0_Pa_s * mean_speed_m_s * b * (2.0 * Rx_m / b**2) * J
    return InletFilm(H * b**2 / (2.0 * Rx_m), force, b, H)
