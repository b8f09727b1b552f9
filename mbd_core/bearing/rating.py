"""ISO 281:2007 basic dynamic load rating and basic rating life.

Basic dynamic load rating (ISO 281:2007, clauses 6.1 and 7.1; Harris & Kotzalas, *Rolling
Bearing Analysis*, 5th ed., vol. 2, ch. 8). ISO writes the formulas in newton with lengths in
millimetres; the functions here take SI lengths (m) and convert them once::

    radial ball     C_r = b_m f_c (i cos α)^0.7 Z^(2/3) D_w^1.8              D_w ≤ 25.4 mm
                    C_r = 3.647 b_m f_c (i cos α)^0.7 Z^(2/3) D_w^1.4        D_w > 25.4 mm
    thrust ball     C_a = b_m f_c Z^(2/3) D_w^1.8                    α = 90°, D_w ≤ 25.4 mm
                    C_a = 3.647 b_m f_c Z^(2/3) D_w^1.4              α = 90°, D_w > 25.4 mm
                    C_a = b_m f_c (cos α)^0.7 tan α Z^(2/3) D_w^1.8          α ≠ 90°, ≤ 25.4 mm
                    C_a = 3.647 b_m f_c (cos α)^0.7 tan α Z^(2/3) D_w^1.4    α ≠ 90°, > 25.4 mm
    radial roller   C_r = b_m f_c (i L_we cos α)^(7/9) Z^(3/4) D_we^(29/27)
    thrust roller   C_a = b_m f_c L_we^(7/9) Z^(3/4) D_we^(29/27)                    α = 90°
                    C_a = b_m f_c (L_we cos α)^(7/9) tan α Z^(3/4) D_we^(29/27)      α ≠ 90°

with D_w the ball diameter, D_we the roller diameter, L_we the effective roller length (mm),
Z the number of elements per row (radial) or carrying load in one direction (thrust), i the
number of rows, α the nominal contact angle. The constant 3.647 ≈ 25.4^0.4 makes the two ball
formulas meet at D_w = 25.4 mm. ISO 281 calls a bearing radial for 0° ≤ α ≤ 45° and thrust for
45° < α ≤ 90°; these ranges are enforced. Thrust bearings are rated here for a single row
only: the ISO 281 rules that combine several thrust rows are not implemented.

The factor f_c depends on the geometry (D_w cos α / D_pw) and the bearing type and must be
taken from ISO 281:2007 Tables 2–5 (ball) or 7–8 (roller); those tables are not implemented
here, f_c is a required input. The rating factor b_m for contemporary material and
manufacturing quality (ISO 281:2007, Table 1) defaults to 1.3 (radial and thrust ball),
1.1 (radial roller: cylindrical, tapered, needle) and 1.0 (thrust roller: cylindrical,
needle); other types (radial filling-slot ball 1.1, spherical roller 1.15, thrust tapered and
spherical roller 1.15, drawn-cup needle 1.0) need an explicit ``bm``.

Basic rating life (ISO 281:2007, clauses 6.2 and 7.2), in millions of revolutions::

    L10 = (C / P)^p,   p = 3 (ball) or 10/3 (roller);   L10h = 10^6 L10 / (60 n)

with the dynamic equivalent load P = X F_r + Y F_a (X, Y from the ISO tables, given by the
user).
"""

from __future__ import annotations

import math
import numbers
from types import MappingProxyType
from typing import Literal

from foundation.validation import check_positive


__all__ = [
    "BM_DEFAULTS",
    "radial_ball_rating_N",
    "thrust_ball_rating_N",
    "radial_roller_rating_N",
    "thrust_roller_rating_N",
    "life_exponent",
    "basic_rating_life_Mrev",
    "rating_life_hours",
    "equivalent_load_N",
]

#: ISO 281:2007 Table 1 rating factors b_m used as defaults.
BM_DEFAULTS = MappingProxyType(
    {"radial_ball": 1.3, "thrust_ball": 1.3, "radial_roller": 1.1, "thrust_roller": 1.0}
)

#: Ball diameter (mm) above which ISO 281 switches to the D_w^1.4 ball formula.
_DW_LIMIT_MM = 25.4
#: ISO 281 constant of the large-ball formula, ≈ 25.4^0.4.
_LARGE_BALL_CONST = 3.647

ElementType = Literal["ball", "roller"]


# --------------------------------------------------------------------------- validation
def _check_count(**values: int) -> None:
    for name, v in values.items():
        if isinstance(v, bool) or not isinstance(v, numbers.Integral) or v < 1:
            raise ValueError(f"{name} must be an integer >= 1, got {v!r}")


def _check_radial_angle(contact_angle_rad: float) -> None:
    if not (math.isfinite(contact_angle_rad) and 0.0 <= contact_angle_rad <= math.pi / 4 + 1e-12):
        raise ValueError(
            "contact_angle_rad of a radial bearing must lie in [0, 45] deg (ISO 281), "
            f"got {math.degrees(contact_angle_rad)} deg"
        )


def _is_pure_thrust(contact_angle_rad: float) -> bool:
    """Check a thrust contact angle (45° < α ≤ 90°) and say whether it is 90°."""
    if not (
        math.isfinite(contact_angle_rad) and math.pi / 4 < contact_angle_rad <= math.pi / 2 + 1e-12
    ):
        raise ValueError(
            "contact_angle_rad of a thrust bearing must lie in (45, 90] deg (ISO 281), "
            f"got {math.degrees(contact_angle_rad)} deg"
        )
    return abs(contact_angle_rad - math.pi / 2) <= 1e-12


def _ball_size_term(ball_diameter_mm: float) -> float:
    """D_w^1.8 for D_w ≤ 25.4 mm, 3.647·D_w^1.4 above (ISO 281:2007, 6.1.1 and 7.1.1)."""
    if ball_diameter_mm <= _DW_LIMIT_MM:
        return ball_diameter_mm**1.8
    return _LARGE_BALL_CONST * ball_diameter_mm**1.4


# --------------------------------------------------------------------------- load ratings
def radial_ball_rating_N(
    ball_diameter_m: float,
    n_balls: int,
    contact_angle_rad: float,
    f_c: float,
    n_rows: int = 1,
    bm: float = BM_DEFAULTS["radial_ball"],
) -> float:
    """Basic dynamic radial load rating C_r of a radial ball bearing, N (ISO 281:2007, 6.1.1).

    C_r = b_m f_c (i cos α)^0.7 Z^(2/3) D_w^1.8 (D_w ≤ 25.4 mm) or
    3.647 b_m f_c (i cos α)^0.7 Z^(2/3) D_w^1.4 (D_w > 25.4 mm), D_w in mm.

    Parameters
    ----------
    ball_diameter_m : float
        Ball diameter D_w, m.
    n_balls : int
        Number of balls per row Z, ≥ 1.
    contact_angle_rad : float
        Nominal contact angle α, rad, 0 ≤ α ≤ π/4.
    f_c : float
        Geometry/material factor from ISO 281:2007 Table 2 (not implemented here), > 0.
    n_rows : int
        Number of ball rows i, ≥ 1.
    bm : float
        Rating factor b_m (ISO 281:2007 Table 1), default 1.3.
    """
    check_positive(ball_diameter_m=ball_diameter_m, f_c=f_c, bm=bm)
    _check_count(n_balls=n_balls, n_rows=n_rows)
    _check_radial_angle(contact_angle_rad)
    dw_mm = 1e3 * ball_diameter_m
    return (
        bm * f_c * (n_rows * math.cos(contact_angle_rad)) ** 0.7 * n_balls ** (2.0 / 3.0)
        * _ball_size_term(dw_mm)
    )


def thrust_ball_rating_N(
    ball_diameter_m: float,
    n_balls: int,
    contact_angle_rad: float,
    f_c: float,
    bm: float = BM_DEFAULTS["thrust_ball"],
) -> float:
    """Basic dynamic axial load rating C_a of a single-row thrust ball bearing, N (ISO 281, 7.1.1).

    α = 90°: C_a = b_m f_c Z^(2/3) D_w^1.8, or 3.647 b_m f_c Z^(2/3) D_w^1.4 for D_w > 25.4 mm;
    α ≠ 90°: the same times (cos α)^0.7 tan α. D_w in mm.

    Parameters
    ----------
    ball_diameter_m : float
        Ball diameter D_w, m.
    n_balls : int
        Number of balls carrying load in one direction Z, ≥ 1 (single row).
    contact_angle_rad : float
        Nominal contact angle α, rad, π/4 < α ≤ π/2.
    f_c : float
        Factor from ISO 281:2007 Table 3 (not implemented here), > 0.
    bm : float
        Rating factor b_m (ISO 281:2007 Table 1), default 1.3.
    """
    check_positive(ball_diameter_m=ball_diameter_m, f_c=f_c, bm=bm)
    _check_count(n_balls=n_balls)
    pure = _is_pure_thrust(contact_angle_rad)
    angle_term = 1.0 if pure else math.cos(contact_angle_rad) ** 0.7 * math.tan(contact_angle_rad)
    dw_mm = 1e3 * ball_diameter_m
    return bm * f_c * angle_term * n_balls ** (2.0 / 3.0) * _ball_size_term(dw_mm)


def radial_roller_rating_N(
    roller_diameter_m: float,
    roller_effective_length_m: float,
    n_rollers: int,
    contact_angle_rad: float,
    f_c: float,
    n_rows: int = 1,
    bm: float = BM_DEFAULTS["radial_roller"],
) -> float:
    """Basic dynamic radial load rating C_r of a radial roller bearing, N (ISO 281:2007, 6.1.2).

    C_r = b_m f_c (i L_we cos α)^(7/9) Z^(3/4) D_we^(29/27), lengths in mm.

    Parameters
    ----------
    roller_diameter_m : float
        Roller diameter D_we, m (mean diameter of a tapered roller).
    roller_effective_length_m : float
        Effective roller length L_we, m.
    n_rollers : int
        Number of rollers per row Z, ≥ 1.
    contact_angle_rad : float
        Nominal contact angle α, rad, 0 ≤ α ≤ π/4.
    f_c : float
        Factor from ISO 281:2007 Table 7 (not implemented here), > 0.
    n_rows : int
        Number of roller rows i, ≥ 1.
    bm : float
        Rating factor b_m (ISO 281:2007 Table 1), default 1.1.
    """
    check_positive(
        roller_diameter_m=roller_diameter_m,
        roller_effective_length_m=roller_effective_length_m,
        f_c=f_c,
        bm=bm,
    )
    _check_count(n_rollers=n_rollers, n_rows=n_rows)
    _check_radial_angle(contact_angle_rad)
    dwe_mm, lwe_mm = 1e3 * roller_diameter_m, 1e3 * roller_effective_length_m
    return (
        bm * f_c * (n_rows * lwe_mm * math.cos(contact_angle_rad)) ** (7.0 / 9.0)
        * n_rollers**0.75 * dwe_mm ** (29.0 / 27.0)
    )


def thrust_roller_rating_N(
    roller_diameter_m: float,
    roller_effective_length_m: float,
    n_rollers: int,
    contact_angle_rad: float,
    f_c: float,
    bm: float = BM_DEFAULTS["thrust_roller"],
) -> float:
    """Basic dynamic axial load rating C_a of a single-row thrust roller bearing, N (ISO 281, 7.1.2).

    α = 90°: C_a = b_m f_c L_we^(7/9) Z^(3/4) D_we^(29/27);
    α ≠ 90°: C_a = b_m f_c (L_we cos α)^(7/9) tan α Z^(3/4) D_we^(29/27); lengths in mm.

    Parameters
    ----------
    roller_diameter_m : float
        Roller diameter D_we, m.
    roller_effective_length_m : float
        Effective roller length L_we, m.
    n_rollers : int
        Number of rollers carrying load in one direction Z, ≥ 1 (single row).
    contact_angle_rad : float
        Nominal contact angle α, rad, π/4 < α ≤ π/2.
    f_c : float
        Factor from ISO 281:2007 Table 8 (not implemented here), > 0.
    bm : float
        Rating factor b_m (ISO 281:2007 Table 1), default 1.0.
    """
    check_positive(
        roller_diameter_m=roller_diameter_m,
        roller_effective_length_m=roller_effective_length_m,
        f_c=f_c,
        bm=bm,
    )
    _check_count(n_rollers=n_rollers)
    pure = _is_pure_thrust(contact_angle_rad)
    dwe_mm, lwe_mm = 1e3 * roller_diameter_m, 1e3 * roller_effective_length_m
    if pure:
        length_angle_term = lwe_mm ** (7.0 / 9.0)
    else:
        length_angle_term = (lwe_mm * math.cos(contact_angle_rad)) ** (7.0 / 9.0) * math.tan(
            contact_angle_rad
        )
    return bm * f_c * length_angle_term * n_rollers**0.75 * dwe_mm ** (29.0 / 27.0)


# --------------------------------------------------------------------------- rating life
def life_exponent(element: ElementType) -> float:
    """Life exponent p of ISO 281: 3 for ball bearings, 10/3 for roller bearings."""
    if element == "ball":
        return 3.0
    if element == "roller":
        return 10.0 / 3.0
    raise ValueError(f"element must be 'ball' or 'roller', got {element!r}")


def basic_rating_life_Mrev(
    dynamic_load_rating_N: float, equivalent_load_N: float, element: ElementType
) -> float:
    """Basic rating life L10 = (C/P)^p, millions of revolutions (ISO 281:2007, 6.2 and 7.2).

    Parameters
    ----------
    dynamic_load_rating_N : float
        Basic dynamic load rating C (C_r or C_a), N.
    equivalent_load_N : float
        Dynamic equivalent load P (P_r or P_a), N, > 0.
    element : {"ball", "roller"}
        Rolling-element type, selects p = 3 or 10/3.
    """
    check_positive(dynamic_load_rating_N=dynamic_load_rating_N, equivalent_load_N=equivalent_load_N)
    return (dynamic_load_rating_N / equivalent_load_N) ** life_exponent(element)


def rating_life_hours(life_Mrev: float, speed_rpm: float) -> float:
    """Life in operating hours at a constant speed, L_h = 10^6 L / (60 n).

    Parameters
    ----------
    life_Mrev : float
        Life in millions of revolutions (≥ 0).
    speed_rpm : float
        Rotational speed n of the rotating ring relative to the other, r/min, > 0.
    """
    if not (math.isfinite(life_Mrev) and life_Mrev >= 0.0):
        raise ValueError(f"life_Mrev must be a finite number >= 0, got {life_Mrev!r}")
    check_positive(speed_rpm=speed_rpm)
    return 1e6 * life_Mrev / (60.0 * speed_rpm)


def equivalent_load_N(radial_load_N: float, axial_load_N: float, X: float, Y: float) -> float:
    """Dynamic equivalent load P = X·F_r + Y·F_a, N (ISO 281:2007, 6.2.2 and 7.2.2).

    Parameters
    ----------
    radial_load_N, axial_load_N : float
        Radial load F_r and axial load F_a, N (≥ 0).
    X, Y : float
        Radial and axial load factors from the ISO 281 tables (≥ 0), given by the user.
    """
    for name, v in (("radial_load_N", radial_load_N), ("axial_load_N", axial_load_N), ("X", X), ("Y", Y)):
        if not (math.isfinite(v) and v >= 0.0):
            raise ValueError(f"{name} must be a finite number >= 0, got {v!r}")
    return X * radial_load_N + Y * axial_load_N
