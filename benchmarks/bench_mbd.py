"""Explicit multibody step: wall time per step of a ball row and a roller row between rigid rings.

Two scenes, each started from its static equilibrium with rolling velocities and
stepped at 1e-5 s by the compiled loop (:func:`mbd_core.kernels.explicit.run_explicit`):

balls
    32 balls Ø95.2 mm (steel, 3.55 kg) on a Ø1.2 m pitch circle, 45° angular contact, conformity
    0.53/0.53, K = 1e11 N/m^1.5 per ball–groove contact (64 contacts), μ = 0.1; inner ring 800 kg
    driven at 15 rpm (free to translate and tilt), outer ring fixed; 100 kN axial + 50 kN radial
    on the inner ring. Exudyn 1.13 needs ≈ 0.43 ms per step for this scene (RK44, on this kind of machine).
rollers
    the radial row of the three-row wind bearing: 98 rollers Ø55 × 55 mm, 20 slices
    each, pitch Ø1.963 m, 10 µm preload, ISO/TS 16281 slice stiffness, μ = 0.1; inner ring 3971 kg
    driven at 15 rpm (free to translate and tilt), outer ring fixed; 500 kN radial.

The start is the quasi-static load distribution of the same row (rigid rings, Newton) with every
element centred between its raceways, then :func:`static_equilibrium` from there for the balls.
The single row tilts the ring by about 1.6 mrad under this load, and a cage-less ball on the tilted
groove is pushed along it by a few newtons: there is no exact equilibrium (the residual is
printed), so the static solver is given a small evaluation budget instead of running to its limit.
For the rollers the centred start is in equilibrium to about 1e-5 of the load already; the static
solver (finite-difference Jacobian over 593 unknowns) would add over 20 s without improving it.
The friction transition speed is the smallest that :func:`stable_timestep` accepts at 1e-5 s
(μ_static = μ_dynamic, v_dynamic = 2 v_static).

Only the stepping is timed (a short run first loads or compiles the kernels). The run is checked
against the load: the contact resultant on the inner ring (forces re-evaluated at the recorded
samples) against the applied load, and the sum of the contact normal forces against the static one.
Run::

    python benchmarks/bench_mbd.py [--quick]

Ends with one line of ``name=value`` figures (``us_per_step_balls=… us_per_contact=…
realtime_factor_balls=… us_per_step_rollers=… ns_per_slice=… peak_rss_mb=…``).
"""

from __future__ import annotations

import argparse
import math
import resource
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from mbd_core.contact.friction import Coulomb
from mbd_core.kernels.explicit import kinetic_energy, run_explicit
from mbd_core.kernels.forces import STATUS_OK, compute_forces
from mbd_core.multibody import (Driven, Fixed, ModelBuilder, State, evaluate_forces, quat_from_axis_angle,
                                stable_timestep)
from mbd_core.multibody.bearings import RowBodies, add_ball_row, add_roller_row, set_rolling_velocities
from mbd_core.multibody.model import Model, make_record_buffers, make_work
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.quasistatic import BallRow, Bearing, RingLoad, RollerRow, solve_load_distribution

TIMESTEP_S = 1e-5
SPEED_RPM = 15.0
MU = 0.1
EXUDYN_US_PER_STEP = 430.0  # Exudyn 1.13 on this kind of machine: 32 balls, 64 contacts, RK44 at 1e-5 s
RECORD_EVERY = 20
STATUS_TEXT = {1: "non-finite force", 2: "penetration beyond the bound", 3: "kinetic-energy runaway"}

BALL_ROW = BallRow("balls", 32, 95.2e-3, 1.2, math.radians(45.0), 0.53, 0.53, "inner", axial_sign=1,
                   stiffness_N_per_m1p5=1e11 / 2**1.5)  # series value: 1e11 N/m^1.5 per contact
BALL_LOAD_N = np.array([50e3, 0.0, 100e3])
ROLLER_ROW = RollerRow("radial", 98, 55e-3, 55e-3, 1.963, "radial", load_sign=1, gap_m=-10e-6, n_slices=20)
ROLLER_LOAD_N = np.array([500e3, 0.0, 0.0])


@dataclass(frozen=True)
class Scene:
    """A model, its start, and where to look: the driven ring, the elements and their contacts."""

    name: str
    model: Model
    state: State
    ring: int
    rows: RowBodies
    load_N: np.ndarray
    v_static_m_s: float


def _thin_ring_inertia(mass_kg: float, radius_m: float) -> tuple[float, float, float]:
    return (0.5 * mass_kg * radius_m**2, 0.5 * mass_kg * radius_m**2, mass_kg * radius_m**2)


def _rings(builder: ModelBuilder, inner_mass_kg: float, inner_radius_m: float, outer_mass_kg: float) -> tuple[int, int]:
    """Driven inner ring (free to translate and tilt) and fixed outer ring, with thin-ring inertias."""
    omega = SPEED_RPM * 2.0 * math.pi / 60.0
    outer = builder.add_body("outer ring", outer_mass_kg, _thin_ring_inertia(outer_mass_kg, 1.15 * inner_radius_m),
                             motion=Fixed())
    inner = builder.add_body("inner ring", inner_mass_kg, _thin_ring_inertia(inner_mass_kg, inner_radius_m),
                             motion=Driven(omega, translation_free=True, tilt_free=True))
    return inner, outer


def _friction(v_static_m_s: float) -> Coulomb:
    return Coulomb(MU, MU, v_static_m_s, 2.0 * v_static_m_s)


def build_balls(v_static_m_s: float):
    b = ModelBuilder()
    inner, outer = _rings(b, 800.0, 0.55, 1200.0)
    rows = add_ball_row(b, BALL_ROW, inner, outer, friction=_friction(v_static_m_s), damping_N_s_m=1e3)
    b.add_force(inner, BALL_LOAD_N)
    model, state = b.finalize()
    return model, state, inner, outer, rows


def build_rollers(v_static_m_s: float):
    b = ModelBuilder()
    inner, outer = _rings(b, 2271.0 + 1700.0, 0.9, 3055.0)
    rows = add_roller_row(b, ROLLER_ROW, inner, outer, friction=_friction(v_static_m_s), damping_N_s_m=50.0)
    b.add_force(inner, ROLLER_LOAD_N)
    model, state = b.finalize()
    return model, state, inner, outer, rows


def _rotate(quat: np.ndarray, x: np.ndarray) -> np.ndarray:
    w, u = quat[0], quat[1:]
    t = 2.0 * np.cross(u, x)
    return x + w * t + np.cross(u, t)


def _place_ring(state: State, ring: int, row, load_N: np.ndarray) -> None:
    """Put the ring where the quasi-static load distribution of ``row`` puts it."""
    load = RingLoad(Fx_N=float(load_N[0]), Fy_N=float(load_N[1]), Fz_N=float(load_N[2]))
    x, y, z, rot_x, rot_y = solve_load_distribution(Bearing("start", (row,)), load).displacement
    state.q[ring, :3] = (x, y, z)
    angle = math.hypot(rot_x, rot_y)
    state.q[ring, 3:] = quat_from_axis_angle((rot_x, rot_y, 0.0), angle) if angle > 0 else (1.0, 0.0, 0.0, 0.0)


def _centre_balls(model: Model, state: State, rows: RowBodies) -> None:
    """Each ball on the line between its two groove curvature centres, at equal approach to both."""
    a = model.arrays
    for e, c_m, c_f in zip(rows.elements, rows.moving_pairs, rows.fixed_pairs):
        x = state.q[e, :3].copy()
        for _ in range(10):  # the nearest curvature centre depends on the ball's angle on the groove
            centres, clear = [], []
            for c in (c_m, c_f):
                body, g = a.pair_b[c], a.pair_geom[c]
                quat = state.q[body, 3:]
                xl = _rotate(quat * (1.0, -1.0, -1.0, -1.0), x - state.q[body, :3])
                th = math.atan2(xl[1], xl[0])
                local = np.array([a.groove_rc[g] * math.cos(th), a.groove_rc[g] * math.sin(th), a.groove_zc[g]])
                centres.append(_rotate(quat, local) + state.q[body, :3])
                clear.append(a.groove_r[g] - a.pair_radius[c])
            span = centres[1] - centres[0]
            length = float(np.linalg.norm(span))
            x = centres[0] + span / length * 0.5 * (length + clear[0] - clear[1])
        state.q[e, :3] = x


def _centre_rollers(model: Model, state: State, rows: RowBodies) -> None:
    """Each radial roller moved along its radius to equal largest-slice approach on both raceways."""
    at_rest = State(state.t, state.q, np.zeros_like(state.v))
    for _ in range(3):  # the approaches are linear in the radius: one pass does it, two confirm
        delta = evaluate_forces(model, at_rest).contact_delta
        for e, c_m, c_f in zip(rows.elements, rows.moving_pairs, rows.fixed_pairs):
            e_r = np.append(state.q[e, :2] / np.linalg.norm(state.q[e, :2]), 0.0)
            moving_inside = model.arrays.race_kind[model.arrays.pair_geom[c_m]] == 0  # moving raceway: inner cylinder
            shift = 0.5 * (delta[c_m] - delta[c_f])
            state.q[e, :3] += (shift if moving_inside else -shift) * e_r


def smallest_transition_speed(build: Callable, state: State) -> tuple[float, str]:
    """Smallest v_static (2 significant digits, rounded up) for which TIMESTEP_S is within the stable limit."""
    def limit(v):
        return stable_timestep(build(v)[0], state)

    lo, hi = 1e-6, 100.0
    if limit(hi).limit_s < TIMESTEP_S:
        raise SystemExit(f"no transition speed makes {TIMESTEP_S:g} s stable: {limit(hi).reason}")
    for _ in range(40):
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if limit(mid).limit_s >= TIMESTEP_S else (mid, hi)
    digits = 1 - math.floor(math.log10(hi))
    v = math.ceil(hi * 10**digits) / 10**digits
    return v, limit(v).reason


def make_scene(name: str, build: Callable, row, load_N: np.ndarray, static_polish: bool) -> Scene:
    model, state, ring, outer, rows = build(1e-3)  # friction plays no part in the start
    t0 = time.perf_counter()
    _place_ring(state, ring, row, load_N)
    (_centre_balls if isinstance(row, BallRow) else _centre_rollers)(model, state, rows)
    if static_polish:  # no exact equilibrium for the balls: a small budget, not the solver's limit
        state = static_equilibrium(model, state, max_evaluations=40).state
    t_static = time.perf_counter() - t0
    at_rest = State(state.t, state.q, np.zeros_like(state.v))
    w = evaluate_forces(model, at_rest)
    elements = np.array(rows.elements)
    print(f"[{name}] start in {t_static:.1f} s: largest force left on an element "
          f"{np.abs(w.body_f[elements]).max():.3g} N, on the ring {np.linalg.norm(w.body_f[ring]):.3g} N "
          f"(load {np.linalg.norm(load_N):.3g} N)")
    v_s, reason = smallest_transition_speed(build, state)
    model, _, ring, outer, rows = build(v_s)
    state = State(state.t, state.q.copy(), state.v.copy())
    set_rolling_velocities(model, state, rows.elements, ring, other_ring=outer)
    limit = stable_timestep(model, state)
    print(f"[{name}] friction transition speed v_static = {v_s:.3g} m/s (v_dynamic {2 * v_s:.3g} m/s): "
          f"stable limit {limit.limit_s:.3g} s ≥ {TIMESTEP_S:g} s, set by {reason}")
    return Scene(name, model, state, ring, rows, load_N, v_s)


def run_steps(scene: Scene, n_steps: int):
    """Step the scene n_steps times; returns (wall seconds of the stepping, record buffers, samples)."""
    a = scene.model.arrays
    warm = scene.state.copy()
    w = make_work(scene.model)
    rec = make_record_buffers(scene.model, 2)
    compute_forces(a, warm.t, warm.q, warm.v, warm.eta, warm.eta_dot, w)
    run_explicit(a, warm.q, warm.v, warm.eta, warm.eta_dot, w, warm.t, 0, 2, TIMESTEP_S, 1, rec, math.inf)  # load or compile

    q, v = scene.state.q.copy(), scene.state.v.copy()
    w = make_work(scene.model)
    rec = make_record_buffers(scene.model, n_steps // RECORD_EVERY)
    e_limit = 1e3 * max(kinetic_energy(a.body_mass, a.body_inertia, v), 10.0)
    status, index = compute_forces(a, scene.state.t, q, v, scene.state.eta, scene.state.eta_dot, w)
    if status != STATUS_OK:
        raise SystemExit(f"[{scene.name}] start state: {STATUS_TEXT.get(status, status)} at {index}")
    t0 = time.perf_counter()
    status, index, done, k = run_explicit(a, q, v, scene.state.eta.copy(), scene.state.eta_dot.copy(), w, scene.state.t, 0, n_steps, TIMESTEP_S, RECORD_EVERY, rec, e_limit)
    wall = time.perf_counter() - t0
    if status != STATUS_OK:
        where = scene.model.pair_names[index] if 0 <= index < scene.model.n_pairs else f"index {index}"
        raise SystemExit(f"[{scene.name}] run stopped after {done} of {n_steps} steps "
                         f"(t = {(done + 1) * TIMESTEP_S:.6g} s): {STATUS_TEXT.get(status, status)} at {where}")
    return wall, rec, k


def check_load(scene: Scene, rec, k: int) -> dict:
    """Contact resultant on the driven ring and normal-force sums over the recorded samples."""
    model, ring = scene.model, scene.ring
    applied = model.arrays.body_force[ring, :3]
    moving = np.array(scene.rows.moving_pairs)
    w = make_work(model)
    resultant = np.empty((k, 3))
    for j in range(k):
        evaluate_forces(model, State(rec.t[j], rec.q[j], rec.v[j]), w)
        resultant[j] = w.body_f[ring] - applied
    start = evaluate_forces(model, State(scene.state.t, scene.state.q, np.zeros_like(scene.state.v)))
    fn = rec.fn[:k, moving]
    axial = (fn * np.abs(np.sin(rec.angle[:k, moving]))).sum(axis=1)
    load = float(np.linalg.norm(applied))
    return {
        "resultant_mean_N": -resultant.mean(axis=0),
        "resultant_dev": float(np.abs(resultant + applied).max()) / load,
        "sum_fn_start_N": float(start.contact_fn[moving].sum()),
        "sum_fn_N": (float(fn.sum(axis=1).mean()), float(fn.sum(axis=1).min()), float(fn.sum(axis=1).max())),
        "sum_fn_axial_N": float(axial.mean()),
        "max_fn_N": float(fn.max()),
        "ring_shift_m": float(np.linalg.norm(rec.q[k - 1, ring, :3] - scene.state.q[ring, :3])),
    }


def report(scene: Scene, n_steps: int, wall_s: float, c: dict, per: str, n_per: int) -> float:
    us = 1e6 * wall_s / n_steps
    print(f"[{scene.name}] {n_steps} steps of {TIMESTEP_S:g} s in {wall_s:.3f} s: {us:.2f} µs/step, "
          f"{1e3 * us / n_per:.1f} ns per {per} ({n_per}), {n_steps / wall_s:,.0f} steps/s, "
          f"real-time factor {n_steps * TIMESTEP_S / wall_s:.3g}")
    mean, lo, hi = c["sum_fn_N"]
    print(f"[{scene.name}] contact resultant on the inner ring (mean over the run) "
          f"{np.array2string(c['resultant_mean_N'] / 1e3, precision=2)} kN vs applied "
          f"{np.array2string(scene.load_N / 1e3, precision=2)} kN; largest deviation {100 * c['resultant_dev']:.2g} % "
          f"of the load (the ring's inertia force)")
    print(f"[{scene.name}] Σ normal force on the inner ring: start {c['sum_fn_start_N'] / 1e3:.2f} kN, run "
          f"{mean / 1e3:.2f} kN (range {lo / 1e3:.2f} … {hi / 1e3:.2f}); axial part Σ Q |sin α| "
          f"{c['sum_fn_axial_N'] / 1e3:.2f} kN; largest element load {c['max_fn_N'] / 1e3:.2f} kN; "
          f"ring moved {1e6 * c['ring_shift_m']:.2f} µm")
    return us


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="200 steps per scene instead of 2000")
    args = ap.parse_args()
    n_steps = 200 if args.quick else 2000

    balls = make_scene("balls", build_balls, BALL_ROW, BALL_LOAD_N, static_polish=True)
    wall, rec, k = run_steps(balls, n_steps)
    n_contacts = 2 * BALL_ROW.n_balls
    us_balls = report(balls, n_steps, wall, check_load(balls, rec, k), "contact", n_contacts)
    rt_balls = n_steps * TIMESTEP_S / wall
    print(f"[balls] Exudyn 0.43 ms/step / this = {EXUDYN_US_PER_STEP / us_balls:.3g} "
          f"(its RK44 evaluates the forces 4 times per step, velocity Verlet once)")

    rollers = make_scene("rollers", build_rollers, ROLLER_ROW, ROLLER_LOAD_N, static_polish=False)
    wall, rec, k = run_steps(rollers, n_steps)
    n_slices = 2 * ROLLER_ROW.n_rollers * ROLLER_ROW.n_slices
    us_rollers = report(rollers, n_steps, wall, check_load(rollers, rec, k), "slice", n_slices)

    figures = {
        "us_per_step_balls": us_balls,
        "us_per_contact": us_balls / n_contacts,
        "steps_per_s_balls": 1e6 / us_balls,
        "realtime_factor_balls": rt_balls,
        "exudyn_speedup": EXUDYN_US_PER_STEP / us_balls,
        "us_per_step_rollers": us_rollers,
        "ns_per_slice": 1e3 * us_rollers / n_slices,
        "realtime_factor_rollers": n_steps * TIMESTEP_S / wall,
        "v_static_balls_m_s": balls.v_static_m_s,
        "v_static_rollers_m_s": rollers.v_static_m_s,
        "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
    }
    print(" ".join(f"{k}={v:.4g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
