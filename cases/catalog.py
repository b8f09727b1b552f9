"""Built-in bearings of the two studies, for the quasi-static load distribution (rigid rings).

Slewing ring of a fast-reactor rotatable plug (the slewing-ring thesis, see README.md, Sources): single-row
angular-contact thrust ball bearing, α0 = 60°, load balls Ø95.25 mm, groove conformity 0.525 on
both races, steel E = 207 GPa, ν = 0.29 for the Hertz constants. The top race is the moving ring;
the dead load presses it down (−z). Its ball contact is taken as the "inner" raceway (convex in
the rolling direction), as in the thesis' Hertz calculation. Spacer balls carry no axial load and
are not part of the load distribution.

12 MW wind main bearing (Pang et al., *Lubricants* 12 (2024) 252): three-row cylindrical roller bearing,
inner ring moving, outer ring (with the nose) fixed. Radial row 98 × Ø55 mm on pitch Ø1963 mm;
front and rear thrust rows 94 × Ø60 mm on pitch Ø2182 mm. Not given in the paper and chosen here:
effective roller lengths equal to the roller diameters; clearances in the middle of the stated
ranges (radial 0.20 mm diametral → 0.10 mm per roller; axial 0.17 mm → 0.085 mm per thrust row);
thrust rows 90 mm in front of / behind the radial row. +z points from the rotor (front) to the
rear: rotor thrust pushes the inner ring towards +z and loads the front thrust row. Rollers are
steel here (the paper lists aluminium bronze, E = 110 GPa; pass another material to compare).
The default load is illustrative, of the magnitudes of §7.2, not a case from the paper.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from foundation.materials import BEARING_STEEL
from mbd_core.quasistatic import BallRow, Bearing, RingLoad, RollerRow

__all__ = ["BuiltinBearing", "BUILTIN_BEARINGS", "builtin_bearing", "slewing_ring", "three_row_roller"]

G_M_S2 = 9.81  # standard gravity as used in the slewing-ring thesis, m/s²


@dataclass(frozen=True)
class BuiltinBearing:
    """A named bearing with its default load and where its data come from."""

    name: str
    bearing: Bearing
    default_load: RingLoad
    description: str


#: Slewing-ring variants of the thesis (full scale, its 1 m and 2 m models): pitch diameter m, load
#: balls, load in tonnes.
_SLEWING_VARIANTS = {
    "full": (6.69, 116, 500.0 + 3.25),
    "1m": (1.0, 16, 68.9),
    "2m": (2.0, 33, 140.0),
}


def slewing_ring(variant: str = "full") -> BuiltinBearing:
    """The fast-reactor slewing ring (``variant`` "full", "1m" or "2m") under its dead load."""
    if variant not in _SLEWING_VARIANTS:
        raise ValueError(f"variant must be one of {sorted(_SLEWING_VARIANTS)}, got {variant!r}")
    pitch_m, n_balls, load_t = _SLEWING_VARIANTS[variant]
    row = BallRow(
        name="load balls",
        n_balls=n_balls,
        ball_diameter_m=95.25e-3,
        pitch_diameter_m=pitch_m,
        contact_angle_rad=math.radians(60.0),
        conformity_moving=0.525,
        conformity_fixed=0.525,
        moving_raceway="inner",
        axial_sign=-1,
        ball_material=BEARING_STEEL,
        race_material=BEARING_STEEL,
    )
    label = {"full": "full-scale Ø6.69 m", "1m": "1 m scaled", "2m": "2 m scaled"}[variant]
    return BuiltinBearing(
        name=f"slewing-ring-{variant}" if variant != "full" else "slewing-ring",
        bearing=Bearing(f"fast-reactor slewing ring, {label}", (row,)),
        default_load=RingLoad(Fz_N=-load_t * 1000.0 * G_M_S2),
        description=f"{label} slewing ring, {n_balls} balls Ø95.25 mm at 60°, dead load {load_t:g} t",
    )


def three_row_roller() -> BuiltinBearing:
    """The 12 MW three-row roller main bearing under an illustrative rated-wind load."""
    radial = RollerRow("radial", 98, 55e-3, 55e-3, 1.963, "radial", load_sign=1, gap_m=0.10e-3,
                       axial_position_m=0.0, n_slices=20)
    front = RollerRow("front thrust", 94, 60e-3, 60e-3, 2.182, "thrust", load_sign=1, gap_m=0.085e-3,
                      axial_position_m=-0.09, n_slices=20)
    rear = RollerRow("rear thrust", 94, 60e-3, 60e-3, 2.182, "thrust", load_sign=-1, gap_m=0.085e-3,
                     axial_position_m=0.09, n_slices=20)
    return BuiltinBearing(
        name="three-row-roller",
        bearing=Bearing("12 MW wind main bearing, three-row roller", (radial, front, rear)),
        default_load=RingLoad(Fy_N=-1.3e6, Fz_N=1.5e6, Mx_Nm=3.0e6),
        description="three-row roller main bearing: 98 radial Ø55 mm, 2 × 94 thrust Ø60 mm rollers; "
        "load: thrust 1.5 MN, radial 1.3 MN, tilting moment 3 MN·m (illustrative)",
    )


BUILTIN_BEARINGS = {
    "slewing-ring": lambda: slewing_ring("full"),
    "slewing-ring-1m": lambda: slewing_ring("1m"),
    "slewing-ring-2m": lambda: slewing_ring("2m"),
    "three-row-roller": three_row_roller,
}


def builtin_bearing(name: str) -> BuiltinBearing:
    """Look up a built-in bearing by name (see :data:`BUILTIN_BEARINGS`)."""
    try:
        return BUILTIN_BEARINGS[name]()
    except KeyError:
        raise ValueError(f"bearing must be one of {sorted(BUILTIN_BEARINGS)}, got {name!r}") from None
