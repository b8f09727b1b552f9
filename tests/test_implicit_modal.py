"""Generalized-α with modal (flexible) bodies (mbd_core.multibody.implicit, mbd_core.kernels.implicit):
the modal accelerations against a numpy twin, free and damped vibration of a ring's modes against the
closed-form solutions, a contact transient on a flexible race against the explicit scheme, and the
invariants of a free, tumbling and vibrating ring.

References: the linear oscillator η̈ + 2ζωη̇ + ω²η = 0 and the generalized-α method on it (Chung &
Hulbert, J. Appl. Mech. 60 (1993) 371: ρ∞ = 1 is the trapezoidal rule, whose solution from rest is
η_n = η_0 cos(n φ) with tan(φ/2) = hω/2); the explicit scheme (mbd_core.multibody.simulate) at a
step 20 to 50 times smaller; the conservation laws of a free body.
"""

import dataclasses
import math

import numpy as np
import pytest

from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from fem_rings import MeshSpec
from fem_rings.profile import rectangle
from fem_rings.sections import SlewingSection, slewing_bottom_race
from mbd_core.contact import ball_on_groove
from mbd_core.kernels import forces as FK
from mbd_core.kernels.implicit import modal_accelerations, step_accelerations
from foundation.materials import ElasticMaterial
from mbd_core.multibody import DivergenceError, ModelBuilder, simulate, stable_timestep
from mbd_core.multibody.builder import ContactLaw, Driven, Fixed, Free
from mbd_core.multibody.implicit import simulate_implicit
from mbd_core.multibody.model import make_work
from tests.reference import modal as ref_modal
from tests.reference import modal_step as twin
from tests.reference.multibody import matrix
from tests.test_kernels_modal_step import SCENARIOS, _loaded_work, _modal_model, _random_state

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
SEED = 19930602


@pytest.fixture(scope="module")
def ring():
    """The free–free 1 m steel ring of tests/test_modal_dynamics.py (100 × 100 mm section): 8 modes
    (229–672 Hz, in pairs) + its centrifugal stretch shape (1612 Hz); mass-normalised, I6 = 1."""
    return reduced_body(rectangle("ring", 0.45, 0.55, 0.0, 0.1), MeshSpec(0.05, "hex27"), STEEL,
                        ReductionSpec(n_modes=8, centrifugal=True))


# ---------------------------------------------------------------------------- kernel against twin
def twin_accelerations(model, q, v, eta, eta_dot, body_f, body_t, modal_f):
    """Accelerations (n_b, 6) and η̈ (n_η,) of the modal bodies from world forces body_f, moments body_t
    (about the frame origin) and modal forces: M_ff(η) u̇_f = (rhs − h)_f by numpy.linalg.solve,
    u̇ = 0 on held components, r̈ = R (u̇_v + ω × u_v) (mbd_core.kernels.implicit module docstring)."""
    m = model.arrays
    out, out_eta = np.zeros((model.n_bodies, 6)), np.zeros(model.n_modal)
    for j, i in enumerate(m.modal_body):
        s = slice(m.modal_off[j], m.modal_off[j + 1])
        inv = twin.invariants(m, j)
        R = matrix(q[i, 3:])
        e, u_v, omega = eta[s], R.T @ v[i, :3], v[i, 3:]
        rhs = twin.constrained_rhs(inv, e, eta_dot[s], u_v, omega, R.T @ body_f[i], R.T @ body_t[i],
                                   R.T @ m.gravity, modal_f[s], m.modal_omega2[s], m.modal_damp[s], True, frozen=False)
        free = np.concatenate([m.modal_frame_free[j].astype(bool), np.ones(len(e), bool)])
        ud = np.zeros(free.size)
        ud[free] = np.linalg.solve(ref_modal.mass_matrix(*inv, e)[np.ix_(free, free)], rhs[free])
        out[i, :3] = R @ (ud[:3] + np.cross(omega, u_v)) if free[0] else 0.0
        out[i, 3:] = ud[3:6]
        out_eta[s] = ud[6:]
    return out, out_eta


def _close_blocks(model, got, want, got_eta, want_eta, rtol=1e-12):
    """Each block (r̈, ω̇ of a body; η̈ of a modal body) to rtol of its largest entry: the linear solve
    with M(η) (condition number ≤ 1e4 for these rings) spreads the round-off of the largest entry."""
    a = model.arrays
    for j, i in enumerate(a.modal_body):
        s = slice(a.modal_off[j], a.modal_off[j + 1])
        for g, w in ((got[i, :3], want[i, :3]), (got[i, 3:], want[i, 3:]), (got_eta[s], want_eta[s])):
            np.testing.assert_allclose(g, w, rtol=0, atol=rtol * max(np.abs(w).max(), 1e-300))


@pytest.mark.parametrize("name", sorted(SCENARIOS))
def test_modal_accelerations_match_twin(name):
    """Random poses, velocities, η, η̇ and loads (world forces ~10 N, moments ~0.1 N·m, modal forces
    ~10 √kg·m/s²) on the synthetic rings of tests/test_kernels_modal_step.py with gravity: every frame
    form (free, fixed, driven spin, driven with free translation and tilt, I6 ≠ 1, several bodies)."""
    model, state = _modal_model(name)
    a = model.arrays
    rng = np.random.default_rng(SEED)
    for _ in range(5):
        q, v, eta, eta_dot = _random_state(model, state, rng)
        w = _loaded_work(model, rng)
        want, want_eta = twin_accelerations(model, q, v, eta, eta_dot, w.body_f, w.body_t, w.modal_f)
        got, got_eta = np.full((model.n_bodies, 6), np.nan), np.full(model.n_modal, np.nan)
        assert modal_accelerations(a, q, v, eta, eta_dot, w, got, got_eta) == -1
        _close_blocks(model, got, want, got_eta, want_eta)
        # the whole stage: forces (here the rigid body's weight and the modal bodies' gravity) then
        # Newton–Euler for the rigid body and the modal solve
        w = make_work(model)
        got[:], got_eta[:] = np.nan, np.nan
        assert step_accelerations(a, 0.0, q, v, eta, eta_dot, w, got, got_eta) == (FK.STATUS_OK, -1)
        want, want_eta = twin_accelerations(model, q, v, eta, eta_dot, w.body_f, w.body_t, w.modal_f)
        _close_blocks(model, got, want, got_eta, want_eta)
        np.testing.assert_allclose(got[0, :3], a.gravity, rtol=1e-15)


def test_indefinite_modal_mass_stops_the_run_with_a_clear_error():
    model, state = _modal_model("fixed_coupled_I6")
    a = model.arrays
    bad = dataclasses.replace(model, arrays=a._replace(modal_I6=-a.modal_I6))
    w = make_work(bad)
    out, out_eta = np.zeros((bad.n_bodies, 6)), np.zeros(bad.n_modal)
    assert step_accelerations(bad.arrays, 0.0, state.q, state.v, state.eta, state.eta_dot, w, out, out_eta) == (
        FK.STATUS_MODAL, 0)
    with pytest.raises(DivergenceError, match="no longer positive definite"):
        simulate_implicit(bad, state, 1e-3, 1e-4)


# ---------------------------------------------------------------------------- modes of a fixed ring
def _fixed_ring(body, eta0):
    b = ModelBuilder()
    b.add_modal_body("ring", body, motion=Fixed(), eta=eta0)
    return b.finalize()


def _omega(model):
    return np.sqrt(model.arrays.modal_omega2)


def test_free_vibration_of_each_mode_is_second_order(ring):
    """A ring held in its frame, released from η_0 ≠ 0 in every mode, no loads: the modes decouple
    (I6 = 1, ω = v = 0) and ρ∞ = 1 is the trapezoidal rule, η_n = η_0 cos(n φ), tan(φ/2) = hω/2, up to
    the Newton tolerance (tol = 1e-10 of the accelerations per step; measured 1.3e-10 of η_0). Steps
    h = T_top/20, /40, /80 (T_top the period of the 1612 Hz mode), two periods of the lowest mode:
    the period error T_h/T − 1, from the slope of the phase atan2(−η̇/ω, η), is (hω)²/12 to leading
    order (8.2e-3 in the top mode at hω = 0.31, 0.65 % below (hω)²/12: the next term is −(hω)⁴/180),
    orders 2.00 under halving; the error against η_0 cos ωt falls with h² too (orders 1.98–2.00;
    0.69, 0.18, 0.044 of η_0 in the top mode after 14 of its periods, 1.8e-3, 4.6e-4, 1.1e-4 in the
    lowest)."""
    eta0 = 1e-3 * (1.0 + np.arange(ring.n_modes))
    model, state = _fixed_ring(ring, eta0)
    omega = _omega(model)
    t_top, t_end = 2 * math.pi / omega.max(), 2 * (2 * math.pi / omega.min())
    steps = np.array([20, 40, 80])
    errors, period_errors = [], []
    for n in steps:
        h = t_top / n
        r = simulate_implicit(model, state.copy(), t_end, h, rho_inf=1.0)
        phi = 2.0 * np.arctan(0.5 * h * omega)
        k = np.round(r["t"] / h)[:, None]
        np.testing.assert_allclose(r["eta"], eta0 * np.cos(k * phi), rtol=0, atol=1e-9 * eta0.max())
        errors.append(np.abs(r["eta"] - eta0 * np.cos(np.outer(r["t"], omega))).max(axis=0) / eta0)
        phase = np.unwrap(np.arctan2(-r["eta_dot"] / omega, r["eta"]), axis=0)
        omega_h = np.array([np.polyfit(r["t"], phase[:, c], 1)[0] for c in range(ring.n_modes)])
        period_errors.append(omega / omega_h - 1.0)
        np.testing.assert_allclose(period_errors[-1], (h * omega) ** 2 / 12, rtol=0.01)
    for e in (errors, period_errors):
        orders = np.array([np.polyfit(np.log(1.0 / steps), np.log(c), 1)[0] for c in np.array(e).T])
        assert np.all(np.abs(orders - 2.0) < 0.05), orders


def test_modal_damping_decays_each_mode_per_period_as_its_damping_ratio(ring):
    """With ζ = 0.05 in every mode the amplitude A = √(η² + ((η̇ + ζωη)/ω_d)²) (A_0 e^{−ζωt} for the
    continuous oscillator, ω_d = ω√(1 − ζ²)) falls per damped period by exp(−2πζ/√(1 − ζ²)) = 0.7301.
    Decay rate and period fitted over three periods of the lowest mode at h = T_top/40 and /80
    (hω ≤ 0.157), ρ∞ = 1: the decay per period is the trapezoidal rule's |z|^(2π/arg z), z = (1 + hλ/2)
    /(1 − hλ/2), λ = −ζω + iω_d, to 4e-13 (no numerical damping of its own), and that differs from the
    exact one by 1.3e-3 and 3.2e-4 at most (the top mode; 2.6e-5 and 6.5e-6 in the lowest): second order."""
    zeta = 0.05
    body = dataclasses.replace(ring, damping_ratio=np.full(ring.n_modes, zeta))
    eta0 = 1e-3 * np.ones(ring.n_modes)
    model, state = _fixed_ring(body, eta0)
    omega = _omega(model)
    np.testing.assert_allclose(model.arrays.modal_damp, 2 * zeta * omega, rtol=1e-14)
    omega_d = omega * math.sqrt(1 - zeta**2)
    want = math.exp(-2 * math.pi * zeta / math.sqrt(1 - zeta**2))
    errors = []
    for n in (40, 80):
        h = 2 * math.pi / omega.max() / n
        r = simulate_implicit(model, state.copy(), 3 * 2 * math.pi / omega.min(), h, rho_inf=1.0)
        x, y = r["eta"], (r["eta_dot"] + zeta * omega * r["eta"]) / omega_d
        log_amp, phase = np.log(np.hypot(x, y)), np.unwrap(np.arctan2(-y, x), axis=0)
        rate = np.array([np.polyfit(r["t"], log_amp[:, c], 1)[0] for c in range(ring.n_modes)])
        omega_h = np.array([np.polyfit(r["t"], phase[:, c], 1)[0] for c in range(ring.n_modes)])
        per_period = np.exp(2 * math.pi * rate / omega_h)
        lam = -zeta * omega + 1j * omega_d
        z = (1 + 0.5 * h * lam) / (1 - 0.5 * h * lam)
        np.testing.assert_allclose(per_period, np.abs(z) ** (2 * math.pi / np.angle(z)), rtol=1e-11)
        errors.append(np.abs(per_period / want - 1).max())
    assert errors[0] < 2e-3
    assert math.log2(errors[0] / errors[1]) == pytest.approx(2.0, abs=0.1)
    # no damping, no decay: ρ∞ = 1 keeps the amplitude of the undamped modes, up to the Newton
    # tolerance (measured 1.1e-12)
    model, state = _fixed_ring(ring, eta0)
    r = simulate_implicit(model, state, 3 * 2 * math.pi / omega.min(), h, rho_inf=1.0)
    amp = np.hypot(r["eta"], r["eta_dot"] / omega)
    assert np.abs(amp / amp[0] - 1).max() < 1e-10


# ---------------------------------------------------------------------------- contact on a flexible race
D_BALL, CONFORMITY, ALPHA, LOAD_N = 95.25e-3, 0.525, math.radians(60.0), 50e3


@pytest.fixture(scope="module")
def race():
    """Bottom race of the 1 m slewing ring bolted down at 4 patches, as in tests/test_modal_dynamics.py:
    20 modes + 33 groove load shapes (up to 21.9 kHz), 2 % modal damping."""
    groove = SlewingSection().groove("bottom", 1.0)
    bolts = InterfaceSpec("bolt_face", (45.0, 135.0, 225.0, 315.0), 0.02)
    samples = RacewaySpec("groove", 360, at_rz_m=tuple(groove.contact_point_m), n_max=16)
    return reduced_body(slewing_bottom_race(1.0), MeshSpec(0.04, "hex27", refine={"groove": 0.5}), STEEL,
                        ReductionSpec(n_modes=20, interfaces=(bolts,), raceways=(samples,), damping_ratio=0.02))


def _ball_on_race(race_body):
    """One ball between the flexible race and a rigid top race (100 kg, free to move along z, held
    radially by a stiff bushing), touching both unloaded; rolling at 1 turn per second; 50 kN on the
    top race from t = 0 (the scene of tests/test_modal_dynamics.py, loaded suddenly)."""
    u = np.array([-math.cos(ALPHA), math.sin(ALPHA)])
    c_f = np.array([0.5, 0.0]) + (CONFORMITY - 0.5) * D_BALL * u
    c_m = np.array([0.5, 0.0]) - (CONFORMITY - 0.5) * D_BALL * u
    k_f = ball_on_groove(D_BALL, CONFORMITY, 1.0, ALPHA, "outer").stiffness_N_per_m1p5
    k_m = ball_on_groove(D_BALL, CONFORMITY, 1.0, ALPHA, "inner").stiffness_N_per_m1p5
    th0 = math.radians(5.0)
    b = ModelBuilder()
    bottom = b.add_modal_body("bottom race", race_body, motion=Fixed())
    top = b.add_body("top race", 100.0, (20.0, 20.0, 40.0), motion=Driven(0.0, translation_free=True))
    ball = b.add_body("ball", 3.55, (3.2e-3,) * 3, position_m=(0.5 * math.cos(th0), 0.5 * math.sin(th0), 0.0),
                      velocity_m_s=math.pi * np.array([-math.sin(th0), math.cos(th0), 0.0]))
    g_f = b.add_groove(bottom, c_f[0], c_f[1], CONFORMITY * D_BALL, raceway="groove")
    g_m = b.add_groove(top, c_m[0], c_m[1], CONFORMITY * D_BALL)
    b.add_ball_groove(ball, bottom, g_f, D_BALL / 2, ContactLaw(k_f, 1.5, 2e4, 1e-5))
    b.add_ball_groove(ball, top, g_m, D_BALL / 2, ContactLaw(k_m, 1.5, 2e4, 1e-5))
    b.add_bushing(bottom, top, (0.0, 0.0, 0.0), (1e9, 1e9, 0, 0, 0, 0), (2e5, 2e5, 0, 0, 0, 0))
    b.add_force(top, (0.0, 0.0, -LOAD_N))
    return b.finalize()


def test_contact_transient_on_a_flexible_race_explicit_and_implicit_agree(race):
    """Both contact forces of the suddenly loaded ball over 20 ms: generalized-α (ρ∞ = 0.9, all 53
    modes in the Newton unknowns) at h = 20 µs and 50 µs — beyond the explicit stability limit of
    14 µs set by the race's 21.9 kHz mode — against the explicit scheme at 1 µs. The peak is 1.97 ×
    the static 57.7 kN (the top race bounces at ≈ 600 Hz on the Hertz contacts). Measured largest
    difference 0.088 % and 0.50 % of the peak (order 1.9 between the two steps), the modal
    coordinates within 0.15 % and 0.9 % of their largest value; 3.3 and 3.5 Newton iterations per
    step, a Jacobian every 18 and 3 steps."""
    model, state = _ball_on_race(race)
    assert stable_timestep(model, state).limit_s < 20e-6
    explicit = simulate(model, state.copy(), 0.02, 1e-6, record_every=10)
    static = LOAD_N / math.sin(ALPHA)
    peak = explicit["fn"].max()
    assert 1.9 * static < peak < 2.0 * static
    errors = []
    for h, tol_fn, tol_eta in ((20e-6, 1.5e-3, 3e-3), (50e-6, 8e-3, 1.5e-2)):
        implicit = simulate_implicit(model, state.copy(), 0.02, h, rho_inf=0.9)
        every = round(h / 10e-6)
        ref = {f: explicit[f][::every] for f in ("t", "fn", "eta")}
        np.testing.assert_allclose(implicit["t"], ref["t"], rtol=0, atol=1e-12)
        errors.append(np.abs(implicit["fn"] - ref["fn"]).max() / peak)
        assert errors[-1] < tol_fn
        assert np.abs(implicit["eta"] - ref["eta"]).max() < tol_eta * np.abs(ref["eta"]).max()
    assert math.log(errors[1] / errors[0]) / math.log(50 / 20) > 1.6


# ---------------------------------------------------------------------------- a free modal ring
def _momentum_energy(a, q, v, eta, eta_dot):
    """World linear momentum, angular momentum about the world origin and total energy of modal body 0
    (its frame at the centre of mass), from the numpy twin of M(η): p = M u."""
    R = matrix(q[3:])
    u = np.concatenate([R.T @ v[:3], v[3:], eta_dot])
    M = ref_modal.mass_matrix(*twin.invariants(a, 0), eta)
    p = M @ u
    P = R @ p[:3]
    return P, np.cross(q[:3], P) + R @ p[3:6], 0.5 * u @ M @ u + 0.5 * np.sum(a.modal_omega2 * eta**2)


def test_free_modal_ring_keeps_momentum_and_energy(ring):
    """The tumbling, translating and vibrating ring of test_free_modal_ring_conserves_momentum_and_energy
    (E = 215 J: 17 J translation, 130 J rotation, 68 J elastic, 0.3 J modal kinetic), 0.25 s at
    hω_top = 0.8 and 0.4, ρ∞ = 1. The linear momentum is kept to round-off (no force: r̈ = R(u̇_v +
    ω × u_v) = 0; measured 1.1e-15). The energy and angular momentum are not invariants of the method on
    this nonlinear system, but their errors are second order (measured 1.4e-7 and 3.0e-8 of E, 5.8e-7
    and 1.6e-7 of |L|) and do not grow: over 2 s (25 000 steps at hω = 0.8) 2.0e-7 of E and 7.0e-7 of
    |L|, a linear trend of E of 2e-9 (the explicit scheme at its step, hω = 1.6, oscillates by 3.4 %)."""
    rng = np.random.default_rng(60)
    m = ring.n_modes
    b = ModelBuilder()
    b.add_modal_body("ring", ring, position_m=(0.1, 0.2, 0.3), velocity_m_s=(0.3, -0.2, 0.1),
                     omega_rad_s=(0.5, -0.3, 2.0), motion=Free(), eta=1e-3 * rng.standard_normal(m),
                     eta_dot=0.3 * rng.standard_normal(m))
    model, state = b.finalize()
    a = model.arrays
    P0, L0, E0 = _momentum_energy(a, state.q[0], state.v[0], state.eta, state.eta_dot)
    w_top = math.sqrt(a.modal_omega2.max())
    errs = {}
    for hw in (0.8, 0.4):
        h = hw / w_top
        out = simulate_implicit(model, state.copy(), 0.25, h, rho_inf=1.0, record_every=int(0.25 / h / 100))
        s = [_momentum_energy(a, out["q"][k, 0], out["v"][k, 0], out["eta"][k], out["eta_dot"][k])
             for k in range(len(out["t"]))]
        P, L, E = (np.array([x[c] for x in s]) for c in range(3))
        assert np.abs(P - P0).max() < 1e-13 * np.linalg.norm(P0)
        errs[hw] = (np.abs(E - E0).max() / E0, np.abs(L - L0).max() / np.linalg.norm(L0))
    assert errs[0.8][0] < 5e-7 and errs[0.8][1] < 2e-6
    for c in range(2):
        assert math.log2(errs[0.8][c] / errs[0.4][c]) > 1.7, errs


@pytest.mark.parametrize("motion", [Free(), Driven(50.0)], ids=["free", "driven"])
def test_spinning_ring_keeps_its_centrifugal_stretch(ring, motion):
    """Spinning about its axis at 50 rad/s (free, or its spin prescribed with translation and tilt held)
    from the static modal equilibrium ω_k² η_k = Ωᵀ G_k(η) Ω, Ω = 50 e_z (the solution of
    test_spinning_ring_keeps_its_centrifugal_stretch in tests/test_modal_dynamics.py, checked there
    against the rotating annular disk): the centrifugal and gyroscopic terms in the implicit
    accelerations hold η there, 0.1 s at h = 100 µs (hω_top = 1.0) with ρ∞ = 0.9, to 1e-12 of the
    stretch (measured 8e-14 and 6e-14), and the spin stays 50 rad/s."""
    omega = 50.0
    b = ModelBuilder()
    b.add_modal_body("ring", ring, motion=motion)
    a = b.finalize()[0].arrays
    m = ring.n_modes
    K = np.diag(a.modal_omega2) - omega**2 * a.modal_I9[0][2, 2].T
    eta_s = np.linalg.solve(K, omega**2 * a.modal_I8[0][2, 2, :m])
    b = ModelBuilder()
    b.add_modal_body("ring", ring, omega_rad_s=(0, 0, omega), motion=motion, eta=eta_s)
    model, state = b.finalize()
    out = simulate_implicit(model, state, 0.1, 1e-4, rho_inf=0.9, record_every=50)
    assert np.abs(out["eta"] - eta_s).max() <= 1e-12 * np.abs(eta_s).max()
    assert np.abs(out["v"][:, 0, 3:] - [0.0, 0.0, omega]).max() < 1e-12 * omega
