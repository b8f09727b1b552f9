"""Roller row types of bearing description files: radial, thrust and crossed cylindrical rollers
(registered in :data:`cases.bearing_rows.ROW_TYPES`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from mbd_core.quasistatic import RollerRow

from .row_keys import Direction, RowContext, SeparatorKeys, _CaseDepthKeys, _check_fits, _sign

__all__ = ["RadialRollerKeys", "ThrustRollerKeys", "CrossedRollerKeys"]


@dataclass(frozen=True)
class _RollerKeys(_CaseDepthKeys):
    """Keys every roller row has, and the case hardening keys of :class:`_CaseDepthKeys`.

    Attributes
    ----------
    name : str
    count : int
        Rollers Z; Z·D_we ≤ π·d_m.
    roller_diameter_m, roller_length_m, pitch_diameter_m : float
        D_we, effective length L_we and d_m, m.
    axial_position_m : float
        z of the roller centres, m.
    first_azimuth_deg : float
        Azimuth of roller 1, deg.
    profile : {"straight", "crowned", "logarithmic"}
        Roller profile: none, a parabolic crown of ``crown_drop_m`` (m, at the ends), or the
        ISO/TS 16281 logarithmic profile of relief ``log_relief_m`` (m, default 0.00035·D_we).
    n_slices : int
        Slices per roller, 1 to 200.
    stiffness_law : {"iso16281", "palmgren"}
    roller_material, ring_material : str
        Material names.
    separator : SeparatorKeys or None
        ``[rows.separator]``: a cage or full complement (the rotation study's).
    """

    name: str
    count: int
    roller_diameter_m: float
    roller_length_m: float
    pitch_diameter_m: float
    axial_position_m: float = 0.0
    first_azimuth_deg: float = 0.0
    profile: Literal["straight", "crowned", "logarithmic"] = "straight"
    crown_drop_m: float | None = None
    log_relief_m: float | None = None
    n_slices: int = 20
    stiffness_law: Literal["iso16281", "palmgren"] = "iso16281"
    roller_material: str = "bearing_steel"
    ring_material: str = "bearing_steel"
    separator: SeparatorKeys | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        for key in ("count", "roller_diameter_m", "roller_length_m", "pitch_diameter_m", "n_slices"):
            if not getattr(self, key) > 0:
                raise ValueError(f"{key}: must be > 0, got {getattr(self, key)!r}")
        self._check_case_depth_below(self.roller_diameter_m, "roller_diameter_m")
        if self.n_slices > 200:
            raise ValueError(f"n_slices: at most 200, got {self.n_slices!r}")
        if self.profile == "crowned":
            if self.crown_drop_m is None or not self.crown_drop_m > 0.0:
                raise ValueError(f"crown_drop_m: a crowned roller needs its crown drop at the ends (> 0), "
                                 f"got {self.crown_drop_m!r}")
        elif self.crown_drop_m is not None:
            raise ValueError(f"crown_drop_m: only for profile = 'crowned', not {self.profile!r}")
        if self.log_relief_m is not None and self.profile != "logarithmic":
            raise ValueError(f"log_relief_m: only for profile = 'logarithmic', not {self.profile!r}")
        if self.log_relief_m is not None and not self.log_relief_m > 0.0:
            raise ValueError(f"log_relief_m: must be > 0, got {self.log_relief_m!r}")


def _roller_common(keys: _RollerKeys, ctx: RowContext) -> dict:
    _check_fits(ctx.where, keys.count, keys.roller_diameter_m, keys.pitch_diameter_m, "rollers")
    if keys.separator is not None:
        keys.separator.check_row(ctx.where, keys.count, keys.roller_diameter_m, keys.pitch_diameter_m, "rollers")
    return dict(name=keys.name, n_rollers=keys.count, roller_diameter_m=keys.roller_diameter_m,
                roller_length_m=keys.roller_length_m, pitch_diameter_m=keys.pitch_diameter_m,
                axial_position_m=keys.axial_position_m, n_slices=keys.n_slices,
                first_azimuth_rad=math.radians(keys.first_azimuth_deg), stiffness_law=keys.stiffness_law,
                profile="logarithmic" if keys.profile == "logarithmic" else "parabolic",
                crown_drop_m=keys.crown_drop_m or 0.0, log_relief_m=keys.log_relief_m,
                roller_material=ctx.material("roller_material", keys.roller_material),
                race_material=ctx.material("ring_material", keys.ring_material))


@dataclass(frozen=True)
class RadialRollerKeys(_RollerKeys):
    """A cylindrical roller row carrying radial load (roller axes parallel to the bearing axis);
    ``diametral_clearance_m`` (m, negative = preload): each roller has half of it."""

    diametral_clearance_m: float = 0.0


def _radial_roller(keys: RadialRollerKeys, ctx: RowContext) -> tuple:
    return (RollerRow(orientation="radial", load_sign=ctx.radial_sign, gap_m=0.5 * keys.diametral_clearance_m,
                      **_roller_common(keys, ctx)),)


@dataclass(frozen=True)
class ThrustRollerKeys(_RollerKeys):
    """A cylindrical roller row carrying axial load (roller axes radial); ``loaded_direction`` the
    push of the moving ring that loads it, ``axial_gap_m`` (m, negative = preload) each roller's gap."""

    loaded_direction: Direction = "+z"
    axial_gap_m: float = 0.0

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.roller_length_m >= self.pitch_diameter_m:
            raise ValueError(f"roller_length_m: must be shorter than pitch_diameter_m ({self.pitch_diameter_m!r}), "
                             f"got {self.roller_length_m!r}")


def _thrust_roller(keys: ThrustRollerKeys, ctx: RowContext) -> tuple:
    return (RollerRow(orientation="thrust", load_sign=_sign(keys.loaded_direction), gap_m=keys.axial_gap_m,
                      **_roller_common(keys, ctx)),)


@dataclass(frozen=True)
class CrossedRollerKeys(_RollerKeys):
    """A crossed cylindrical roller row: rollers alternating between the two diagonals of V-grooves.

    Attributes
    ----------
    contact_angle_deg : float
        Nominal contact angle α0, deg, in (0, 90); default 45 (90° V-grooves).
    diametral_clearance_m : float
        P_d of the unloaded concentric bearing, m (negative = preload): each roller has the gap
        (P_d/2)·cos α0 along its normal (:mod:`mbd_core.quasistatic.rows`).
    pattern : str
        ``"alternate"`` (roller 1 on +α0, roller 2 on −α0, …) or a string of ``+`` and ``-``
        repeated around the row.
    """

    contact_angle_deg: float = 45.0
    diametral_clearance_m: float = 0.0
    pattern: str = "alternate"

    def __post_init__(self) -> None:
        super().__post_init__()
        if not 0.0 < self.contact_angle_deg < 90.0:
            raise ValueError(f"contact_angle_deg: must lie in (0, 90), got {self.contact_angle_deg!r}")
        p = self.pattern
        if not (p == "alternate" or (p and set(p) <= {"+", "-"})):
            raise ValueError(f"pattern: must be \"alternate\" or a string of '+' and '-' (the diagonal of each "
                             f"roller, repeated around the row), got {p!r}")
        if -0.5 * self.diametral_clearance_m >= self.roller_diameter_m:
            raise ValueError(f"diametral_clearance_m: a preload of {-self.diametral_clearance_m:g} m exceeds the "
                             f"roller diameter ({self.roller_diameter_m:g} m)")


def _crossed_roller(keys: CrossedRollerKeys, ctx: RowContext) -> tuple:
    a0 = math.radians(keys.contact_angle_deg)
    return (RollerRow(orientation="crossed", load_sign=ctx.radial_sign, contact_angle_rad=a0, pattern=keys.pattern,
                      gap_m=0.5 * keys.diametral_clearance_m * math.cos(a0), **_roller_common(keys, ctx)),)
