"""Generalized-α reference integrator (mbd_core.multibody.implicit): its kernels against numpy twins,
the scheme against a scalar twin and the analytic oscillator, the invariants of the free rigid body,
and the explicit scheme on a ball–groove contact transient with a closed-form static end."""

import math

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import brentq

from mbd_core.kernels.forces import compute_forces
from mbd_core.kernels.implicit import accelerations, compose
from mbd_core.kernels.rigid import free_rotation_step
from mbd_core.multibody import ContactLaw, DivergenceError, Driven, Fixed, ModelBuilder, simulate, stable_timestep
from mbd_core.multibody.implicit import gen_alpha_coefficients, simulate_implicit
from mbd_core.multibody.model import make_work
from tests.reference.rigid_rotation import quat_to_matrix

RNG = np.random.default_rng(19930601)


def _hat(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def _random_quats(n):
    q = RNG.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


# -- kernels --------------------------------------------------------------------------------------

def test_compose_matches_matrix_exponential_including_tiny_and_large_turns():
    # twin: r + h dq_r and R(q) expm(h [dq_ω]×) (body-frame increment, Brüls & Cardona 2010 eq. 8)
    n = 40
    q = np.hstack([RNG.normal(size=(n, 3)), _random_quats(n)])
    dq = RNG.normal(size=(n, 6)) * RNG.choice([1e-9, 1e-3, 1.0, 300.0], size=(n, 1))
    dq[0, 3:] = 0.0                                   # no turn
    dq[1, 3:] = [1e-6, 0.0, 0.0]                      # below the series switch
    dq[2, 3:] = [0.0, 0.0, math.pi / 1e-2 - 1e-9]     # almost half a turn at h = 1e-2
    h = 1e-2
    out = np.empty_like(q)
    compose(q, dq, h, out)
    for i in range(n):
        assert out[i, :3] == pytest.approx(q[i, :3] + h * dq[i, :3], rel=1e-14, abs=1e-15)
        R = quat_to_matrix(q[i, 3:]) @ expm(_hat(h * dq[i, 3:]))
        assert quat_to_matrix(out[i, 3:]) == pytest.approx(R, abs=2e-14)
        assert np.linalg.norm(out[i, 3:]) == pytest.approx(1.0, abs=1e-15)
    in_place = q.copy()
    compose(in_place, dq, h, in_place)                 # out may alias q
    assert np.array_equal(in_place, out)


def _mixed_model():
    b = ModelBuilder()
    b.add_body("ground", 1.0, (1, 1, 1), motion=Fixed())
    b.add_body("free", 2.0, (0.01, 0.02, 0.03), position_m=(0.1, 0, 0))
    b.add_body("driven", 3.0, (0.05, 0.05, 0.08), position_m=(0, 0.2, 0),
               motion=Driven(50.0, translation_free=True, tilt_free=True))
    b.add_body("spinner", 1.5, (0.02, 0.02, 0.03), position_m=(0, 0, 0.3), motion=Driven(20.0))
    k = (1e5, 2e5, 3e5, 1e3, 2e3, 3e3)
    b.add_bushing("ground", "free", (0.1, 0, 0), k, damping=(10, 20, 30, 1, 2, 3))
    b.add_bushing("free", "driven", (0.05, 0.1, 0), k)
    b.add_bushing("driven", "spinner", (0, 0.1, 0.15), k, damping=(5, 5, 5, 0.5, 0.5, 0.5))
    b.add_force("free", (1.0, -2.0, 3.0), (0.1, 0.2, -0.3))
    return b.finalize()


def test_accelerations_match_newton_euler_twin_on_random_states():
    # twin: F/m and I⁻¹(Rᵀτ − ω × Iω) on free components, 0 on held ones (Fixed, Driven spin)
    model, state = _mixed_model()
    a = model.arrays
    free = model.free_mask()
    for trial in range(20):
        q = state.q.copy()
        q[:, :3] += 1e-3 * RNG.normal(size=(4, 3))
        q[:, 3:] = _random_quats(4) if trial else q[:, 3:]
        v = RNG.normal(size=(4, 6)) * [1, 1, 1, 30, 30, 30]
        v[~free] = state.v[~free]
        w = make_work(model)
        out = np.full((4, 6), np.nan)
        assert accelerations(a, 0.0, q, v, w, out) == (0, -1)
        w_ref = make_work(model)
        compute_forces(a, 0.0, q, v, np.zeros(0), np.zeros(0), w_ref)
        for i in range(4):
            inertia, om = a.body_inertia[i], v[i, 3:]
            tau_b = quat_to_matrix(q[i, 3:]).T @ w_ref.body_t[i]
            ref = np.concatenate([w_ref.body_f[i] / a.body_mass[i], (tau_b - np.cross(om, inertia * om)) / inertia])
            ref[~free[i]] = 0.0
            assert out[i] == pytest.approx(ref, rel=1e-12, abs=1e-12 * np.abs(ref).max())


# -- linear oscillator: twin, convergence order, dissipation ------------------------------------

MASS_KG, K_N_M, X0_M = 2.0, 2e4, 1e-3
OMEGA = math.sqrt(K_N_M / MASS_KG)           # 100 rad/s
PERIOD = 2 * math.pi / OMEGA


def _oscillator():
    """A free mass on a linear bushing to a fixed body, released from x = X0 at rest."""
    b = ModelBuilder()
    b.add_body("ground", 1.0, (1, 1, 1), motion=Fixed())
    b.add_body("mass", MASS_KG, (0.01, 0.01, 0.01))
    b.add_bushing("ground", "mass", (0, 0, 0), (K_N_M, K_N_M, K_N_M, 10, 10, 10))
    model, state = b.finalize()
    state.q[1, 0] = X0_M
    return model, state


def _run_oscillator(steps_per_period, periods, rho_inf):
    model, state = _oscillator()
    r = simulate_implicit(model, state, periods * PERIOD, PERIOD / steps_per_period, rho_inf=rho_inf)
    return r["t"], r["q"][:, 1, 0], r["v"][:, 1, 0]


def _scalar_gen_alpha(h, n, rho_inf):
    """Chung & Hulbert (1993) on ẍ = −ω²x, the linear step solved in closed form."""
    c = gen_alpha_coefficients(rho_inf)
    am, af, beta, gamma = c.alpha_m, c.alpha_f, c.beta, c.gamma
    x, v, vd = X0_M, 0.0, -OMEGA**2 * X0_M
    acc = vd
    xs = [x]
    for _ in range(n):
        known = x + h * v + h * h * ((0.5 - beta) * acc + beta * (af * vd - am * acc) / (1 - am))
        vd1 = -OMEGA**2 * known / (1 + OMEGA**2 * h * h * beta * (1 - af) / (1 - am))
        acc1 = ((1 - af) * vd1 + af * vd - am * acc) / (1 - am)
        x = known + h * h * beta * (1 - af) / (1 - am) * vd1
        v += h * ((1 - gamma) * acc + gamma * acc1)
        vd, acc = vd1, acc1
        xs.append(x)
    return np.array(xs)


@pytest.mark.parametrize("rho_inf", [1.0, 0.9, 0.5, 0.0])
def test_oscillator_matches_scalar_twin(rho_inf):
    # a coarse step (ωh = 0.63) makes every coefficient matter
    _, x, _ = _run_oscillator(10, 3, rho_inf)
    assert x == pytest.approx(_scalar_gen_alpha(PERIOD / 10, 30, rho_inf), rel=0, abs=1e-10 * X0_M)


def test_oscillator_error_is_second_order():
    # reference: x(t) = X0 cos ωt; max error over two periods at h = T/20, T/40, T/80.
    # Measured: 9.0e-5, 2.3e-5, 5.7e-6 m (p = 1.99).
    errs = []
    for n in (20, 40, 80):
        t, x, _ = _run_oscillator(n, 2, 0.9)
        errs.append(np.max(np.abs(x - X0_M * np.cos(OMEGA * t))))
    p = np.polyfit(np.log([PERIOD / 20, PERIOD / 40, PERIOD / 80]), np.log(errs), 1)[0]
    assert 1.8 < p < 2.2, (errs, p)
    assert errs[-1] < 0.01 * X0_M


def test_oscillator_dissipation_follows_rho_inf():
    # ρ∞ = 1 is the trapezoidal rule on a linear system: the amplitude √(x² + (v/ω)²) is kept
    # (Chung & Hulbert 1993, §3); smaller ρ∞ damp more. Measured amplitude loss over 10 periods at
    # T/40: 4e-12 (ρ∞ = 1), 1.8e-5 (0.9), 4.4e-3 (0.5).
    loss = {}
    for rho in (1.0, 0.9, 0.5):
        _, x, v = _run_oscillator(40, 10, rho)
        amp = np.hypot(x, v / OMEGA)
        loss[rho] = 1 - amp[-1] / amp[0]
        if rho == 1.0:
            assert np.max(np.abs(amp / amp[0] - 1)) < 1e-3
    assert abs(loss[1.0]) < loss[0.9] < loss[0.5]


def test_newton_failure_names_the_time():
    model, state = _oscillator()
    with pytest.raises(DivergenceError, match=r"did not converge in 1 iterations at t = 0\.00314159"):
        simulate_implicit(model, state, PERIOD, PERIOD / 20, tol=1e-30, max_iter=1)
    assert state.t == 0.0                           # the state is that of the last completed step


# -- torque-free asymmetric body -----------------------------------------------------------------

INERTIA = np.array([1.0, 2.5, 4.0])   # kg·m², unstable middle axis


@pytest.mark.parametrize("omega0,n_steps,tumbles", [
    ((0.05, 2.0, 0.0125), 500, True),      # near the middle axis: turns over within 5 s
    ((0.1, 0.2, 1.0), 300, False),         # near the major axis
], ids=["middle_axis", "major_axis"])
def test_free_body_keeps_energy_and_momentum(omega0, n_steps, tumbles):
    # Euler's equations conserve T = ½ ωᵀIω and the world angular momentum R I ω. Measured with
    # ρ∞ = 1, h = 10 ms: near the middle axis 5.6e-5 (T) and 5.8e-5 (L vector); near the major axis
    # 5.6e-7 and 1.3e-6. Reference attitude: the symplectic splitting (kernels.rigid, Dullweber et
    # al. 1997) at h/100; measured 2.5e-4 and 1.0e-3 at h and 2h (second order).
    h = 1e-2
    b = ModelBuilder()
    b.add_body("top", 3.0, INERTIA, omega_rad_s=omega0)
    model, state = b.finalize()
    r = simulate_implicit(model, state, n_steps * h, h, rho_inf=1.0)
    om = r["v"][:, 0, 3:]
    energy = 0.5 * np.sum(INERTIA * om**2, axis=1)
    L = np.einsum("kij,kj->ki", np.array([quat_to_matrix(q) for q in r["q"][:, 0, 3:]]), INERTIA * om)
    assert np.max(np.abs(energy / energy[0] - 1)) < 1e-4
    assert np.max(np.abs(np.linalg.norm(L, axis=1) / np.linalg.norm(L[0]) - 1)) < 1e-4
    assert np.max(np.linalg.norm(L - L[0], axis=1)) < 1e-4 * np.linalg.norm(L[0])
    assert (om[:, 1].min() < -1.5) == tumbles
    q, pi = np.array([1.0, 0.0, 0.0, 0.0]), INERTIA * np.array(omega0)
    for _ in range(100 * n_steps):
        free_rotation_step(q, pi, INERTIA, h / 100)
    assert np.linalg.norm(quat_to_matrix(r["q"][-1, 0, 3:]) - quat_to_matrix(q)) < 1e-3


# -- contact transient: explicit vs generalized-α -----------------------------------------------

Z_BALLS, BALL_D_M, PITCH_R_M, AXIAL_N = 4, 0.02, 0.1, 4000.0
CONFORMITY, ALPHA0_RAD, K_HERTZ = 0.52, math.radians(45.0), 1e10
D0_M = (CONFORMITY - 0.5) * BALL_D_M          # curvature centre ↔ touching ball centre
UPPER_Z_M = 0.03


def _angular_contact_model():
    """Z steel balls between a fixed lower and a free upper ring, touching and unloaded at 45°.

    Each groove's curvature centre lies on the contact line through the ball centre, D0 beyond
    it; an axial force on the upper ring is switched on at t = 0.
    """
    rb = BALL_D_M / 2
    m_ball = 7850.0 * 4 / 3 * math.pi * rb**3
    ca, sa = math.cos(ALPHA0_RAD), math.sin(ALPHA0_RAD)
    b = ModelBuilder()
    b.add_body("lower", 5.0, (0.05, 0.05, 0.1), motion=Fixed())
    b.add_body("upper", 2.0, (0.01, 0.01, 0.02), position_m=(0, 0, UPPER_Z_M))
    g_low = b.add_groove("lower", PITCH_R_M + D0_M * ca, D0_M * sa, CONFORMITY * BALL_D_M)
    g_up = b.add_groove("upper", PITCH_R_M - D0_M * ca, -UPPER_Z_M - D0_M * sa, CONFORMITY * BALL_D_M)
    law = ContactLaw(K_HERTZ, 1.5, damping=3e3, d_max_m=1e-6)
    for j in range(Z_BALLS):
        th = 2 * math.pi * (j + 0.5) / Z_BALLS
        b.add_body(f"ball{j}", m_ball, (0.4 * m_ball * rb**2,) * 3,
                   position_m=(PITCH_R_M * math.cos(th), PITCH_R_M * math.sin(th), 0.0))
        b.add_ball_groove(f"ball{j}", "lower", g_low, rb, law, name=f"lower{j}")
        b.add_ball_groove(f"ball{j}", "upper", g_up, rb, law, name=f"upper{j}")
    b.add_force("upper", (0, 0, -AXIAL_N))
    return b.finalize()


def _static_angular_contact():
    """Loaded contact angle α and ring approach of a thrust-loaded angular-contact row.

    Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., vol. 2, §1.2 (axial load):
    F/(Z K_n (BD)^1.5) = sin α (cos α₀/cos α − 1)^1.5, with BD = 2 D0 the distance of the
    curvature centres and K_n = K/2^1.5 (two equal Hertz contacts in series); the axial approach
    is BD cos α₀ (tan α − tan α₀).
    """
    bd = 2 * D0_M
    k_n = K_HERTZ / 2**1.5
    lhs = AXIAL_N / (Z_BALLS * k_n * bd**1.5)
    g = lambda a: math.sin(a) * (math.cos(ALPHA0_RAD) / math.cos(a) - 1) ** 1.5 - lhs  # noqa: E731
    alpha = brentq(g, ALPHA0_RAD + 1e-12, math.radians(80.0), xtol=1e-14)
    return alpha, bd * math.cos(ALPHA0_RAD) * (math.tan(alpha) - math.tan(ALPHA0_RAD))


@pytest.fixture(scope="module")
def contact_runs():
    model, state = _angular_contact_model()
    assert stable_timestep(model, state).limit_s > 2 * 2e-6
    explicit = simulate(model, state, 0.1, 2e-6, record_every=5)
    model, state = _angular_contact_model()
    implicit = simulate_implicit(model, state, 0.1, 1e-5, rho_inf=0.9)
    return explicit, implicit


def test_contact_transient_explicit_and_implicit_agree(contact_runs):
    # Step load on a touching row: peak 2681 N (2.0 × static), ringing at the ring's axial mode
    # and the balls' rocking across the contact line (≈ 2.2 kHz, lightly damped: the damper acts
    # along the normal only). Measured largest difference 9.3 N = 0.35 % of the peak (at 34 ms)
    # over 0.1 s, sampled every 1e-5 s.
    explicit, implicit = contact_runs
    assert np.allclose(explicit["t"], implicit["t"], rtol=0, atol=1e-12)
    peak = explicit["fn"].max()
    assert 2.0 * AXIAL_N / (Z_BALLS * math.sin(ALPHA0_RAD)) > peak > AXIAL_N / (Z_BALLS * math.sin(ALPHA0_RAD))
    assert np.max(np.abs(explicit["fn"] - implicit["fn"])) < 0.01 * peak


def test_contact_transient_ends_at_the_static_share(contact_runs):
    # Mean over the last 10 ms (residual ringing 6.5 N peak to peak) against Q = F/(Z sin α) =
    # 1336.9 N at the loaded angle α = 48.416° of _static_angular_contact (the unloaded 45° would
    # be 5.8 % off). Measured, explicit and implicit: forces 2e-5, angles 0.003°, approach 2e-4.
    alpha, approach = _static_angular_contact()
    q_static = AXIAL_N / (Z_BALLS * math.sin(alpha))
    for run in contact_runs:
        tail = run["t"] > 0.09
        assert run["fn"][tail].mean(axis=0) == pytest.approx(q_static, rel=1e-3)
        assert np.degrees(np.abs(run["angle"][tail]).mean(axis=0)) == pytest.approx(math.degrees(alpha), abs=0.01)
        assert UPPER_Z_M - run["q"][tail, 1, 2].mean() == pytest.approx(approach, rel=2e-3)
