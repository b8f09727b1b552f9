"""Where a quasi-static load distribution leaves the validity of its model.

Checked at equilibrium, per row (limits and references in :mod:`mbd_core.contact.limits`):

* the largest contact pressure p0 of any element against the ISO 76 static limit (4.2 GPa ball,
  4.0 GPa roller bearings), balls from the Hertz contacts of both grooves at the nominal contact
  angle, roller slices as line contacts of length L/n_s on the inner (convex) raceway;
* a ball's contact ellipse running over the groove edge (truncation; for four-point rows each
  diagonal against its own range, apex to shoulder), and balls whose contact
  angle reached its limit or ran over the groove edge (they are unloaded there);
* the ring displacement against a quarter of the smallest rolling-element diameter (the model
  takes small displacements: fixed element azimuths, small rotations, contact normals of the
  unloaded geometry for rollers).

An approach beyond the rolling element's own diameter is no result at all:
:func:`approach_limit_error` names it and the solver raises.
"""

from __future__ import annotations

import math

import numpy as np

from ..contact.hertz import ball_on_groove
from ..contact.limits import (
    P0_STATIC_LIMIT_BALL_PA,
    P0_STATIC_LIMIT_ROLLER_PA,
    groove_edge_warning,
    pressure_warning,
    small_contact_warning,
)
from foundation.text import plural

from ..contact.line import line_contact
from .rows import BallRow, Bearing, FourPointRow, RollerRow

#: Names of a four-point row's diagonals, in the order of its per-contact arrays.
DIAGONAL_LABELS = ("+α", "−α")

__all__ = ["DIAGONAL_LABELS", "DISPLACEMENT_LIMIT_RATIO", "ANGLE_LIMIT_MARGIN_RAD", "load_distribution_warnings", "approach_limit_error"]

#: Largest ring displacement, as a fraction of the smallest rolling-element diameter, for the
#: small-displacement model.
DISPLACEMENT_LIMIT_RATIO = 0.25
#: A loaded contact angle this close to the groove's limit counts as "at its limit", rad.
ANGLE_LIMIT_MARGIN_RAD = math.radians(0.5)


def _element_diameter_m(row) -> float:
    return row.ball_diameter_m if isinstance(row, (BallRow, FourPointRow)) else row.roller_diameter_m


def approach_limit_error(bearing: Bearing, rows) -> str | None:
    """Text naming the first row whose largest approach exceeds its rolling-element diameter, or None."""
    for row, res in zip(bearing.rows, rows):
        d = _element_diameter_m(row)
        worst = float(np.max(res.approach_m)) if res.approach_m.size else 0.0
        if not worst <= d:
            return (f"row {row.name!r} needs an approach of {worst:.4g} m, more than its rolling element's diameter "
                    f"{d:.4g} m; the rows cannot carry this load")
    return None


def _ball_row_warnings(row: BallRow | FourPointRow, res, which: str = "") -> list[str]:
    """Warnings of the balls of ``row`` with loads ``res``; ``which`` names the contacts (a four-point
    row's diagonal) in the messages."""
    fixed = "outer" if row.moving_raceway == "inner" else "inner"
    out = []
    loaded = res.load_N > 0.0
    lo, hi = row.groove_angle_range_rad
    if loaded.any():
        i = int(np.argmax(res.load_N))
        Q, alpha = float(res.load_N[i]), float(res.contact_angle_rad[i])
        for raceway, f in ((row.moving_raceway, row.conformity_moving), (fixed, row.conformity_fixed)):
            c = ball_on_groove(row.ball_diameter_m, f, row.pitch_diameter_m, row.contact_angle_rad, raceway,
                               row.ball_material, row.race_material)
            a, _ = (float(x) for x in c.semi_axes_m(Q))
            found = [pressure_warning(float(c.max_pressure_Pa(Q)), P0_STATIC_LIMIT_BALL_PA, "ball"),
                     small_contact_warning(a, row.ball_diameter_m / 2.0),
                     groove_edge_warning(a, f * row.ball_diameter_m, alpha, lo, hi)]
            out += [f"row {row.name!r}, {raceway} groove{which}, ball at ψ = {math.degrees(res.azimuth_rad[i]):.4g}°: {w}"
                    for w in found if w]
        at_limit = loaded & ((res.contact_angle_rad - lo < ANGLE_LIMIT_MARGIN_RAD)
                             | (hi - res.contact_angle_rad < ANGLE_LIMIT_MARGIN_RAD))
        if at_limit.any():
            out.append(f"row {row.name!r}{which}: {plural(int(at_limit.sum()), 'loaded ball')} at the groove's contact-angle limit "
                       f"({math.degrees(lo):.3g}° / {math.degrees(hi):.3g}°)")
    off = (res.approach_m > 0.0) & ~loaded
    if off.any():
        out.append(f"row {row.name!r}{which}: {plural(int(off.sum()), 'ball')} pressed beyond the groove edge carry no load "
                   "(the groove model ends there)")
    return out


def _roller_row_warnings(row: RollerRow, res) -> list[str]:
    if res.slice_load_N is None or not (res.slice_load_N > 0.0).any():
        return []
    _, raceway_m, _ = row.raceway_diameters_m()[0]  # the inner, convex raceway
    c = line_contact(row.roller_diameter_m, raceway_m, row.roller_length_m / row.n_slices,
                     row.roller_material, row.race_material)
    k, j = np.unravel_index(int(np.argmax(res.slice_load_N)), res.slice_load_N.shape)
    q = float(res.slice_load_N[k, j])
    found = [pressure_warning(float(c.max_pressure_Pa(q)), P0_STATIC_LIMIT_ROLLER_PA, "roller"),
             small_contact_warning(float(c.half_width_m(q)), row.roller_diameter_m / 2.0)]
    return [f"row {row.name!r}, roller at ψ = {math.degrees(res.azimuth_rad[k]):.4g}°, slice {j + 1} of {row.n_slices}: {w}"
            for w in found if w]


def load_distribution_warnings(bearing: Bearing, rows, q: np.ndarray) -> tuple[str, ...]:
    """Validity warnings (module docstring) of a load distribution.

    Parameters
    ----------
    bearing : Bearing
    rows : sequence of RowLoads, in the order of ``bearing.rows``
    q : (5,) ring displacement (x, y, z, θx, θy), m and rad
    """
    out: list[str] = []
    for row, res in zip(bearing.rows, rows):
        if isinstance(row, FourPointRow):
            for j, label in enumerate(DIAGONAL_LABELS):
                out += _ball_row_warnings(row, res.diagonal(j), f", diagonal {label}")
        elif isinstance(row, BallRow):
            out += _ball_row_warnings(row, res)
        else:
            out += _roller_row_warnings(row, res)
    d_min = min(_element_diameter_m(r) for r in bearing.rows)
    move = max(float(np.max(np.abs(q[:3]))), float(np.max(np.abs(q[3:]))) * bearing.reference_length_m)
    if not move <= DISPLACEMENT_LIMIT_RATIO * d_min:
        out.append(f"ring displacement {move:.4g} m exceeds {DISPLACEMENT_LIMIT_RATIO:g} of the smallest rolling "
                   f"element's diameter ({d_min:.4g} m): beyond the small-displacement model")
    return tuple(out)
