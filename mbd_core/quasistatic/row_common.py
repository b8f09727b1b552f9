"""Checks and ball-contact constants shared by the row types of :mod:`.rows` and :mod:`.rows_four_point`."""

from __future__ import annotations

import math

import numpy as np

from foundation.validation import check_positive

from ..contact.hertz import ball_on_groove, series_stiffness

__all__ = ["BallRowGeometry", "check_finite", "check_count", "check_sign", "check_ball_row", "settled_clearance", "ball_pair_stiffness",
           "element_azimuths_rad"]


def check_finite(owner: str, **values: float) -> None:
    """Raise ValueError naming the first value that is not a finite number."""
    for name, v in values.items():
        if not (isinstance(v, (int, float)) and math.isfinite(v)):
            raise ValueError(f"{owner}: {name} must be a finite number, got {v!r}")


def check_count(owner: str, name: str, n: int, minimum: int = 1) -> None:
    if isinstance(n, bool) or not isinstance(n, int) or n < minimum:
        raise ValueError(f"{owner}: {name} must be an integer >= {minimum}, got {n!r}")


def check_sign(owner: str, name: str, s: int) -> None:
    if s not in (1, -1):
        raise ValueError(f"{owner}: {name} must be +1 or -1, got {s!r}")


def check_ball_row(who: str, row) -> None:
    """The checks every ball row shares (``row`` has the fields of :class:`.rows.BallRow`): ball count,
    sizes, conformities, which raceway moves, positions, stiffness override and that the balls fit
    on the pitch circle; ValueError naming the field otherwise."""
    check_count(who, "n_balls", row.n_balls)
    check_positive(who, ball_diameter_m=row.ball_diameter_m, pitch_diameter_m=row.pitch_diameter_m)
    if row.pitch_diameter_m <= row.ball_diameter_m:
        raise ValueError(f"{who}: pitch_diameter_m must exceed ball_diameter_m")
    for name in ("conformity_moving", "conformity_fixed"):
        f = getattr(row, name)
        if not (isinstance(f, (int, float)) and f > 0.5):
            raise ValueError(f"{who}: {name} must be > 0.5 (the ball must be smaller than its groove), got {f!r}")
    if row.moving_raceway not in ("inner", "outer"):
        raise ValueError(f"{who}: moving_raceway must be 'inner' or 'outer', got {row.moving_raceway!r}")
    check_finite(who, axial_position_m=row.axial_position_m, first_azimuth_rad=row.first_azimuth_rad)
    _check_offsets(who, row.azimuth_offsets_rad, row.n_balls)
    if row.stiffness_N_per_m1p5 is not None:
        check_positive(who, stiffness_N_per_m1p5=row.stiffness_N_per_m1p5)
    if row.n_balls * row.ball_diameter_m > math.pi * row.pitch_diameter_m * (1 + 1e-9):
        raise ValueError(f"{who}: {row.n_balls} balls of {row.ball_diameter_m} m do not fit on the pitch "
                         f"circle of {row.pitch_diameter_m} m")


def settled_clearance(who: str, diametral_m: float | None, radial_m: float | None, A_m: float,
                      contact_angle_rad: float) -> tuple[float, float]:
    """(P_d, P_d/2) from whichever of the diametral and radial clearance is given, m.

    Both None: no clearance. Both given: they must agree (P_d = 2·radial). The radial clearance
    must stay below A·cos α0 (more play and the ball leaves the groove before it touches), a
    preload (negative) below A = (f_m + f_f − 1)·D; ValueError naming the field otherwise.
    """
    d, r = diametral_m, radial_m
    for name, v in (("diametral_clearance_m", d), ("radial_clearance_m", r)):
        if v is not None:
            check_finite(who, **{name: v})
    if d is None and r is None:
        d = r = 0.0
    elif d is None:
        d = 2.0 * r
    elif r is None:
        r = 0.5 * d
    elif abs(d - 2.0 * r) > 1e-12 * max(abs(d), 1e-12):
        raise ValueError(
            f"{who}: diametral_clearance_m ({d!r}) and radial_clearance_m ({r!r}) disagree "
            "(P_d = 2·radial); give one of them, the other as None"
        )
    if r >= A_m * math.cos(contact_angle_rad) and r > 0.0:
        raise ValueError(
            f"{who}: radial_clearance_m = {r!r} must be below A·cos α0 = {A_m * math.cos(contact_angle_rad):.6g} m "
            "(A = (f_m + f_f − 1)·D): with more play the ball leaves the groove before it touches"
        )
    if -r >= A_m:
        raise ValueError(f"{who}: a preload (negative clearance) of {d!r} m exceeds the groove geometry "
                         f"(A = {A_m:.6g} m)")
    return float(d), float(r)


def _check_offsets(who: str, offsets_rad, n: int) -> None:
    """Per-element offsets from the even spacing: none, or one finite value per element, each less
    than half a spacing (π/n), so the elements keep their order round the row."""
    if len(offsets_rad) == 0:
        return
    o = np.asarray(offsets_rad, dtype=float)
    if o.shape != (n,):
        raise ValueError(f"{who}: azimuth_offsets_rad must hold one value per ball ({n}), got {o.shape[0]}")
    if not np.all(np.isfinite(o)) or np.abs(o).max() >= math.pi / n:
        raise ValueError(f"{who}: azimuth_offsets_rad must be finite and below half the spacing "
                         f"(π/{n} = {math.pi / n:.6g} rad) each, got up to {np.abs(o).max():.6g}")


def element_azimuths_rad(n: int, first_rad: float, offsets_rad=()) -> np.ndarray:
    """Azimuths ψ_j = ψ_0 + 2πj/n (+ the per-element offsets, if any) of the n elements of a row, rad."""
    psi = first_rad + 2.0 * np.pi * np.arange(n) / n
    return psi + np.asarray(offsets_rad, dtype=float) if len(offsets_rad) else psi


def ball_mass_kg(diameter_m: float, density_kg_m3: float) -> float:
    """Mass of a ball, kg."""
    return density_kg_m3 * math.pi * diameter_m**3 / 6.0


def ball_contact_stiffnesses(row) -> tuple[float, float]:
    """(K_moving, K_fixed) of Q = K·δ^1.5 at the moving and the fixed groove of ``row`` (Hertz
    constants at the nominal contact angle; Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed.,
    ch. 7), N/m^1.5. ``row`` has the fields of :class:`.rows.BallRow`."""
    fixed = "outer" if row.moving_raceway == "inner" else "inner"
    common = (row.ball_diameter_m,)
    k_m = ball_on_groove(*common, row.conformity_moving, row.pitch_diameter_m, row.contact_angle_rad,
                         row.moving_raceway, row.ball_material, row.race_material)
    k_f = ball_on_groove(*common, row.conformity_fixed, row.pitch_diameter_m, row.contact_angle_rad,
                         fixed, row.ball_material, row.race_material)
    return k_m.stiffness_N_per_m1p5, k_f.stiffness_N_per_m1p5


def ball_pair_stiffness(row) -> float:
    """K of Q = K·δ^1.5 of a ball between the moving and the fixed groove of ``row``: its two
    contacts (:func:`ball_contact_stiffnesses`) in series, N/m^1.5."""
    return series_stiffness(*ball_contact_stiffnesses(row))


class BallRowGeometry:
    """Groove geometry every ball row derives from its fields (those of :class:`.rows.BallRow`):
    a base of the ball row dataclasses."""

    #: a row whose dataclass has no ``azimuth_offsets_rad`` field keeps its balls evenly spaced
    azimuth_offsets_rad: tuple = ()

    @property
    def radial_sign(self) -> int:
        """+1 if moving the moving ring outwards loads the row (it carries the inner raceway)."""
        return 1 if self.moving_raceway == "inner" else -1

    @property
    def curvature_centre_distance_m(self) -> float:
        """A = (f_m + f_f − 1)·D, m (of each diagonal of a four-point row)."""
        return (self.conformity_moving + self.conformity_fixed - 1.0) * self.ball_diameter_m

    @property
    def gap_m(self) -> float:
        """Radial clearance P_d/2, m."""
        return self.radial_clearance_m

    @property
    def free_contact_angle_rad(self) -> float:
        """Contact angle of the unloaded ball pushed axially until it touches, rad.

        From the curvature-centre geometry: the radial and axial components of s0 with |s| = A
        (Harris & Kotzalas ch. 2 for α0 = 0: cos α_f = 1 − P_d/(2A)). Without clearance α0.
        """
        A = self.curvature_centre_distance_m
        s_r = A * math.cos(self.contact_angle_rad) - self.radial_clearance_m
        return math.acos(max(-1.0, min(1.0, s_r / A)))

    @property
    def n_elements(self) -> int:
        return self.n_balls

    def azimuths_rad(self) -> np.ndarray:
        """(Z,) ball azimuths, rad: evenly spaced from ``first_azimuth_rad``, plus the row's offsets."""
        return element_azimuths_rad(self.n_balls, self.first_azimuth_rad, self.azimuth_offsets_rad)

    def contact_stiffness(self) -> float:
        """K of Q = K·δ^1.5 of one ball (of one diagonal of a four-point ball): moving and fixed
        contacts in series, N/m^1.5; the row's override if given."""
        if self.stiffness_N_per_m1p5 is not None:
            return self.stiffness_N_per_m1p5
        return ball_pair_stiffness(self)
