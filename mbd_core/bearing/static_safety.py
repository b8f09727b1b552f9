"""Static safety factor s0 per row from a load distribution (ISO 76:2006).

ISO 76:2006 (*Rolling bearings — Static load ratings*, 3.1–3.6) defines the basic static load
rating C0 as the load that gives, at the centre of the most heavily loaded contact, the pressure
p_lim = 4 200 MPa (ball bearings) or 4 000 MPa (roller bearings), and the static safety factor as
s0 = C0/P0. Under a load distribution the most loaded contact decides: with Hertz theory the
contact load scales as Q ∝ p0³ (point contact) and q ∝ p0² (line contact) (Harris & Kotzalas,
*Rolling Bearing Analysis*, 5th ed., 2007, ch. 6; the same relation NREL DG03, Harris, Rumbarger
& Butterfield, "Wind turbine design guideline DG03: Yaw and pitch rolling bearing life", 2009,
§ static capacity, uses for slewing bearings), so

    s0 = min over the row's contacts of (p_lim / p0)^n,   n = 3 (point), 2 (line),

is the factor by which the most loaded contact's load may grow before p0 reaches p_lim — the
C0/P0 of ISO 76 whenever the distribution scales with the load.

The classical s0 = C0/P0 of ISO 76 is also given for a :class:`BallRow` (clause 5 and 7): C0 from
the Hertz constants of the row (the load at which the more curved raceway's contact reaches
4.2 GPa; ISO 76's tabulated f0 comes from the same Hertz relation, ISO/TR 10657) and

    radial row (α0 ≤ 45°): C0r = Z·Q_lim·cos α0 / 5,   P0r = max(X0·F_r + Y0·F_a, F_r)
    thrust row (α0 > 45°): C0a = Z·Q_lim·sin α0,      P0a = F_a + 2.3·F_r·tan α0

The factor 5 is Stribeck's Q_max = 5·F_r/(Z cos α) that ISO 76 assumes for radial bearings (a
load zone of a bearing with normal clearance); with zero clearance the exact factor is 4.37
(Harris & Kotzalas, ch. 7), so for a radial row the two s0 differ by about 5/4.37. For a thrust
row under a centric axial load every ball carries F_a/(Z sin α): the two agree up to the change
of the contact angle under load (α instead of α0).

Roller rows (ISO 76 6.1 and 8.1; :func:`roller_row_static_rating_N`): C0r = Z·Q_lim/5 (α = 0) and
C0a = Z·Q_lim (α = 90°), Q_lim the roller load at p0 = 4.0 GPa on the more curved raceway
(line contact, p0² = Q·E'/(2π·R·L), Johnson, *Contact Mechanics*, 1985, eq. 4.45); with
R = (D/2)(1 − γ) this is ISO 76's C0r = 44·(1 − γ)·Z·L_we·D_we and C0a = 220·Z·L_we·D_we
(the constants rounded for E = 207 GPa, ν = 0.3). P0r = F_r, P0a = F_a.

Crossed roller rows (:mod:`..quasistatic.rows`) at α0 ≤ 45° are rated as the double-row radial
roller bearing they are (each diagonal an angular-contact row of its rollers, i·Z = Z in all):
C0r = Z·Q_lim·cos α0/5 (ISO 76 6.1: C0r = 44·(1 − D_we·cos α/D_pw)·i·Z·L_we·D_we·cos α), Q_lim on
the conical raceways (γ = D·cos α0/d_m), and P0r = X0·F_r + Y0·F_a with ISO 76 6.2's double-row
factors X0 = 1, Y0 = 0.44·cot α0. Above 45° they are thrust rows loaded in either direction by
the rollers of one diagonal: C0a = Z_d·Q_lim·sin α0 (ISO 76 8.1, Z_d the fewer rollers of the two
diagonals) and P0a = F_a + 2.3·F_r·tan α0 (ISO 76 8.2). The rows' tilting moment, which ISO 76
does not cover, is in the contact-pressure s0 of :func:`static_safety` only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..contact.hertz import ball_on_groove
from ..contact.limits import P0_STATIC_LIMIT_BALL_PA, P0_STATIC_LIMIT_ROLLER_PA
from ..contact.line import line_contact
from ..quasistatic.contacts import ContactSet, contact_sets
from ..quasistatic.results import LoadDistribution
from ..quasistatic.rows import BallRow, Bearing, RollerRow

__all__ = ["RowStaticSafety", "static_safety", "contact_load_at_pressure_N", "ball_row_static_rating_N",
           "ball_row_equivalent_static_load_N", "roller_row_static_rating_N", "roller_row_equivalent_static_load_N",
           "classical_static_safety",
           "row_forces_N", "STRIBECK_ISO76"]

#: Stribeck's factor of ISO 76's radial ball rating: Q_max = 5·F_r/(Z·cos α).
STRIBECK_ISO76 = 5.0


@dataclass(frozen=True)
class RowStaticSafety:
    """Static safety of one row.

    Attributes
    ----------
    row : str
    s0 : float
        min over the row's contacts of (p_lim/p0)^n (inf if no contact is loaded).
    contact : str
        Label of the deciding contact set (e.g. "inner groove").
    element : int
        Index of the deciding element in its row.
    max_pressure_Pa : float
        p0 of the deciding contact, Pa.
    static_limit_Pa : float
        p_lim of the deciding contact, Pa.
    """

    row: str
    s0: float
    contact: str
    element: int
    max_pressure_Pa: float
    static_limit_Pa: float

    def to_dict(self) -> dict:
        return {"row": self.row, "s0": self.s0, "contact": self.contact, "element": self.element,
                "max_pressure_Pa": self.max_pressure_Pa, "static_limit_Pa": self.static_limit_Pa}


def set_safety(s: ContactSet) -> tuple[float, int]:
    """(s0, element) of one contact set: min of (p_lim/p0)^n over its elements."""
    p0 = np.asarray(s.max_pressure_Pa, dtype=float)
    if p0.size == 0 or not np.any(p0 > 0.0):
        return math.inf, -1
    k = int(np.argmax(p0))
    return float((s.static_limit_Pa / p0[k]) ** s.pressure_exponent), k


def static_safety(bearing: Bearing, dist: LoadDistribution) -> tuple[RowStaticSafety, ...]:
    """s0 = min (p_lim/p0)^n of every row of a load distribution (ISO 76:2006; module docstring)."""
    out = []
    sets = contact_sets(bearing, dist)
    for row in bearing.rows:
        best = None
        for s in (s for s in sets if s.row == row.name):
            s0, k = set_safety(s)
            if best is None or s0 < best.s0:
                p0 = float(s.max_pressure_Pa[k]) if k >= 0 else 0.0
                best = RowStaticSafety(row.name, s0, s.label if k >= 0 else "", k, p0, s.static_limit_Pa)
        out.append(best)
    return tuple(out)


def contact_load_at_pressure_N(contact, pressure_Pa: float) -> float:
    """Load Q of a Hertz point contact at which p0 = ``pressure_Pa``, N.

    p0 = 3Q/(2πab) with a, b ∝ Q^(1/3) (Hertz; Johnson, *Contact Mechanics*, 1985, §4.2), so
    Q = Q_1·(p/p0(Q_1))³ for any reference load Q_1.
    """
    if not (math.isfinite(pressure_Pa) and pressure_Pa > 0.0):
        raise ValueError(f"pressure_Pa must be a finite number > 0, got {pressure_Pa!r}")
    q1 = 1.0
    return q1 * (pressure_Pa / float(contact.max_pressure_Pa(q1))) ** 3


def _ball_contacts(row: BallRow):
    """The Hertz contacts of a ball with the moving and the fixed groove (nominal angle)."""
    fixed = "outer" if row.moving_raceway == "inner" else "inner"
    return [ball_on_groove(row.ball_diameter_m, f, row.pitch_diameter_m, row.contact_angle_rad, rw,
                           row.ball_material, row.race_material)
            for rw, f in ((row.moving_raceway, row.conformity_moving), (fixed, row.conformity_fixed))]


def ball_row_static_rating_N(row: BallRow, pressure_limit_Pa: float | None = None) -> float:
    """ISO 76 basic static load rating of a ball row from its Hertz constants, N (module docstring):
    C0r = Z·Q_lim·cos α0/5 for α0 ≤ 45°, C0a = Z·Q_lim·sin α0 above; Q_lim the ball load at which
    the more curved raceway reaches ``pressure_limit_Pa`` (default 4.2 GPa, ISO 76 3.2–3.3)."""
    if not isinstance(row, BallRow):
        raise ValueError(f"row: ISO 76 ratings are given here for BallRow only, got {type(row).__name__}")
    p = P0_STATIC_LIMIT_BALL_PA if pressure_limit_Pa is None else pressure_limit_Pa
    q_lim = min(contact_load_at_pressure_N(c, p) for c in _ball_contacts(row))
    a0 = row.contact_angle_rad
    if a0 <= math.pi / 4 + 1e-12:
        return row.n_balls * q_lim * math.cos(a0) / STRIBECK_ISO76
    return row.n_balls * q_lim * math.sin(a0)


def row_forces_N(dist: LoadDistribution, row_name: str, axial_sign: int = 1) -> tuple[float, float]:
    """(F_r, F_a) a row carries: |Σ Q cos α e_r| and Σ Q sin α, N (axial along the row's loaded side)."""
    r = dist.row(row_name)
    Q, a, psi = (np.asarray(v, dtype=float) for v in (r.load_N, r.contact_angle_rad, r.azimuth_rad))
    fr = np.hypot(np.sum(Q * np.cos(a) * np.cos(psi)), np.sum(Q * np.cos(a) * np.sin(psi)))
    return float(fr), float(np.sum(Q * np.sin(a)))


def ball_row_equivalent_static_load_N(row: BallRow, radial_N: float, axial_N: float,
                                      X0: float = 0.6, Y0: float = 0.5) -> float:
    """ISO 76 static equivalent load of a ball row, N (clauses 5.2 and 7.2).

    Radial row (α0 ≤ 45°): P0r = max(X0·F_r + Y0·F_a, F_r); X0, Y0 from ISO 76 Table 1 given by
    the user (defaults 0.6 and 0.5: single-row radial contact groove ball bearings). Thrust row
    (45° < α0 < 90°): P0a = F_a + 2.3·F_r·tan α0; α0 = 90°: P0a = F_a.
    """
    for name, v in (("radial_N", radial_N), ("axial_N", axial_N), ("X0", X0), ("Y0", Y0)):
        if not (math.isfinite(v) and v >= 0.0):
            raise ValueError(f"{name} must be a finite number >= 0, got {v!r}")
    a0 = row.contact_angle_rad
    if a0 <= math.pi / 4 + 1e-12:
        return max(X0 * radial_N + Y0 * axial_N, radial_N)
    if a0 >= math.pi / 2 - 1e-12:
        return axial_N
    return axial_N + 2.3 * radial_N * math.tan(a0)


def roller_row_static_rating_N(row: RollerRow, pressure_limit_Pa: float | None = None) -> float:
    """ISO 76 basic static load rating of a roller row from the line-contact Hertz relation, N
    (module docstring): C0r = Z·Q_lim·cos α0/5 (radial and crossed rows, α0 ≤ 45°), C0a = Z·Q_lim·sin α0
    (thrust rows; crossed rows above 45° with the rollers of one diagonal); Q_lim the whole roller's
    load at p0 = ``pressure_limit_Pa`` (default 4.0 GPa) on the more curved raceway."""
    if not isinstance(row, RollerRow):
        raise ValueError(f"row: expected a RollerRow, got {type(row).__name__}")
    p = P0_STATIC_LIMIT_ROLLER_PA if pressure_limit_Pa is None else pressure_limit_Pa
    if not (math.isfinite(p) and p > 0.0):
        raise ValueError(f"pressure_limit_Pa must be a finite number > 0, got {pressure_limit_Pa!r}")
    q1 = 1.0
    q_lim = min(q1 * (p / float(line_contact(row.roller_diameter_m, d, row.roller_length_m, row.roller_material,
                                             row.race_material, concave=c).max_pressure_Pa(q1))) ** 2
                for _, d, c in row.raceway_diameters_m())
    a0 = row.nominal_contact_angle_rad
    if row.orientation == "thrust":
        return row.n_rollers * q_lim
    if a0 <= math.pi / 4 + 1e-12:
        return row.n_rollers * q_lim * math.cos(a0) / STRIBECK_ISO76
    sig = row.diagonal_signs
    return float(min(np.sum(sig > 0), np.sum(sig < 0))) * q_lim * math.sin(a0)


def roller_row_equivalent_static_load_N(row: RollerRow, radial_N: float, axial_N: float) -> float:
    """ISO 76 static equivalent load of a roller row, N (module docstring): P0r = F_r (radial),
    P0a = F_a (thrust); crossed rows P0r = F_r + 0.44·cot α0·F_a (α0 ≤ 45°, ISO 76 6.2, double row)
    or P0a = F_a + 2.3·F_r·tan α0 (ISO 76 8.2)."""
    for name, v in (("radial_N", radial_N), ("axial_N", axial_N)):
        if not (math.isfinite(v) and v >= 0.0):
            raise ValueError(f"{name} must be a finite number >= 0, got {v!r}")
    if row.orientation == "radial":
        return radial_N
    if row.orientation == "thrust":
        return axial_N
    a0 = row.contact_angle_rad
    if a0 <= math.pi / 4 + 1e-12:
        return radial_N + 0.44 / math.tan(a0) * axial_N
    return axial_N + 2.3 * radial_N * math.tan(a0)


def classical_static_safety(row, radial_N: float, axial_N: float, X0: float = 0.6, Y0: float = 0.5) -> float:
    """s0 = C0/P0 of ISO 76 for a ball or roller row under the row forces (F_r, F_a), N.

    Ball rows: :func:`ball_row_static_rating_N`, :func:`ball_row_equivalent_static_load_N` (X0, Y0 of
    radial rows). Roller rows: :func:`roller_row_static_rating_N`, :func:`roller_row_equivalent_static_load_N`
    (F_a the row's axial force either way). ISO 76
    has no C0 here for four-point rows (rated by their contact pressure, :func:`static_safety`): ValueError.
    """
    if isinstance(row, BallRow):
        P0 = ball_row_equivalent_static_load_N(row, radial_N, axial_N, X0, Y0)
        C0 = ball_row_static_rating_N(row)
    elif isinstance(row, RollerRow):
        P0 = roller_row_equivalent_static_load_N(row, radial_N, axial_N)
        C0 = roller_row_static_rating_N(row)
    else:
        raise ValueError(f"row {getattr(row, 'name', row)!r}: ISO 76 defines C0 and P0 for ball and roller rows, "
                         f"not {type(row).__name__}")
    return math.inf if P0 == 0.0 else C0 / P0
