"""The compiled explicit integrator (mbd_core.kernels.explicit.run_explicit) against its numpy twin
tests/reference/explicit_step.py, which is written from the scheme in the kernel's module docstring
and evaluates the forces with the numpy twin of compute_forces (tests/reference/multibody.py).

Two models, 50 steps each: an angular-contact ball bearing (inner ring driven about its axis but
free to translate and tilt, fixed outer ring, free balls and cage, Coulomb friction at the raceways
and in the pockets, gravity, a constant force and a load history whose knots fall inside the run),
and an asymmetric top (three unequal inertias, all rotations free) on a bushing. Few steps: two
integrations of a contact system that differ by round-off drift apart at the rate of its fastest
dynamics, so only a short run can be compared to round-off.

Tolerances, kernel against twin: rtol 1e-12 on every value, plus absolute floors where a value is
near zero or is a sum of terms of both signs (built from the twin's run; n steps of size h, T = n h):

* velocities of body i: 1e-12 (|v_i| + Σ_steps h F_scale,i/m_i), with F_scale,i = Σ|terms| of the
  body's force (its round-off scale, as in test_kernels_multibody); angular velocities likewise with
  |ω_i| and Σ h M_scale,i / min I_i;
* displacements r − r₀: the velocity floor times T (a displacement is the time integral of v);
* quaternion components: n ε (each step rounds a unit quaternion by ~ε per component);
* penetrations: 1e-16 m (the round-off of a difference of coordinates of ~0.02 m); normal forces:
  the change n K δⁿ⁻¹ × 1e-16 m this makes; friction forces: μ_static times that; slip: 1e-12 × the
  largest slip (a difference of point velocities of up to ~5 m/s).
"""

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from mbd_core.contact.friction import Coulomb
from mbd_core.kernels import explicit as EX
from mbd_core.kernels import forces as FK
from mbd_core.multibody import Driven, Fixed, ModelBuilder, stable_timestep
from mbd_core.multibody.bearings import add_ball_row
from mbd_core.multibody.model import RECORDED_CONTACT_FIELDS, make_record_buffers, make_work
from mbd_core.quasistatic import BallRow
from tests.reference import explicit_step as twin
from tests.reference import multibody as ref

RTOL = 1e-12
ATOL_M = 1e-16           # penetrations, m (see the module docstring)
N_STEPS, EVERY = 50, 7
SEED = 20260412
OMEGA_INNER = 300.0      # rad/s


# -- models -------------------------------------------------------------------------------------
def _ball_bearing():
    """7 balls Ø8 mm on a 40 mm pitch at 25°, 4 µm preload; the cage turned and shifted so that some
    balls bear on their pockets; balls nearly at rest, so their outer-ring slip is in the transition
    range of the Coulomb law and their inner-ring slip (~5 m/s) beyond it."""
    rng = np.random.default_rng(SEED)
    row = BallRow("row", 7, 8e-3, 0.04, math.radians(25), 0.52, 0.53, "inner", axial_sign=1, radial_clearance_m=-4e-6)
    mb = ModelBuilder(gravity_m_s2=(0.0, -9.81, 0.0))
    inner = mb.add_body("inner", 0.12, (3e-5, 3e-5, 5e-5), omega_rad_s=(2.0, -3.0, 0.0),
                        motion=Driven(OMEGA_INNER, translation_free=True, tilt_free=True))
    outer = mb.add_body("outer", 0.2, (6e-5, 6e-5, 1e-4), motion=Fixed())
    row_bodies = add_ball_row(mb, row, inner, outer, friction=Coulomb(0.1, 0.08, 1e-3, 2e-3), damping_N_s_m=50.0,
                              d_max_m=1e-6, cage_mass_kg=0.01, pocket_clearance_m=3e-5, cage_stiffness_N_per_m=2e6,
                              pocket_friction=Coulomb(0.15, 0.1, 1e-3, 2e-3))
    mb.add_force(inner, (40.0, -20.0, 300.0), (0.2, -0.1, 0.0))
    mb.add_load_history(inner, [2e-7, 4e-7, 6e-7, 8e-7], rng.normal(size=(4, 6)) * [50, 50, 100, 0.3, 0.3, 0.0])
    model, state = mb.finalize()
    state.t = 3e-7                                   # the run crosses the knots at 4, 6 and 8 × 1e-7 s
    cage = row_bodies.cage
    state.q[cage, :3] = (1e-5, -2e-5, 0.0)
    state.q[cage, 3:] = Rotation.from_rotvec([1e-4, -2e-4, 6e-4]).as_quat(scalar_first=True)
    state.v[cage] = (0.01, 0.0, 0.0, 1.0, -2.0, 120.0)
    for e in row_bodies.elements:
        state.q[e, :3] += rng.normal(size=3) * 1e-6
        state.v[e] = rng.normal(size=6) * [1e-3, 1e-3, 1e-3, 0.3, 0.3, 0.3]
    return model, state, 1e-8                        # step below the stable limit, 1.3e-8 s (pocket friction)


def _top_on_bushing():
    """A body with inertias 0.01, 0.025, 0.04 kg·m² in a random orientation, tumbling at 15–30 rad/s
    (0.06–0.12 rad per step), held to a fixed ground by a bushing stiff in translation and soft in
    rotation; gravity and a constant load."""
    rng = np.random.default_rng(SEED + 1)
    mb = ModelBuilder(gravity_m_s2=(0.0, 0.0, -9.81))
    mb.add_body("ground", 1.0, (1.0, 1.0, 1.0), motion=Fixed())
    mb.add_body("top", 2.0, (0.01, 0.025, 0.04), (0.1, 0.05, 0.2),
                orientation=Rotation.random(random_state=rng).as_quat(scalar_first=True),
                velocity_m_s=(0.1, -0.2, 0.05), omega_rad_s=(3.0, 25.0, -12.0))
    mb.add_bushing("ground", "top", (0.1, 0.06, 0.18), (1e5, 2e5, 3e5, 0.5, 1.0, 1.5),
                   (20.0, 30.0, 40.0, 0.01, 0.02, 0.03))
    mb.add_force("top", (5.0, -3.0, 2.0), (0.3, -0.2, 0.1))
    model, state = mb.finalize()
    return model, state, 4e-3                        # stable limit 5.0e-3 s (bushing)


MODELS = {"ball_bearing": _ball_bearing, "top_on_bushing": _top_on_bushing}


@pytest.fixture(scope="module", params=sorted(MODELS))
def case(request):
    """(model, initial state, h, twin samples after each of the N_STEPS steps)."""
    model, state, h = MODELS[request.param]()
    assert h < stable_timestep(model, state).limit_s
    m = model.arrays
    forces = ref.compute_forces(m, state.t, state.q, state.v)
    *_, samples = twin.run(m, state.q, state.v, forces, state.t, 0, N_STEPS, h, 1)
    return model, state, h, samples


def _kernel_run(model, state, h, step0=0, n_steps=N_STEPS, q=None, v=None, work=None, energy_limit=math.inf):
    """run_explicit from ``state`` (or from q, v, work of an earlier run) with fresh record buffers."""
    m = model.arrays
    if work is None:
        q, v, work = state.q.copy(), state.v.copy(), make_work(model)
        assert FK.compute_forces(m, state.t, q, v, state.eta, state.eta_dot, work) == (FK.STATUS_OK, -1)
    rec = make_record_buffers(model, N_STEPS // EVERY + 1)
    out = EX.run_explicit(m, q, v, state.eta.copy(), state.eta_dot.copy(), work, state.t, step0, n_steps, h, EVERY, rec, energy_limit)
    return out, q, v, work, rec


# -- comparison ---------------------------------------------------------------------------------------
def _close(got, want, atol=0.0, rtol=RTOL):
    """|got − want| ≤ atol + rtol |want| elementwise (atol may be an array broadcast against want)."""
    got, want = np.asarray(got, float), np.asarray(want, float)
    err = np.abs(got - want) - (atol + rtol * np.abs(want))
    assert got.shape == want.shape and np.all(err <= 0), (
        f"worst excess {err.max():.3g} at {np.unravel_index(np.argmax(err), err.shape)}:\n{got}\n!=\n{want}")


def _assert_state_close(model, state, h, samples, k, q, v):
    """Kernel state (q, v) against the twin's after step k + 1 (floors from its first k + 1 steps)."""
    m, want = model.arrays, samples[k]
    run = samples[:k + 1]
    v_floor = h * sum(s.forces.body_f_scale for s in run) / m.body_mass
    w_floor = h * sum(s.forces.body_t_scale for s in run) / m.body_inertia.min(axis=1)
    atol_v = RTOL * (np.linalg.norm(want.v[:, :3], axis=1) + v_floor)
    atol_w = RTOL * (np.linalg.norm(want.v[:, 3:], axis=1) + w_floor)
    v_max = np.max([np.linalg.norm(s.v[:, :3], axis=1) for s in run], axis=0)
    _close(v[:, :3], want.v[:, :3], atol_v[:, None])
    _close(v[:, 3:], want.v[:, 3:], atol_w[:, None])
    _close(q[:, :3] - state.q[:, :3], want.q[:, :3] - state.q[:, :3],
           (RTOL * (k + 1) * h * (v_max + v_floor))[:, None])
    _close(q[:, 3:], want.q[:, 3:], (k + 1) * np.finfo(float).eps)


def _assert_contacts_close(model, got, want):
    """Per-contact outputs ``got`` (dict name → (n_c,)) against a twin Forces ``want``."""
    m = model.arrays
    fn_floor = m.pair_n * m.pair_k * np.maximum(want.delta, 0.0) ** (m.pair_n - 1.0) * ATOL_M
    _close(got["delta"], want.delta, ATOL_M)
    _close(got["fn"], want.fn, fn_floor)
    _close(got["ft"], want.ft, m.pair_fric_p[:, 0] * fn_floor)
    _close(got["slip"], want.slip, RTOL * max(np.max(want.slip, initial=0.0), 1e-300))
    _close(got["angle"], want.angle, 1e-14)
    _close(got["theta"], want.theta, 1e-14)
    # contact points and normals: the record keeps them in float32 (relative round-off 6e-8)
    tol = 1e-14 if got["point"].dtype == np.float64 else 2e-7
    scale = np.max(np.abs(want.point), initial=1.0)
    _close(got["point"], want.point, tol * scale)
    _close(got["normal"], want.normal, tol)


def _work_contacts(work):
    return {f: getattr(work, f"contact_{f}") for f in RECORDED_CONTACT_FIELDS}


# -- the run against its twin ---------------------------------------------------------------------------
def test_run_matches_twin_state_records_and_contacts(case):
    model, state, h, samples = case
    m = model.arrays
    (status, index, done, n_rec), q, v, work, rec = _kernel_run(model, state, h)
    assert (status, index, done, n_rec) == (FK.STATUS_OK, -1, N_STEPS, N_STEPS // EVERY)
    _assert_state_close(model, state, h, samples, N_STEPS - 1, q, v)
    _assert_contacts_close(model, _work_contacts(work), samples[-1].forces)
    # samples after global steps 7, 14, …, 49, at t = t_origin + step h (the same arithmetic: exact)
    steps = np.arange(EVERY, N_STEPS + 1, EVERY)
    assert np.array_equal(rec.t[:n_rec], state.t + steps * h)
    for j, step in enumerate(steps):
        _assert_state_close(model, state, h, samples, step - 1, rec.q[j], rec.v[j])
        _assert_contacts_close(model, {f: getattr(rec, f)[j] for f in RECORDED_CONTACT_FIELDS},
                               samples[step - 1].forces)
    assert EX.kinetic_energy(m.body_mass, m.body_inertia, v) == pytest.approx(
        ref.kinetic_energy(m.body_mass, m.body_inertia, samples[-1].v), rel=RTOL, abs=0.0)
    # held components keep their values exactly: the fixed body's pose, the driven spin
    for i in range(model.n_bodies):
        held = m.body_free[i] == 0
        assert np.all(v[i, held] == state.v[i, held])
        if not m.body_free[i].any():
            assert np.all(q[i] == state.q[i])


def test_run_exercises_what_it_is_meant_to(case):
    """The comparison covers contacts loaded and apart, friction in and beyond the transition range of
    the Coulomb law, a partly free body whose tilt rates change; the top turns by > 0.05 rad in every step."""
    model, state, h, samples = case
    m = model.arrays
    if model.n_pairs:
        delta = np.array([s.forces.delta for s in samples])
        slip = np.array([s.forces.slip for s in samples])[delta > 0]
        pockets = model.pairs_of("element_pocket")
        assert np.any(delta[:, pockets] > 0) and np.any(delta[:, pockets] <= 0)
        assert np.any(slip > 2e-3) and np.any((slip > 0) & (slip < 1e-3))
        partly = [i for i in range(model.n_bodies) if 0 < m.body_free[i, 3:].sum() < 3]
        assert partly and np.all(samples[-1].v[partly, 3:5] != state.v[partly, 3:5])
    else:
        assert np.all(m.body_free[1] == 1) and len(set(m.body_inertia[1])) == 3
        assert h * min(np.linalg.norm(s.v[1, 3:]) for s in samples) > 0.05


def test_resumed_run_continues_bit_for_bit_and_records_global_steps(case):
    """Split 20 + 30: the forces left in the work arrays carry the run on exactly (module docstring)."""
    model, state, h, _ = case
    m = model.arrays
    (_, _, _, n_all), q_all, v_all, _, rec_all = _kernel_run(model, state, h)
    out1, q, v, work, rec1 = _kernel_run(model, state, h, n_steps=20)
    out2, q, v, work, rec2 = _kernel_run(model, state, h, step0=20, n_steps=30, q=q, v=v, work=work)
    assert out1 == (FK.STATUS_OK, -1, 20, 2) and out2 == (FK.STATUS_OK, -1, 30, 5)
    assert np.array_equal(rec2.t[:5], state.t + np.array([21, 28, 35, 42, 49]) * h)
    assert np.array_equal(q, q_all) and np.array_equal(v, v_all)
    for f in rec_all._fields:
        joined = np.concatenate([getattr(rec1, f)[:2], getattr(rec2, f)[:5]])
        assert np.array_equal(joined, getattr(rec_all, f)[:n_all]), f
    # record_now stores the present state and contact outputs as a sample
    EX.record_now(m, q, v, state.eta, state.eta_dot, work, state.t + N_STEPS * h, 3, rec1)
    assert rec1.t[3] == state.t + N_STEPS * h and np.array_equal(rec1.q[3], q) and np.array_equal(rec1.v[3], v)
    for f, values in _work_contacts(work).items():  # (points and normals in float32)
        assert np.array_equal(getattr(rec1, f)[3], values.astype(getattr(rec1, f).dtype)), f


def test_energy_runaway_stops_with_the_state_of_the_failed_step_unrecorded(case):
    model, state, h, samples = case
    m = model.arrays
    limit = 0.5 * ref.kinetic_energy(m.body_mass, m.body_inertia, state.v)
    (status, index, done, n_rec), q, v, _, rec = _kernel_run(model, state, h, energy_limit=limit)
    assert (status, index) == (FK.STATUS_ENERGY, -1) and 0 <= done < N_STEPS
    assert n_rec == done // EVERY                     # samples of the completed steps only
    _assert_state_close(model, state, h, samples, done, q, v)        # state after step done + 1
    assert EX.kinetic_energy(m.body_mass, m.body_inertia, v) > limit
    steps = np.arange(1, n_rec + 1) * EVERY
    assert np.array_equal(rec.t[:n_rec], state.t + steps * h)
