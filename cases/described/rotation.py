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

Friction torque: the moment about the bearing axis of what the elements, cages and spacers put on each
ring (:func:`mbd_core.multibody.ring_torque.axial_torques`), its mean, ripple and spectrum over the run
after its start-up share, and the residual of their balance with the rate of the rolling set's angular
momentum (``balance_residual_Nm``; exact for explicit friction, approximate with implicit friction).

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
from mbd_core.multibody import StepTooLargeError, largest_load_step_error
from mbd_core.multibody.bearings import _rotate, row_speed_rad_s
from mbd_core.quasistatic import Bearing, FourPointRow, solve_load_distribution

from ..config import CaseError
from ..integrate import integrate, integrate_implicit
from ..ring_torque_report import write_ring_torque
from .rotation_scene import RotationScene, build_scene, check_rotation, modal_mass_kg, modal_rings, start_state

__all__ = ["RotationScene", "check_rotation", "modal_rings", "build_scene", "start_state", "reference_loads",
           "flexible_reference_loads", "compare", "run_rotation", "START_UP_SHARE", "COMPARED_SAMPLES"]

#: share of the run at its start (the transient from the start state) left out of the key figures
START_UP_SHARE = 0.3
#: samples of the settled window compared with the quasi-static load distribution
COMPARED_SAMPLES = 12
#: the implicit run's default step over the automatic explicit one: the caged angular-contact test
#: bearing at 1000 r/min (cage pockets with play) runs at 2× to 4×; from 5× on its Newton iteration
#: fails at some steps on the pocket impacts (the slewing ring takes 20×)
IMPLICIT_STEP_FACTOR = 3.0


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


def _row_phase_rad(row, q: np.ndarray) -> float:
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


def _kinematic_cage_rad_s(row, alpha_rad: float, omega_rad_s: float) -> float:
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
        pairs = list(rb.moving_pairs)
        qs = np.array([loads[i] for loads, _ in refs])
        q_max = float(qs.max())
        dev = np.abs(run["fn"][picks][:, pairs] - qs) / q_max if q_max > 0 else np.full(qs.shape, math.nan)
        fn = run["fn"][settled][:, pairs]
        alpha = row.contact_angle_rad
        if fn.max() > 0:
            alpha = float(run["angle"][settled][:, pairs][fn > 0.05 * fn.max()].mean())
        kin = _kinematic_cage_rad_s(row, alpha, omega_rad_s)
        w = row_speed_rad_s(rb, run["q"][settled], run["v"][settled])
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


def _ring_torque(sc: RotationScene, run: dict, out) -> None:
    """The friction torque on both rings about the axis over the settled part (:mod:`cases.ring_torque_report`)."""
    t = np.asarray(run["t"])
    write_ring_torque(sc.model, run, {"moving": sc.moving, "fixed": sc.fixed}, t[0] + START_UP_SHARE * (t[-1] - t[0]),
                      out, "Torque of the rolling elements, cages and drag on the rings about the axis")


def run_rotation(case, desc, out, progress=None) -> None:
    """Build, start and run the scene; write the series, the comparison and a plot."""
    from .rotation_plots import plot_rotation

    check_rotation(desc, case.bearing.rings, case.rotation)
    rot = case.rotation
    reference = solve_load_distribution(desc.bearing, desc.default_load)
    sc = build_scene(desc, rot, reference, modal_rings(desc, case.bearing.rings))
    state = start_state(sc)
    implicit = rot.integrator == "implicit"
    if implicit:
        run = integrate_implicit(sc.model, state, rot.duration_s, rot.record_every, rot.rho_inf, rot.timestep_s,
                                 key="rotation.timestep_s", step_factor=IMPLICIT_STEP_FACTOR)
    else:
        try:
            run = integrate(sc.model, state, rot.duration_s, rot.record_every, progress, timestep_s=rot.timestep_s)
        except StepTooLargeError as exc:
            raise CaseError(f"rotation.timestep_s = {rot.timestep_s:g} s: {exc}") from None
    omega = rot.speed_rpm * 2.0 * math.pi / 60.0
    fig = compare(sc, desc, run, omega)
    moving = [p for rb in sc.row_bodies for p in rb.moving_pairs]
    fig["error_estimates"] = {"time_step": None if implicit else
                              largest_load_step_error(sc.model, state, run["timestep_s"], moving)}
    fig["integrator"] = ({"kind": "generalized-alpha (implicit)", "rho_inf": rot.rho_inf} if implicit
                         else {"kind": "explicit (velocity Verlet)"})
    fig["rings"] = {side: {"modal": side in sc.modal, **({"n_modes": int(sc.modal[side][1].n_modes),
                                                         "mass_kg": modal_mass_kg(sc.modal[side][1])}
                                                      if side in sc.modal else {})} for side in ("moving", "fixed")}
    fig.update(timestep_s=run["timestep_s"], steps=int(round(rot.duration_s / run["timestep_s"])),
               pocket_clearance_m={r.name: desc.separators[r.name].pocket_clearance(r.ball_diameter_m)
                                   for r in sc.rows if desc.separators[r.name].kind == "cage"})
    out.summary.update(fig)
    out.write_timeseries(sc.model, run, case=case.name, study="rotation")
    t = run["t"]
    for i, (row, rb) in enumerate(zip(sc.rows, sc.row_bodies)):
        name = "".join(c if c.isalnum() else "_" for c in row.name)
        columns = ([f"ball_{j + 1}_{d}_N" for j in range(row.n_balls) for d in ("plus_alpha", "minus_alpha")]
                   if isinstance(row, FourPointRow) else [f"ball_{j + 1}_N" for j in range(row.n_balls)])
        out.write_csv(f"element_loads_{name}.csv", ["t_s"] + columns,
                      (np.concatenate([[ti], fi]) for ti, fi in zip(t, run["fn"][:, list(rb.moving_pairs)])))
    out.save_figure(plot_rotation(sc, desc, run, fig), "rotation.png")
    _ring_torque(sc, run, out)
    for r in fig["rows"]:
        speed = r.get("cage_speed_rpm", r.get("ball_orbit_speed_rpm"))
        out.note(f"row {r['row']}: largest ball load {r['largest_load_N']:.0f} N (quasi-static "
                 f"{r['quasistatic_largest_load_N']:.0f} N), largest deviation from the quasi-static loads "
                 f"{100 * r['max_deviation_from_quasistatic']:.2f} % of it; "
                 f"{'cage' if 'cage_speed_rpm' in r else 'ball orbit'} {speed:.3f} rpm = "
                 f"{r['orbit_over_kinematic']:.4f} × no-slip")
    step = fig["error_estimates"]["time_step"]
    if step is None:
        out.note(f"implicit generalized-α run, ρ∞ = {rot.rho_inf:g}, step {run['timestep_s']:.3g} s, {fig['steps']} "
                 "steps (its step is not estimated: the Richardson window repeats explicit steps)")
    else:
        out.note(f"explicit step {run['timestep_s']:.3g} s, {fig['steps']} steps; time-step error of the largest "
                 f"ball load (Richardson): {100 * step['max_load']:.2g} %")
