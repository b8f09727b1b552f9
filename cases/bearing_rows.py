"""Row types of bearing description files: one registry entry per type, its keys and its builder.

Each ``[[rows]]`` table of a description file (:mod:`cases.bearing_file`, format reference in
``cases/bearings/README.md``) names its ``type``; :data:`ROW_TYPES` maps that name to the
frozen dataclass of the table's keys (read by :func:`cases.config.from_mapping`, which names
unknown and ill-typed keys) and to the builder that turns the keys into rows of
:mod:`mbd_core.quasistatic`. Adding a type is one entry.

Engineers give the conformities of the inner and the outer ring (groove radius / ball diameter);
the rows take them for the moving and the fixed ring, by ``[bearing] moving_ring``. An axial
direction ``loaded_direction = "+z"`` says that pushing the moving ring towards +z loads the row.

Double-row angular-contact arrangements (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed.,
ch. 1): the contact lines of a back-to-back (O) pair meet the axis outside the two rows, those of
a face-to-face (X) pair between them, and a tandem pair carries axial load in one direction with
both rows. A contact line through the ball centre along the direction d̂ = s_r·cos α·e_r +
s_z·sin α·e_z (:mod:`mbd_core.quasistatic.rows`) meets the axis at z_ball − s_r·s_z·(d_m/2)·tan α,
so a back-to-back row on the +z side takes s_z = −s_r, a face-to-face one s_z = +s_r.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from mbd_core.quasistatic import BallRow, FourPointRow

from .bearing_roller_rows import (CrossedRollerKeys, RadialRollerKeys, ThrustRollerKeys, _crossed_roller,
                                  _radial_roller, _thrust_roller)
from .config import CaseError
from .row_keys import (CORE_STRENGTH_KEYS, MAX_ELEMENTS, Direction, RowContext, SeparatorKeys, _CaseDepthKeys,
                       _check_fits, _sign)

__all__ = ["ROW_TYPES", "RowType", "RowContext", "build_rows", "MAX_ELEMENTS", "CORE_STRENGTH_KEYS"]


# --- ball rows -----------------------------------------------------------------------------------
@dataclass(frozen=True)
class _BallKeys(_CaseDepthKeys):
    """Keys every ball row has (format reference: ``cases/bearings/README.md``); and the case
    hardening keys of :class:`_CaseDepthKeys`.

    Attributes
    ----------
    name : str
        Row name, unique in the bearing.
    count : int
        Balls Z; Z·D ≤ π·d_m.
    ball_diameter_m, pitch_diameter_m : float
        D and d_m, m.
    conformity_inner, conformity_outer : float
        Groove radius / D of the inner and the outer ring, > 0.5.
    diametral_clearance_m : float
        P_d of the unloaded concentric bearing, m; negative = preload (|P_d|/2 < (f_i + f_o − 1)·D).
    axial_position_m : float
        z of the ball centres (of the pair's middle for double rows), m.
    first_azimuth_deg : float
        Azimuth of ball 1, deg.
    ball_material, ring_material : str
        Material names (``[materials.NAME]`` or ``"bearing_steel"``).
    separator : SeparatorKeys or None
        ``[rows.separator]``: cage, spacer balls or full complement (the rotation study's).
    """

    name: str
    count: int
    ball_diameter_m: float
    pitch_diameter_m: float
    conformity_inner: float
    conformity_outer: float
    diametral_clearance_m: float = 0.0
    axial_position_m: float = 0.0
    first_azimuth_deg: float = 0.0
    ball_material: str = "bearing_steel"
    ring_material: str = "bearing_steel"
    separator: SeparatorKeys | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        for key in ("count", "ball_diameter_m", "pitch_diameter_m"):
            if not getattr(self, key) > 0:
                raise ValueError(f"{key}: must be > 0, got {getattr(self, key)!r}")
        self._check_case_depth_below(self.ball_diameter_m, "ball_diameter_m")
        if self.pitch_diameter_m <= self.ball_diameter_m:
            raise ValueError(f"pitch_diameter_m: must exceed ball_diameter_m ({self.ball_diameter_m!r}), "
                             f"got {self.pitch_diameter_m!r}")
        for key in ("conformity_inner", "conformity_outer"):
            f = getattr(self, key)
            if not f > 0.5:
                raise ValueError(f"{key}: must be > 0.5 (groove radius / ball diameter: the ball must be "
                                 f"smaller than its groove), got {f!r}")
        A = (self.conformity_inner + self.conformity_outer - 1.0) * self.ball_diameter_m
        if -0.5 * self.diametral_clearance_m >= A:
            raise ValueError(f"diametral_clearance_m: a preload of {-self.diametral_clearance_m:g} m exceeds what the "
                             f"balls' approach can take: the radial preload must stay below "
                             f"A = (f_i + f_o − 1)·D = {A:.6g} m")


def _conformities(keys: _BallKeys, ctx: RowContext) -> dict:
    inner, outer = keys.conformity_inner, keys.conformity_outer
    moving, fixed = (inner, outer) if ctx.moving_ring == "inner" else (outer, inner)
    return dict(conformity_moving=moving, conformity_fixed=fixed, moving_raceway=ctx.moving_ring)


def _ball_common(keys: _BallKeys, ctx: RowContext) -> dict:
    _check_fits(ctx.where, keys.count, keys.ball_diameter_m, keys.pitch_diameter_m, "balls")
    if keys.separator is not None:
        keys.separator.check_row(ctx.where, keys.count, keys.ball_diameter_m, keys.pitch_diameter_m, "balls")
    return dict(name=keys.name, n_balls=keys.count, ball_diameter_m=keys.ball_diameter_m,
                pitch_diameter_m=keys.pitch_diameter_m, diametral_clearance_m=keys.diametral_clearance_m,
                axial_position_m=keys.axial_position_m, first_azimuth_rad=math.radians(keys.first_azimuth_deg),
                ball_material=ctx.material("ball_material", keys.ball_material),
                race_material=ctx.material("ring_material", keys.ring_material), **_conformities(keys, ctx))


@dataclass(frozen=True)
class DeepGrooveKeys(_BallKeys):
    """A deep-groove ball row: nominal contact angle 0."""


def _deep_groove(keys: DeepGrooveKeys, ctx: RowContext) -> tuple:
    return (BallRow(contact_angle_rad=0.0, axial_sign=1, **_ball_common(keys, ctx)),)


@dataclass(frozen=True)
class AngularContactKeys(_BallKeys):
    """An angular-contact ball row, single or double (two rows ``row_spacing_m`` apart about
    ``axial_position_m``).

    Attributes
    ----------
    contact_angle_deg : float
        Nominal contact angle α0, deg, in (0, 90); required.
    loaded_direction : {"+z", "-z"} or None
        Push of the moving ring that loads the row (single, tandem); not with back_to_back/face_to_face.
    arrangement : {"single", "back_to_back", "face_to_face", "tandem"}
    row_spacing_m : float or None
        Axial distance of the two rows of a double arrangement, m.
    """

    contact_angle_deg: float | None = None
    loaded_direction: Direction | None = None
    arrangement: Literal["single", "back_to_back", "face_to_face", "tandem"] = "single"
    row_spacing_m: float | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.contact_angle_deg is None:
            raise ValueError("contact_angle_deg: missing key (the nominal contact angle, in (0, 90) deg)")
        if not 0.0 < self.contact_angle_deg < 90.0:
            raise ValueError(f"contact_angle_deg: must lie in (0, 90), got {self.contact_angle_deg!r}")
        double = self.arrangement != "single"
        if double and not (self.row_spacing_m is not None and self.row_spacing_m > 0.0):
            raise ValueError(f"row_spacing_m: arrangement {self.arrangement!r} needs the axial distance of its "
                             f"two rows (> 0), got {self.row_spacing_m!r}")
        if not double and self.row_spacing_m is not None:
            raise ValueError("row_spacing_m: only for the double-row arrangements (back_to_back, face_to_face, tandem)")
        if self.arrangement in ("back_to_back", "face_to_face"):
            if self.loaded_direction is not None:
                raise ValueError(f"loaded_direction: not used with arrangement {self.arrangement!r} "
                                 "(its two rows are loaded in opposite directions)")
        elif self.loaded_direction is None:
            raise ValueError(f"loaded_direction: required for arrangement {self.arrangement!r} ('+z' or '-z')")


def _angular_contact(keys: AngularContactKeys, ctx: RowContext) -> tuple:
    common = _ball_common(keys, ctx)
    common["contact_angle_rad"] = math.radians(keys.contact_angle_deg)
    if keys.arrangement == "single":
        return (BallRow(axial_sign=_sign(keys.loaded_direction), **common),)
    half = 0.5 * keys.row_spacing_m
    rows = []
    for k, side in enumerate((-1, 1)):  # row 1 on the −z side, row 2 on the +z side
        if keys.arrangement == "tandem":
            s_z = _sign(keys.loaded_direction)
        else:  # pressure centres outside (O) or between (X) the rows, see the module docstring
            s_z = -ctx.radial_sign * side if keys.arrangement == "back_to_back" else ctx.radial_sign * side
        rows.append(BallRow(**{**common, "name": f"{keys.name} ({k + 1})",
                               "axial_position_m": keys.axial_position_m + side * half}, axial_sign=s_z))
    return tuple(rows)


@dataclass(frozen=True)
class ThrustBallKeys(_BallKeys):
    """A thrust ball row: nominal contact angle 90°; the clearance must be zero or a preload.
    ``loaded_direction`` ("+z" or "-z"): the push of the moving ring that loads it."""

    loaded_direction: Direction = "+z"

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.diametral_clearance_m > 0.0:
            raise ValueError("diametral_clearance_m: a thrust ball row has no radial play; give 0 "
                             f"(or a preload, < 0), got {self.diametral_clearance_m!r}")


def _thrust_ball(keys: ThrustBallKeys, ctx: RowContext) -> tuple:
    return (BallRow(contact_angle_rad=math.pi / 2, axial_sign=_sign(keys.loaded_direction), **_ball_common(keys, ctx)),)


@dataclass(frozen=True)
class FourPointKeys(_BallKeys):
    """A four-point contact (gothic-arch) ball row: both diagonals at ±``contact_angle_deg`` (deg,
    default 45), carried up to the groove shoulder at ``shoulder_angle_deg`` (deg, default 70)."""

    contact_angle_deg: float = 45.0
    shoulder_angle_deg: float = 70.0

    def __post_init__(self) -> None:
        super().__post_init__()
        if not 0.0 < self.shoulder_angle_deg <= 90.0:
            raise ValueError(f"shoulder_angle_deg: must lie in (0, 90], got {self.shoulder_angle_deg!r}")
        if not 0.0 < self.contact_angle_deg < self.shoulder_angle_deg:
            raise ValueError(f"contact_angle_deg: must lie between 0 and shoulder_angle_deg "
                             f"({self.shoulder_angle_deg!r}), got {self.contact_angle_deg!r}")


def _four_point_kwargs(keys: FourPointKeys, ctx: RowContext) -> dict:
    return dict(contact_angle_rad=math.radians(keys.contact_angle_deg),
                shoulder_angle_rad=math.radians(keys.shoulder_angle_deg), **_ball_common(keys, ctx))


def _four_point(keys: FourPointKeys, ctx: RowContext) -> tuple:
    return (FourPointRow(**_four_point_kwargs(keys, ctx)),)


@dataclass(frozen=True)
class DoubleFourPointKeys(FourPointKeys):
    """Two equal four-point rows ``row_spacing_m`` (m, required) apart about ``axial_position_m``."""

    row_spacing_m: float | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.row_spacing_m is None or not self.row_spacing_m > 0.0:
            raise ValueError(f"row_spacing_m: the axial distance of the two rows must be > 0 (required), "
                             f"got {self.row_spacing_m!r}")


def _double_four_point(keys: DoubleFourPointKeys, ctx: RowContext) -> tuple:
    kw = _four_point_kwargs(keys, ctx)
    half = 0.5 * keys.row_spacing_m
    return tuple(FourPointRow(**{**kw, "name": f"{keys.name} ({k + 1})",
                                 "axial_position_m": keys.axial_position_m + side * half})
                 for k, side in enumerate((-1, 1)))


# --- roller rows ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class RowType:
    """One registry entry: the dataclass of the row table's keys and the builder of its rows."""

    keys: type
    build: Callable[[object, RowContext], tuple]
    summary: str


#: Row types of description files: ``type`` key → keys and builder. Adding a type is one entry.
ROW_TYPES: dict[str, RowType] = {
    "deep_groove": RowType(DeepGrooveKeys, _deep_groove, "deep-groove ball row, α0 = 0"),
    "angular_contact": RowType(AngularContactKeys, _angular_contact,
                               "angular-contact ball row, single or double (back_to_back, face_to_face, tandem)"),
    "thrust_ball": RowType(ThrustBallKeys, _thrust_ball, "thrust ball row, α0 = 90°"),
    "four_point": RowType(FourPointKeys, _four_point, "four-point contact (gothic-arch) ball row"),
    "double_four_point": RowType(DoubleFourPointKeys, _double_four_point, "two four-point rows"),
    "radial_roller": RowType(RadialRollerKeys, _radial_roller, "cylindrical roller row, radial"),
    "thrust_roller": RowType(ThrustRollerKeys, _thrust_roller, "cylindrical roller row, axial"),
    "crossed_roller": RowType(CrossedRollerKeys, _crossed_roller,
                              "crossed cylindrical roller row (V-grooves, rollers alternating ±α0)"),
}


def _row_message(message: str) -> str:
    """A row dataclass's message without its ``ball row 'x': `` owner (the key path replaces it)."""
    head, sep, rest = message.partition(": ")
    return rest if sep and " row " in f" {head}" else message


#: fields of the row dataclasses → the file key that sets them
_FILE_KEYS = {"n_balls": "count", "n_rollers": "count", "radial_clearance_m": "diametral_clearance_m",
              "diametral_clearance_m": "diametral_clearance_m", "gap_m": "diametral_clearance_m",
              "contact_angle": "contact_angle_deg", "shoulder_angle": "shoulder_angle_deg", "pattern": "pattern"}


def build_rows(keys: object, row_type: RowType, ctx: RowContext) -> tuple:
    """The rows of one ``[[rows]]`` table; a row dataclass's ValueError comes back naming the row's key path."""
    try:
        return row_type.build(keys, ctx)
    except CaseError:
        raise
    except (ValueError, TypeError) as exc:
        message = _row_message(str(exc))
        key = _FILE_KEYS.get(message.split(" ", 1)[0])
        raise CaseError(f"{ctx.where}.{key}: {message}" if key else f"{ctx.where}: {message}") from exc

