"""Case-depth life factor of case-hardened raceways (Harris, Rumbarger & Butterfield, *Wind
Turbine Design Guideline DG03: Yaw and Pitch Rolling Bearing Life*, NREL/TP-500-42362, 2009,
as applied to slewing rings): the core below an effective case depth h must carry the contact
shear stress. The stress is the maximum (Tresca) shear stress on the contact axis at the depth
1.1·h, τ_c = τ_max(1.1 h); the core shear fatigue strength is τ_f = 0.6·τ_y,core with the core
shear yield strength τ_y,core given or estimated as 0.425·UTS (Sague & Rumbarger, ASME paper
77-DE-39, 1977) or 0.5·σ_y (Tresca). The life factor is A_cd = τ_f/τ_c, capped at 1 by default
(a deep enough case cannot raise the life above L10), and the corrected life L = A_cd·L10.
For a line contact (a roller) τ_c is the plane-strain line contact's (McEwen; Johnson, *Contact
Mechanics*, eq. 4.75): :func:`line_case_depth_life_factor`.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from ..contact.subsurface import line_max_shear_profile_Pa, max_shear_profile_Pa, subsurface_shear
from foundation.validation import check_positive

__all__ = [
    "shear_yield_from_uts_Pa",
    "shear_yield_from_tensile_yield_Pa",
    "core_shear_fatigue_strength_Pa",
    "case_depth_life_factor",
    "line_case_depth_life_factor",
    "required_case_depth_m",
    "case_depth_corrected_life_Mrev",
]

#: Case-depth criterion: depth of the shear-stress check over the effective case depth.
CASE_DEPTH_STRESS_DEPTH_FACTOR = 1.1
#: Core shear fatigue strength over core shear yield strength (DG03).
SHEAR_FATIGUE_OVER_SHEAR_YIELD = 0.6


def shear_yield_from_uts_Pa(ultimate_tensile_strength_Pa: float) -> float:
    """Core shear yield strength estimated as 0.425·UTS, Pa (Sague & Rumbarger 1977, via DG03)."""
    check_positive(ultimate_tensile_strength_Pa=ultimate_tensile_strength_Pa)
    return 0.425 * ultimate_tensile_strength_Pa


def shear_yield_from_tensile_yield_Pa(yield_strength_Pa: float) -> float:
    """Core shear yield strength estimated as 0.5·σ_y, Pa (Tresca criterion)."""
    check_positive(yield_strength_Pa=yield_strength_Pa)
    return 0.5 * yield_strength_Pa


def core_shear_fatigue_strength_Pa(
    *,
    core_shear_yield_Pa: float | None = None,
    core_uts_Pa: float | None = None,
    core_yield_Pa: float | None = None,
) -> float:
    """Core shear fatigue strength τ_f = 0.6·τ_y,core, Pa (DG03).

    Give exactly one of:

    core_shear_yield_Pa : float
        Core shear yield strength τ_y,core, Pa.
    core_uts_Pa : float
        Core ultimate tensile strength, Pa; τ_y,core = 0.425·UTS.
    core_yield_Pa : float
        Core tensile yield strength, Pa; τ_y,core = 0.5·σ_y.
    """
    given = {
        k: v
        for k, v in (
            ("core_shear_yield_Pa", core_shear_yield_Pa),
            ("core_uts_Pa", core_uts_Pa),
            ("core_yield_Pa", core_yield_Pa),
        )
        if v is not None
    }
    if len(given) != 1:
        raise ValueError(
            "give exactly one of core_shear_yield_Pa, core_uts_Pa, core_yield_Pa; "
            f"got {sorted(given) or 'none'}"
        )
    if core_shear_yield_Pa is not None:
        check_positive(core_shear_yield_Pa=core_shear_yield_Pa)
        tau_y = core_shear_yield_Pa
    elif core_uts_Pa is not None:
        tau_y = shear_yield_from_uts_Pa(core_uts_Pa)
    else:
        tau_y = shear_yield_from_tensile_yield_Pa(core_yield_Pa)
    return SHEAR_FATIGUE_OVER_SHEAR_YIELD * tau_y


def _check_hertz(p0_Pa: float, semi_major_m: float, semi_minor_m: float, nu: float) -> None:
    check_positive(p0_Pa=p0_Pa, semi_major_m=semi_major_m, semi_minor_m=semi_minor_m)
    if semi_minor_m > semi_major_m * (1.0 + 1e-12):
        raise ValueError(
            f"semi_minor_m ({semi_minor_m}) must not exceed semi_major_m ({semi_major_m})"
        )
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu must lie in (-1, 0.5), got {nu!r}")


def case_depth_life_factor(
    p0_Pa: float,
    semi_major_m: float,
    semi_minor_m: float,
    case_depth_m,
    nu: float,
    core_shear_fatigue_Pa: float,
    cap: bool = True,
):
    """Case-depth life factor A_cd = τ_f / τ_max(1.1·h) (DG03), capped at 1 by default.

    Parameters
    ----------
    p0_Pa : float
        Maximum Hertz pressure of the contact, Pa.
    semi_major_m, semi_minor_m : float
        Semi-axes a ≥ b of the contact ellipse, m.
    case_depth_m : float or array
        Effective case depth h, m (> 0).
    nu : float
        Poisson's ratio of the raceway.
    core_shear_fatigue_Pa : float
        Core shear fatigue strength τ_f, Pa (see :func:`core_shear_fatigue_strength_Pa`).
    cap : bool
        If True (default) return min(A_cd, 1): the case depth can only shorten the life.
        If False return the raw ratio τ_f/τ_c.

    Returns
    -------
    float or array like ``case_depth_m``
    """
    _check_hertz(p0_Pa, semi_major_m, semi_minor_m, nu)
    check_positive(core_shear_fatigue_Pa=core_shear_fatigue_Pa)
    p0_Pa, semi_major_m, semi_minor_m = float(p0_Pa), float(semi_major_m), float(semi_minor_m)
    core_shear_fatigue_Pa, nu = float(core_shear_fatigue_Pa), float(nu)
    h = _checked_depth(case_depth_m)
    tau_c = max_shear_profile_Pa(
        p0_Pa, semi_major_m, semi_minor_m, CASE_DEPTH_STRESS_DEPTH_FACTOR * h, nu
    )
    return _factor(core_shear_fatigue_Pa, tau_c, cap)


def _checked_depth(case_depth_m) -> np.ndarray:
    h = np.asarray(case_depth_m, dtype=float)
    if not np.all(np.isfinite(h) & (h > 0.0)):
        raise ValueError(f"case_depth_m must be positive and finite, got {case_depth_m!r}")
    return h


def _factor(core_shear_fatigue_Pa: float, tau_c, cap: bool):
    """A_cd = τ_f/τ_c, capped at 1 if ``cap`` (DG03); float or array like ``tau_c``."""
    a_cd = core_shear_fatigue_Pa / np.asarray(tau_c, dtype=float)
    if cap:
        a_cd = np.minimum(a_cd, 1.0)
    return float(a_cd) if a_cd.ndim == 0 else a_cd


def line_case_depth_life_factor(p0_Pa: float, half_width_m: float, case_depth_m, nu: float,
                                core_shear_fatigue_Pa: float, cap: bool = True):
    """A_cd = τ_f / τ_max(1.1·h) of a line contact (plane strain), capped at 1 by default (DG03).

    As :func:`case_depth_life_factor`, with the half-width b of the line contact for the ellipse
    (:func:`..contact.subsurface.line_max_shear_profile_Pa`).
    """
    check_positive(p0_Pa=p0_Pa, half_width_m=half_width_m, core_shear_fatigue_Pa=core_shear_fatigue_Pa)
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu must lie in (-1, 0.5), got {nu!r}")
    h = _checked_depth(case_depth_m)
    tau_c = line_max_shear_profile_Pa(float(p0_Pa), float(half_width_m), CASE_DEPTH_STRESS_DEPTH_FACTOR * h, float(nu))
    return _factor(float(core_shear_fatigue_Pa), tau_c, cap)


def required_case_depth_m(
    p0_Pa: float,
    semi_major_m: float,
    semi_minor_m: float,
    nu: float,
    core_shear_fatigue_Pa: float,
) -> float:
    """Effective case depth h at which A_cd = 1, m.

    Root of τ_max(1.1·h) = τ_f on the decreasing branch of τ_max(z), i.e. beyond the depth of
    the peak shear stress (scipy ``brentq``). Any deeper case gives A_cd ≥ 1. If τ_f is not
    below the peak of τ_max(z) the core never governs and 0.0 is returned.

    Parameters
    ----------
    p0_Pa : float
        Maximum Hertz pressure, Pa.
    semi_major_m, semi_minor_m : float
        Semi-axes a ≥ b of the contact ellipse, m.
    nu : float
        Poisson's ratio of the raceway.
    core_shear_fatigue_Pa : float
        Core shear fatigue strength τ_f, Pa.
    """
    _check_hertz(p0_Pa, semi_major_m, semi_minor_m, nu)
    check_positive(core_shear_fatigue_Pa=core_shear_fatigue_Pa)
    p0_Pa, semi_major_m, semi_minor_m = float(p0_Pa), float(semi_major_m), float(semi_minor_m)
    core_shear_fatigue_Pa, nu = float(core_shear_fatigue_Pa), float(nu)
    peak = subsurface_shear(p0_Pa, semi_major_m, semi_minor_m, nu)
    if core_shear_fatigue_Pa >= peak.tau_max_Pa:
        return 0.0

    def excess(z: float) -> float:
        return float(max_shear_profile_Pa(p0_Pa, semi_major_m, semi_minor_m, z, nu)) - core_shear_fatigue_Pa

    lo = peak.depth_tau_max_m
    if excess(lo) <= 0.0:  # only possible with τ_f within the peak-search tolerance
        return lo / CASE_DEPTH_STRESS_DEPTH_FACTOR
    hi = 2.0 * lo
    while excess(hi) > 0.0:
        hi *= 2.0
        if hi > 1e6 * semi_major_m:
            raise ValueError(
                f"core_shear_fatigue_Pa ({core_shear_fatigue_Pa}) too small: no depth found "
                "where the shear stress falls below it"
            )
    z = brentq(excess, lo, hi, xtol=1e-15, rtol=4.0 * np.finfo(float).eps)
    return z / CASE_DEPTH_STRESS_DEPTH_FACTOR


def case_depth_corrected_life_Mrev(basic_life_Mrev: float, case_depth_factor: float) -> float:
    """Life corrected for the case depth, L = A_cd·L10, millions of revolutions (DG03)."""
    if not (math.isfinite(basic_life_Mrev) and basic_life_Mrev >= 0.0):
        raise ValueError(f"basic_life_Mrev must be a finite number >= 0, got {basic_life_Mrev!r}")
    check_positive(case_depth_factor=case_depth_factor)
    return case_depth_factor * basic_life_Mrev
