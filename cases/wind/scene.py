"""The multibody scene of the wind main bearing: driven inner ring, fixed outer ring, three roller rows.

Bodies: the inner ring (3971 kg, the paper's two pieces as one body) turns at the
driving speed about z and is free to translate and tilt under the spectrum loads at its centre
and gravity (−y); the outer ring with the nose is fixed. Each row (radial 98 × Ø55 mm, front and
rear thrust 94 × Ø60 mm) has sliced roller–raceway contacts on both rings, a free cage with slot
pockets (radial cage 70 kg, thrust cages 90.2 kg) and end guides at both roller ends: ribs on the
inner ring for the radial rollers, the ends of the window pockets of their cage for the thrust
rollers (a slot pocket holds a roller only round the circumference: unguided, the thrust rollers,
axis radial, would drift outwards under their orbit's centrifugal force; their ends face no ring
in the section, and stops on the inner ring would drag them at the ring's speed). Each cage is
guided along the axis and in tilt by its land on the outer ring (:func:`guide_cage`). Rollers
are steel or aluminium bronze (paper Table 2).

With ``bodies.rings = "modal"`` the rings are the reduced bodies of :mod:`.bodies` (the inner
ring's frame carries the drive, loads and gravity; the outer ring's modes are integrated
implicitly) and the rollers' slices follow the sampled raceway grids; with ``bodies.cages =
"modal"`` each cage is a floating modal body whose pocket walls deform with it.

Start: the inner ring is placed at the quasi-static equilibrium of the first load (rigid rings,
:func:`mbd_core.quasistatic.solve_load_distribution`, the inner ring's weight included) with the
rollers moved by half the ring's displacement at their centres, so that the two equal slice laws
of a roller share its approach (to first order in the tilt); the
rollers and cages get their no-slip velocities (:func:`rolling_speeds`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from cases.catalog import three_row_roller
from foundation.materials import BEARING_STEEL, ElasticMaterial
from mbd_core.multibody import ModelBuilder
from mbd_core.multibody.bearings import LINE_EXPONENT, _rotate, _rotate_back, add_roller_row, roller_mass_kg
from mbd_core.multibody.builder import Driven, Fixed, Free, quat_from_axis_angle
from mbd_core.quasistatic import RingLoad, solve_load_distribution

from .bodies import RACEWAYS, ModalBodies, modal_bodies, rib_grids
from .case import (ADAMS_CONTACT, INNER_RING_MASS_KG, OUTER_RING_MASS_KG, RADIAL_CAGE_MASS_KG, THRUST_CAGE_MASS_KG,
                   WindCase)
from .spectrum import load_cases, read_csv, sequence

__all__ = ["ALUMINIUM_BRONZE", "G_M_S2", "WindScene", "rows", "load_history", "inner_ring_load", "build_scene"]

#: aluminium bronze ZCuAl10Fe3Mn2 (paper Table 2: E = 110 GPa, ν = 0.32; density of the alloy 7600 kg/m³)
ALUMINIUM_BRONZE = ElasticMaterial("aluminium bronze", 110e9, 0.32, 7600.0)
G_M_S2 = 9.81
#: penetration over which the IMPACT damping ramps in, m
D_MAX_M = 1e-6
#: radius of gyration of the inner ring section about the axis (mean of bore 0.855 m and flange 1.15 m), m
INNER_RING_GYRATION_M = 1.0
CAGE_MASSES_KG = (RADIAL_CAGE_MASS_KG, THRUST_CAGE_MASS_KG, THRUST_CAGE_MASS_KG)
#: axial stiffness of a cage's land guidance (all three springs, :func:`guide_cage`), N/m, and its damping ratio
CAGE_GUIDE_STIFFNESS_N_PER_M = 1e7
CAGE_GUIDE_DAMPING_RATIO = 0.3


@dataclass
class WindScene:
    """The model and what a run reads back: the rings, each row's :class:`RowBodies`, the loads,
    the reduced bodies of the modal ones."""

    model: object
    state: object
    inner: int
    outer: int
    rows: tuple
    row_defs: tuple
    times_s: np.ndarray
    loads: np.ndarray
    modal: ModalBodies


def rows(case: WindCase):
    """The three :class:`RollerRow` of the bearing with the case's slices and roller material."""
    mat = ALUMINIUM_BRONZE if case.rollers.material == "bronze" else BEARING_STEEL
    return tuple(replace(r, n_slices=case.rollers.n_slices, roller_material=mat) for r in three_row_roller().bearing.rows)


def load_history(case: WindCase) -> tuple[np.ndarray, np.ndarray]:
    """Knot times (s) and loads (k, 6) at the inner-ring centre, N and N·m (Mz zeroed unless
    ``include_torque``)."""
    lc = case.loads
    if lc.source == "csv":
        t, f = read_csv(lc.csv_path)
    else:
        loads, share = load_cases()
        if lc.source == "constant":
            t, f = np.array([0.0, lc.spectrum_duration_s]), np.repeat(loads[lc.case_index][None, :], 2, axis=0)
        else:
            t, f = sequence(loads, share, duration_s=lc.spectrum_duration_s)
    f = np.array(f, float) * lc.scale
    if not lc.include_torque:
        f[:, 5] = 0.0
    return np.asarray(t, float), f


def _roller_law(case: WindCase, row) -> tuple[tuple[float, float] | None, float, float]:
    """(roller_law, damping per slice N·s/m, d_max m) of a row under the case's contact preset."""
    if case.contact.preset == "adams":
        a = ADAMS_CONTACT
        return (a["stiffness_N_per_m1p5"], a["exponent"]), a["damping_N_s_m"] / row.n_slices, a["d_max_m"]
    return None, _damping(case, row), D_MAX_M


def _damping(case: WindCase, row) -> float:
    """``damping_ratio`` × 2√(k m) per slice: k = (10/9) Q/δ of one contact at the mean roller load
    Q of the radial row under 1.3 MN (Q = 5 F_r/Z, Stribeck), shared by the slices."""
    Q = 5.0 * 1.3e6 / 98
    c_contact = row.contact_stiffness() * 2.0**LINE_EXPONENT
    delta = (Q / c_contact) ** (1.0 / LINE_EXPONENT)
    k_lin = LINE_EXPONENT * Q / delta
    m = roller_mass_kg(row.roller_diameter_m, row.roller_length_m, row.roller_material.density_kg_m3)
    return case.contact.damping_ratio * 2.0 * math.sqrt(k_lin * m) / row.n_slices


def inner_ring_load(f: np.ndarray) -> RingLoad:
    """The load on the inner ring for the quasi-static solver: the load case ``f`` (Fx, Fy, Fz, Mx,
    My at its centre, N and N·m) and the ring's weight (−y)."""
    return RingLoad(Fx_N=f[0], Fy_N=f[1] - INNER_RING_MASS_KG * G_M_S2, Fz_N=f[2], Mx_Nm=f[3], My_Nm=f[4])


def initial_displacement(case: WindCase, row_defs, load0: np.ndarray) -> np.ndarray:
    """(x, y, z, θx, θy) of the inner ring at the quasi-static equilibrium under ``load0`` and its weight."""
    from mbd_core.quasistatic import Bearing

    bearing = Bearing("three-row roller", tuple(row_defs))
    return np.asarray(solve_load_distribution(bearing, inner_ring_load(load0)).displacement, float)


def build_scene(case: WindCase) -> WindScene:
    """The rigid-ring model of the case, placed at its start (module docstring)."""
    row_defs = rows(case)
    t, f = load_history(case)
    q0 = initial_displacement(case, row_defs, f[0])
    omega = case.analysis.speed_rpm * 2.0 * math.pi / 60.0
    mb = modal_bodies(case) if case.bodies.any_modal else ModalBodies(None, None, (None, None, None))
    b = ModelBuilder(gravity_m_s2=(0.0, -G_M_S2, 0.0), implicit_friction=case.contact.implicit_friction)
    tilt = math.hypot(q0[3], q0[4])
    orient = quat_from_axis_angle((q0[3], q0[4], 0.0), tilt) if tilt > 0 else (1.0, 0.0, 0.0, 0.0)
    drive = Driven(omega, translation_free=True, tilt_free=True)
    if mb.inner is None:
        m, r = INNER_RING_MASS_KG, INNER_RING_GYRATION_M
        inner = b.add_body("inner ring", m, (0.5 * m * r * r, 0.5 * m * r * r, m * r * r), position_m=tuple(q0[:3]),
                           orientation=orient, motion=drive, omega_rad_s=(0.0, 0.0, omega))
        outer = b.add_body("outer ring", OUTER_RING_MASS_KG, (1e3, 1e3, 2e3), motion=Fixed())
    else:
        inner = b.add_modal_body("inner ring", mb.inner, position_m=tuple(q0[:3]), orientation=orient, motion=drive,
                                 omega_rad_s=(0.0, 0.0, omega))
        outer = b.add_modal_body("outer ring", mb.outer, motion=Fixed(), implicit_modes=True)
    friction = case.contact.friction_law()
    added = []
    for k, (row, cage_kg) in enumerate(zip(row_defs, CAGE_MASSES_KG)):
        law, c, d_max = _roller_law(case, row)
        play, radial = case.rollers.rib_clearance_m, row.orientation == "radial"
        grids = {}
        if mb.inner is not None:
            grids = dict(moving_raceway=RACEWAYS[k], fixed_raceway=RACEWAYS[k])
        cage = None
        if mb.cages[k] is not None:
            cage = b.add_modal_body(f"{row.name} cage", mb.cages[k], motion=Free(), omega_rad_s=(0.0, 0.0, 0.0))
        guide = mb.inner if radial else mb.cages[k]  # radial: ribs on the inner ring; thrust: pocket ends
        if guide is not None:
            grids["rib_raceways"] = rib_grids(guide, row, case.bodies.n_theta, play)
        added.append(add_roller_row(
            b, row, inner, outer, friction=friction, damping_N_s_m=c, d_max_m=d_max, roller_law=law,
            rib_clearance_m=play,
            edge_radius_m=None if radial else case.rollers.thrust_end_radius_m, ribs_on="moving" if radial else "cage",
            cage_mass_kg=cage_kg, pocket_clearance_m=case.rollers.pocket_clearance_m,
            cage_stiffness_N_per_m=case.contact.pocket_stiffness_N_per_m, pocket_friction=friction,
            cage=cage, pocket_walls=cage is not None, **grids))
    for rb, row, cage_kg in zip(added, row_defs, CAGE_MASSES_KG):
        guide_cage(b, outer, rb.cage, row, cage_kg)
    b.add_load_history(inner, t, f)
    model, state = b.finalize()
    rot = np.array([q0[3], q0[4], 0.0])
    for rb in added:
        for e in rb.elements:
            x = state.q[e, :3].copy()
            state.q[e, :3] = x + 0.5 * (q0[:3] + np.cross(rot, x))
    for rb, row in zip(added, row_defs):
        w_c = set_rolling(state, rb.elements, row, omega)
        state.v[rb.cage, 3:] = (0.0, 0.0, w_c)
    return WindScene(model, state, inner, outer, tuple(added), row_defs, t, f, mb)


def guide_cage(b: ModelBuilder, outer: int, cage: int, row, cage_kg: float) -> None:
    """Guidance of a cage by its land on the outer ring: three axial springs at 120° on the cage's
    pitch circle (``CAGE_GUIDE_STIFFNESS_N_PER_M`` together, ``CAGE_GUIDE_DAMPING_RATIO`` of
    critical for the cage's mass) hold it along the axis and in tilt, and a radial spring of the
    same stiffness at its centre holds it on the axis; it turns freely. Land friction is left out.

    A slot pocket pushes a roller only round the circumference, so nothing else holds a cage along
    the axis; the friction of the spinning rollers on the pocket walls of a thrust cage all points
    the same way along z (their surface moves axially there) and would push the cage off its row.
    Radially, a thrust cage carries its rollers' weight through the pocket ends and would sink."""
    R, z0 = row.pitch_diameter_m / 2, row.axial_position_m
    k = CAGE_GUIDE_STIFFNESS_N_PER_M / 3.0
    c = CAGE_GUIDE_DAMPING_RATIO * 2.0 * math.sqrt(CAGE_GUIDE_STIFFNESS_N_PER_M * cage_kg) / 3.0
    for phi in 2.0 * math.pi * np.arange(3) / 3.0:
        b.add_bushing(outer, cage, (R * math.cos(phi), R * math.sin(phi), z0), (0.0, 0.0, k, 0.0, 0.0, 0.0),
                      (0.0, 0.0, c, 0.0, 0.0, 0.0))
    # radially: one spring pair at the centre, a point that the cage's turning does not move
    k, c = 3.0 * k, 3.0 * c
    b.add_bushing(outer, cage, (0.0, 0.0, z0), (k, k, 0.0, 0.0, 0.0, 0.0), (c, c, 0.0, 0.0, 0.0, 0.0))


def rolling_speeds(row, omega_inner_rad_s: float) -> tuple[float, float]:
    """(orbit speed ω_c about z, spin ω_s about the roller axis, absolute) of a roller rolling
    without slip between the inner ring turning at ω_i and the fixed outer ring, rad/s.

    With a the roller axis (+z for the radial row, +e_r for the thrust rows), n the unit vector
    from the roller centre x towards the inner ring's raceway and r = D/2, the roller's absolute
    angular velocity is ω_c ẑ + ω_s a; no slip at p± = x ± r n along e_θ gives
        ω_c ρ(p+) + ω_s ((a × r n)·e_θ) = ω_i ρ(p+),   ω_c ρ(p−) − ω_s ((a × r n)·e_θ) = 0,
    ρ the distance from the axis (Harris & Kotzalas, *Essential Concepts*, ch. 8: ω_c = ω_i(1 − γ)/2
    for the radial row, ω_i/2 for a thrust row).
    """
    R, r = row.pitch_diameter_m / 2, row.roller_diameter_m / 2
    e_r, e_t, z = np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), np.array([0, 0, 1.0])
    if row.orientation == "radial":
        a, n = z, -e_r
    else:
        a, n = e_r, -row.load_sign * z
    x = R * e_r
    rho_p, rho_m = np.linalg.norm((x + r * n)[:2]), np.linalg.norm((x - r * n)[:2])
    g = float(np.cross(a, r * n) @ e_t)
    A = np.array([[rho_p, g], [rho_m, -g]])
    w_c, w_s = np.linalg.solve(A, [omega_inner_rad_s * rho_p, 0.0])
    return float(w_c), float(w_s)


def set_rolling(state, elements, row, omega_inner_rad_s: float) -> float:
    """Give a row's rollers their no-slip velocities (:func:`rolling_speeds`); returns ω_c."""
    w_c, w_s = rolling_speeds(row, omega_inner_rad_s)
    for e in elements:
        x = state.q[e, :3]
        state.v[e, :3] = w_c * np.array([-x[1], x[0], 0.0])
        qe = state.q[e, 3:]
        axis_world = _rotate(qe, np.array([0.0, 0.0, 1.0]))
        state.v[e, 3:] = _rotate_back(qe, w_c * np.array([0.0, 0.0, 1.0]) + w_s * axis_world)
    return w_c
