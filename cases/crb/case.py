"""The friction torque of a cylindrical roller bearing with ribs (NJ type) under radial and axial
load, quasi-static, contact by contact (:mod:`mbd_core.bearing.roller_friction`), beside the bearing
maker's catalogue model (:mod:`mbd_core.bearing.catalogue_friction`).

The inner ring turns at ``operation.speed_rpm``, the outer ring is held; the oil (an ISO VG grade of
mineral oil, ``lubrication.iso_vg``) is at ``lubrication.temperature_C`` throughout.

Studies:

- ``point``: one operating point; the loads, films and losses of every roller;
- ``speed-axial``: torque over ``study.speeds_rpm`` for each of ``study.axial_loads_N`` at the radial
  load of ``operation`` (the MEGT study's Fig. 3 grid), both models.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar, Literal

from foundation.validation import check_positive
from mbd_core.bearing.catalogue_friction import CatalogueConstants
from mbd_core.bearing.roller_friction import MixedLubrication

from ..config import CaseTables

__all__ = ["CrbBearing", "Lubrication", "Operation", "Study", "CrbCase"]


@dataclass(frozen=True)
class CrbBearing:
    """``[bearing]``: boundary dimensions and inner geometry (m); radial clearance in operation
    (after fits); the roller end's contact on the ribs: its height e above the roller's axis and
    the end's sphere radius."""

    bore_m: float = 0.080
    outside_diameter_m: float = 0.140
    n_rollers: int = 18
    roller_diameter_m: float = 0.015
    roller_length_m: float = 0.020
    pitch_diameter_m: float = 0.110
    radial_clearance_m: float = 40e-6
    rib_contact_height_m: float = 0.00525
    roller_end_radius_m: float = 0.06

    def __post_init__(self) -> None:
        check_positive(bore_m=self.bore_m, outside_diameter_m=self.outside_diameter_m,
                       roller_diameter_m=self.roller_diameter_m, roller_length_m=self.roller_length_m,
                       pitch_diameter_m=self.pitch_diameter_m, roller_end_radius_m=self.roller_end_radius_m)
        if not (isinstance(self.n_rollers, int) and 4 <= self.n_rollers <= 200):
            raise ValueError(f"n_rollers: must be an integer in 4 … 200, got {self.n_rollers!r}")
        if not self.bore_m < self.pitch_diameter_m - self.roller_diameter_m:
            raise ValueError(f"bore_m: the inner raceway (Ø{self.pitch_diameter_m - self.roller_diameter_m:g} m) "
                             f"must lie outside the bore ({self.bore_m!r} m)")
        if not self.outside_diameter_m > self.pitch_diameter_m + self.roller_diameter_m:
            raise ValueError(f"outside_diameter_m: the outer raceway (Ø{self.pitch_diameter_m + self.roller_diameter_m:g}"
                             f" m) must lie inside it, got {self.outside_diameter_m!r}")
        if self.n_rollers * self.roller_diameter_m >= math.pi * self.pitch_diameter_m:
            raise ValueError(f"n_rollers: {self.n_rollers} rollers of {self.roller_diameter_m} m do not fit on the "
                             f"pitch circle of {self.pitch_diameter_m} m")
        if not (isinstance(self.radial_clearance_m, (int, float)) and 0.0 <= self.radial_clearance_m <= 1e-3):
            raise ValueError(f"radial_clearance_m: must lie in 0 … 0.001 m, got {self.radial_clearance_m!r}")
        check_positive(rib_contact_height_m=self.rib_contact_height_m)
        if not self.rib_contact_height_m < self.roller_diameter_m / 2:
            raise ValueError(f"rib_contact_height_m: must lie below the roller's radius {self.roller_diameter_m / 2:g} m, "
                             f"got {self.rib_contact_height_m!r}")

    def model(self):
        from mbd_core.bearing.roller_friction import CylindricalRollerBearing

        return CylindricalRollerBearing(self.n_rollers, self.roller_diameter_m, self.roller_length_m,
                                        self.pitch_diameter_m, self.radial_clearance_m, self.rib_contact_height_m,
                                        self.roller_end_radius_m)


@dataclass(frozen=True)
class Lubrication:
    """``[lubrication]``: the oil (ISO VG grade of mineral oil) and its temperature (°C). The surfaces
    are ``[surfaces]`` (:class:`mbd_core.bearing.roller_friction.MixedLubrication`: composite RMS
    roughness of the raceway and rib contacts in m, Zhou & Hoeprich's B and C, boundary friction, the
    oil's limiting shear coefficient τ_L/p)."""

    iso_vg: int = 100
    temperature_C: float = 50.0

    def __post_init__(self) -> None:
        from foundation.lubricants import ISO_VG_MINERAL_100C_MM2_S

        if self.iso_vg not in ISO_VG_MINERAL_100C_MM2_S:
            raise ValueError(f"iso_vg: one of {', '.join(map(str, ISO_VG_MINERAL_100C_MM2_S))}, got {self.iso_vg!r}")
        if not (isinstance(self.temperature_C, (int, float)) and -20.0 <= self.temperature_C <= 150.0):
            raise ValueError(f"temperature_C: must lie in −20 … 150, got {self.temperature_C!r}")

    def oil(self):
        from foundation.lubricants import iso_vg_mineral_oil

        return iso_vg_mineral_oil(self.iso_vg, self.temperature_C)


@dataclass(frozen=True)
class Operation:
    """``[operation]``: radial and axial load (N) and the inner ring's speed (rev/min)."""

    radial_load_N: float = 20e3
    axial_load_N: float = 0.0
    speed_rpm: float = 1500.0

    def __post_init__(self) -> None:
        check_positive(radial_load_N=self.radial_load_N, speed_rpm=self.speed_rpm)
        if not (isinstance(self.axial_load_N, (int, float)) and 0.0 <= self.axial_load_N < math.inf):
            raise ValueError(f"axial_load_N: must be a number ≥ 0, got {self.axial_load_N!r}")


@dataclass(frozen=True)
class Study:
    """``[study]``: ``kind``; the ``speed-axial`` study's inner ring speeds (rev/min) and axial loads (N)."""

    kind: Literal["point", "speed-axial"] = "point"
    speeds_rpm: tuple[float, ...] = (100.0, 250.0, 500.0, 750.0, 1000.0, 1500.0, 2000.0, 3000.0, 4000.0)
    axial_loads_N: tuple[float, ...] = (0.0, 1000.0, 2000.0, 4000.0)

    def __post_init__(self) -> None:
        for key, zero_ok in (("speeds_rpm", False), ("axial_loads_N", True)):
            values = getattr(self, key)
            if not values or len(values) > 50 or not all(
                    isinstance(v, (int, float)) and math.isfinite(v) and (v > 0.0 or zero_ok and v == 0.0)
                    for v in values):
                raise ValueError(f"{key}: must hold 1 … 50 numbers {'≥' if zero_ok else '>'} 0, got {values!r}")


@dataclass(frozen=True)
class CrbCase(CaseTables):
    """A friction-torque case of a cylindrical roller bearing (module docstring)."""

    FAMILY: ClassVar[str] = "crb"  # the ``family`` key of its case files
    name: str = "crb"
    description: str = ""
    bearing: CrbBearing = field(default_factory=CrbBearing)
    lubrication: Lubrication = field(default_factory=Lubrication)
    surfaces: MixedLubrication = field(default_factory=MixedLubrication)
    operation: Operation = field(default_factory=Operation)
    catalogue: CatalogueConstants = field(default_factory=CatalogueConstants)
    study: Study = field(default_factory=Study)
