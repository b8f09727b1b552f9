"""The contacts of a load distribution, one set per row and raceway: load, angle, pressure, ellipse.

A rolling element touches each raceway in one contact (more for a four-point ball). For every row
of a bearing at equilibrium, :func:`contact_sets` returns one :class:`ContactSet` per raceway
contact family, with per element: the normal load, the contact angle, the largest Hertz pressure
p0, the contact's semi-axes and whether the contact ellipse runs over the groove edge. Static
safety, rating life and the limiting load curve are computed from these sets, so a new row type
plugs in by registering one function (:func:`register_contact_sets`), not by an ``if`` in each of
them.

Ball contacts: Hertz point contacts of the ball with each groove (:func:`..contact.hertz.ball_on_groove`)
at the row's nominal contact angle, the angle at which the solver's load–deflection constant is
computed; the ellipse is truncated when α ± a/(f·D) leaves the groove's angle range (Harris &
Kotzalas, *Rolling Bearing Analysis*, 5th ed., ch. 6, contact ellipse truncation). Roller contacts:
each slice a Hertz line contact of length L/n_s (:func:`..contact.line.line_contact`); the set holds
the most loaded slice of each roller (p0 and the half-width b there; semi-major = half the slice
length), on raceways of the curvature across the roller axis (conical for crossed rows,
:meth:`.rows.RollerRow.raceway_diameters_m`). Static limits of p0 after ISO 76:2006: 4.2 GPa for
ball, 4.0 GPa for roller bearings.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..contact.hertz import ball_on_groove
from ..contact.limits import P0_STATIC_LIMIT_BALL_PA, P0_STATIC_LIMIT_ROLLER_PA
from ..contact.line import line_contact
from .results import LoadDistribution, RowLoads
from .validity import DIAGONAL_LABELS
from .rows import BallRow, Bearing, FourPointRow, RollerRow

__all__ = ["ContactSet", "contact_sets", "register_contact_sets", "CONTACT_SET_BUILDERS"]


@dataclass(frozen=True)
class ContactSet:
    """One contact family of a row (e.g. the balls on the inner groove), per element.

    Attributes (Z = elements of the row)
    ----------
    row : str
        Name of the row.
    label : str
        Which contacts: the raceway, and for rows with several contacts per raceway which one.
    raceway : {"inner", "outer"}
        Ring of the contact ("inner" for the moving ring of the slewing ring's convention, see
        :class:`.rows.BallRow`; thrust roller rows call the moving ring's raceway "inner").
    geometry : {"point", "line"}
        Hertz point (ball) or line (roller slice) contact: p0 scales with Q^(1/3) or q^(1/2).
    load_N : (Z,) normal load of the contact, N (rollers: the most loaded slice's load)
    contact_angle_rad : (Z,) loaded contact angle, rad
    max_pressure_Pa : (Z,) largest Hertz pressure p0, Pa (0 where unloaded)
    semi_major_m, semi_minor_m : (Z,) contact semi-axes a ≥ b, m (line: half the slice length and
        the half-width b)
    truncated : (Z,) True where the contact ellipse runs over the groove edge
    static_limit_Pa : float
        ISO 76 static limit of p0 for this kind of element, Pa.
    """

    row: str
    label: str
    raceway: Literal["inner", "outer"]
    geometry: Literal["point", "line"]
    load_N: np.ndarray
    contact_angle_rad: np.ndarray
    max_pressure_Pa: np.ndarray
    semi_major_m: np.ndarray
    semi_minor_m: np.ndarray
    truncated: np.ndarray
    static_limit_Pa: float

    @property
    def pressure_exponent(self) -> float:
        """n of Q ∝ p0^n (Hertz: 3 for point, 2 for line contacts)."""
        return 3.0 if self.geometry == "point" else 2.0

    def to_dict(self) -> dict:
        return {
            "row": self.row,
            "label": self.label,
            "raceway": self.raceway,
            "geometry": self.geometry,
            "load_N": self.load_N.tolist(),
            "contact_angle_deg": np.degrees(self.contact_angle_rad).tolist(),
            "max_pressure_Pa": self.max_pressure_Pa.tolist(),
            "semi_major_m": self.semi_major_m.tolist(),
            "semi_minor_m": self.semi_minor_m.tolist(),
            "truncated": self.truncated.tolist(),
            "static_limit_Pa": self.static_limit_Pa,
        }


#: row class -> function (row, its RowLoads) -> contact sets of that row
CONTACT_SET_BUILDERS: dict[type, Callable[[object, RowLoads], list[ContactSet]]] = {}


def register_contact_sets(row_type: type):
    """Decorator registering the contact-set builder of a row class."""

    def register(fn):
        CONTACT_SET_BUILDERS[row_type] = fn
        return fn

    return register


def groove_truncated(semi_major_m: np.ndarray, groove_radius_m: float, contact_angle_rad: np.ndarray,
                     angle_min_rad: float, angle_max_rad: float) -> np.ndarray:
    """True where the ellipse, spanning ±a/(f·D) about α on the groove section, leaves [min, max]."""
    half = np.asarray(semi_major_m, dtype=float) / groove_radius_m
    alpha = np.asarray(contact_angle_rad, dtype=float)
    return (alpha - half < angle_min_rad) | (alpha + half > angle_max_rad)


def ball_groove_sets(row: BallRow | FourPointRow, res: RowLoads, label_suffix: str = "",
                     angle_range_rad: tuple[float, float] | None = None) -> list[ContactSet]:
    """Contact sets of balls in two grooves (moving and fixed ring), loads ``res.load_N``."""
    fixed = "outer" if row.moving_raceway == "inner" else "inner"
    lo, hi = row.groove_angle_range_rad if angle_range_rad is None else angle_range_rad
    Q = np.asarray(res.load_N, dtype=float)
    alpha = np.asarray(res.contact_angle_rad, dtype=float)
    loaded = Q > 0.0
    out = []
    for raceway, f in ((row.moving_raceway, row.conformity_moving), (fixed, row.conformity_fixed)):
        c = ball_on_groove(row.ball_diameter_m, f, row.pitch_diameter_m, row.contact_angle_rad, raceway,
                           row.ball_material, row.race_material)
        a, b = c.semi_axes_m(Q)
        out.append(ContactSet(
            row=row.name, label=f"{raceway} groove{label_suffix}", raceway=raceway, geometry="point",
            load_N=Q, contact_angle_rad=alpha, max_pressure_Pa=np.asarray(c.max_pressure_Pa(Q), dtype=float),
            semi_major_m=np.asarray(a, dtype=float), semi_minor_m=np.asarray(b, dtype=float),
            truncated=loaded & groove_truncated(a, f * row.ball_diameter_m, alpha, lo, hi),
            static_limit_Pa=P0_STATIC_LIMIT_BALL_PA,
        ))
    return out


@register_contact_sets(BallRow)
def _ball_row_sets(row: BallRow, res: RowLoads) -> list[ContactSet]:
    return ball_groove_sets(row, res)


@register_contact_sets(FourPointRow)
def _four_point_row_sets(row: FourPointRow, res: RowLoads) -> list[ContactSet]:
    """Four sets: the moving and the fixed groove of each diagonal (+α, −α), each diagonal's ellipse
    truncated where it leaves its arc between the arch apex and the shoulder (:mod:`.rows_four_point`)."""
    out = []
    for j, label in enumerate(DIAGONAL_LABELS):
        out += ball_groove_sets(row, res.diagonal(j), f", diagonal {label}", row.groove_angle_range_rad)
    return out


def roller_line_sets(row: RollerRow, q_max: np.ndarray, angle_rad: np.ndarray, label_suffix: str = "") -> list[ContactSet]:
    """The inner and the outer raceway set of a roller row's most loaded slices ``q_max`` (Z,), N:
    Hertz line contacts of length L/n_s on the raceways of :meth:`.rows.RollerRow.raceway_diameters_m`."""
    half_length = np.full(len(q_max), 0.5 * row.roller_length_m / row.n_slices)
    out = []
    for raceway, diameter_m, concave in row.raceway_diameters_m():
        c = line_contact(row.roller_diameter_m, diameter_m, row.roller_length_m / row.n_slices,
                         row.roller_material, row.race_material, concave=concave)
        out.append(ContactSet(
            row=row.name, label=f"{raceway} raceway{label_suffix}", raceway=raceway, geometry="line",
            load_N=q_max, contact_angle_rad=np.asarray(angle_rad, dtype=float),
            max_pressure_Pa=np.asarray(c.max_pressure_Pa(q_max), dtype=float),
            semi_major_m=half_length, semi_minor_m=np.asarray(c.half_width_m(q_max), dtype=float),
            truncated=np.zeros(len(q_max), dtype=bool), static_limit_Pa=P0_STATIC_LIMIT_ROLLER_PA,
        ))
    return out


@register_contact_sets(RollerRow)
def _roller_row_sets(row: RollerRow, res: RowLoads) -> list[ContactSet]:
    """Two sets (inner and outer raceway); a crossed row four, the two raceways of each diagonal
    (+α0, −α0), each holding the rollers of its diagonal (the others zero): the two diagonals roll on
    different flanks of the V-grooves."""
    q = np.zeros((len(res.load_N), row.n_slices)) if res.slice_load_N is None else np.asarray(res.slice_load_N)
    q_max = q.max(axis=1) if q.size else np.zeros(len(res.load_N))
    if row.orientation != "crossed":
        return roller_line_sets(row, q_max, res.contact_angle_rad)
    out = []
    for sign, label in zip((1.0, -1.0), DIAGONAL_LABELS):
        on = row.diagonal_signs == sign
        out += roller_line_sets(row, np.where(on, q_max, 0.0), np.full(len(q_max), row.contact_angle_rad),
                                f", diagonal {label}")
    return out


def contact_sets(bearing: Bearing, dist: LoadDistribution) -> tuple[ContactSet, ...]:
    """Every contact set of a load distribution, in row order (see :class:`ContactSet`)."""
    out: list[ContactSet] = []
    for row, res in zip(bearing.rows, dist.rows):
        try:
            build = CONTACT_SET_BUILDERS[type(row)]
        except KeyError:
            raise TypeError(f"no contact sets registered for rows of type {type(row).__name__}") from None
        out += build(row, res)
    return tuple(out)
