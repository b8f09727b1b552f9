"""Implicit friction of free rigid bodies (mbd_core.kernels.explicit, ``implicit_friction``) against
references: the damping matrix against a finite-difference Jacobian of the forces, and a roller
launched sliding on a plane against the closed-form slide-to-roll solution, at a step far above the
explicit friction limit and against the explicit run at its own step."""

import math

import numpy as np
import pytest

from mbd_core.contact.friction import Coulomb, DrebLinear
from mbd_core.multibody import (ContactLaw, Fixed, ModelBuilder, StepTooLargeError, evaluate_forces, simulate,
                                stable_timestep)
from mbd_core.multibody.statics import static_equilibrium
from tests.reference.force_jacobian import force_velocity_jacobian

G = 9.81
R_M, L_M, MASS_KG = 0.03, 0.05, 1.0
INERTIA = (MASS_KG * (3 * R_M**2 + L_M**2) / 12, MASS_KG * (3 * R_M**2 + L_M**2) / 12, MASS_KG * R_M**2 / 2)
AXIS_ALONG_X = (math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4), 0.0)  # body z → world x


def roller_on_plane(friction, implicit, damping=200.0, v0=(0.0, 0.0, 0.0), omega=(0.0, 0.0, 0.0),
                    orientation=AXIS_ALONG_X, z0=R_M, motion=None):
    """A solid cylinder (body z its axis) lying on a fixed plane z = 0 under gravity, 10 slices of a
    linear 2e7 N/m law each; free unless ``motion`` is given."""
    b = ModelBuilder(gravity_m_s2=(0.0, 0.0, -G), implicit_friction=implicit)
    ground = b.add_body("ground", 100.0, (1.0, 1.0, 1.0), motion=Fixed())
    extra = {} if motion is None else {"motion": motion}
    roller = b.add_body("roller", MASS_KG, INERTIA, position_m=(0.0, 0.0, z0), orientation=orientation,
                        velocity_m_s=v0, omega_rad_s=omega, **extra)
    plane = b.add_surface(ground, "plane_up", 0.0)
    b.add_roller_raceway(roller, ground, plane, R_M, L_M, ContactLaw(2e7, 1.0, damping, 1e-6, friction=friction),
                         n_slices=10)
    model, state = b.finalize()
    return model, state, roller


def _damping_and_jacobian(friction, v0, omega):
    """The assembled damping matrix C of the roller and −∂(F, τ)/∂(v, ω_world) by central differences
    at a fixed pose (no normal damping), with the roller tilted and turned so that every slice's
    lever and normal differ."""
    from scipy.spatial.transform import Rotation

    x, y, z, w0 = Rotation.from_euler("zxy", [20.0, 0.6, 90.0], degrees=True).as_quat()  # axis 0.6° off level
    model, state, i = roller_on_plane(friction, True, damping=0.0, orientation=(w0, x, y, z), z0=R_M - 1e-5,
                                      v0=v0, omega=omega)
    w = evaluate_forces(model, state)
    C = w.fric_c[i].copy()
    assert np.count_nonzero(w.contact_fn) == 1 and w.contact_fn[0] > 0
    return C, force_velocity_jacobian(model, state, i, 1e-4 * max(np.abs(v0).max(), 1e-3)), w.contact_slip[0]


def test_damping_matrix_is_the_jacobian_of_a_linear_friction_law():
    # DREB linear traction F_t = −B F_n v_t is linear in the velocities at a fixed pose, so the
    # central differences are exact up to rounding and must equal C = Σ c Jᵀ(I − m mᵀ)J
    C, jac, _ = _damping_and_jacobian(DrebLinear(0.4), (0.3, -0.2, 0.0), (1.0, 2.0, 30.0))
    np.testing.assert_allclose(C, jac, rtol=1e-7, atol=1e-9 * np.abs(C).max())
    np.testing.assert_allclose(C, C.T, rtol=0, atol=1e-12 * np.abs(C).max())
    assert np.linalg.eigvalsh(C).min() > -1e-9 * np.abs(C).max()  # a damper: positive semidefinite


def test_damping_matrix_is_the_jacobian_at_the_start_of_a_regularised_step():
    # Coulomb's cubic step below v_static is convex (μ = μ_s (3x² − 2x³), x = u/v_s, for x < 1/2 its
    # slope μ' exceeds the secant μ/u): there C takes the slope along the slip and the secant across
    # it, which is the exact Jacobian of F_t = −μ(|u|) F_n u/|u| at a fixed pose (central differences
    # to 1e-6 with steps 1e-4 of the slip; the curvature of μ bounds their error)
    law = Coulomb(0.1, 0.08, 1e-3, 2e-3)
    C, jac, slip = _damping_and_jacobian(law, (1e-4, -0.5e-4, 0.0), (0.0, 0.0, 0.0))
    assert 0.0 < slip < 0.5e-3  # on the convex part of the step (slope > secant)
    np.testing.assert_allclose(C, jac, rtol=1e-5, atol=1e-6 * np.abs(C).max())
    np.testing.assert_allclose(C, C.T, rtol=0, atol=1e-12 * np.abs(C).max())
    assert np.linalg.eigvalsh(C).min() > -1e-9 * np.abs(C).max()


def _rotation(qw):
    from scipy.spatial.transform import Rotation

    return Rotation.from_quat([qw[1], qw[2], qw[3], qw[0]]).as_matrix()


def slide_to_roll(friction, implicit, timestep_s=None, t_end_s=0.5, v0=1.0):
    model, state, i = roller_on_plane(friction, implicit)
    eq = static_equilibrium(model, state).state
    eq.v[i, 1] = v0  # sliding along world y, not turning
    out = simulate(model, eq, t_end_s, timestep_s=timestep_s, record_every=10)
    return model, eq, out, i


def test_sliding_roller_rolls_at_two_thirds_of_its_speed_at_a_step_far_above_the_friction_limit():
    # Closed form (a cylinder launched sliding at v0 on a plane, Coulomb friction μ; Kleppner &
    # Kolenkow, An Introduction to Mechanics, ch. 7): while it slides v = v0 − μ g t and
    # ω r = 2 μ g t (I = m r²/2); it rolls from t* = v0 / (3 μ g) on at v = 2 v0 / 3 (angular
    # momentum about the contact line is kept).
    mu, v0 = 0.1, 1.0
    law = Coulomb(mu, mu, 1e-5, 2e-5)  # a steep regularisation: slope 1.5 μ / v_s = 15000 s/m
    m_exp, s_exp, _ = roller_on_plane(law, False)
    h_explicit = stable_timestep(m_exp, static_equilibrium(m_exp, s_exp).state).timestep_s
    model, eq, out, i = slide_to_roll(law, True, v0=v0)
    h = out["timestep_s"]
    assert h > 50 * h_explicit  # the friction law no longer limits the step
    with pytest.raises(StepTooLargeError, match="friction"):
        simulate(m_exp, static_equilibrium(m_exp, s_exp).state, 10 * h, timestep_s=h)
    t, v = out["t"], out["v"][:, i, 1]
    t_star = v0 / (3 * mu * G)
    sliding = (t > 0.02) & (t < 0.8 * t_star)
    # the deceleration while sliding, a least-squares slope (0.05 % off here; tolerance 0.2 % for the
    # contact's vertical vibration around its static load)
    slope = np.polyfit(t[sliding], v[sliding], 1)[0]
    assert slope == pytest.approx(-mu * G, rel=2e-3)
    rolling = t > 1.2 * t_star
    assert np.mean(v[rolling]) == pytest.approx(2 * v0 / 3, rel=1e-6)  # 5e-11 here
    # rolling without slip: ω r = v (ω about the axis, body z)
    omega_r = -out["v"][rolling, i, 5] * R_M
    np.testing.assert_allclose(np.abs(omega_r), v[rolling], rtol=2e-3)
    assert np.all(np.isfinite(out["v"]))


def test_implicit_friction_matches_the_explicit_run_at_its_own_step():
    # the same slide-to-roll history, explicit friction at its (small) stable step as the reference:
    # speeds within 0.1 % of v0 at every recorded instant (0.05 % here)
    law = Coulomb(0.1, 0.1, 2e-4, 4e-4)
    _, _, ref, i = slide_to_roll(law, False, t_end_s=0.45)
    _, _, out, _ = slide_to_roll(law, True, t_end_s=0.45)
    assert out["timestep_s"] > 3 * ref["timestep_s"]
    v_ref = np.interp(out["t"], ref["t"], ref["v"][:, i, 1])
    np.testing.assert_allclose(out["v"][:, i, 1], v_ref, atol=1e-3)


def _random_kick_inputs(model, state, i, seed, turn_seed):
    """Work arrays with a random symmetric positive definite damping matrix, evaluation velocity,
    force and moment on body i, a random orientation of it and random velocities: (w, q, v, R)."""
    from scipy.spatial.transform import Rotation

    from mbd_core.multibody.model import make_work

    rng = np.random.default_rng(seed)
    w = make_work(model)
    A = rng.normal(size=(6, 6))
    w.fric_c[i] = A @ A.T
    w.fric_v[i] = rng.normal(size=6)
    w.body_f[i], w.body_t[i] = rng.normal(size=3) * 10, rng.normal(size=3)
    q = state.q.copy()
    q[i, 3:] = Rotation.random(random_state=turn_seed).as_quat()[[3, 0, 1, 2]]
    v = rng.normal(size=state.v.shape)
    return w, q, v, _rotation(q[i, 3:])


def test_friction_kick_matches_its_numpy_twin():
    # the kick of mbd_core.kernels.explicit against a dense numpy solve of the same linear system,
    # (M + h/2 C) Δu = h/2 (F − C (u − u_e)) in world (v, ω), M = diag(m, R I Rᵀ); ω stored in the body frame
    from mbd_core.kernels.explicit import _friction_kick

    model, state, i = roller_on_plane(Coulomb(0.1, 0.1, 1e-3, 2e-3), True)
    a = model.arrays
    w, q, v, R = _random_kick_inputs(model, state, i, 7, 3)
    hh = 1e-3
    M = np.zeros((6, 6))
    M[:3, :3] = a.body_mass[i] * np.eye(3)
    M[3:, 3:] = R @ np.diag(a.body_inertia[i]) @ R.T
    du = np.concatenate([v[i, :3] - w.fric_v[i, :3], R @ (v[i, 3:] - w.fric_v[i, 3:])])
    step = np.linalg.solve(M + hh * w.fric_c[i], hh * (np.concatenate([w.body_f[i], w.body_t[i]]) - w.fric_c[i] @ du))
    want = v[i] + np.concatenate([step[:3], R.T @ step[3:]])
    others = v.copy()
    _friction_kick(q, v, w, a.body_mass, a.body_inertia, a.body_free, a.body_fric_implicit, hh)
    np.testing.assert_allclose(v[i], want, rtol=1e-12, atol=1e-14 * np.abs(want).max())
    np.testing.assert_array_equal(np.delete(v, i, axis=0), np.delete(others, i, axis=0))  # the fixed ground


def test_friction_kick_of_a_driven_body_matches_its_numpy_twin():
    # a body driven about its own z axis, free to move and tilt: the kick in the stored coordinates
    # u = (v world, ω body), M' = diag(m, I), C' = Tᵀ C T (T = diag(1, R)), solved for the five free
    # components with the driven ω_z kept, and the gyroscopic torque −ω × Iω of its partly free
    # rotation on the right-hand side, against a dense numpy solve
    from mbd_core.kernels.explicit import _friction_kick
    from mbd_core.multibody import Driven

    model, state, i = roller_on_plane(Coulomb(0.1, 0.1, 1e-3, 2e-3), True,
                                      motion=Driven(40.0, translation_free=True, tilt_free=True))
    a = model.arrays
    assert a.body_fric_implicit[i] == 1 and list(a.body_free[i]) == [1, 1, 1, 1, 1, 0]
    w, q, v, R = _random_kick_inputs(model, state, i, 11, 5)
    hh = 1e-3
    T = np.eye(6)
    T[3:, 3:] = R
    Cp = T.T @ w.fric_c[i] @ T
    inertia = a.body_inertia[i]
    M = np.diag(np.concatenate([np.full(3, a.body_mass[i]), inertia]))
    omega = v[i, 3:].copy()
    F = np.concatenate([w.body_f[i], R.T @ w.body_t[i] - np.cross(omega, inertia * omega)])
    rhs = hh * (F - Cp @ (v[i] - w.fric_v[i]))
    free = np.flatnonzero(a.body_free[i])
    want = v[i].copy()
    want[free] += np.linalg.solve((M + hh * Cp)[np.ix_(free, free)], rhs[free])
    _friction_kick(q, v, w, a.body_mass, a.body_inertia, a.body_free, a.body_fric_implicit, hh)
    np.testing.assert_allclose(v[i], want, rtol=1e-12, atol=1e-14 * np.abs(want).max())
    assert v[i, 5] == want[5] == omega[2]  # the driven spin is kept


def test_an_interrupted_run_with_implicit_friction_resumes_bit_for_bit(tmp_path):
    # the damping matrices and the velocity of the last force evaluation are integrator state too
    model, state, i = roller_on_plane(Coulomb(0.1, 0.1, 1e-5, 2e-5), True)
    state = static_equilibrium(model, state).state
    state.v[i, 1] = 1.0
    h = stable_timestep(model, state).timestep_s
    whole = simulate(model, state.copy(), 600 * h, timestep_s=h, folder=tmp_path / "a", record_every=20,
                     chunk_samples=5)
    simulate(model, state.copy(), 300 * h, timestep_s=h, folder=tmp_path / "b", record_every=20, chunk_samples=5)
    resumed = simulate(model, state.copy(), 600 * h, folder=tmp_path / "b", record_every=20, chunk_samples=5,
                       resume=True)
    for key in ("t", "q", "v", "fn", "slip", "ft"):
        np.testing.assert_array_equal(resumed[key], whole[key])
