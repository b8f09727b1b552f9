"""Four-point contact (gothic-arch) ball rows: the common slewing-bearing type.

Each ring's groove is a gothic arch: two circular arcs of radius f·D whose curvature centres are
offset to either side of the ball's mid-plane, so that a ball can touch each ring at two points.
The contacts pair up along two diagonals through the ball centre, at +α and −α (α0 nominal,
typically 45°). With rigid rings each diagonal behaves as an angular-contact pair whose curvature
centres are A = (f_m + f_f − 1)·D apart when the ball touches unloaded, the model of
Amasorrain, Sagartzazu & Damián, "Load distribution in a four contact-point slewing bearing",
Mech. Mach. Theory 38 (2003) 479–496, and of Aguirrebeitia, Avilés, Fernández de Bustos &
Abasolo, "Calculation of general static load-carrying capacity for the design of
four-contact-point slewing bearings", J. Mech. Des. 132 (2010) 064501; the approach of each
diagonal is the change of its curvature-centre distance and Q = K·δ^1.5 as for an angular-contact
ball (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., ch. 2 and 7). So a ball carries
two entries of the solver's ball group, one per diagonal, each the pair of :class:`.rows.BallRow`
with axial sign +1 (the diagonal loaded when the moving ring moves towards +z: +α) or −1 (−α).

Each diagonal carries contact angles only on its own side of the groove, from the arch apex
(0°) up to the groove shoulder; beyond the shoulder the ball rides over it and the diagonal is
unloaded, as at a :class:`.rows.BallRow` groove edge (the contact point reaches the apex itself
at a small positive angle, sin α = (1 − 1/(2f))·sin α0 of the unloaded geometry, which the model
rounds to 0°). A ball touches 2 or 4 points (or none).

Clearance: a radial clearance P_d/2 moves the two gothic arches apart radially (the rings
concentric), so both diagonals open by it alike; a negative clearance preloads both. The
unloaded centre-distance vector of a diagonal is s0 = A·d̂ − (P_d/2)·s_r·e_r with
d̂ = s_r·cos α0·e_r ± sin α0·e_z (:mod:`.rows`), which puts the rings' free radial play at P_d
and their free axial play at 2·(√(A² − (A·cos α0 − P_d/2)²) − A·sin α0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

from foundation.materials import BEARING_STEEL, ElasticMaterial

from .row_common import BallRowGeometry, check_ball_row, check_finite, settled_clearance

__all__ = ["FourPointRow", "DEFAULT_SHOULDER_ANGLE_RAD"]

#: Default contact angle at the groove shoulder, rad. An assumption of typical design, not a
#: standard value: slewing-ring grooves are cut deep enough that a 45° row's loaded contact angles
#: (which stay below ~60° up to its static rating) keep the contact ellipse inside the groove, and
#: the ring's shoulder left beside the groove bounds the depth; 70° sits between the two.
#: Give the bearing's own value where it is known (a drawing's shoulder height fixes it).
DEFAULT_SHOULDER_ANGLE_RAD = math.radians(70.0)


@dataclass(frozen=True)
class FourPointRow(BallRowGeometry):
    """A row of balls in two gothic-arch grooves (four-point contact).

    Parameters
    ----------
    name : str
        Row label.
    n_balls : int
        Number of balls Z.
    ball_diameter_m, pitch_diameter_m : float
        Ball diameter D and pitch diameter d_m, m.
    contact_angle_rad : float
        Nominal contact angle α0 of both diagonals, rad, in (0, shoulder).
    conformity_moving, conformity_fixed : float
        Arc radius / D of the moving and of the fixed ring's groove, > 0.5.
    moving_raceway : {"inner", "outer"}
        Whether the moving ring carries the inner or the outer groove.
    diametral_clearance_m, radial_clearance_m : float or None
        Internal clearance P_d or P_d/2 of the unloaded concentric bearing, m (either; negative =
        preload; default none), as in :class:`.rows.BallRow` (module docstring: both diagonals).
    axial_position_m : float
        z of the ball centres, m.
    first_azimuth_rad : float
        Azimuth of ball 0, rad; the others follow at 2π/Z.
    shoulder_angle_rad : float
        Contact angle at the groove shoulder of both rings, rad, in (α0, π/2]; beyond it a
        diagonal is unloaded. Default :data:`DEFAULT_SHOULDER_ANGLE_RAD` (70°).
    stiffness_N_per_m1p5 : float or None
        Override of one diagonal's load–deflection constant (both contacts in series), N/m^1.5.
    ball_material, race_material : ElasticMaterial
    """

    name: str
    n_balls: int
    ball_diameter_m: float
    pitch_diameter_m: float
    contact_angle_rad: float = math.radians(45.0)
    conformity_moving: float = 0.53
    conformity_fixed: float = 0.53
    moving_raceway: Literal["inner", "outer"] = "inner"
    diametral_clearance_m: float | None = None
    radial_clearance_m: float | None = None
    axial_position_m: float = 0.0
    first_azimuth_rad: float = 0.0
    shoulder_angle_rad: float = DEFAULT_SHOULDER_ANGLE_RAD
    stiffness_N_per_m1p5: float | None = None
    ball_material: ElasticMaterial = field(default=BEARING_STEEL)
    race_material: ElasticMaterial = field(default=BEARING_STEEL)

    def __post_init__(self) -> None:
        who = f"four-point row {self.name!r}"
        check_ball_row(who, self)
        check_finite(who, contact_angle_rad=self.contact_angle_rad, shoulder_angle_rad=self.shoulder_angle_rad)
        if not 0.0 < self.shoulder_angle_rad <= math.pi / 2 + 1e-12:
            raise ValueError(f"{who}: shoulder_angle must lie in (0, 90] deg, got "
                             f"{math.degrees(self.shoulder_angle_rad):.6g}")
        if not 0.0 < self.contact_angle_rad < self.shoulder_angle_rad:
            raise ValueError(f"{who}: contact_angle ({math.degrees(self.contact_angle_rad):.6g} deg) must lie "
                             f"between 0 deg and shoulder_angle ({math.degrees(self.shoulder_angle_rad):.6g} deg)")
        d, r = settled_clearance(who, self.diametral_clearance_m, self.radial_clearance_m,
                                 self.curvature_centre_distance_m, self.contact_angle_rad)
        object.__setattr__(self, "diametral_clearance_m", d)
        object.__setattr__(self, "radial_clearance_m", r)

    #: Axial sign of the two diagonals (+α, −α), in the order of the per-contact result arrays.
    DIAGONAL_SIGNS = (1, -1)

    @property
    def groove_angle_range_rad(self) -> tuple[float, float]:
        """Loaded contact angles each diagonal can carry: from the arch apex to the shoulder, rad."""
        return (0.0, self.shoulder_angle_rad)
