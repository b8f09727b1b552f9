"""Case-depth life factor per row of a load distribution (NREL DG03, for case-hardened raceways).

Harris, Rumbarger & Butterfield, *Wind Turbine Design Guideline DG03: Yaw and Pitch Rolling
Bearing Life*, NREL/TP-500-42362, 2009: the core below the effective case depth h must carry the
contact shear stress; the check compares the Tresca shear stress on the contact axis at 1.1·h
with the core shear fatigue strength τ_f, A_cd = min(τ_f/τ_max(1.1·h), 1)
(:func:`.case_depth.case_depth_life_factor`). The check is a strength check of the case–core
interface under the largest contact stress of the raceway, not a per-contact damage sum, so the
factor of a row is evaluated at its most loaded contact (the highest Hertz pressure p0 of all its
contact sets and, for a load spectrum, of all load cases) and multiplies the row's L10:
L_cd = A_cd·L10 — as the slewing-ring study applies it to the most loaded ball
(:mod:`cases.slewing.life`; thesis §4.4.2, L_cd = 0.35 × L10).

Ball rows: the Hertz ellipse of that contact (:mod:`..quasistatic.contacts`). Roller rows: the
contact sets hold the most loaded slice of each roller (p0 and half-width b); the slices are parts
of one line contact, so τ_max(z) is the plane-strain line contact's (McEwen; Johnson, *Contact
Mechanics*, 1985, eq. 4.75; :func:`.case_depth.line_case_depth_life_factor`), not that of an
ellipse as long as one slice (which would underestimate it by 27 % at z = 5·b for 20 slices).

The bearing's corrected life combines the rows' corrected lives in series like the L10 of
:mod:`.distribution_life` (Weibull slope e: L = (Σ L_row^(−e))^(−1/e)); rows without a case depth
count with A_cd = 1.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..contact.subsurface import line_max_shear_profile_Pa, max_shear_profile_Pa
from ..quasistatic.contacts import contact_sets
from ..quasistatic.results import LoadDistribution
from ..quasistatic.rows import Bearing, RollerRow
from .case_depth import CASE_DEPTH_STRESS_DEPTH_FACTOR, case_depth_life_factor, line_case_depth_life_factor
from .distribution_life import BearingLife, bearing_weibull_slope, combined_life

__all__ = ["CaseDepth", "RowCaseDepth", "row_case_depth_factors", "case_depth_bearing_life_Mrev"]


@dataclass(frozen=True)
class CaseDepth:
    """A row's case hardening: effective case depth h, m, and core shear fatigue strength τ_f, Pa
    (:func:`.case_depth.core_shear_fatigue_strength_Pa`)."""

    case_depth_m: float
    core_shear_fatigue_Pa: float

    def __post_init__(self) -> None:
        for name in ("case_depth_m", "core_shear_fatigue_Pa"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0.0):
                raise ValueError(f"{name} must be a finite number > 0, got {v!r}")


@dataclass(frozen=True)
class RowCaseDepth:
    """The case-depth factor of one row and the contact it was evaluated at.

    ``factor`` A_cd (1 for an unloaded row); ``p0_Pa``, ``semi_major_m``, ``semi_minor_m`` the Hertz
    contact used (rollers: a = inf, a line contact); ``nu`` the raceway's Poisson's ratio; ``tau_check_Pa`` the
    Tresca shear τ_max(1.1·h); ``contact`` the contact set's label, ``element`` and ``load_case``
    numbered from 0 (−1 when unloaded).
    """

    row: str
    case_depth_m: float
    core_shear_fatigue_Pa: float
    factor: float
    p0_Pa: float
    semi_major_m: float
    semi_minor_m: float
    nu: float
    tau_check_Pa: float
    contact: str
    element: int
    load_case: int

    def to_dict(self) -> dict:
        """Fields by name; element and load case numbered from 1, None when unloaded (also a and b; a
        of a line contact)."""
        return {"factor": self.factor, "case_depth_m": self.case_depth_m,
                "check_depth_m": CASE_DEPTH_STRESS_DEPTH_FACTOR * self.case_depth_m,
                "core_shear_fatigue_Pa": self.core_shear_fatigue_Pa, "shear_at_check_depth_Pa": self.tau_check_Pa,
                "p0_Pa": self.p0_Pa, "a_m": _finite(self.semi_major_m), "b_m": _finite(self.semi_minor_m),
                "contact": self.contact,
                "element": self.element + 1 if self.element >= 0 else None,
                "load_case": self.load_case + 1 if self.load_case >= 0 else None}


def _finite(x: float) -> float | None:
    return x if math.isfinite(x) else None


def _most_loaded(bearing: Bearing, dists: Sequence[LoadDistribution], row_name: str):
    """(p0, a, b, label, element, case) of the row's contact of highest p0 over all load cases."""
    best = (0.0, math.nan, math.nan, "", -1, -1)
    for k, dist in enumerate(dists):
        for s in contact_sets(bearing, dist):
            if s.row != row_name or not len(s.max_pressure_Pa):
                continue
            i = int(np.argmax(s.max_pressure_Pa))
            if s.max_pressure_Pa[i] > best[0]:
                best = (float(s.max_pressure_Pa[i]), float(s.semi_major_m[i]), float(s.semi_minor_m[i]),
                        s.label, i, k)
    return best


def row_case_depth_factors(bearing: Bearing, dists: Sequence[LoadDistribution],
                           case_depths: Mapping[str, CaseDepth]) -> tuple[RowCaseDepth, ...]:
    """A_cd of every row named in ``case_depths``, in row order (module docstring).

    Parameters
    ----------
    bearing : Bearing
    dists : sequence of LoadDistribution
        The solved load cases (one, or every case of a spectrum).
    case_depths : mapping row name → CaseDepth
        The rows with a case depth; the others are left out.
    """
    rows = {row.name: row for row in bearing.rows}
    unknown = sorted(set(case_depths) - set(rows))
    if unknown:
        raise ValueError(f"case_depths: no row named {unknown[0]!r} in bearing {bearing.name!r}")
    out = []
    for row in bearing.rows:
        spec = case_depths.get(row.name)
        if spec is None:
            continue
        p0, a, b, label, element, case = _most_loaded(bearing, dists, row.name)
        nu = row.race_material.nu
        if p0 <= 0.0:
            out.append(RowCaseDepth(row.name, spec.case_depth_m, spec.core_shear_fatigue_Pa, 1.0, 0.0, math.nan,
                                    math.nan, nu, 0.0, "", -1, -1))
            continue
        z, h, tau_f = CASE_DEPTH_STRESS_DEPTH_FACTOR * spec.case_depth_m, spec.case_depth_m, spec.core_shear_fatigue_Pa
        if isinstance(row, RollerRow):  # the slice is part of one line contact (module docstring)
            a = math.inf
            tau = float(line_max_shear_profile_Pa(p0, b, z, nu))
            factor = line_case_depth_life_factor(p0, b, h, nu, tau_f)
        else:
            tau = float(max_shear_profile_Pa(p0, a, b, z, nu))
            factor = case_depth_life_factor(p0, a, b, h, nu, tau_f)
        out.append(RowCaseDepth(row.name, spec.case_depth_m, spec.core_shear_fatigue_Pa, factor, p0, a, b, nu, tau,
                                label, element, case))
    return tuple(out)


def case_depth_bearing_life_Mrev(bearing: Bearing, life: BearingLife, factors: Sequence[RowCaseDepth]) -> float:
    """The bearing's life from its rows' corrected lives A_cd·L_row in series (A_cd = 1 for rows
    without a factor), 10^6 revolutions (module docstring)."""
    by_row = {f.row: f.factor for f in factors}
    lives = [by_row.get(r.row, 1.0) * r.life_Mrev for r in life.rows]
    return combined_life(lives, bearing_weibull_slope(bearing))
