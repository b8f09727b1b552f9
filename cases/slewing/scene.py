"""From a slewing-ring case to what the solvers take: ball row, groove offsets, reduced bodies.

Only what the case asks for is built: a rigid ring is no body at all for the quasi-static solver;
a modal ring is meshed and reduced (cached on disk by its inputs, :func:`cms_reduction.reduced_body`)
and a second Young's modulus of the same ring is a rescaling of the first, not a new reduction
(:func:`cms_reduction.body.with_stiffness_scaled`).

Top structure (top race, with the TMR bolted to it when ``include_tmr``): floating, free–free
modes plus groove load shapes (inertia relief) up to ``groove_harmonics``; its density is raised
so that its weight is the dead load (:mod:`.case`). Bottom race: grounded at ``bolts`` patches of
its bolt face (30 mm half-width) when modal.

Undulation h(θ) = scale × periodic cubic spline through the points of
:data:`.case.UNDULATION_PROFILE_DEG_MM` (Bartels, Beatty &
Barsky: the periodic spline is C² and closes at 360° ≡ 0°). Thermal offset: Δ·w(θ) with
w = 1 inside the sector and raised-cosine edges of ``edge_deg`` inside it, 0 outside.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.interpolate import CubicSpline

from cms_reduction.body import with_stiffness_scaled
from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from fem_rings import MeshSpec
from fem_rings.sections import slewing_bottom_race, slewing_top_race, slewing_top_structure
from mbd_core.bearing.kinematics import cage_speed_rad_s
from foundation.materials import BEARING_STEEL, ElasticMaterial
from mbd_core.quasistatic import BallRow
from mbd_core.quasistatic.flexible import FlexibleRing, GrooveOffset

from .case import THESIS_CONTACT_STIFFNESS_N_PER_M1P5, SlewingCase, Undulation

__all__ = ["Bodies", "ball_row", "undulation_m", "thermal_offset_m", "groove_offsets", "top_body", "bottom_body",
           "flexible_rings", "orbit_ratio", "with_modulus", "REFERENCE_E_PA", "DEFAULT_ELEMENT_SIZE_M"]

log = logging.getLogger(__name__)

#: the races' steel; other moduli are rescalings of bodies reduced with this one
REFERENCE_E_PA = 200e9
NU, DENSITY_KG_M3 = 0.3, 7850.0
#: element size of the ring meshes per variant (quadratic hexahedra; the bending of rings this
#: size converges within 1 % with 2–3 elements across the section height)
DEFAULT_ELEMENT_SIZE_M = {"1m": 0.05, "2m": 0.07, "full": 0.15}
#: raceway samples round the ring (interpolated linearly between them)
N_THETA = 720
BOLT_HALF_WIDTH_M = 0.03


def ball_row(case: SlewingCase, phase_rad: float = 0.0, offsets_rad=()) -> BallRow:
    """The load balls (top race = moving ring, its contact the "inner" raceway, load downwards), ball
    j at ``phase_rad`` + 2πj/Z (+ ``offsets_rad[j]``, when given)."""
    g = case.geometry
    stiffness = None
    if case.contact.preset == "thesis":
        stiffness = THESIS_CONTACT_STIFFNESS_N_PER_M1P5 / 2.0**1.5  # two equal contacts in series
    return BallRow("load balls", g.n_balls, g.ball_diameter_m, g.pitch_diameter_m, math.radians(g.contact_angle_deg),
                   g.conformity, g.conformity, "inner", axial_sign=-1, first_azimuth_rad=phase_rad,
                   azimuth_offsets_rad=tuple(offsets_rad),
                   stiffness_N_per_m1p5=stiffness, ball_material=BEARING_STEEL, race_material=BEARING_STEEL)


def orbit_ratio(case: SlewingCase) -> float:
    """Ball orbit speed over top-race speed, bottom race fixed (Harris & Kotzalas, ch. 8; the top race
    touches the balls nearer the axis, the "inner" raceway of the kinematics)."""
    g = case.geometry
    return cage_speed_rad_s(g.ball_diameter_m, g.pitch_diameter_m, math.radians(g.contact_angle_deg), inner_speed_rad_s=1.0)


@lru_cache(maxsize=16)
def _spline(profile: tuple) -> CubicSpline:
    deg = np.array([p[0] for p in profile] + [360.0])
    mm = np.array([p[1] for p in profile] + [profile[0][1]])
    return CubicSpline(np.radians(deg), 1e-3 * mm, bc_type="periodic")


def undulation_m(undulation: Undulation, theta_rad) -> np.ndarray:
    """Bottom-race axial undulation h(θ), m, at angles θ (rad, any range)."""
    theta = np.mod(np.asarray(theta_rad, dtype=float), 2.0 * math.pi)
    return undulation.scale * _spline(tuple(map(tuple, undulation.profile_deg_mm)))(theta)


def _sector_weight(theta_rad, sector_deg, edge_deg: float) -> np.ndarray:
    a, b = (math.radians(x) for x in sector_deg)
    e = math.radians(edge_deg)
    t = np.mod(np.asarray(theta_rad, dtype=float) - a, 2.0 * math.pi)  # angle into the sector
    width = b - a
    w = np.where(t <= width, 1.0, 0.0)
    if e > 0.0:
        rise = np.clip(t / e, 0.0, 1.0)
        fall = np.clip((width - t) / e, 0.0, 1.0)
        w = w * 0.5 * (1.0 - np.cos(math.pi * np.minimum(rise, fall)))
    return w


def thermal_offset_m(case: SlewingCase, race: str, theta_rad) -> np.ndarray:
    """Radial groove offset Δr(θ) of the ``"top"`` or ``"bottom"`` race in its own angle θ, m."""
    th = case.thermal
    sector = th.top_sector_deg if race == "top" else th.bottom_sector_deg
    return th.offset_m * _sector_weight(theta_rad, sector, th.edge_deg)


def groove_offsets(case: SlewingCase, top_rotation_rad: float = 0.0) -> tuple[GrooveOffset, ...]:
    """Offsets of the quasi-static model: undulation and thermal offset of the bottom race, thermal
    offset of the top race (turned with it by ``top_rotation_rad``)."""
    row = "load balls"
    out = []
    bottom_thermal = (lambda th: thermal_offset_m(case, "bottom", th)) if case.thermal.offset_m else None
    if case.undulation.scale > 0.0 or bottom_thermal is not None:
        axial = (lambda th: undulation_m(case.undulation, th)) if case.undulation.scale > 0.0 else None
        out.append(GrooveOffset(row, "fixed", axial_m=axial, radial_m=bottom_thermal))
    if case.thermal.offset_m:
        out.append(GrooveOffset(row, "moving", radial_m=lambda th: thermal_offset_m(case, "top", th),
                                rotation_rad=top_rotation_rad))
    return tuple(out)


def _mesh(case: SlewingCase, fidelity) -> MeshSpec:
    size = fidelity.element_size_m or DEFAULT_ELEMENT_SIZE_M[case.geometry.variant]
    return MeshSpec(size, "hex27")


#: the groove region a ball spans, as a share of the ball diameter: the patch of the ball load
#: shapes in the fidelity ladder and of the residual-flexibility probe (:mod:`.fidelity`)
GROOVE_PATCH_SHARE = 0.3


def groove_patch_m(case: SlewingCase) -> float:
    """The groove patch s = 0.3·D (:data:`GROOVE_PATCH_SHARE`), rounded to 0.1 mm."""
    return round(GROOVE_PATCH_SHARE * case.geometry.ball_diameter_m, 4)


def ball_angles_deg(case: SlewingCase) -> tuple:
    """The load balls' angles at the first position (ball_row, phase 0), degrees."""
    return tuple(360.0 * i / case.geometry.n_balls for i in range(case.geometry.n_balls))


def _groove_spec(case: SlewingCase, race: str, harmonics: int, probe_all_balls: bool = False) -> RacewaySpec:
    """The race's sampled groove; its probe (the compliance to a ball force on the groove patch) at
    θ = 0 for the truncation estimate, or at every ball for ``auto``'s static response."""
    groove = case.geometry.section().groove(race, case.geometry.pitch_diameter_m)
    fidelity = getattr(case, race)
    balls = ball_angles_deg(case) if fidelity.ball_load_shapes else ()
    return RacewaySpec("groove", N_THETA, at_rz_m=tuple(groove.contact_point_m), n_max=harmonics,
                       spread_m=fidelity.raceway_spread_m, element_angles_deg=balls,
                       probe_spread_m=groove_patch_m(case),
                       probe_angles_deg=ball_angles_deg(case) if probe_all_balls else (0.0,))


def top_model_inputs(case: SlewingCase):
    """(profile, mesh spec, material) of the top structure's finite-element model: steel whose
    density is raised until the structure's weight is the dead load (module docstring)."""
    f, g = case.top, case.geometry
    make = slewing_top_structure if f.include_tmr else slewing_top_race
    profile = make(g.pitch_diameter_m, g.section(), "top structure" if f.include_tmr else "top race")
    mass_kg = profile.revolved_properties(DENSITY_KG_M3)["mass_kg"]
    density = DENSITY_KG_M3 * 1000.0 * case.dead_load_t / mass_kg
    log.info("top structure: %.1f t of steel carrying %.1f t (density ×%.2f)", mass_kg / 1e3, case.dead_load_t,
             density / DENSITY_KG_M3)
    return profile, _mesh(case, f), ElasticMaterial("steel carrying the dead load", REFERENCE_E_PA, NU, density)


def top_body(case: SlewingCase, probe_all_balls: bool = False):
    """The reduced top structure (floating), or None when the case keeps it rigid; ``probe_all_balls``:
    its probe at every ball (:func:`_groove_spec`)."""
    f = case.top
    if f.kind != "modal":
        return None
    spec = ReductionSpec(n_modes=f.n_modes, raceways=(_groove_spec(case, "top", f.groove_harmonics, probe_all_balls),),
                         damping_ratio=f.damping_ratio, stress_modes=f.stress_modes)
    body = reduced_body(*top_model_inputs(case), spec)
    return with_modulus(body, f.E_Pa)


def bottom_body(case: SlewingCase, probe_all_balls: bool = False):
    """The reduced bottom race (grounded at its bolt patches), or None when rigid; ``probe_all_balls``:
    its probe at every ball (:func:`_groove_spec`)."""
    f = case.bottom
    if f.kind != "modal":
        return None
    g = case.geometry
    bolts = tuple(360.0 * (k + 0.5) / f.bolts for k in range(f.bolts))
    spec = ReductionSpec(n_modes=f.n_modes, interfaces=(InterfaceSpec("bolt_face", bolts, BOLT_HALF_WIDTH_M),),
                         raceways=(_groove_spec(case, "bottom", f.groove_harmonics, probe_all_balls),),
                         damping_ratio=f.damping_ratio, stress_modes=f.stress_modes)
    material = ElasticMaterial("steel", REFERENCE_E_PA, NU, DENSITY_KG_M3)
    body = reduced_body(slewing_bottom_race(g.pitch_diameter_m, g.section()), _mesh(case, f), material, spec)
    return with_modulus(body, f.E_Pa)


def with_modulus(body, E_Pa: float):
    """A body reduced with :data:`REFERENCE_E_PA`, rescaled to Young's modulus ``E_Pa``."""
    return body if E_Pa == REFERENCE_E_PA else with_stiffness_scaled(body, E_Pa / REFERENCE_E_PA)


@dataclass(frozen=True)
class Bodies:
    """The reduced bodies of a case (None: rigid)."""

    top: object | None
    bottom: object | None


def flexible_rings(bodies: Bodies, top_rotation_rad: float = 0.0) -> tuple[FlexibleRing, ...]:
    rings = []
    if bodies.top is not None:
        rings.append(FlexibleRing("top", bodies.top, "moving", {"load balls": "groove"}, rotation_rad=top_rotation_rad))
    if bodies.bottom is not None:
        rings.append(FlexibleRing("bottom", bodies.bottom, "fixed", {"load balls": "groove"}))
    return tuple(rings)
