"""Cages: plain rings with pockets for balls or rollers, SI units.

A cage is a ring section (a :class:`~fem_rings.profile.Profile`) plus a :class:`CagePockets`
description; the mesher revolves the ring and cuts the pockets with boolean operations
(tetrahedra only).

12 MW three-row roller main bearing (geometry of :class:`fem_rings.sections.ThreeRowGeometry`):
steel cages, pocket clearance 0.5 mm per side; radial cage ring 26 mm radial × 105 mm axial, 69 kg
with its pockets (paper 70 kg); thrust cages 110 mm radial × 28 mm axial, 89 kg (paper 90.2 kg).
Cage rings lie between the raceways (thinner than the rollers) and clear the ring lands.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .profile import Profile, rectangle
from .sections import ThreeRowGeometry, _positive

__all__ = ["CagePockets", "ball_cage", "roller_cage", "three_row_cages"]


# -- cages ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CagePockets:
    """Pockets to cut from a plain cage ring (by the mesher): prisms or cylinders about ``axis``.

    Parameters
    ----------
    n_pockets : int
        Number of pockets, equally spaced.
    shape : {"cylinder", "box"}
        Cylindrical pocket of ``radius_m``, or a box ``width_m`` (circumferential) × ``height_m``
        (the other transverse direction: z for radial pockets, r for axial pockets).
    axis : {"radial", "axial"}
        Direction of the pocket axis (through the cage ring).
    pitch_radius_m, z_m : float
        Radius and axial position of the pocket centres, m.
    angle_offset_deg : float
        Angle of the first pocket centre from the x axis, degrees.
    """

    n_pockets: int
    shape: str
    axis: str
    pitch_radius_m: float
    z_m: float = 0.0
    radius_m: float | None = None
    width_m: float | None = None
    height_m: float | None = None
    angle_offset_deg: float = 0.0

    def __post_init__(self) -> None:
        if int(self.n_pockets) != self.n_pockets or self.n_pockets < 1:
            raise ValueError(f"n_pockets must be a positive integer, got {self.n_pockets!r}")
        if self.shape not in ("cylinder", "box"):
            raise ValueError(f"shape must be 'cylinder' or 'box', got {self.shape!r}")
        if self.axis not in ("radial", "axial"):
            raise ValueError(f"axis must be 'radial' or 'axial', got {self.axis!r}")
        _positive(self.pitch_radius_m, "pitch_radius_m")
        for f in (("radius_m",) if self.shape == "cylinder" else ("width_m", "height_m")):
            if getattr(self, f) is None:
                raise ValueError(f"a {self.shape} pocket needs {f}")
            _positive(getattr(self, f), f)
        if not self.pitch_radius_m > self.overlap_radius_m:
            raise ValueError(f"n_pockets = {self.n_pockets} pockets of circumferential width "
                             f"{self.circumferential_width_m:.6g} m overlap on the pitch circle of radius "
                             f"{self.pitch_radius_m:.6g} m")

    @property
    def circumferential_width_m(self) -> float:
        """Pocket width along the pitch circle, m."""
        return 2.0 * self.radius_m if self.shape == "cylinder" else self.width_m

    @property
    def overlap_radius_m(self) -> float:
        """pitch_radius_m must exceed this for neighbouring pockets to stay apart, m.

        Radial pockets: parallel-sided strips of width w meet at radius (w/2)/sin(π/n), so a cage
        ring must lie wholly outside it. Axial pockets: the nearest point to the bisector between
        neighbours decides (disc: R·sin(π/n) > a; box: (R − h/2)·sin(π/n) > (w/2)·cos(π/n)).
        """
        s, c, w = math.sin(math.pi / self.n_pockets), math.cos(math.pi / self.n_pockets), self.circumferential_width_m
        if self.n_pockets < 2:
            return 0.0
        if self.axis == "radial":
            return 0.5 * w / s
        if self.shape == "cylinder":
            return self.radius_m / s
        return 0.5 * self.height_m + 0.5 * w * c / s

    @property
    def angles_rad(self) -> np.ndarray:
        """Angles of the pocket centres, (n_pockets,) rad."""
        return math.radians(self.angle_offset_deg) + 2.0 * math.pi * np.arange(self.n_pockets) / self.n_pockets


def _cage(name: str, pockets: CagePockets, thickness_m: float, extent_m: float, axial_size_m: float,
          element_diameter_m: float) -> tuple[Profile, CagePockets]:
    """Plain ring: ``thickness_m`` along the pocket axis, ``extent_m`` across it (in the section)."""
    _positive(thickness_m, "thickness_m"), _positive(extent_m, "extent_m")
    if not thickness_m < element_diameter_m:
        raise ValueError(f"thickness_m ({thickness_m}) must be below the rolling-element diameter "
                         f"({element_diameter_m}) to stay clear of the raceways")
    if not extent_m > axial_size_m:
        raise ValueError(f"extent_m ({extent_m}) must exceed the pocket size across the ring ({axial_size_m:.6g})")
    rp, z = pockets.pitch_radius_m, pockets.z_m
    dr, dz = (thickness_m, extent_m) if pockets.axis == "radial" else (extent_m, thickness_m)
    if pockets.axis == "radial" and not rp - dr / 2 > pockets.overlap_radius_m:
        raise ValueError(f"n_pockets = {pockets.n_pockets} radial pockets overlap at the cage bore "
                         f"(r = {rp - dr / 2:.6g} m < {pockets.overlap_radius_m:.6g} m): reduce thickness_m")
    return rectangle(name, rp - dr / 2, rp + dr / 2, z - dz / 2, z + dz / 2), pockets


def ball_cage(name: str, *, n_balls: int, ball_diameter_m: float, pitch_diameter_m: float, thickness_m: float,
              extent_m: float, z_m: float = 0.0, axis: str = "radial", pocket_clearance_m: float = 0.5e-3,
              angle_offset_deg: float = 0.0) -> tuple[Profile, CagePockets]:
    """Plain cage ring on the pitch circle and its cylindrical pockets (radius D/2 + clearance).

    ``thickness_m`` is the ring's size along the pocket axis (radial or axial), ``extent_m`` across it.
    """
    a = 0.5 * _positive(ball_diameter_m, "ball_diameter_m") + _positive(pocket_clearance_m, "pocket_clearance_m")
    pockets = CagePockets(n_balls, "cylinder", axis, 0.5 * _positive(pitch_diameter_m, "pitch_diameter_m"),
                          z_m, radius_m=a, angle_offset_deg=angle_offset_deg)
    return _cage(name, pockets, thickness_m, extent_m, 2.0 * a, ball_diameter_m)


def roller_cage(name: str, *, row: str, n_rollers: int, roller_diameter_m: float, roller_length_m: float,
                pitch_diameter_m: float, z_m: float, thickness_m: float, extent_m: float,
                pocket_clearance_m: float = 0.5e-3, angle_offset_deg: float = 0.0) -> tuple[Profile, CagePockets]:
    """Plain cage ring and box pockets (roller + clearance on each side) of a ``"radial"`` or ``"thrust"`` row.

    Radial row: pockets along r, ring ``thickness_m`` radial × ``extent_m`` axial. Thrust row
    (roller axes radial): pockets along z, ring ``extent_m`` radial × ``thickness_m`` axial.
    """
    if row not in ("radial", "thrust"):
        raise ValueError(f"row must be 'radial' or 'thrust', got {row!r}")
    c = _positive(pocket_clearance_m, "pocket_clearance_m")
    w = _positive(roller_diameter_m, "roller_diameter_m") + 2.0 * c
    h = _positive(roller_length_m, "roller_length_m") + 2.0 * c
    pockets = CagePockets(n_rollers, "box", "radial" if row == "radial" else "axial",
                          0.5 * _positive(pitch_diameter_m, "pitch_diameter_m"), z_m, width_m=w, height_m=h,
                          angle_offset_deg=angle_offset_deg)
    return _cage(name, pockets, thickness_m, extent_m, h, roller_diameter_m)


def three_row_cages(geometry: ThreeRowGeometry = ThreeRowGeometry(), radial_thickness_m: float = 0.026,
                    radial_extent_m: float = 0.105, thrust_thickness_m: float = 0.028,
                    thrust_extent_m: float = 0.110) -> dict[str, tuple[Profile, CagePockets]]:
    """Cages of the three-row bearing: ``"radial"``, ``"front_thrust"``, ``"rear_thrust"``."""
    g = geometry
    radial = dict(n_rollers=g.n_radial, roller_diameter_m=g.radial_roller_diameter_m,
                  roller_length_m=g.radial_roller_length_m, pitch_diameter_m=g.radial_pitch_diameter_m)
    thrust = dict(n_rollers=g.n_thrust, roller_diameter_m=g.thrust_roller_diameter_m,
                  roller_length_m=g.thrust_roller_length_m, pitch_diameter_m=g.thrust_pitch_diameter_m,
                  thickness_m=thrust_thickness_m, extent_m=thrust_extent_m)
    return {
        "radial": roller_cage("radial cage", row="radial", z_m=g.radial_z_m, thickness_m=radial_thickness_m,
                              extent_m=radial_extent_m, **radial),
        "front_thrust": roller_cage("front thrust cage", row="thrust", z_m=g.front_thrust_z_m, **thrust),
        "rear_thrust": roller_cage("rear thrust cage", row="thrust", z_m=g.rear_thrust_z_m, **thrust),
    }
