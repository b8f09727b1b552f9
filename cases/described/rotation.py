"""The ``rotation`` study of a described bearing: its moving ring turning under the file's load.

Scene: the fixed ring held; the moving ring driven about the bearing axis at ``rotation.speed_rpm``,
free to move and tilt under the load of the file (constant, applied at the bearing centre; with
``rotation.gravity_m_s2`` the elements, spacers and cages have their weight too); every
ball row with its balls in both grooves (Hertz contacts, damping, friction) and its
``[rows.separator]``:

- ``cage``: a rigid cage of the given mass with a cylindrical pocket per ball and the given play
  (:func:`mbd_core.multibody.bearings.add_ball_row`), centred on the fixed ring by a radial
  spring (land guidance, ``CAGE_GUIDE_STIFFNESS_N_PER_M``) and free to turn, move along the axis
  and tilt (its pockets hold it there);
- ``spacer_balls``: a spacer ball between each pair of neighbouring balls, in both grooves and
  touching its two neighbours (ball–ball Hertz contacts), no cage;
- ``full_complement``: neighbouring balls touch each other.

Start: the static equilibrium with every ball (and spacer) held at its azimuth, then the no-slip
rolling velocities of the balls, the cage at their mean orbit speed and the spacers rolling on the
fixed groove at that speed.

Reference: the quasi-static load distribution of the same rows under the same load
(:func:`mbd_core.quasistatic.solve_load_distribution`), evaluated with the balls at the azimuths
they have in the run (one solve per compared sample, each ball a one-ball row at its azimuth), and
the no-slip cage speed ω_c = ω_m (1 ∓ D cos α/d_m)/2 of the loaded contact angle (Harris &
Kotzalas, *Essential Concepts*, ch. 8). The quasi-static model has neither friction nor the balls'
centrifugal and gyroscopic forces: the deviation from it measures them.

Modal rings: the rings the file gives ``[rings.X]`` tables (unless ``bearing.rings = "rigid"``) are
modal bodies (their reductions as for the quasi-static study, raceways sampled the same way): the
moving one driven, its mass that of its finite-element model; the fixed one held at its frame.
Their reference is then the flexible-ring quasi-static solution
(:func:`flexible_reference_loads`), each row evenly spaced at the phase of its balls.

Four-point rows: each ring's gothic arch is two grooves, one per diagonal, and each ball has four
contacts (:func:`mbd_core.multibody.bearings.add_ball_row`); loads are compared per ball and
diagonal. Rows the multibody model does not have (roller rows) are refused, naming the key,
before anything is built.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from mbd_core.bearing import rolling_kinematics
from mbd_core.contact import ball_on_groove
from mbd_core.contact.hertz import sphere_on_sphere
from mbd_core.multibody import Driven, Fixed, ModelBuilder, StepTooLargeError, largest_load_step_error
from mbd_core.multibody.bearings import _rotate, _rotate_back, add_ball_row, ball_mass_kg, set_rolling_velocities
from mbd_core.multibody.builder import ContactLaw
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.quasistatic import BallRow, Bearing, FourPointRow, solve_load_distribution

from ..config import CaseError
from ..integrate import integrate

__all__ = ["RotationScene", "check_rotation", "modal_rings", "build_scene", "start_state", "reference_loads",
           "flexible_reference_loads", "compare", "run_rotation", "CAGE_GUIDE_STIFFNESS_N_PER_M",
           "POCKET_STIFFNESS_N_PER_M"]

#: radial stiffness of a cage's land guidance on the fixed ring, N/m; its damping ratio
CAGE_GUIDE_STIFFNESS_N_PER_M = 1e7
CAGE_GUIDE_DAMPING_RATIO = 0.3
#: stiffness of a ball in its cage pocket (linear), N/m
POCKET_STIFFNESS_N_PER_M = 1e8
#: penetration over which the contact damping ramps in, m (well below a Hertz approach)
D_MAX_M = 1e-6
#: share of the run at its start (the transient from the start state) left out of the key figures
START_UP_SHARE = 0.3
#: samples of the settled window compared with the quasi-static load distribution
COMPARED_SAMPLES = 12


@dataclasses.dataclass
class RotationScene:
    """The model, its start state and what a run reads back, per row: the ``RowBodies`` and the
    spacers; ``modal``: the modal rings by side (:func:`modal_rings`)."""

    model: object
    state: object
    moving: int
    fixed: int
    rows: tuple
    row_bodies: tuple
    spacers: tuple
    spacer_pairs: tuple
    neighbour_pairs: tuple
    modal: dict = dataclasses.field(default_factory=dict)


def check_rotation(desc, rings: str, rotation) -> None:
    """Refuse, naming the key, what the rotation study does not model (before anything is built)."""
    modal_moving = rings == "file" and any(m.side == "moving" for m in desc.rings.values())
    if rotation.moving_ring_mass_kg is None and not modal_moving:
        raise CaseError("rotation.moving_ring_mass_kg: missing key (the mass of the moving ring and of what turns "
                        "with it, kg; the rotation study needs it)")
    if rotation.moving_ring_mass_kg is not None and modal_moving:
        raise CaseError("rotation.moving_ring_mass_kg: the moving ring is modal ([rings.X] of the file): its mass is "
                        "its finite-element model's; leave the key out (or set bearing.rings = \"rigid\")")
    if len(desc.load_cases) != 1:
        raise CaseError(f"bearing.file: the rotation study applies one constant load; the file gives "
                        f"{len(desc.load_cases)} load cases (a spectrum or a time history)")
    for row in desc.bearing.rows:
        where = f"the row {row.name!r}"
        if not isinstance(row, (BallRow, FourPointRow)):
            raise CaseError(f"bearing.file: {where}: the rotation study runs ball rows; roller rows are modelled "
                            "quasi-statically only")
        if row.name not in desc.separators:
            raise CaseError(f"bearing.file: {where} has no [rows.separator] table: the rotation study needs "
                            "kind = 'cage', 'spacer_balls' or 'full_complement'")


def modal_rings(desc, rings: str) -> dict:
    """side ("moving", "fixed") → (RingModel, ReducedBody) of the rings the file makes modal
    (reduced here or loaded from the cache); none with ``rings = "rigid"``."""
    if rings == "rigid" or not desc.rings:
        return {}
    from foundation.progress import phase

    from ..bearing_rings import reduce_ring

    with phase(f"modal rings of {desc.name}"):
        return {m.side: (m, reduce_ring(m, desc.bearing)) for m in desc.rings.values()}


def _modal_mass_kg(body) -> float:
    from cms_reduction.invariants import Invariants

    return float(Invariants.from_arrays(body.extras).mass_kg)


def _contact_constants(row: BallRow) -> tuple[float, float]:
    """Hertz constants K (N/m^1.5) of a ball on the moving and on the fixed groove."""
    fixed = "outer" if row.moving_raceway == "inner" else "inner"
    k_m = ball_on_groove(row.ball_diameter_m, row.conformity_moving, row.pitch_diameter_m, row.contact_angle_rad,
                         row.moving_raceway, row.ball_material, row.race_material).stiffness_N_per_m1p5
    k_f = ball_on_groove(row.ball_diameter_m, row.conformity_fixed, row.pitch_diameter_m, row.contact_angle_rad,
                         fixed, row.ball_material, row.race_material).stiffness_N_per_m1p5
    return k_m, k_f


def _damping_N_s_m(row: BallRow, largest_load_N: float, ratio: float) -> float:
    """``ratio`` × 2√(k m): k = 1.5 K δ^½ the linearised stiffness of the stiffer contact at the
    row's largest quasi-static load (at least 1 % of the ball's weight-free scale: 1 N)."""
    K = max(_contact_constants(row))
    delta = (max(largest_load_N, 1.0) / K) ** (2.0 / 3.0)
    m = ball_mass_kg(row.ball_diameter_m, row.ball_material.density_kg_m3)
    return ratio * 2.0 * math.sqrt(1.5 * K * math.sqrt(delta) * m)


def _add_spacers(b, row: BallRow, rb, moving, fixed, diameter_m: float, damping: float, friction):
    """A spacer ball half-way between each pair of neighbouring balls, on the balls' pitch circle,
    with contacts to both grooves and to its two neighbours."""
    D, d = row.ball_diameter_m, diameter_m
    fixed_raceway = "outer" if row.moving_raceway == "inner" else "inner"
    laws = []
    for conformity, raceway in ((row.conformity_moving, row.moving_raceway), (row.conformity_fixed, fixed_raceway)):
        k = ball_on_groove(d, conformity * D / d, row.pitch_diameter_m, row.contact_angle_rad, raceway,
                           row.ball_material, row.race_material).stiffness_N_per_m1p5
        laws.append(ContactLaw(k, 1.5, damping, D_MAX_M, friction=friction))
    law_ball = ContactLaw(sphere_on_sphere(D, d).stiffness_N_per_m1p5, 1.5, damping, D_MAX_M, friction=friction)
    m = ball_mass_kg(d, row.ball_material.density_kg_m3)
    R, n = row.pitch_diameter_m / 2, row.n_balls
    spacers, pairs = [], []
    for j in range(n):
        psi = row.first_azimuth_rad + 2.0 * math.pi * (j + 0.5) / n
        s = b.add_body(f"{row.name} spacer {j}", m, (0.1 * m * d * d,) * 3,
                       position_m=(R * math.cos(psi), R * math.sin(psi), row.axial_position_m))
        for k, diagonal in enumerate(rb.grooves):  # both arches of a four-point groove
            for ring, side, groove, law in zip((moving, fixed), ("moving", "fixed"), diagonal, laws):
                b.add_ball_groove(s, ring, groove, d / 2, law, name=f"{row.name} spacer {j}–{side} {k}")
        for k in (j, (j + 1) % n):
            pairs.append(b.add_ball_ball(rb.elements[k], s, D / 2, d / 2, law_ball,
                                         name=f"{row.name} ball {k}–spacer {j}"))
        spacers.append(s)
    return tuple(spacers), tuple(pairs)


def _add_neighbours(b, row: BallRow, rb, damping: float, friction) -> tuple:
    """Full complement: ball j touches ball j + 1."""
    D, n = row.ball_diameter_m, row.n_balls
    law = ContactLaw(sphere_on_sphere(D, D).stiffness_N_per_m1p5, 1.5, damping, D_MAX_M, friction=friction)
    return tuple(b.add_ball_ball(rb.elements[j], rb.elements[(j + 1) % n], D / 2, D / 2, law,
                                 name=f"{row.name} ball {j}–ball {(j + 1) % n}") for j in range(n))


def _ring(b, name: str, motion, omega: float, modal: tuple | None, mass_kg: float, radius_m: float):
    """A ring body: the modal one of ``modal`` (RingModel, ReducedBody), else rigid, a thin ring of
    ``mass_kg`` on ``radius_m``; returns (index, mass kg)."""
    if modal is not None:
        return b.add_modal_body(name, modal[1], motion=motion, omega_rad_s=(0.0, 0.0, omega)), _modal_mass_kg(modal[1])
    m, R = mass_kg, radius_m
    return b.add_body(name, m, (0.5 * m * R * R, 0.5 * m * R * R, m * R * R), motion=motion,
                      omega_rad_s=(0.0, 0.0, omega)), m


def build_scene(desc, rotation, reference, modal: dict | None = None) -> RotationScene:
    """The multibody model of the described bearing at rest (``reference``: its quasi-static
    load distribution, for the damping scale; ``modal``: :func:`modal_rings`)."""
    rows = desc.bearing.rows
    modal = modal or {}
    omega = rotation.speed_rpm * 2.0 * math.pi / 60.0
    g = rotation.gravity_m_s2
    b = ModelBuilder(gravity_m_s2=(0.0, 0.0, -g))
    R = max(r.pitch_diameter_m for r in rows) / 2
    m_given = rotation.moving_ring_mass_kg
    moving, m = _ring(b, "moving ring", Driven(omega, translation_free=True, tilt_free=True), omega,
                      modal.get("moving"), m_given or 0.0, R)
    fixed, _ = _ring(b, "fixed ring", Fixed(), 0.0, modal.get("fixed"), m, R)
    samples = {side: ring[0].raceways for side, ring in modal.items()}
    friction = rotation.friction_law()
    added, spacers, spacer_pairs, neighbours = [], [], [], []
    for row, loads in zip(rows, reference.rows):
        sep = desc.separators[row.name]
        c = _damping_N_s_m(row, float(np.max(loads.load_N)), rotation.damping_ratio)
        cage = {}
        if sep.kind == "cage":
            cage = dict(cage_mass_kg=sep.mass_kg, pocket_clearance_m=sep.pocket_clearance(row.ball_diameter_m),
                        cage_stiffness_N_per_m=POCKET_STIFFNESS_N_PER_M, pocket_friction=friction)
        rb = add_ball_row(b, row, moving, fixed, friction=friction, damping_N_s_m=c, d_max_m=D_MAX_M,
                          moving_sample=samples.get("moving", {}).get(row.name),
                          fixed_sample=samples.get("fixed", {}).get(row.name), **cage)
        if rb.cage is not None:
            k = CAGE_GUIDE_STIFFNESS_N_PER_M
            c_g = CAGE_GUIDE_DAMPING_RATIO * 2.0 * math.sqrt(k * sep.mass_kg)
            b.add_bushing(fixed, rb.cage, (0.0, 0.0, row.axial_position_m), (k, k, 0, 0, 0, 0), (c_g, c_g, 0, 0, 0, 0))
        if sep.kind == "spacer_balls":
            s, p = _add_spacers(b, row, rb, moving, fixed, sep.spacer_diameter_m, c, friction)
            spacers.append(s)
            spacer_pairs.append(p)
        else:
            spacers.append(())
            spacer_pairs.append(())
        neighbours.append(_add_neighbours(b, row, rb, c, friction) if sep.kind == "full_complement" else ())
        added.append(rb)
    load = desc.default_load
    # the file's load includes the moving ring's weight: gravity on its mass is taken off again
    b.add_force(moving, (load.Fx_N, load.Fy_N, load.Fz_N + m * g), (load.Mx_Nm, load.My_Nm, 0.0))
    model, state = b.finalize()
    return RotationScene(model, state, moving, fixed, tuple(rows), tuple(added), tuple(spacers), tuple(spacer_pairs),
                         tuple(neighbours), modal)


def _orbit_rad_s(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Orbit speed about z of points at q moving at v (last axis x, y, z), rad/s."""
    return (q[..., 0] * v[..., 1] - q[..., 1] * v[..., 0]) / (q[..., 0] ** 2 + q[..., 1] ** 2)


def start_state(sc: RotationScene):
    """The static equilibrium with the balls and spacers held at their azimuths, then rolling velocities."""
    held = [e for rb in sc.row_bodies for e in rb.elements] + [s for row in sc.spacers for s in row]
    spin = sc.state.v[sc.moving, 3:].copy()
    state = static_equilibrium(sc.model, sc.state, fixed_azimuth=held).state
    state.v[sc.moving, 3:] = spin
    for rb, spacers, row in zip(sc.row_bodies, sc.spacers, sc.rows):
        set_rolling_velocities(sc.model, state, rb.elements, sc.moving, sc.fixed)
        idx = list(rb.elements)
        w_c = float(np.mean(_orbit_rad_s(state.q[idx, :3], state.v[idx, :3])))
        if rb.cage is not None:
            state.v[rb.cage, 3:] = _rotate_back(state.q[rb.cage, 3:], np.array([0.0, 0.0, w_c]))
        a = sc.model.arrays
        for s in spacers:
            x = state.q[s, :3]
            v = w_c * np.cross([0.0, 0.0, 1.0], x)
            c = int(np.flatnonzero((a.pair_a == s) & (a.pair_b == sc.fixed))[0])
            g = a.pair_geom[c]
            centre = np.array([a.groove_rc[g] * x[0], a.groove_rc[g] * x[1], 0.0]) / math.hypot(x[0], x[1])
            centre[2] = a.groove_zc[g]
            n = (x - centre) / np.linalg.norm(x - centre)  # towards the fixed groove's surface
            state.v[s, :3] = v
            state.v[s, 3:] = _rotate_back(state.q[s, 3:], np.cross(v, n) / a.pair_radius[c])  # rolls on it
    return state


def reference_loads(desc, q_elements: list[np.ndarray]) -> tuple[list[np.ndarray], np.ndarray]:
    """The quasi-static solution with every ball at its azimuth in ``q_elements`` (per row,
    (balls, 3) positions): per row the contact loads, N (:func:`_contact_loads`), and the moving
    ring's displacement (x, y, z, θx, θy). Each ball is a one-ball row of its own, so that balls that
    a cage's play or their free orbits have moved off the even spacing are where the run has them."""
    singles = []
    for row, q in zip(desc.bearing.rows, q_elements):
        psi = np.arctan2(q[:, 1], q[:, 0])
        singles += [dataclasses.replace(row, name=f"{row.name} #{j}", n_balls=1, first_azimuth_rad=float(p))
                    for j, p in enumerate(psi)]
    res = solve_load_distribution(Bearing(desc.bearing.name, tuple(singles)), desc.default_load)
    loads = [_contact_loads(r) for r in res.rows]
    ends = np.cumsum([0] + [len(q) for q in q_elements])
    return [np.concatenate(loads[a:b]) for a, b in zip(ends[:-1], ends[1:])], np.asarray(res.displacement, float)


def _contact_loads(r) -> np.ndarray:
    """A row's loads in the order of its moving contact pairs: per ball, or (four-point rows) per
    ball and diagonal, +α then −α."""
    return np.asarray(r.load_N if r.contact_load_N is None else r.contact_load_N, float).reshape(-1)


def _row_phase_rad(row: BallRow, q: np.ndarray) -> float:
    """The row's first azimuth that fits its balls' azimuths best (circular mean of ψ_j − 2πj/Z)."""
    psi = np.arctan2(q[:, 1], q[:, 0]) - 2.0 * math.pi * np.arange(row.n_balls) / row.n_balls
    return float(np.arctan2(np.sin(psi).mean(), np.cos(psi).mean()))


def flexible_reference_loads(desc, modal: dict, q_elements: list[np.ndarray],
                             ring_angle_rad: float) -> tuple[list[np.ndarray], np.ndarray]:
    """As :func:`reference_loads` with the file's modal rings (:func:`modal_rings`), the moving one
    turned by ``ring_angle_rad``: each row evenly spaced at the phase that fits its balls (the
    flexible model samples each row's raceway as a whole, so a ball off the even spacing is not
    placed on its own; with a cage they stay within the pocket play)."""
    from mbd_core.quasistatic.flexible import FlexibleRing, build_flexible_model
    from mbd_core.quasistatic.flexible_solve import solve_flexible_load_distribution

    rows = tuple(dataclasses.replace(r, first_azimuth_rad=_row_phase_rad(r, q))
                 for r, q in zip(desc.bearing.rows, q_elements))
    rings = tuple(FlexibleRing(m.name, body, side, dict(m.raceways), ring_angle_rad if side == "moving" else 0.0)
                  for side, (m, body) in modal.items())
    res = solve_flexible_load_distribution(build_flexible_model(Bearing(desc.bearing.name, rows), rings),
                                           desc.default_load)
    return [_contact_loads(r) for r in res.rows], np.asarray(res.displacement, float)[:5]


def _kinematic_cage_rad_s(row: BallRow, alpha_rad: float, omega_rad_s: float) -> float:
    inner, outer = (omega_rad_s, 0.0) if row.moving_raceway == "inner" else (0.0, omega_rad_s)
    return rolling_kinematics(row.ball_diameter_m, row.pitch_diameter_m, alpha_rad, row.n_balls, inner,
                              outer).cage_speed_rad_s


def _ring_displacement(q_ring: np.ndarray) -> np.ndarray:
    """(samples, 7) poses of the moving ring → (samples, 5) displacements x, y, z, θx, θy (its
    axis ẑ_body = (θy, −θx, 1) for small tilts)."""
    axis = np.array([_rotate(qi[3:], np.array([0.0, 0.0, 1.0])) for qi in q_ring])
    return np.column_stack([q_ring[:, :3], -axis[:, 1], axis[:, 0]])


def _separator_forces(run: dict, settled: np.ndarray, pairs, what: str) -> dict:
    if not pairs:
        return {}
    f = run["fn"][settled][:, list(pairs)]
    return {f"max_{what}_force_N": float(f.max()), f"mean_{what}_force_N": float(f.mean())}


def compare(sc: RotationScene, desc, run: dict, omega_rad_s: float) -> dict:
    """Per row and over the bearing: the run's settled ball loads against the quasi-static ones at
    the same azimuths, the cage (or ball orbit) speed against the no-slip one, cage and spacer
    forces; the moving ring's mean displacement against the quasi-static one at the same samples."""
    t = run["t"]
    settled = t >= t[0] + START_UP_SHARE * (t[-1] - t[0])
    picks = np.flatnonzero(settled)[np.linspace(0, settled.sum() - 1, min(COMPARED_SAMPLES, settled.sum())).astype(int)]
    refs = []
    for k in picks:
        q_elements = [run["q"][k, list(rb.elements), :3] for rb in sc.row_bodies]
        if sc.modal:
            qw, qz = run["q"][k, sc.moving, 3], run["q"][k, sc.moving, 6]
            refs.append(flexible_reference_loads(desc, sc.modal, q_elements, 2.0 * math.atan2(qz, qw)))
        else:
            refs.append(reference_loads(desc, q_elements))
    rows_out = []
    for i, (row, rb) in enumerate(zip(sc.rows, sc.row_bodies)):
        idx, pairs = list(rb.elements), list(rb.moving_pairs)
        qs = np.array([loads[i] for loads, _ in refs])
        q_max = float(qs.max())
        dev = np.abs(run["fn"][picks][:, pairs] - qs) / q_max if q_max > 0 else np.full(qs.shape, math.nan)
        fn = run["fn"][settled][:, pairs]
        alpha = row.contact_angle_rad
        if fn.max() > 0:
            alpha = float(run["angle"][settled][:, pairs][fn > 0.05 * fn.max()].mean())
        kin = _kinematic_cage_rad_s(row, alpha, omega_rad_s)
        if rb.cage is not None:
            w = run["v"][settled, rb.cage, 5]  # a cage turns about its own z, the axis
        else:
            w = _orbit_rad_s(run["q"][settled][:, idx, :3], run["v"][settled][:, idx, :3]).mean(axis=1)
        out = {"row": row.name, "largest_load_N": float(fn.max()), "quasistatic_largest_load_N": q_max,
               "max_deviation_from_quasistatic": float(dev.max()),
               "rms_deviation_from_quasistatic": float(np.sqrt((dev**2).mean())),
               "loaded_contact_angle_deg": math.degrees(alpha),
               "cage_speed_rpm" if rb.cage is not None else "ball_orbit_speed_rpm": float(w.mean() * 30 / math.pi),
               "kinematic_cage_speed_rpm": kin * 30 / math.pi, "orbit_over_kinematic": float(w.mean() / kin)}
        out.update(_separator_forces(run, settled, rb.pocket_pairs, "pocket"))
        out.update(_separator_forces(run, settled, sc.spacer_pairs[i], "spacer"))
        out.update(_separator_forces(run, settled, sc.neighbour_pairs[i], "ball_ball"))
        rows_out.append(out)
    scale = np.array([1e6, 1e6, 1e6, 1e3, 1e3])
    ring = {"components": ["x_um", "y_um", "z_um", "theta_x_mrad", "theta_y_mrad"],
            "dynamic_mean": [float(v) for v in _ring_displacement(run["q"][picks, sc.moving]).mean(axis=0) * scale],
            "quasistatic": [float(v) for v in np.mean([d for _, d in refs], axis=0) * scale]}
    worst = max(r["max_deviation_from_quasistatic"] for r in rows_out)
    return {"rows": rows_out, "max_deviation_from_quasistatic": worst,
            "settled_from_s": float(t[settled][0]), "compared_samples": len(picks), "moving_ring": ring}


def run_rotation(case, desc, out, progress=None) -> None:
    """Build, start and run the scene; write the series, the comparison and a plot."""
    from .rotation_plots import plot_rotation

    check_rotation(desc, case.bearing.rings, case.rotation)
    rot = case.rotation
    reference = solve_load_distribution(desc.bearing, desc.default_load)
    sc = build_scene(desc, rot, reference, modal_rings(desc, case.bearing.rings))
    state = start_state(sc)
    try:
        run = integrate(sc.model, state, rot.duration_s, rot.record_every, progress, timestep_s=rot.timestep_s)
    except StepTooLargeError as exc:
        raise CaseError(f"rotation.timestep_s = {rot.timestep_s:g} s: {exc}") from None
    omega = rot.speed_rpm * 2.0 * math.pi / 60.0
    fig = compare(sc, desc, run, omega)
    moving = [p for rb in sc.row_bodies for p in rb.moving_pairs]
    fig["error_estimates"] = {"time_step": largest_load_step_error(sc.model, state, run["timestep_s"], moving)}
    fig["rings"] = {side: {"modal": side in sc.modal, **({"n_modes": int(sc.modal[side][1].n_modes),
                                                         "mass_kg": _modal_mass_kg(sc.modal[side][1])}
                                                      if side in sc.modal else {})} for side in ("moving", "fixed")}
    fig.update(timestep_s=run["timestep_s"], steps=int(round(rot.duration_s / run["timestep_s"])),
               pocket_clearance_m={r.name: desc.separators[r.name].pocket_clearance(r.ball_diameter_m)
                                   for r in sc.rows if desc.separators[r.name].kind == "cage"})
    out.summary.update(fig)
    t = run["t"]
    for i, (row, rb) in enumerate(zip(sc.rows, sc.row_bodies)):
        name = "".join(c if c.isalnum() else "_" for c in row.name)
        columns = ([f"ball_{j + 1}_{d}_N" for j in range(row.n_balls) for d in ("plus_alpha", "minus_alpha")]
                   if isinstance(row, FourPointRow) else [f"ball_{j + 1}_N" for j in range(row.n_balls)])
        out.write_csv(f"element_loads_{name}.csv", ["t_s"] + columns,
                      (np.concatenate([[ti], fi]) for ti, fi in zip(t, run["fn"][:, list(rb.moving_pairs)])))
    out.save_figure(plot_rotation(sc, desc, run, fig), "rotation.png")
    for r in fig["rows"]:
        speed = r.get("cage_speed_rpm", r.get("ball_orbit_speed_rpm"))
        out.note(f"row {r['row']}: largest ball load {r['largest_load_N']:.0f} N (quasi-static "
                 f"{r['quasistatic_largest_load_N']:.0f} N), largest deviation from the quasi-static loads "
                 f"{100 * r['max_deviation_from_quasistatic']:.2f} % of it; "
                 f"{'cage' if 'cage_speed_rpm' in r else 'ball orbit'} {speed:.3f} rpm = "
                 f"{r['orbit_over_kinematic']:.4f} × no-slip")
    step = fig["error_estimates"]["time_step"]
    out.note(f"explicit step {run['timestep_s']:.3g} s, {fig['steps']} steps; time-step error of the largest "
             f"ball load (Richardson): {100 * step['max_load']:.2g} %")
