"""Explicit multibody step with a flexible (modal) ring whose ball contacts move along its raceway.

Two scenes, each started from its static equilibrium with rolling velocities and
stepped by the compiled loop (:func:`mbd_core.kernels.explicit.run_explicit`). Ring material of the
FE models: steel E = 200 GPa, ν = 0.3, ρ = 7850 kg/m³. Every flexible ring is a Craig–Bampton
reduction held at bolt patches (±30 mm of arc) with 13 fixed-interface normal modes plus 7 groove
load shapes (harmonics n = 0…3 along the contact normal): 20 modes, 2 % modal damping; its groove is
sampled at 360 angles, and a ball contact follows the deformed groove wherever the ball rolls.
Meshes: 27-node hexahedra of 40 mm (20 mm on the groove); ``--quick``: 10-node tetrahedra of 120 mm
(60 mm on the groove).

balls
    The "balls" scene of bench_mbd.py — 32 balls Ø95.2 mm (3.55 kg) on a Ø1.2 m pitch circle, 45°
    angular contact, conformity 0.53/0.53, K = 1e11 N/m^1.5 per ball–groove contact (64
    contacts), IMPACT damping 1e3 N·s/m, μ = 0.1; inner ring 800 kg driven at 15 rpm (free to
    translate and tilt); 100 kN axial + 50 kN radial on it — with the fixed outer ring in three
    variants: (rigid) a plain fixed body of the same mass; (modal explicit) a modal body with a
    fixed frame, its modes integrated explicitly; (modal implicit) the same with
    ``implicit_modes=True``. The modal outer ring is a 100 mm (radial) × 120 mm (axial) rectangle
    whose bore carries the groove (depth 0.3 D), 339 kg, held at 12 bolt patches on its top face at
    15° + k·30° (ball k at k·11.25°). 32 of the 64 contacts are then on the flexible groove. All
    three are timed at the common step 1e-5 s (Exudyn 1.13 with a 20-mode Craig–Bampton ring and
    contacts that cannot move: ≈ 8 ms per step on this kind of machine); each one's automatic stable step and
    the real-time factor there are reported too.
slewing
    The 1 m model of the slewing ring: 16 load balls Ø95.25 mm (3.55 kg) on a Ø1 m pitch circle,
    60° contact, conformity 0.525, Hertz stiffness (exact, AISI 52100 / 4140), alternating with 16
    spacer balls Ø85.25 mm (2.55 kg) that touch only the bottom race (ball–groove contact in the
    same groove, the spacer resting at its bottom) and their two neighbouring load balls (Hertz
    sphere–sphere), with about 8 mm of play at each at the start: 80 contacts. IMPACT damping
    2e4 N·s/m reached at 10 µm; μ_static 0.24, μ_dynamic 0.14. Bottom race rigid and fixed; top
    race (:func:`fem_rings.sections.slewing_top_race`, 220 × 100 mm, 494 kg) a modal body held at
    16 bolt patches on its bolt face, half-way between the load balls — the top-and-middle ring
    taken as rigid and part of the frame, which is driven at 6.55 rpm and free to translate and
    tilt; 68.9 t × g on the frame, gravity along −z. Measured: simulated seconds per wall second
    and the wall time of 25 simulated seconds (the source study's RecurDyn run needed 8 days).
    The same scene with the top race rigid (same mass) is timed for comparison, and with the modal top
    race's modes implicit (``implicit_modes``: the kicks solve with the augmented mass M + (h/2)C +
    (h/2)²K, :mod:`mbd_core.kernels.modal_step`) at the step its contacts allow: with the v_static that
    step needs, and with the explicit variant's v_static and the balls' friction implicit
    (``implicit_friction``, as in the named cases), the same friction law as the explicit variant.

Start: the rigid-ring variant's static equilibrium (:func:`static_equilibrium`, balls and spacers
held at their azimuth; the balls scene's ring placed first by the quasi-static load distribution),
then the modal variant's from there (its frame is held by the static solver; for the slewing ring
the rigid solution puts the frame where the load is carried, and the force left on it is printed).
Load balls get no-slip rolling velocities, spacers the same orbit speed rolling on the bottom race.

Time step. The friction law is regularised (Adams STEP, v_dynamic = 2 v_static) and an explicit
step must resolve its slope: as in bench_mbd.py, v_static is the smallest (2 significant digits)
that :func:`stable_timestep` accepts at the step used. The automatic step of each balls variant is
the one its contacts and modes allow (friction aside; v_static then grows in proportion). For the
slewing ring the frame is free to translate and tilt, and the inertia coupling of frame and
fixed-interface modes (∫ρΦ dV ≠ 0) raises the top frequency well above the highest kept mode;
:func:`stable_timestep` bounds the modes with unit modal mass, so the step used here is also kept
below the coupled bound 2/ω_max of (K, M_ff(η)), the generalised eigenvalues of the modal
stiffness and the mass matrix of the frame's free components and the modes (safety 0.8, which
also covers the raceway contacts' share, about 10 % in frequency).

Only the stepping is timed (a short run first loads or compiles the kernels), the fastest of
five runs from the same start. The run is checked against the load: Σ Q sin α of the contacts on
the loaded ring over the recorded samples against the applied load (and the weights it carries).
Run::

    python benchmarks/bench_modal.py [--quick]

Ends with one line of ``name=value`` figures (``us_per_step_modal_explicit=…
us_per_step_modal_implicit=… us_per_step_rigid=… realtime_factor_slewing=… wall_s_25s_slewing=…
wall_s_25s_slewing_implicit_modes=… wall_s_25s_slewing_implicit_modes_friction=… peak_rss_mb=…``).
"""

from __future__ import annotations

import argparse
import math
import resource
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.linalg

from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from fem_rings import MeshSpec
from fem_rings.sections import BallGroove, SlewingSection, grooved_ring, slewing_bottom_race, slewing_top_race
from mbd_core.contact import ball_on_groove, sphere_on_sphere
from mbd_core.contact.friction import Coulomb
from mbd_core.kernels.explicit import run_explicit, total_kinetic_energy
from mbd_core.kernels.forces import STATUS_OK, compute_forces
from mbd_core.kernels.modal import modal_mass_matrix
from foundation.materials import ElasticMaterial
from mbd_core.multibody import (ContactLaw, Driven, Fixed, ModelBuilder, State, evaluate_forces,
                                quat_from_axis_angle, stable_timestep)
from mbd_core.multibody.bearings import RowBodies, add_ball_row, ball_mass_kg, set_rolling_velocities
from mbd_core.multibody.model import Model, make_record_buffers, make_work
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.quasistatic import BallRow, Bearing, RingLoad, solve_load_distribution

G = 9.81
STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
REPEATS = 5
RECORD_EVERY = 10
STATIC_BUDGET = 100  # evaluations per continuation stage of the modal static solve (it converges in the later ones)
SAFETY = 0.8
STATUS_TEXT = {1: "non-finite force", 2: "penetration beyond the bound", 3: "kinetic-energy runaway",
               4: "modal mass matrix no longer positive definite"}
#: Exudyn 1.13 on this kind of machine: 32 balls, 20-mode CB outer ring, RK44 at 1e-5 s
EXUDYN_MODAL_US_PER_STEP = 8000.0

# flexible rings: 13 normal modes + groove load shapes n = 0…3 (1 + 2·3 = 7) = 20 modes
N_NORMAL_MODES, N_MAX_HARMONIC, MODAL_DAMPING = 13, 3, 0.02
BOLT_HALF_WIDTH_M = 0.03

# balls scene (bench_mbd.py)
BALL_ROW = BallRow("balls", 32, 95.2e-3, 1.2, math.radians(45.0), 0.53, 0.53, "inner", axial_sign=1,
                   stiffness_N_per_m1p5=1e11 / 2**1.5)  # series value: 1e11 N/m^1.5 per contact
BALL_LOAD_N = np.array([50e3, 0.0, 100e3])
BALL_SPEED_RPM, BALL_MU, BALL_DAMPING_N_S_M = 15.0, 0.1, 1e3
BALL_TIMESTEP_S = 1e-5
INNER_MASS_KG, INNER_RADIUS_M = 800.0, 0.55
OUTER_GROOVE = BallGroove(95.2e-3, 0.53, 45.0, (0.6, 0.0), (1, 1), 0.3 * 95.2e-3, "inner")
OUTER_WIDTH_M, OUTER_HALF_HEIGHT_M = 0.100, 0.060
OUTER_BOLTS_DEG = tuple(30.0 * k + 15.0 for k in range(12))
VARIANTS = ("rigid", "modal explicit", "modal implicit")

# slewing ring (1 m model)
SLEWING = SlewingSection()
PITCH_M = 1.0
N_LOAD_BALLS = 16
SPACER_D_M = 85.25e-3
SLEWING_LOAD_N = 68.9e3 * G
SLEWING_SPEED_RPM = 6.55
SLEWING_MU = (0.24, 0.14)
SLEWING_DAMPING_N_S_M, SLEWING_D_MAX_M = 2e4, 1e-5
TOP_BOLTS_DEG = tuple(360.0 / N_LOAD_BALLS * (k + 0.5) for k in range(N_LOAD_BALLS))
SLEWING_ROW = BallRow("load balls", N_LOAD_BALLS, SLEWING.ball_diameter_m, PITCH_M,
                      math.radians(SLEWING.contact_angle_deg), SLEWING.conformity, SLEWING.conformity, "inner",
                      axial_sign=-1)
THESIS_V_STATIC_M_S = 1e-3
SIMULATED_S = 25.0


def _rpm(speed_rpm: float) -> float:
    return speed_rpm * 2.0 * math.pi / 60.0


def _ring_inertia(mass_kg: float, radius_m: float) -> tuple[float, float, float]:
    return (0.5 * mass_kg * radius_m**2, 0.5 * mass_kg * radius_m**2, mass_kg * radius_m**2)


def _mesh(quick: bool) -> MeshSpec:
    groove = {"groove": 0.5}
    return MeshSpec(0.12, "tet10", refine=groove) if quick else MeshSpec(0.04, "hex27", refine=groove)


def _reduction(bolts_deg: tuple, contact_rz_m) -> ReductionSpec:
    bolts = InterfaceSpec("bolt_face", bolts_deg, BOLT_HALF_WIDTH_M)
    groove = RacewaySpec("groove", 360, at_rz_m=tuple(contact_rz_m), n_max=N_MAX_HARMONIC)
    return ReductionSpec(n_modes=N_NORMAL_MODES, interfaces=(bolts,), raceways=(groove,), damping_ratio=MODAL_DAMPING)


def _friction(mu: tuple[float, float], v_static_m_s: float | None) -> Coulomb | None:
    return None if v_static_m_s is None else Coulomb(mu[0], mu[1], v_static_m_s, 2.0 * v_static_m_s)


# ---------------------------------------------------------------------------- models
def outer_ring_profile():
    """The balls scene's outer ring: rectangle with the groove in its bore, bolted on its top face."""
    r0 = OUTER_GROOVE.face_position_m
    return grooved_ring("outer ring", r0, r0 + OUTER_WIDTH_M, -OUTER_HALF_HEIGHT_M, OUTER_HALF_HEIGHT_M,
                        (OUTER_GROOVE,), {"top": "bolt_face"})


def build_balls(variant: str, outer_body, outer_mass_kg: float, v_static_m_s: float | None):
    """Model of the balls scene (``variant`` in VARIANTS); v_static None: frictionless."""
    b = ModelBuilder()
    if variant == "rigid":
        radius = OUTER_GROOVE.face_position_m + OUTER_WIDTH_M / 2
        outer = b.add_body("outer ring", outer_mass_kg, _ring_inertia(outer_mass_kg, radius), motion=Fixed())
    else:
        outer = b.add_modal_body("outer ring", outer_body, motion=Fixed(), implicit_modes=variant == "modal implicit")
    inner = b.add_body("inner ring", INNER_MASS_KG, _ring_inertia(INNER_MASS_KG, INNER_RADIUS_M),
                       motion=Driven(_rpm(BALL_SPEED_RPM), translation_free=True, tilt_free=True))
    rows = add_ball_row(b, BALL_ROW, inner, outer, friction=_friction((BALL_MU, BALL_MU), v_static_m_s),
                        damping_N_s_m=BALL_DAMPING_N_S_M, fixed_sample=None if variant == "rigid" else "groove")
    b.add_force(inner, BALL_LOAD_N)
    model, state = b.finalize()
    return model, state, inner, outer, rows


@dataclass(frozen=True)
class SlewingParts:
    """Body and contact indices of the slewing-ring model."""

    top: int
    bottom: int
    rows: RowBodies
    spacers: tuple[int, ...]
    spacer_pairs: tuple[int, ...]
    ball_ball_pairs: tuple[int, ...]


def build_slewing(top_body, top_mass_kg: float, v_static_m_s: float | None, implicit_modes: bool = False,
                  implicit_friction: bool = False):
    """Model of the slewing ring; ``top_body`` None: a rigid top race of ``top_mass_kg``; ``implicit_modes``:
    the modal top race's modes integrated with the augmented mass, so that they do not limit the step;
    ``implicit_friction``: the balls' and spacers' friction integrated implicitly, so that v_static does
    not either."""
    fr = _friction(SLEWING_MU, v_static_m_s)
    D, f = SLEWING.ball_diameter_m, SLEWING.conformity
    b = ModelBuilder(gravity_m_s2=(0.0, 0.0, -G), implicit_friction=implicit_friction)
    m_bottom = slewing_bottom_race(PITCH_M).revolved_properties(STEEL.density_kg_m3)["mass_kg"]
    bottom = b.add_body("bottom race", m_bottom, _ring_inertia(m_bottom, PITCH_M / 2), motion=Fixed())
    motion = Driven(_rpm(SLEWING_SPEED_RPM), translation_free=True, tilt_free=True)
    if top_body is None:
        top = b.add_body("top race", top_mass_kg, _ring_inertia(top_mass_kg, PITCH_M / 2), motion=motion)
    else:
        top = b.add_modal_body("top race", top_body, motion=motion, implicit_modes=implicit_modes)
    rows = add_ball_row(b, SLEWING_ROW, top, bottom, friction=fr, damping_N_s_m=SLEWING_DAMPING_N_S_M,
                        d_max_m=SLEWING_D_MAX_M, moving_sample=None if top_body is None else "groove")
    # spacers: in the load balls' groove of the bottom race, resting at its bottom
    c_rz = SLEWING.groove("bottom", PITCH_M).curvature_center_m
    groove = b.add_groove(bottom, c_rz[0], c_rz[1], f * D)
    k_groove = ball_on_groove(SPACER_D_M, f * D / SPACER_D_M, PITCH_M, math.pi / 2, "outer").stiffness_N_per_m1p5
    law_groove = ContactLaw(k_groove, 1.5, SLEWING_DAMPING_N_S_M, SLEWING_D_MAX_M, friction=fr)
    law_ball = ContactLaw(sphere_on_sphere(D, SPACER_D_M).stiffness_N_per_m1p5, 1.5, SLEWING_DAMPING_N_S_M,
                          SLEWING_D_MAX_M, friction=fr)
    mass = ball_mass_kg(SPACER_D_M, STEEL.density_kg_m3)
    z = c_rz[1] - (f * D - SPACER_D_M / 2)
    spacers, spacer_pairs, ball_pairs = [], [], []
    for k in range(N_LOAD_BALLS):
        psi = 2.0 * math.pi * (k + 0.5) / N_LOAD_BALLS
        s = b.add_body(f"spacer {k}", mass, (0.1 * mass * SPACER_D_M**2,) * 3,
                       position_m=(c_rz[0] * math.cos(psi), c_rz[0] * math.sin(psi), z))
        spacers.append(s)
        spacer_pairs.append(b.add_ball_groove(s, bottom, groove, SPACER_D_M / 2, law_groove,
                                              name=f"spacer {k}–bottom"))
        for j in (k, (k + 1) % N_LOAD_BALLS):
            ball_pairs.append(b.add_ball_ball(rows.elements[j], s, D / 2, SPACER_D_M / 2, law_ball,
                                              name=f"load ball {j}–spacer {k}"))
    b.add_force(top, (0.0, 0.0, -SLEWING_LOAD_N))
    model, state = b.finalize()
    return model, state, SlewingParts(top, bottom, rows, tuple(spacers), tuple(spacer_pairs), tuple(ball_pairs))


# ---------------------------------------------------------------------------- starts and steps
def _place_ring(state: State, ring: int) -> None:
    """Put the balls scene's inner ring where the quasi-static load distribution puts it."""
    load = RingLoad(Fx_N=float(BALL_LOAD_N[0]), Fy_N=float(BALL_LOAD_N[1]), Fz_N=float(BALL_LOAD_N[2]))
    x, y, z, rot_x, rot_y = solve_load_distribution(Bearing("start", (BALL_ROW,)), load).displacement
    state.q[ring, :3] = (x, y, z)
    angle = math.hypot(rot_x, rot_y)
    state.q[ring, 3:] = quat_from_axis_angle((rot_x, rot_y, 0.0), angle) if angle > 0 else (1.0, 0.0, 0.0, 0.0)


def _equilibrium(name: str, model: Model, state: State, held, **kw) -> State:
    t0 = time.perf_counter()
    res = static_equilibrium(model, state, fixed_azimuth=held, **kw)
    print(f"[{name}] static equilibrium in {time.perf_counter() - t0:.1f} s ({res.n_evaluations} evaluations): "
          f"largest force left {res.force_residual_N:.3g} N (load scale {res.force_scale_N:.3g} N)")
    return res.state


def _orbit_speed(state: State, body: int) -> float:
    x, v = state.q[body, :3], state.v[body, :3]
    return float((x[0] * v[1] - x[1] * v[0]) / (x[0] ** 2 + x[1] ** 2))


def _roll_spacers(state: State, spacers, omega_orbit: float) -> None:
    """Orbit at ``omega_orbit`` about z, rolling without slip on the groove bottom below the centre."""
    r = SPACER_D_M / 2
    for s in spacers:
        x = state.q[s, :3]
        v = omega_orbit * np.array([-x[1], x[0], 0.0])
        state.v[s, :3] = v
        state.v[s, 3:] = (-v[1] / r, v[0] / r, 0.0)  # ω × (−r e_z) = −v; body axes = world at the start


def smallest_transition_speed(models: Callable[[float], list], states: list, timestep_s: float) -> float:
    """Smallest v_static (2 significant digits, rounded up) for which ``timestep_s`` is within the stable
    limit of every model ``models(v)`` at its state."""
    def limit(v):
        return min(stable_timestep(m, s).limit_s for m, s in zip(models(v), states))

    lo, hi = 1e-6, 100.0
    if limit(hi) < timestep_s:
        raise SystemExit(f"no transition speed makes {timestep_s:.3g} s stable")
    for _ in range(30):
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if limit(mid) >= timestep_s else (mid, hi)
    digits = 1 - math.floor(math.log10(hi))
    return math.ceil(hi * 10**digits) / 10**digits


def coupled_modal_limit_s(model: Model, state: State) -> tuple[float, float]:
    """Stable step 2/ω_max (with the modal damping) of the modes together with the free components of
    their frame, and the top frequency ω_max/2π, Hz: generalised eigenvalues of K = diag(0, ω_k²) and
    the matching block of M(η) (:func:`mbd_core.kernels.modal.modal_mass_matrix`). (inf, 0) when no
    modal frame has free components."""
    a = model.arrays
    best, f_top = math.inf, 0.0
    for j in range(a.modal_body.shape[0]):
        free = np.flatnonzero(a.modal_frame_free[j])
        if free.size == 0:
            continue
        o0, o1 = int(a.modal_off[j]), int(a.modal_off[j + 1])
        mj = o1 - o0
        inv = [np.ascontiguousarray(x) for x in (a.modal_I2[j], a.modal_I3[j, :, :mj], a.modal_I4[j, :, :mj],
                                                 a.modal_I5[j, :, :mj, :mj], a.modal_I6[j, :mj, :mj], a.modal_I7[j],
                                                 a.modal_I8[j, :, :, :mj], a.modal_I9[j, :, :, :mj, :mj])]
        M = np.zeros((6 + mj, 6 + mj))
        modal_mass_matrix(float(a.modal_mass[j]), *inv, np.ascontiguousarray(state.eta[o0:o1]), M)
        sel = np.concatenate([free, 6 + np.arange(mj)])
        K = np.zeros((sel.size, sel.size))
        K[free.size:, free.size:] = np.diag(a.modal_omega2[o0:o1])
        omega = math.sqrt(float(scipy.linalg.eigh(K, M[np.ix_(sel, sel)], eigvals_only=True)[-1]))
        zeta = float(np.max(a.modal_damp[o0:o1] / (2.0 * np.sqrt(a.modal_omega2[o0:o1]))))
        h = 2.0 / omega * (math.sqrt(1.0 + zeta * zeta) - zeta)
        if h < best:
            best, f_top = h, omega / (2.0 * math.pi)
    return best, f_top


def run_steps(name: str, model: Model, state: State, n_steps: int, timestep_s: float):
    """Step n_steps from ``state`` REPEATS times; returns (fastest wall seconds of the stepping, record
    buffers of the last run, samples)."""
    a = model.arrays
    warm = state.copy()
    w = make_work(model)
    rec = make_record_buffers(model, 2)
    compute_forces(a, warm.t, warm.q, warm.v, warm.eta, warm.eta_dot, w)
    run_explicit(a, warm.q, warm.v, warm.eta, warm.eta_dot, w, warm.t, 0, 2, timestep_s, 1, rec,
                 math.inf)  # load or compile
    best = math.inf
    for _ in range(REPEATS):
        s = state.copy()
        w = make_work(model)
        rec = make_record_buffers(model, n_steps // RECORD_EVERY)
        status, index = compute_forces(a, s.t, s.q, s.v, s.eta, s.eta_dot, w)
        if status != STATUS_OK:
            raise SystemExit(f"[{name}] start state: {STATUS_TEXT.get(status, status)} at {index}")
        e_limit = 1e3 * max(total_kinetic_energy(a, s.q, s.v, s.eta, s.eta_dot, w), 10.0)
        t0 = time.perf_counter()
        status, index, done, k = run_explicit(a, s.q, s.v, s.eta, s.eta_dot, w, s.t, 0, n_steps, timestep_s,
                                              RECORD_EVERY, rec, e_limit)
        wall = time.perf_counter() - t0
        if status != STATUS_OK:
            where = model.pair_names[index] if 0 <= index < model.n_pairs else f"index {index}"
            raise SystemExit(f"[{name}] run stopped after {done} of {n_steps} steps "
                             f"(t = {(done + 1) * timestep_s:.6g} s): {STATUS_TEXT.get(status, status)} at {where}")
        best = min(best, wall)
    return best, rec, k


def axial_sum_N(rec, k: int, pairs) -> np.ndarray:
    """Σ Q |sin α| over ``pairs`` at each recorded sample, N."""
    p = np.asarray(pairs)
    return (rec.fn[:k, p] * np.abs(np.sin(rec.angle[:k, p]))).sum(axis=1)


def _load_line(name: str, what: str, values_N: np.ndarray, expected_N: float) -> None:
    dev = float(np.abs(values_N - expected_N).max()) / expected_N
    print(f"[{name}] {what}: mean {values_N.mean() / 1e3:.2f} kN (range {values_N.min() / 1e3:.2f} … "
          f"{values_N.max() / 1e3:.2f}) vs {expected_N / 1e3:.2f} kN, largest deviation {100 * dev:.2g} %")


# ---------------------------------------------------------------------------- scenes
def balls_scene(quick: bool, n_steps: int) -> dict:
    """Reduce the outer ring, start the three variants and time n_steps of each at the common step."""
    profile = outer_ring_profile()
    t0 = time.perf_counter()
    outer_body = reduced_body(profile, _mesh(quick), STEEL, _reduction(OUTER_BOLTS_DEG, OUTER_GROOVE.contact_point_m))
    outer_mass = profile.revolved_properties(STEEL.density_kg_m3)["mass_kg"]
    print(f"[balls] outer ring {outer_mass:.0f} kg reduced (or loaded) in {time.perf_counter() - t0:.1f} s: "
          f"{outer_body.n_modes} modes, {outer_body.frequencies_Hz[0]:.0f}–{outer_body.frequencies_Hz[-1]:.0f} Hz")

    def build(variant, v):
        return build_balls(variant, outer_body, outer_mass, v)

    model, state, inner, _, rows = build("rigid", None)
    _place_ring(state, inner)
    rigid_start = _equilibrium("balls/rigid", model, state, rows.elements)
    model, state, *_ = build("modal explicit", None)
    state.q[:] = rigid_start.q
    modal_start = _equilibrium("balls/modal", model, state, rows.elements, max_evaluations=STATIC_BUDGET)
    starts = {v: (rigid_start if v == "rigid" else modal_start) for v in VARIANTS}
    v_s = smallest_transition_speed(lambda v: [build(x, v)[0] for x in VARIANTS], [starts[x] for x in VARIANTS],
                                    BALL_TIMESTEP_S)
    print(f"[balls] friction transition speed v_static = {v_s:.3g} m/s: {BALL_TIMESTEP_S:g} s within the stable "
          "limit of all three variants")
    n_contacts = 2 * BALL_ROW.n_balls
    out = {}
    for variant in VARIANTS:
        name = f"balls/{variant}"
        model, _, inner, outer, rows = build(variant, v_s)
        state = starts[variant].copy()
        set_rolling_velocities(model, state, rows.elements, inner, other_ring=outer)
        auto = stable_timestep(build(variant, None)[0], state)
        wall, rec, k = run_steps(name, model, state, n_steps, BALL_TIMESTEP_S)
        us = 1e6 * wall / n_steps
        rt = auto.timestep_s / (1e-6 * us)
        print(f"[{name}] {n_steps} steps of {BALL_TIMESTEP_S:g} s in {wall:.3f} s: {us:.2f} µs/step, "
              f"{1e3 * us / n_contacts:.0f} ns per contact ({n_contacts}), {n_steps / wall:,.0f} steps/s, "
              f"real-time factor {BALL_TIMESTEP_S / (1e-6 * us):.3g} at {BALL_TIMESTEP_S:g} s")
        print(f"[{name}] automatic step {auto.timestep_s:.3g} s (limit {auto.limit_s:.3g} s, friction aside: "
              f"v_static ≥ {v_s * auto.timestep_s / BALL_TIMESTEP_S:.2g} m/s there) set by {auto.reason}; "
              f"real-time factor there {rt:.3g}")
        _load_line(name, "Σ Q |sin α| on the inner ring", axial_sum_N(rec, k, rows.moving_pairs),
                   float(BALL_LOAD_N[2]))
        out[variant] = dict(us=us, h_auto=auto.timestep_s, rt=rt)
    extra = out["modal explicit"]["us"] - out["rigid"]["us"]
    print(f"[balls] the modal ring adds {extra:.1f} µs/step ({1e3 * extra / BALL_ROW.n_balls:.0f} ns per contact on "
          f"the flexible groove, {outer_body.n_modes} modes); Exudyn ≈ 8 ms/step with fixed contact points / this = "
          f"{EXUDYN_MODAL_US_PER_STEP / out['modal explicit']['us']:.3g}")
    out["v_static"] = v_s
    out["n_modes"] = outer_body.n_modes
    return out


def slewing_scene(quick: bool, n_steps: int | None, simulated_s: float) -> dict:
    """Reduce the top race, start the slewing ring, choose its step and time n_steps (None: as many as
    ``simulated_s`` takes) with the modal and with a rigid top race."""
    profile = slewing_top_race(PITCH_M)
    t0 = time.perf_counter()
    top_body = reduced_body(profile, _mesh(quick), STEEL,
                            _reduction(TOP_BOLTS_DEG, SLEWING.groove("top", PITCH_M).contact_point_m))
    top_mass = profile.revolved_properties(STEEL.density_kg_m3)["mass_kg"]
    print(f"[slewing] top race {top_mass:.0f} kg reduced (or loaded) in {time.perf_counter() - t0:.1f} s: "
          f"{top_body.n_modes} modes, {top_body.frequencies_Hz[0]:.0f}–{top_body.frequencies_Hz[-1]:.0f} Hz")

    model, state, parts = build_slewing(None, top_mass, None)
    held = parts.rows.elements + parts.spacers
    rigid_start = _equilibrium("slewing/rigid", model, state, held)
    model, state, parts = build_slewing(top_body, top_mass, None)
    state.q[:] = rigid_start.q
    modal_start = _equilibrium("slewing/modal", model, state, held, max_evaluations=STATIC_BUDGET)
    a = model.arrays
    w = evaluate_forces(model, modal_start)
    frame_f = w.body_f[parts.top] + a.modal_mass[0] * a.gravity  # the modal body's weight is not in body_f
    print(f"[slewing] force left on the top race's frame at the start {np.array2string(frame_f, precision=3)} N "
          f"({100 * np.linalg.norm(frame_f) / SLEWING_LOAD_N:.2g} % of the load), moment "
          f"{np.array2string(w.body_t[parts.top], precision=3)} N·m")
    gaps = [w.contact_delta[c] for c in parts.ball_ball_pairs]
    print(f"[slewing] load balls–spacers: play {-1e3 * max(gaps):.2f} … {-1e3 * min(gaps):.2f} mm at the start")

    library = stable_timestep(model, modal_start)
    coupled, f_top = coupled_modal_limit_s(model, modal_start)
    h = SAFETY * min(library.limit_s, coupled)
    print(f"[slewing] stable_timestep (friction aside): {library.limit_s:.3g} s, set by {library.reason}; "
          f"modes with the frame's free components: top frequency {f_top:.4g} Hz, limit {coupled:.3g} s → "
          f"step {h:.3g} s")
    v_s = smallest_transition_speed(lambda v: [build_slewing(top_body, top_mass, v)[0]], [modal_start], h)
    thesis = stable_timestep(build_slewing(top_body, top_mass, THESIS_V_STATIC_M_S)[0], modal_start)
    print(f"[slewing] friction transition speed v_static = {v_s:.3g} m/s; with the source study's 1 mm/s friction "
          f"alone would limit the step to {thesis.limit_s:.2g} s")

    implicit = build_slewing(top_body, top_mass, None, implicit_modes=True)[0]
    h_imp = SAFETY * stable_timestep(implicit, modal_start).limit_s
    v_imp = smallest_transition_speed(lambda v: [build_slewing(top_body, top_mass, v, implicit_modes=True)[0]],
                                      [modal_start], h_imp)
    print(f"[slewing] with implicit modes the contacts alone set the step: {h_imp:.3g} s, at which the friction "
          f"transition speed v_static = {v_imp:.3g} m/s")

    results = {}
    variants = (("rigid top race", None, rigid_start, h, v_s, False, False),
                ("modal top race", top_body, modal_start, h, v_s, False, False),
                ("modal top race, implicit modes", top_body, modal_start, h_imp, v_imp, True, False),
                ("modal top race, implicit modes and friction", top_body, modal_start, h_imp, v_s, True, True))
    for label, body, start, h, v_s, imp, imp_friction in variants:
        name = f"slewing/{label}"
        model, _, parts = build_slewing(body, top_mass, v_s, implicit_modes=imp, implicit_friction=imp_friction)
        state = start.copy()
        set_rolling_velocities(model, state, parts.rows.elements, parts.top, other_ring=parts.bottom)
        _roll_spacers(state, parts.spacers, _orbit_speed(state, parts.rows.elements[0]))
        steps = n_steps or int(round(simulated_s / h))
        limit = stable_timestep(model, state)
        if limit.limit_s < h:
            print(f"[{name}] the step exceeds stable_timestep's limit {limit.limit_s:.3g} s ({limit.reason})")
        wall, rec, k = run_steps(name, model, state, steps, h)
        us = 1e6 * wall / steps
        rt = h / (1e-6 * us)
        print(f"[{name}] {steps} steps of {h:.3g} s ({steps * h:.3g} s simulated) in {wall:.3f} s: {us:.1f} µs/step, "
              f"{1e3 * us / model.n_pairs:.0f} ns per contact ({model.n_pairs}); simulated s per wall s {rt:.3g}; "
              f"{SIMULATED_S:g} s would take {SIMULATED_S / rt:.0f} s ({SIMULATED_S / rt / 60:.1f} min)")
        m_top = float(model.arrays.modal_mass[0]) if body is not None else top_mass
        m_balls = N_LOAD_BALLS * (ball_mass_kg(SLEWING.ball_diameter_m, STEEL.density_kg_m3)
                                  + ball_mass_kg(SPACER_D_M, STEEL.density_kg_m3))
        _load_line(name, "Σ Q sin α on the top race", axial_sum_N(rec, k, parts.rows.moving_pairs),
                   SLEWING_LOAD_N + m_top * G)
        _load_line(name, "Σ Q sin α on the bottom race (load balls and spacers)",
                   axial_sum_N(rec, k, parts.rows.fixed_pairs + parts.spacer_pairs),
                   SLEWING_LOAD_N + (m_top + m_balls) * G)
        dz = rec.q[:k, parts.top, 2] - start.q[parts.top, 2]
        spacer_fn = rec.fn[:k, list(parts.spacer_pairs)]
        print(f"[{name}] top race moved {1e6 * dz.min():.2f} … {1e6 * dz.max():.2f} µm axially; spacer–race "
              f"{spacer_fn.min():.1f} … {spacer_fn.max():.1f} N, "
              f"ball–spacer up to {rec.fn[:k, list(parts.ball_ball_pairs)].max():.1f} N")
        results[label] = dict(us=us, rt=rt, h=h, v_static=v_s)
    explicit, implicit = results["modal top race"], results["modal top race, implicit modes"]
    both = results["modal top race, implicit modes and friction"]
    return dict(us=explicit["us"], us_rigid=results["rigid top race"]["us"], h=explicit["h"], rt=explicit["rt"],
                v_static=explicit["v_static"], f_top=f_top, us_implicit=implicit["us"], h_implicit=implicit["h"],
                rt_implicit=implicit["rt"], v_static_implicit=implicit["v_static"], us_both=both["us"],
                rt_both=both["rt"])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="coarse meshes, 300 steps per run")
    args = ap.parse_args()
    n_steps = 300 if args.quick else 4000
    balls = balls_scene(args.quick, n_steps)
    slewing = slewing_scene(args.quick, 300 if args.quick else None, 0.2)
    figures = {
        "us_per_step_modal_explicit": balls["modal explicit"]["us"],
        "us_per_step_modal_implicit": balls["modal implicit"]["us"],
        "us_per_step_rigid": balls["rigid"]["us"],
        "timestep_auto_modal_explicit_s": balls["modal explicit"]["h_auto"],
        "timestep_auto_modal_implicit_s": balls["modal implicit"]["h_auto"],
        "realtime_factor_modal_explicit": balls["modal explicit"]["rt"],
        "realtime_factor_modal_implicit": balls["modal implicit"]["rt"],
        "exudyn_speedup_modal": EXUDYN_MODAL_US_PER_STEP / balls["modal explicit"]["us"],
        "v_static_balls_m_s": balls["v_static"],
        "n_modes": balls["n_modes"],
        "us_per_step_slewing": slewing["us"],
        "us_per_step_slewing_rigid": slewing["us_rigid"],
        "timestep_slewing_s": slewing["h"],
        "realtime_factor_slewing": slewing["rt"],
        "wall_s_25s_slewing": SIMULATED_S / slewing["rt"],
        "v_static_slewing_m_s": slewing["v_static"],
        "us_per_step_slewing_implicit_modes": slewing["us_implicit"],
        "timestep_slewing_implicit_modes_s": slewing["h_implicit"],
        "realtime_factor_slewing_implicit_modes": slewing["rt_implicit"],
        "wall_s_25s_slewing_implicit_modes": SIMULATED_S / slewing["rt_implicit"],
        "v_static_slewing_implicit_modes_m_s": slewing["v_static_implicit"],
        "us_per_step_slewing_implicit_modes_friction": slewing["us_both"],
        "wall_s_25s_slewing_implicit_modes_friction": SIMULATED_S / slewing["rt_both"],
        "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
    }
    print(" ".join(f"{k}={v:.4g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
