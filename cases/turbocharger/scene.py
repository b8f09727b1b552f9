"""The multibody model of a turbocharger case (:mod:`.case`): the reduced rotor, the two ball rows
with their cages, the outer rings in their squeeze-film dampers, the unbalance and the start at the
rows' quasi-static high-speed equilibrium.

Frames: the rotor's frame is its FE frame (z along the axis from the turbine wheel's face), at the
world origin at the start, driven about z at the running speed and free to translate and tilt. Each
outer ring, and its cage, has its reference point at its own centre on the axis (z = the row's
height), so that the film, the land and the anti-rotation pin act there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.spatial.transform import Rotation

from cms_reduction import prestressed
from cms_reduction.pipeline import RacewaySpec, ReductionSpec, reduced_body
from fem_rings.cache import input_hash, load_arrays, save_arrays
from fem_rings.mesh import MeshSpec
from fem_rings.profile import polygon
from foundation.materials import BEARING_STEEL, SILICON_NITRIDE
from mbd_core.bearing.spall import spall_radial_offset_m
from mbd_core.contact.friction import Coulomb
from mbd_core.multibody import Driven, Fixed, Free, ModelBuilder
from mbd_core.multibody.bearings import add_ball_row, place_balls
from mbd_core.quasistatic import BallRow, RingLoad, solve_high_speed_row
from mbd_core.squeeze_film import FilmGrid, SqueezeFilmDamper
from mbd_core.squeeze_film.force_table import TABLE_VERSION, FilmForceTable, tabulate

from .case import Damper, TurbochargerCase

__all__ = ["TurboScene", "build_scene", "rotor_body", "rows_of", "wheel_points_m", "film_table", "SPALL_SAMPLES"]

#: samples of a spalled groove's Δr(θ) table round the circle
SPALL_SAMPLES = 4096
#: stiffness of what holds an outer ring: axially (turbine side), in tilt (soft: a short film land
#: hardly resists a tilt; this only keeps the tilt from drifting), and about its axis (the pin)
_HELD_AXIAL_N_M, _HELD_TILT_NM_RAD, _PIN_NM_RAD = 2e8, 50.0, 2e4
#: damping of those holds (N·s/m, N·m·s/rad): a few per cent of critical for the outer ring
_HELD_AXIAL_N_S_M, _HELD_TILT_NM_S = 200.0, 0.02
#: viscous damping of the ball contacts (N·s/m), reached at 1 µm of penetration
_CONTACT_DAMPING_N_S_M = 20.0


@dataclass
class TurboScene:
    """A built model with the indices and data its studies read."""

    model: object
    state: object
    rotor: int
    outers: tuple[int, int]
    housing: int
    rows: tuple                      # RowBodies of the turbine-side and compressor-side row
    specs: tuple[BallRow, BallRow]
    quasi: tuple                     # HighSpeedRow of each row at the start
    body: object                     # the prestressed ReducedBody of the rotor
    speed_rad_s: float
    row_z_m: tuple[float, float]
    tables: tuple                    # the dampers' FilmForceTable


def _profile(case: TurbochargerCase):
    r = case.rotor
    ball = case.bearings
    a = r.shaft_diameter_m / 2
    ring = ball.pitch_diameter_m / 2 - ball.ball_diameter_m / 2    # the inner raceway's bottom
    zt, zc = r.turbine_bearing_at_m, r.turbine_bearing_at_m + r.bearing_span_m
    h = r.inner_ring_width_m / 2
    if not ring > a:
        raise ValueError(f"bearings.pitch_diameter_m: the inner raceway (Ø{2 * ring:g} m) must lie outside the shaft "
                         f"(Ø{r.shaft_diameter_m:g} m)")
    points = [(0, 0), (r.turbine_diameter_m / 2, 0), (r.turbine_diameter_m / 2, r.turbine_width_m), (a, r.turbine_width_m),
              (a, zt - h), (ring, zt - h), (ring, zt + h), (a, zt + h), (a, zc - h), (ring, zc - h), (ring, zc + h),
              (a, zc + h), (a, r.length_m - r.compressor_width_m), (r.compressor_diameter_m / 2, r.length_m - r.compressor_width_m),
              (r.compressor_diameter_m / 2, r.length_m), (0, r.length_m)]
    names = ["turbine_face", "turbine_rim", "turbine_back", "shaft_turbine", "ring_t_side", "ring_t", "ring_t_back",
             "shaft_mid", "ring_c_side", "ring_c", "ring_c_back", "shaft_compressor", "compressor_back",
             "compressor_rim", "compressor_nose", "axis"]
    return polygon("turbocharger rotor", points, names), ring, (zt, zc)


def rotor_body(case: TurbochargerCase):
    """The rotor reduced to free–free modes with its stress stiffening and the inner raceways sampled
    (cached), not yet prestressed."""
    profile, ring, (zt, zc) = _profile(case)
    r = case.rotor
    shaft = {n: 0.75 for n in ("shaft_turbine", "shaft_mid", "shaft_compressor", "ring_t", "ring_c")}
    spec = ReductionSpec(n_modes=r.n_modes, damping_ratio=r.damping_ratio, spin_stiffening=True,
                         raceways=(RacewaySpec("ring_t", 360, at_rz_m=(ring, zt), n_max=-1),
                                   RacewaySpec("ring_c", 360, at_rz_m=(ring, zc), n_max=-1)))
    return reduced_body(profile, MeshSpec(size_m=r.mesh_size_m, refine=shaft), BEARING_STEEL, spec)


def rows_of(case: TurbochargerCase) -> tuple[BallRow, BallRow]:
    """The turbine-side row (loaded by the rotor pushed towards the compressor) and the compressor-side
    one (back to back: loaded the other way), at their heights on the rotor."""
    b, r = case.bearings, case.rotor
    material = SILICON_NITRIDE if b.ball_material == "silicon_nitride" else BEARING_STEEL
    common = dict(n_balls=b.n_balls, ball_diameter_m=b.ball_diameter_m, pitch_diameter_m=b.pitch_diameter_m,
                  contact_angle_rad=math.radians(b.contact_angle_deg), conformity_moving=b.conformity_inner,
                  conformity_fixed=b.conformity_outer, moving_raceway="inner", ball_material=material)
    return (BallRow("turbine row", axial_sign=1, axial_position_m=r.turbine_bearing_at_m, **common),
            BallRow("compressor row", axial_sign=-1, axial_position_m=r.turbine_bearing_at_m + r.bearing_span_m,
                    **common))


def wheel_points_m(case: TurbochargerCase) -> dict[str, np.ndarray]:
    """Rim points of the wheels at their mid-width (rotor frame, on its x axis), m."""
    r = case.rotor
    return {"turbine": np.array([r.turbine_diameter_m / 2, 0.0, r.turbine_width_m / 2]),
            "compressor": np.array([r.compressor_diameter_m / 2, 0.0, r.length_m - r.compressor_width_m / 2])}


def film_table(damper: Damper):
    """The damper's force table (``damper.method``), cached by its inputs in ``FLEXBEARING_CACHE`` (the
    grid solver's table takes about two minutes)."""
    sfd = SqueezeFilmDamper(damper.journal_radius_m, damper.length_m, damper.clearance_m, damper.viscosity_Pa_s,
                            damper.cavitation)
    size = dict(n_eps=41, n_psi=96) if damper.method == "grid" else dict(n_eps=61, n_psi=288)
    key = input_hash("sfd-table", TABLE_VERSION, sfd, damper.method, size, damper.max_eccentricity_ratio, FilmGrid())
    stored = load_arrays("sfd-table", key)
    if stored is not None:
        return FilmForceTable(stored["scaled_N_s_m"], damper.max_eccentricity_ratio, damper.method, damper.clearance_m)
    table = tabulate(sfd, damper.method, max_eccentricity_ratio=damper.max_eccentricity_ratio, **size)
    save_arrays("sfd-table", key, {"scaled_N_s_m": np.asarray(table.scaled_N_s_m)})
    return table


def _outer_ring(case: TurbochargerCase, row: BallRow):
    """Mass (kg) and inertia (kg·m², about its centre) of an outer ring: a steel annulus from the outer
    raceway's bottom to the damper's journal, as wide as the inner ring."""
    ro = case.damper.journal_radius_m
    ri = row.pitch_diameter_m / 2 + row.ball_diameter_m / 2
    if not ro > ri:
        raise ValueError(f"damper.journal_radius_m: the outer ring's outside ({ro:g} m) must lie outside its raceway "
                         f"({ri:g} m)")
    w = case.rotor.inner_ring_width_m
    m = BEARING_STEEL.density_kg_m3 * math.pi * (ro * ro - ri * ri) * w
    polar = 0.5 * m * (ro * ro + ri * ri)
    return m, (0.5 * polar + m * w * w / 12, 0.5 * polar + m * w * w / 12, polar)


def _spall(case: TurbochargerCase, row: BallRow, race: str):
    d = case.defect
    radius = row.pitch_diameter_m / 2 + (row.ball_diameter_m / 2 if race == "outer" else -row.ball_diameter_m / 2)
    dr = spall_radial_offset_m(SPALL_SAMPLES, radius, math.radians(d.angle_deg), d.length_m, d.depth_m,
                               row.ball_diameter_m / 2, race, row.contact_angle_rad)
    return (None, dr)


def build_scene(case: TurbochargerCase, speed_rpm: float | None = None) -> TurboScene:
    """The model at ``speed_rpm`` (default the case's), started at the rows' high-speed equilibrium
    under the preload."""
    speed = (case.operation.speed_rpm if speed_rpm is None else speed_rpm) * math.pi / 30.0
    body = prestressed(rotor_body(case), speed)
    rows = rows_of(case)
    zs = tuple(r.axial_position_m for r in rows)
    b = ModelBuilder()
    rotor = b.add_modal_body("rotor", body, motion=Driven(speed, translation_free=True, tilt_free=True),
                             omega_rad_s=(0.0, 0.0, speed))
    housing = b.add_body("housing", 1.0, (1.0, 1.0, 1.0), motion=Fixed())
    friction = Coulomb(case.bearings.friction, 0.8 * case.bearings.friction, 0.05, 0.1) \
        if case.bearings.friction > 0.0 else None
    bearings = case.bearings
    dmp = case.damper
    tables = (film_table(dmp),) * 2
    outers, row_bodies = [], []
    for k, (row, z) in enumerate(zip(rows, zs)):
        side = ("turbine", "compressor")[k]
        m, inertia = _outer_ring(case, row)
        outer = b.add_body(f"{side} outer ring", m, inertia, position_m=(0.0, 0.0, z), motion=Free())
        grooves = {}
        if k == 0 and case.defect.race != "none":
            key = "moving_groove_m" if case.defect.race == "inner" else "fixed_groove_m"
            grooves[key] = _spall(case, row, case.defect.race)
        rb = add_ball_row(b, row, rotor, outer, friction=friction, damping_N_s_m=_CONTACT_DAMPING_N_S_M,
                          cage_mass_kg=bearings.cage_mass_kg, pocket_clearance_m=bearings.pocket_clearance_m,
                          cage_stiffness_N_per_m=1e6, moving_sample=("ring_t", "ring_c")[k], fixed_frame_z_m=z,
                          **grooves)
        b.add_bushing(outer, rb.cage, (0.0, 0.0, z), (bearings.land_stiffness_N_m,) * 2 + (0, 0, 0, 0),
                      (bearings.land_damping_N_s_m,) * 2 + (0, 0, 0, 0))
        axial = _HELD_AXIAL_N_M if k == 0 else 0.0
        b.add_bushing(housing, outer, (0.0, 0.0, z),
                      (dmp.centring_stiffness_N_m, dmp.centring_stiffness_N_m, axial, _HELD_TILT_NM_RAD,
                       _HELD_TILT_NM_RAD, _PIN_NM_RAD),
                      (0.0, 0.0, _HELD_AXIAL_N_S_M, _HELD_TILT_NM_S, _HELD_TILT_NM_S, _HELD_TILT_NM_S))
        b.add_squeeze_film(outer, housing, tables[k], bore_center_m=(0.0, 0.0, z), name=f"{side} damper")
        outers.append(outer)
        row_bodies.append(rb)
    # the preload spring pushes the compressor-side outer ring away from the turbine: both rows carry it
    b.add_force(outers[1], (0.0, 0.0, bearings.preload_N))
    u = case.operation.unbalance_g_mm * 1e-6
    if u > 0.0:
        b.add_unbalance(rotor, wheel_points_m(case)[case.operation.unbalance_at], u)
    model, state = b.finalize()
    quasi = (solve_high_speed_row(rows[0], RingLoad(Fz_N=bearings.preload_N), speed),
             solve_high_speed_row(rows[1], RingLoad(Fz_N=-bearings.preload_N), speed))
    _start(model, state, rotor, outers, row_bodies, quasi, zs)
    scene = TurboScene(model, state, rotor, tuple(outers), housing, tuple(row_bodies), rows, quasi, body, speed, zs,
                       tables)
    _whirl_start(scene, u, wheel_points_m(case)[case.operation.unbalance_at])
    return scene


def _start(model, state, rotor, outers, rows, quasi, zs) -> None:
    """Rotor, compressor-side outer ring and balls at the rows' quasi-static equilibrium under the preload
    (the turbine-side outer ring stays where it is held); balls rolling, cages at the balls' orbit speed."""
    rotor_z = float(quasi[0].displacement[2])
    state.q[rotor, 2] = rotor_z
    outer_z = (0.0, rotor_z - float(quasi[1].displacement[2]))
    state.q[outers[1], 2] += outer_z[1]
    for rb, qs, dz, outer in zip(rows, quasi, outer_z, outers):
        place_balls(model, state, rb, rotor, outer, qs, dz)


def _whirl_start(scene: TurboScene, unbalance_kg_m: float, point_m: np.ndarray) -> None:
    """Put the rotor on its steady unbalance orbit as a free rigid body, and each bearing with it.

    A free rigid rotor with a body-fixed force U Ω² at p turns steadily about a fixed axis: its centre of
    mass on a circle of radius U/m opposite the unbalance, its axis tilted by β = Δz U/(I_p − I_d)
    (Δz the unbalance's height above the centre of mass; Euler's equations M = ω × Iω for a steady spin
    ω about the tilted principal axis). Started at rest instead, the rotor would drift at UΩ/m (a
    rotating force on a mass at rest has a mean velocity) and the dampers would be pushed to their
    ends in a millisecond. At tens of thousands of rev/min the rotor runs far above its rigid modes on
    the dampers, so the free orbit is close to the steady one and the rest settles. Each bearing (outer
    ring, balls, cage) is moved with the rotor's axis at its height and given the orbit's translation
    and the tilt's precession, with no spin of its own added."""
    from cms_reduction.invariants import Invariants

    if unbalance_kg_m <= 0.0:
        return
    inv = Invariants.from_arrays(scene.body.extras)
    W, m = scene.speed_rad_s, inv.mass_kg
    z_g = float(inv.I2[2] / m)
    I_p, I_d = float(inv.I7[2, 2]), float(inv.I7[0, 0] - m * z_g * z_g)
    beta = (float(point_m[2]) - z_g) * unbalance_kg_m / (I_p - I_d)
    q, v = scene.state.q, scene.state.v
    tilt = Rotation.from_rotvec([0.0, beta, 0.0])
    rot = tilt.as_matrix()
    rotor = scene.rotor
    base = q[rotor, :3].copy()
    origin = np.array([-unbalance_kg_m / m, 0.0, base[2] + z_g]) - rot @ np.array([0.0, 0.0, z_g])
    spin = np.array([0.0, 0.0, W])
    tilt_rate = np.cross(spin, [0.0, beta, 0.0])             # the tilt (about y) precessing at Ω
    q[rotor, :3] = origin
    q[rotor, 3:] = tilt.as_quat(scalar_first=True)
    v[rotor, :3] = np.cross(spin, origin)
    v[rotor, 3:] = (-W * math.sin(beta), 0.0, W)
    bearing_bodies = [[outer, rb.cage, *rb.elements] for outer, rb in zip(scene.outers, scene.rows)]
    for z, bodies in zip(scene.row_z_m, bearing_bodies):
        centre_old = base + np.array([0.0, 0.0, z])
        centre = origin + rot @ np.array([0.0, 0.0, z])
        whirl = np.cross(spin, centre * [1.0, 1.0, 0.0])
        for body in bodies:
            x = q[body, :3].copy()
            q[body, :3] = centre + rot @ (x - centre_old)
            v[body, :3] += whirl + np.cross(tilt_rate, q[body, :3] - centre)
            turned = tilt * Rotation.from_quat(q[body, 3:], scalar_first=True)
            q[body, 3:] = turned.as_quat(scalar_first=True)
            v[body, 3:] += turned.inv().apply(tilt_rate)     # the precession, in the body's axes


def with_speed(case: TurbochargerCase, speed_rpm: float) -> TurbochargerCase:
    return replace(case, operation=replace(case.operation, speed_rpm=float(speed_rpm)))
