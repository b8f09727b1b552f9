"""Rows of rolling elements between a fixed and a moving ring, for the quasi-static solver.

Frame: z along the bearing axis, the fixed ring at rest, the moving ring displaced by
q = (x, y, z, θx, θy) (m, rad; small rotations about its reference point, the origin).
An element sits at azimuth ψ (from +x towards +y); e_r, e_t, e_z are the radial, tangential and
axial unit vectors there.

Ball rows (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., ch. 2, 7 and 9, "rigid rings";
ISO/TS 16281:2008): the groove curvature centres of the two rings lie on a line through the ball
centre, A = (f_m + f_f − 1)·D apart when the ball touches both grooves unloaded. Without
clearance, at q = 0 the moving ring's centre sits A from the fixed ring's along
d̂ = (s_r·cos α0)·e_r + (s_z·sin α0)·e_z, the direction in which the moving ring must move to
compress the ball (s_r = +1 when the moving ring carries the inner raceway, s_z = ``axial_sign``).
A diametral clearance P_d moves the grooves apart radially by P_d/2 (the rings concentric):
s0 = A·d̂ − (P_d/2)·s_r·e_r. For a deep groove (α0 = 0) pushed axially until the ball touches,
the free contact angle is then cos α_f = 1 − P_d/(2A) (Harris & Kotzalas, ch. 2, free contact angle).
Displaced, the centre distance is |s| with s = s0 + (u − (u·e_t)e_t), u = d + θ × p the
displacement of the moving centre p; the approach is δ = |s| − A (the geometry, not a gap along
a fixed contact line), the ball load Q = K·δ^1.5 with K the series constant of the two Hertz
contacts, and the loaded contact angle α = atan2(s_z·s·e_z, s_r·s·e_r). The groove carries only
contact angles on its loaded side (see ``BallRow.groove_angle_range_rad``): beyond, the ball has
run over the groove edge and is unloaded, so a single-row angular-contact ring tips under a moment
it cannot carry instead of the ball finding the opposite flank of a full torus. Ball centrifugal
force and gyroscopic moment are neglected (slow bearings).

Four-point (gothic-arch) ball rows, two such ball pairs per ball along the diagonals ±α, are in
:mod:`.rows_four_point`.

Roller rows (ISO/TS 16281 slices): a roller of effective length L is cut into n_s slices along
its axis a; slice k at p_k = c + x_k·a (c the roller centre) has approach
δ_k = u(p_k)·n − gap − drop(x_k) along the fixed contact normal n (radial row: n = s·e_r, a = e_z;
thrust row: n = s·e_z, a = e_r; crossed row, below) and carries
q_k = (c_L/n_s)·δ_k^(10/9), c_L the roller's constant between both raceways. The roller profile
drop(x) is parabolic, c·(2x/L)² with c the crown drop at the ends (0: straight roller), or
logarithmic, p·ln(1/(1 − (2x/L)²)) (ISO/TS 16281:2008, the logarithmic roller profile; its default
relief p = 0.00035·D_we), see :func:`roller_drop_m`.

Crossed roller rows (``orientation="crossed"``): the rollers alternate between the two diagonals
of a V-groove in each ring (90° for α0 = 45°), each roller touching each ring in one line contact,
both on its normal n_k = s_r·cos α0·e_r + σ_k·sin α0·e_z (s_r = ``load_sign``, +1 when the moving
ring carries the inner raceway; σ_k = ±1 the roller's diagonal, :attr:`RollerRow.diagonal_signs`),
its axis a_k = cos α0·e_z − σ_k·s_r·sin α0·e_r in the meridian plane, perpendicular to n_k
(pointing to +z: the slices are numbered from the roller's −z end, as in radial rows). With
rigid rings each roller is then a sliced angular-contact roller along its own fixed normal,
treated exactly as the radial and thrust rows: the rigid-ring load distribution of Harris &
Kotzalas, *Rolling Bearing Analysis*, 5th ed., ch. 7, with the line contacts sliced along a
normal that does not turn under load, as ISO/TS 16281:2008 slices angular-contact (tapered)
rollers. A diametral clearance P_d (the free radial play of the concentric rings) gives each
roller the gap g = (P_d/2)·cos α0 along its normal: a radial shift u_r of the moving ring closes
n·u_r·e_r = u_r·cos α0 at the roller in its direction, so the ring touches at u_r = ±g/cos α0 and
the free radial play is 2g/cos α0 = P_d; the free axial play is 2g/sin α0 = P_d·cot α0 (P_d at
45°). (Harris & Kotzalas, ch. 2, radial and axial play of angular-contact bearings.) Negative =
preload.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from typing import Literal

from ..contact.line import LINE_EXPONENT, iso16281_stiffness, palmgren_stiffness, series_line_stiffness
from foundation.materials import BEARING_STEEL, ElasticMaterial, effective_modulus_Pa
from foundation.validation import check_positive

from .row_common import (BallRowGeometry, check_ball_row, check_count, check_finite, check_sign,
                         element_azimuths_rad, settled_clearance)
from .rows_four_point import FourPointRow

__all__ = ["BallRow", "FourPointRow", "RollerRow", "Bearing", "roller_drop_m", "ISO16281_LOG_RELIEF_PER_D"]

#: Default relief of the logarithmic roller profile per roller diameter, ISO/TS 16281:2008
#: (p = 0.00035·D_we; about 3000 MPa of contact pressure for short cylindrical rollers).
ISO16281_LOG_RELIEF_PER_D = 0.00035


def roller_drop_m(x_m: np.ndarray, length_m: float, profile: str, crown_drop_m: float,
                  log_relief_m: float) -> np.ndarray:
    """Drop of the roller surface below its straight generatrix at ``x_m`` (n,) from the centre, m.

    ``"parabolic"``: c·(2x/L)², c = ``crown_drop_m`` (0: straight roller).
    ``"logarithmic"``: p·ln(1/(1 − (2x/L)²)), p = ``log_relief_m`` (ISO/TS 16281:2008, logarithmic
    roller profile; Lundberg's profile in the form of Johns & Gohar, "Roller bearings under radial
    and eccentric loads", Tribology International 14 (1981) 131–136). Finite for |x| < L/2, where
    the slice centres lie.
    """
    u = 2.0 * x_m / length_m
    if profile == "logarithmic":
        return -log_relief_m * np.log1p(-u * u)
    return crown_drop_m * u ** 2


@dataclass(frozen=True)
class BallRow(BallRowGeometry):
    """A row of balls in grooves.

    Parameters
    ----------
    name : str
        Row label.
    n_balls : int
        Number of load-carrying balls Z.
    ball_diameter_m : float
        Ball diameter D, m.
    pitch_diameter_m : float
        Pitch diameter d_m, m.
    contact_angle_rad : float
        Nominal (unloaded) contact angle α0, rad, in [0, π/2].
    conformity_moving, conformity_fixed : float
        Groove radius / D of the moving and of the fixed ring, > 0.5.
    moving_raceway : {"inner", "outer"}
        Whether the moving ring's raceway is the inner (convex in the rolling direction,
        contact nearer the axis) or the outer one.
    axial_sign : int
        +1 if an axial displacement of the moving ring towards +z loads the row, −1 if towards −z.
        Irrelevant for α0 = 0.
    diametral_clearance_m, radial_clearance_m : float or None
        Internal clearance of the unloaded, concentric bearing, m: the diametral clearance P_d
        (total radial free play) or the radial clearance P_d/2 — give either (the other follows;
        both must agree if both are given); negative = preload; default none. Modelled through
        the groove geometry (see the module docstring). To change it with
        :func:`dataclasses.replace`, pass the new one and ``None`` for the other.
    axial_position_m : float
        z of the ball centres, m.
    first_azimuth_rad : float
        Azimuth of ball 0, rad; the others follow at 2π/Z spacing.
    stiffness_N_per_m1p5 : float or None
        Override of the ball's load–deflection constant (both contacts in series), N/m^1.5.
    ball_material, race_material : ElasticMaterial
    azimuth_offsets_rad : tuple of float
        Each ball's angle from its place in the even spacing, rad (Z values, each below π/Z); empty:
        evenly spaced. For balls that a cage's play or spacers have moved, as a dynamic run has them.
    """

    name: str
    n_balls: int
    ball_diameter_m: float
    pitch_diameter_m: float
    contact_angle_rad: float
    conformity_moving: float
    conformity_fixed: float
    moving_raceway: Literal["inner", "outer"] = "inner"
    axial_sign: int = 1
    diametral_clearance_m: float | None = None
    radial_clearance_m: float | None = None
    axial_position_m: float = 0.0
    first_azimuth_rad: float = 0.0
    stiffness_N_per_m1p5: float | None = None
    ball_material: ElasticMaterial = field(default=BEARING_STEEL)
    race_material: ElasticMaterial = field(default=BEARING_STEEL)
    azimuth_offsets_rad: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        who = f"ball row {self.name!r}"
        object.__setattr__(self, "azimuth_offsets_rad", tuple(float(x) for x in self.azimuth_offsets_rad))
        check_ball_row(who, self)
        if not 0.0 <= self.contact_angle_rad <= math.pi / 2 + 1e-12:
            raise ValueError(
                f"{who}: contact_angle must lie in [0, 90] deg, got {math.degrees(self.contact_angle_rad):.6g}"
            )
        check_sign(who, "axial_sign", self.axial_sign)
        self._settle_clearance(who)

    def _settle_clearance(self, who: str) -> None:
        """Fill in the clearance not given from the one given (P_d = 2·radial)."""
        d, r = settled_clearance(who, self.diametral_clearance_m, self.radial_clearance_m,
                                 self.curvature_centre_distance_m, self.contact_angle_rad)
        object.__setattr__(self, "diametral_clearance_m", d)
        object.__setattr__(self, "radial_clearance_m", r)

    @property
    def groove_angle_range_rad(self) -> tuple[float, float]:
        """Loaded contact angles the grooves can carry, rad.

        A deep groove (α0 = 0) carries contact angles in (−90°, 90°), axial load either way;
        an angular-contact groove (α0 > 0) only in [0°, 90°] on its loaded side. A ball whose
        contact would leave this range has run over the groove edge and carries no load.
        """
        return (-math.pi / 2, math.pi / 2) if self.contact_angle_rad == 0.0 else (0.0, math.pi / 2)


@dataclass(frozen=True)
class RollerRow:
    """A row of cylindrical rollers, each cut into slices.

    Parameters
    ----------
    name : str
        Row label.
    n_rollers : int
        Number of rollers Z.
    roller_diameter_m : float
        Roller diameter D_we, m.
    roller_length_m : float
        Effective contact length L_we, m.
    pitch_diameter_m : float
        Pitch diameter d_m, m.
    orientation : {"radial", "thrust", "crossed"}
        Radial row (roller axis parallel to the bearing axis, normal radial), thrust row
        (roller axis radial, normal axial) or crossed row (rollers alternating between the two
        diagonals ±α0 of V-grooves, module docstring).
    load_sign : int
        +1 if a moving-ring displacement towards +e_r (radial and crossed rows: the moving ring
        carries the inner raceway) or +z (thrust row) loads the row, −1 for the opposite direction.
    gap_m : float
        Clearance per roller along the normal, m (negative = preload); of a crossed row
        (P_d/2)·cos α0 for the diametral clearance P_d (module docstring).
    axial_position_m : float
        z of the roller centres, m.
    n_slices : int
        Slices per roller (ISO/TS 16281 suggests ≥ 20 for tilted rollers).
    crown_drop_m : float
        Drop of a parabolic crown at the roller ends, m (0 = straight roller); profile "parabolic".
    profile : {"parabolic", "logarithmic"}
        Roller profile (:func:`roller_drop_m`): a parabolic crown of ``crown_drop_m`` (default) or
        the logarithmic profile of ISO/TS 16281:2008 with relief ``log_relief_m``.
    log_relief_m : float or None
        Relief p of the logarithmic profile, m; None: the ISO/TS 16281 default 0.00035·D_we.
    stiffness_law : {"iso16281", "palmgren"}
        c_L from ISO/TS 16281 (default) or two Palmgren contacts in series.
    stiffness_N_per_m10_9 : float or None
        Override of the whole roller's constant c_L (both contacts), N/m^(10/9).
    first_azimuth_rad : float
        Azimuth of roller 0, rad.
    roller_material, race_material : ElasticMaterial
    contact_angle_rad : float or None
        Crossed rows only: nominal contact angle α0, rad, in (0, π/2); default π/4 (a 90° V-groove).
    pattern : str
        Crossed rows only: the diagonal of each roller, ``"alternate"`` (roller 0 on +α0, roller 1
        on −α0, …) or a string of ``+`` and ``-`` repeated around the row (``"++--"``).
    """

    name: str
    n_rollers: int
    roller_diameter_m: float
    roller_length_m: float
    pitch_diameter_m: float
    orientation: Literal["radial", "thrust", "crossed"] = "radial"
    load_sign: int = 1
    gap_m: float = 0.0
    axial_position_m: float = 0.0
    n_slices: int = 20
    crown_drop_m: float = 0.0
    stiffness_law: Literal["iso16281", "palmgren"] = "iso16281"
    stiffness_N_per_m10_9: float | None = None
    first_azimuth_rad: float = 0.0
    roller_material: ElasticMaterial = field(default=BEARING_STEEL)
    race_material: ElasticMaterial = field(default=BEARING_STEEL)
    profile: Literal["parabolic", "logarithmic"] = "parabolic"
    log_relief_m: float | None = None
    contact_angle_rad: float | None = None
    pattern: str = "alternate"

    def __post_init__(self) -> None:
        who = f"roller row {self.name!r}"
        check_count(who, "n_rollers", self.n_rollers)
        check_count(who, "n_slices", self.n_slices)
        check_positive(who, roller_diameter_m=self.roller_diameter_m, roller_length_m=self.roller_length_m,
                  pitch_diameter_m=self.pitch_diameter_m)
        if self.orientation not in ("radial", "thrust", "crossed"):
            raise ValueError(f"{who}: orientation must be 'radial', 'thrust' or 'crossed', got {self.orientation!r}")
        self._check_crossed(who)
        check_sign(who, "load_sign", self.load_sign)
        check_finite(who, gap_m=self.gap_m, axial_position_m=self.axial_position_m,
                crown_drop_m=self.crown_drop_m, first_azimuth_rad=self.first_azimuth_rad)
        if self.crown_drop_m < 0.0:
            raise ValueError(f"{who}: crown_drop_m must be >= 0, got {self.crown_drop_m}")
        self._check_profile(who)
        if self.stiffness_law not in ("iso16281", "palmgren"):
            raise ValueError(f"{who}: stiffness_law must be 'iso16281' or 'palmgren', got {self.stiffness_law!r}")
        if self.stiffness_N_per_m10_9 is not None:
            check_positive(who, stiffness_N_per_m10_9=self.stiffness_N_per_m10_9)
        if self.orientation == "thrust" and self.roller_length_m >= self.pitch_diameter_m:
            raise ValueError(f"{who}: roller_length_m must be shorter than pitch_diameter_m")
        if self.orientation != "thrust" and self.pitch_diameter_m <= self.roller_diameter_m:
            raise ValueError(f"{who}: pitch_diameter_m must exceed roller_diameter_m")
        if self.n_rollers * self.roller_diameter_m > math.pi * self.pitch_diameter_m * (1 + 1e-9):
            raise ValueError(
                f"{who}: {self.n_rollers} rollers of {self.roller_diameter_m} m do not fit on the pitch circle "
                f"of {self.pitch_diameter_m} m"
            )

    def _check_crossed(self, who: str) -> None:
        """Contact angle and pattern: given for crossed rows only (the angle defaults to π/4 there)."""
        if self.orientation != "crossed":
            if self.contact_angle_rad is not None:
                raise ValueError(f"{who}: contact_angle is only used by crossed rows, not {self.orientation!r} ones")
            if self.pattern != "alternate":
                raise ValueError(f"{who}: pattern is only used by crossed rows, not {self.orientation!r} ones")
            return
        if self.contact_angle_rad is None:
            object.__setattr__(self, "contact_angle_rad", math.pi / 4)
        a = self.contact_angle_rad
        if not (isinstance(a, (int, float)) and 0.0 < a < math.pi / 2):
            raise ValueError(f"{who}: contact_angle must lie in (0, 90) deg, got "
                             f"{math.degrees(a) if isinstance(a, (int, float)) else a!r}")
        p = self.pattern
        if not (isinstance(p, str) and (p == "alternate" or (p and set(p) <= {"+", "-"}))):
            raise ValueError(f"{who}: pattern must be 'alternate' or a string of '+' and '-' (the diagonal of "
                             f"each roller, repeated around the row), got {p!r}")

    @property
    def nominal_contact_angle_rad(self) -> float:
        """α0 of the roller contacts, rad: 0 (radial), π/2 (thrust), ``contact_angle_rad`` (crossed)."""
        if self.orientation == "crossed":
            return self.contact_angle_rad
        return 0.0 if self.orientation == "radial" else math.pi / 2

    @property
    def diagonal_signs(self) -> np.ndarray:
        """σ_k = ±1 (Z,) of every roller: its diagonal (+α0 or −α0) in a crossed row, +1 in the others."""
        if self.orientation != "crossed":
            return np.ones(self.n_rollers)
        p = "+-" if self.pattern == "alternate" else self.pattern
        return np.array([1.0 if p[k % len(p)] == "+" else -1.0 for k in range(self.n_rollers)])

    @property
    def contact_angles_rad(self) -> np.ndarray:
        """Nominal contact angle of every roller (Z,), rad: σ_k·α0 for crossed rows (signed by the
        diagonal), 0 (radial) and π/2 (thrust) otherwise."""
        return self.nominal_contact_angle_rad * self.diagonal_signs

    def roller_frames(self, e_r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Unit roller axes and contact normals (Z, 3) for the radial unit vectors ``e_r`` (Z, 3) of
        the rollers (module docstring): the slices lie along the axis, the moving ring loads the
        roller along the normal."""
        e_z = np.zeros_like(e_r)
        e_z[:, 2] = 1.0
        s = float(self.load_sign)
        if self.orientation == "radial":
            return e_z, s * e_r
        if self.orientation == "thrust":
            return e_r, s * e_z
        a, sig = self.contact_angle_rad, self.diagonal_signs[:, None]
        normal = (s * math.cos(a)) * e_r + (sig * math.sin(a)) * e_z
        axis = math.cos(a) * e_z - (sig * s * math.sin(a)) * e_r
        return axis, normal

    def raceway_diameters_m(self) -> list[tuple[str, float, bool]]:
        """(raceway, diameter m, concave) of the roller's two line contacts, the diameter the one of
        the cylinder with the raceway's curvature across the roller axis.

        A conical raceway at contact angle α touched at radius r = (d_m ∓ D·cos α)/2 has that
        curvature cos α/r (Meusnier), so the diameter is (d_m ∓ D·cos α)/cos α, giving the curvature
        sums (2/D)/(1 ∓ γ) with γ = D·cos α/d_m of ISO 281 and ISO 76 (Harris & Kotzalas, *Rolling
        Bearing Analysis*, 5th ed., ch. 2, curvature of angular-contact raceways): d_m ∓ D for
        radial rows, flat (inf) for thrust rows; "inner" the convex one.
        """
        if self.orientation == "thrust":
            return [("inner", math.inf, False), ("outer", math.inf, False)]
        c = math.cos(self.nominal_contact_angle_rad)
        d, D = self.pitch_diameter_m, self.roller_diameter_m
        return [("inner", (d - D * c) / c, False), ("outer", (d + D * c) / c, True)]

    def _check_profile(self, who: str) -> None:
        if self.profile not in ("parabolic", "logarithmic"):
            raise ValueError(f"{who}: profile must be 'parabolic' or 'logarithmic', got {self.profile!r}")
        if self.profile == "logarithmic" and self.crown_drop_m != 0.0:
            raise ValueError(f"{who}: crown_drop_m must be 0 with the logarithmic profile, got {self.crown_drop_m}")
        if self.log_relief_m is not None:
            if self.profile != "logarithmic":
                raise ValueError(f"{who}: log_relief_m is only used by the logarithmic profile")
            check_positive(who, log_relief_m=self.log_relief_m)

    @property
    def log_relief_or_default_m(self) -> float:
        """Relief p of the logarithmic profile, m (the ISO/TS 16281 default when not given)."""
        return ISO16281_LOG_RELIEF_PER_D * self.roller_diameter_m if self.log_relief_m is None else self.log_relief_m

    def drop_m(self, x_m: np.ndarray) -> np.ndarray:
        """Profile drop at ``x_m`` (n,) from the roller centre, m (:func:`roller_drop_m`)."""
        return roller_drop_m(x_m, self.roller_length_m, self.profile, self.crown_drop_m,
                             self.log_relief_or_default_m)

    @property
    def n_elements(self) -> int:
        return self.n_rollers

    def azimuths_rad(self) -> np.ndarray:
        """(Z,) roller azimuths, rad, evenly spaced from ``first_azimuth_rad``."""
        return element_azimuths_rad(self.n_rollers, self.first_azimuth_rad)

    def contact_stiffness(self) -> float:
        """c_L of Q = c_L·δ^(10/9) for the whole roller between both raceways, N/m^(10/9)."""
        if self.stiffness_N_per_m10_9 is not None:
            return self.stiffness_N_per_m10_9
        e_eff = effective_modulus_Pa(self.roller_material, self.race_material)
        if self.stiffness_law == "iso16281":
            return iso16281_stiffness(self.roller_length_m, e_eff)
        k = palmgren_stiffness(self.roller_length_m, e_eff)
        return series_line_stiffness(k, k)

    @property
    def exponent(self) -> float:
        return LINE_EXPONENT


@dataclass(frozen=True)
class Bearing:
    """Rows of rolling elements acting in parallel between one fixed and one moving ring."""

    name: str
    rows: tuple[BallRow | FourPointRow | RollerRow, ...]

    def __post_init__(self) -> None:
        if not self.rows:
            raise ValueError(f"bearing {self.name!r}: rows must not be empty")
        names = [r.name for r in self.rows]
        if len(set(names)) != len(names):
            raise ValueError(f"bearing {self.name!r}: row names must be unique, got {names}")
        for r in self.rows:
            if not isinstance(r, (BallRow, FourPointRow, RollerRow)):
                raise ValueError(f"bearing {self.name!r}: rows must be BallRow, FourPointRow or RollerRow, got {type(r)}")

    @property
    def reference_length_m(self) -> float:
        """Largest pitch radius, m: scales moments and rotations in the solver."""
        return max(r.pitch_diameter_m for r in self.rows) / 2.0
