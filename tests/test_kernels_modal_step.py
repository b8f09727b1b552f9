"""Modal-body step kernels (mbd_core.kernels.modal_step) and the flexible ball–groove contact of the force
stage (mbd_core.kernels.forces, groove_modal ≥ 0) against their numpy twins (tests/reference/modal_step.py,
tests/reference/multibody.py, tests/reference/explicit_step.py), on seeded random states of small
synthetic modal rings, plus the mechanics the kernels must respect.

The rings are clouds of 30 point masses around a 50 mm circle with random mode shapes (mass-normalised,
or scaled so that I6 is not the identity; for a free frame without translation, I3 = 0), reduced
through cms_reduction.invariants.compute_invariants: their invariants have every symmetry of a real
body and M(η) is positive definite by construction (a Gram matrix). The raceway samples are random
tables D, Ω (n, 3, m) on a full circle (θ_0 = 0, so a ball at θ = 0 sits exactly on a sample) or on an
arc, with the sample points on the groove bottom.

Tolerances, kernel against twin:

* one kick or drift (the same scheme; Cholesky against numpy.linalg.solve, quaternions against
  rotation matrices): rtol 1e-12 with a floor of 1e-12 × the largest entry of each block (v, ω, η̇ of
  a body; η), since the linear solves with M(η) (condition number ≤ 1e4 here) make every entry of a
  block carry the round-off of the largest; quaternions 4 ε. Measured: ≤ 0.07 of that.
* the force stage, the twin evaluated at the kernel's groove angle θ_k: as in test_kernels_multibody
  and test_kernels_explicit — rtol 1e-12; penetrations 1e-16 m (coordinates of ~0.2 m); each normal
  force n K δⁿ⁻¹ × 1e-16 m more, which enters the floors of the body forces (with 1e-12 × Σ|terms|),
  moments (levers < 0.2 m) and modal forces (× |D| + F_D |Ω| per unit force).
* the nearest point itself: the twin minimises |x − c'(θ)| (bounded Brent, then brentq on the exact
  stationarity condition, to round-off); the kernel takes two Gauss–Newton steps from the ball's
  angle with a tangent that leaves out the lever's θ-derivative ψ × ∂(c − p_s)/∂θ, a term first
  order in ψ. Its angle is therefore θ* plus one Gauss–Newton step of its own tangent from θ*, plus
  what two steps leave of the start offset |θ_ball − θ*|: each step contracts it by ~d/r ≈ 4e-3 on
  one interval of the piecewise-linear tables and by up to ~0.1 when θ* lies across a kink (the wrap
  at 0, a sample angle), so 1e-3 of the start offset bounds the rest (5.6e-5 measured); the step from
  θ* is at most d |ψ| 2F_D / |t|² (0.65 of it measured, |θ_k − θ*| ≤ 8e-8 rad). The penetration,
  stationary at θ*, is deeper by |∂c'/∂θ|²Δθ²/d at most.
* ten explicit steps with modal bodies (run_explicit against the twin's modal_step, nearest point as
  the kernel's): rtol 1e-11 (ten steps of 1e-12, passed on by the contact dynamics at hω ≈ 0.2), with
  the floors of test_kernels_explicit for v, ω and r (accumulated h Σ|F|/m, h Σ|M|/I) and 1e-11 × the
  largest entry for η, η̇ and F_n. Measured ≤ 0.22 of that.
"""

import dataclasses
import math

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.spatial.transform import Rotation

from cms_reduction.body import ReducedBody
from cms_reduction.invariants import compute_invariants
from cms_reduction.sampling import RacewaySample
from mbd_core.contact.friction import Coulomb
from mbd_core.kernels import explicit as EX
from mbd_core.kernels import flexible_surface as FS
from mbd_core.kernels import forces as FK
from mbd_core.kernels import modal_step as MS
from mbd_core.kernels.modal import eta_terms
from mbd_core.kernels.raceway import interp_index
from mbd_core.multibody import ContactLaw, Driven, Fixed, Free, ModelBuilder
from mbd_core.multibody.model import make_record_buffers, make_work
from mbd_core.multibody.parts import StripTraction
from tests.reference import explicit_step as twin_step
from tests.reference import modal as ref_modal
from tests.reference import modal_step as twin
from tests.reference import multibody as ref
from tests.reference import multibody_flexible as flex

RTOL = 1e-12
ATOL_M = 1e-16
POINT_ATOL_M, NORMAL_ATOL = 1e-12, 1e-12  # contact points (m) and normals against the twin
EPS = np.finfo(float).eps
SEED = 20260502
R_RING = 0.05                      # radius of the rings' mass points, m
H = 2.0**-13                       # step of the kick/drift tests (≈ 122 µs); 2^14 rad/s has hω = 2 exactly


# -- synthetic modal rings -------------------------------------------------------------------------
def _cloud_body(rng, freqs_hz, free=False, normalised=True, n_points=30, zeta=0.02):
    """A ReducedBody of n_points point masses (0.3 kg in all) near a 50 mm circle at z ≈ 10 mm, with random
    mode shapes: mass-normalised (I6 = 1) or scaled per mode (I6 full); ``free`` puts the centre of mass on
    the axis and removes the modes' mean translation (I3 = 0)."""
    n, m = n_points, len(freqs_hz)
    th = 2 * np.pi * np.arange(n) / n + rng.uniform(-0.05, 0.05, n)
    r = R_RING + rng.uniform(-5e-3, 5e-3, n)
    x = np.column_stack((r * np.cos(th), r * np.sin(th), 0.01 + rng.uniform(-5e-3, 5e-3, n)))
    w = rng.uniform(0.5, 1.5, n) * 0.3 / n
    if free:
        x[:, :2] -= (w @ x[:, :2]) / w.sum()
    phi = rng.standard_normal((n, 3, m))
    if free:
        phi -= np.einsum("i,icm->cm", w, phi) / w.sum()
    phi = phi.reshape(3 * n, m)
    gram = phi.T @ (np.repeat(w, 3)[:, None] * phi)
    if normalised:
        phi = phi @ np.linalg.inv(np.linalg.cholesky(gram)).T
    else:
        phi = phi / np.sqrt(np.diag(gram)) * rng.uniform(0.5, 2.0, m)
    inv = compute_invariants(sp.diags(w), x, phi)
    return ReducedBody("cloud", x, phi, np.asarray(freqs_hz, float), np.full(m, zeta), free, "hex27",
                       np.zeros((3, n)), np.zeros((27, 0), dtype=np.int64), extras=inv.to_arrays())


#: (motion, frequencies Hz, mass-normalised, implicit modes) of the modal bodies of each scenario.
#: With H: 100 Hz → hω = 0.08, 2.6 kHz → 2.0 (resolved), 20 kHz → 15 (unresolved).
SCENARIOS = {
    "free": [(Free(), [100.0, 2000.0, 20000.0], True, False)],
    "fixed": [(Fixed(), [300.0, 5000.0], True, False)],
    "fixed_coupled_I6": [(Fixed(), [300.0, 5000.0, 9000.0], False, False)],
    "driven_spin": [(Driven(80.0), [200.0, 3000.0], True, False)],
    "driven_translation_tilt": [(Driven(80.0, translation_free=True, tilt_free=True), [200.0, 1000.0, 7000.0], True,
                                 False)],
    "fixed_implicit": [(Fixed(), [100.0, 2607.6, 20000.0], True, True)],
    "driven_implicit": [(Driven(-60.0), [100.0, 2607.6, 20000.0, 1e5], True, True)],
    "fixed_implicit_I6": [(Fixed(), [100.0, 2607.6, 20000.0], False, True)],
    # (no 1e5 Hz mode with the tilting frame: the augmented matrix's condition number would then take the
    # kick's round-off to the tolerance, 0.87 of it measured)
    "driven_translation_tilt_implicit": [(Driven(80.0, translation_free=True, tilt_free=True),
                                          [200.0, 2607.6, 20000.0], True, True)],
    "driven_translation_tilt_implicit_I6": [(Driven(80.0, translation_free=True, tilt_free=True),
                                             [200.0, 2607.6, 20000.0], False, True)],
    "driven_translation_implicit": [(Driven(0.0, translation_free=True), [200.0, 2607.6, 20000.0, 1e5], True, True)],
    "driven_translation_implicit_I6": [(Driven(0.0, translation_free=True), [200.0, 2607.6, 20000.0, 1e5], False,
                                        True)],
    "mixed": [(Free(), [150.0, 4000.0], True, False), (Fixed(), [300.0, 5000.0, 9000.0], False, False),
              (Driven(80.0, translation_free=True, tilt_free=True), [200.0, 1000.0, 3000.0, 7000.0], True, False)],
}


def _modal_model(name, seed=SEED):
    """The scenario's modal bodies after a rigid body (so body and modal indices differ), with gravity.
    The 2607.6 Hz modes are set to ω = 2^14 rad/s exactly, so that hω = 2 (the switch to critical damping of the implicit modes)."""
    rng = np.random.default_rng(seed)
    mb = ModelBuilder(gravity_m_s2=(1.5, -9.81, -3.0))
    mb.add_body("rigid", 1.0, (1.0, 2.0, 3.0), velocity_m_s=(0.1, 0.2, 0.3), omega_rad_s=(1.0, 2.0, 3.0))
    for k, (motion, freqs, normalised, implicit) in enumerate(SCENARIOS[name]):
        mb.add_modal_body(f"ring{k}", _cloud_body(rng, freqs, isinstance(motion, Free), normalised), motion=motion,
                          implicit_modes=implicit)
    model, state = mb.finalize()
    a = model.arrays
    omega2 = np.where(np.isclose(a.modal_omega2, (2 * np.pi * 2607.6) ** 2), 2.0**28, a.modal_omega2)
    return dataclasses.replace(model, arrays=a._replace(modal_omega2=omega2)), state


def _random_state(model, state, rng):
    """Random pose and integrated velocities of every modal body (held ones as built: a driven spin, a
    fixed frame at rest); η with modal stiffness forces ω_k² η_k ~ ω_k 2 √kg/s² (nodal displacements
    up to ~3 mm at the lowest mode), η̇ ~ 2 √kg/s (nodal velocities ~ 2 m/s)."""
    a = model.arrays
    q, v = state.q.copy(), state.v.copy()
    for j, i in enumerate(a.modal_body):
        free = a.modal_frame_free[j].astype(bool)
        q[i, :3] = rng.normal(size=3) * 0.1
        q[i, 3:] = Rotation.random(random_state=rng).as_quat(scalar_first=True)
        v[i, :3] = np.where(free[:3], rng.normal(size=3), v[i, :3])
        v[i, 3:] = np.where(free[3:], rng.normal(size=3) * 50.0, v[i, 3:])
    omega = np.sqrt(a.modal_omega2)
    eta = rng.normal(size=model.n_modal) * 2.0 / omega
    return q, v, eta, rng.normal(size=model.n_modal) * 2.0


def _loaded_work(model, rng):
    """Work arrays with random world forces ~10 N, moments ~0.1 N·m and modal forces ~10 √kg·m/s²."""
    w = make_work(model)
    w.body_f[:] = rng.normal(size=w.body_f.shape) * 10.0
    w.body_t[:] = rng.normal(size=w.body_t.shape) * 0.1
    w.modal_f[:] = rng.normal(size=w.modal_f.shape) * 10.0
    return w


# -- comparison ------------------------------------------------------------------------------------
def _close(got, want, atol=0.0, rtol=RTOL):
    """|got − want| ≤ atol + rtol |want| elementwise (atol may be an array broadcast against want)."""
    got, want = np.asarray(got, float), np.asarray(want, float)
    err = np.abs(got - want) - (atol + rtol * np.abs(want))
    assert got.shape == want.shape and np.all(err <= 0), (
        f"worst excess {err.max():.3g} at {np.unravel_index(np.argmax(err), err.shape)}:\n{got}\n!=\n{want}")
    return np.max(np.abs(got - want) / (atol + rtol * np.abs(want) + 1e-300), initial=0.0)


def _close_block(got, want, rtol=RTOL):
    """rtol on each entry plus a floor of rtol × the largest |entry| of the block (linear solves)."""
    want = np.asarray(want, float)
    return _close(got, want, atol=rtol * max(np.max(np.abs(want), initial=0.0), 1e-300), rtol=rtol)


def _close_bodies(model, v_got, v_want, e_got, e_want, rtol=RTOL):
    """Velocities of every modal body by block (v, ω, η̇ or η); rigid bodies must be untouched."""
    a = model.arrays
    worst = 0.0
    for j, i in enumerate(a.modal_body):
        s = slice(a.modal_off[j], a.modal_off[j + 1])
        for got, want in ((v_got[i, :3], v_want[i, :3]), (v_got[i, 3:], v_want[i, 3:]), (e_got[s], e_want[s])):
            worst = max(worst, _close_block(got, want, rtol))
    return worst


# -- Cholesky, ∂T/∂η and the constrained right-hand side ---------------------------------------------
def test_cholesky_matches_numpy_on_leading_blocks_and_refuses_indefinite_matrices():
    rng = np.random.default_rng(SEED)
    for n in range(1, 10):
        B = rng.normal(size=(n, n))
        A = np.full((n + 3, n + 3), np.nan)                  # only the leading n × n block is read
        A[:n, :n] = B @ B.T + 1e-3 * np.eye(n)
        want_L = np.linalg.cholesky(A[:n, :n])
        b = rng.normal(size=n + 2)
        want_x = np.linalg.solve(A[:n, :n], b[:n])
        L = A.copy()
        assert MS.cholesky_in_place(L, n)
        _close_block(np.tril(L[:n, :n]), want_L)
        x = b.copy()
        MS.cholesky_solve(L, n, x)
        _close(x[:n], want_x, atol=RTOL * np.linalg.cond(A[:n, :n]) * np.abs(want_x).max())
        assert np.array_equal(x[n:], b[n:])                 # the rest of b is untouched
    for bad in (np.diag([1.0, -1.0, 2.0]), np.diag([1.0, 0.0, 2.0]), np.array([[1.0, 2.0], [2.0, 1.0]]),
                np.array([[np.nan]])):
        assert not MS.cholesky_in_place(bad.copy(), len(bad))


def _random_invariants(rng, m):
    """Invariant-shaped arrays with the symmetries of M(η) (I6, I7 symmetric, I9_ijkl = I9_jilk), as in
    test_kernels_modal."""
    I7, I6, I9 = rng.standard_normal((3, 3)), rng.standard_normal((m, m)), rng.standard_normal((3, 3, m, m))
    return (rng.uniform(0.5, 2.0), rng.standard_normal(3), rng.standard_normal((3, m)),
            rng.standard_normal((3, m)), rng.standard_normal((3, m, m)), I6 + I6.T, I7 + I7.T,
            rng.standard_normal((3, 3, m)), I9 + I9.transpose(1, 0, 3, 2))


def _eta_terms(inv, eta):
    """S, J, G, I4(η) of the kernel's η-terms at η."""
    m = eta.size
    S, J, G, I4e = np.zeros(3), np.zeros((3, 3)), np.zeros((3, 3, m)), np.zeros((3, m))
    eta_terms(*inv[1:5], *inv[6:9], eta, S, J, G, I4e)
    return S, J, G, I4e


@pytest.mark.parametrize("m", [1, 2, 5])
def test_inertia_force_is_the_eta_gradient_of_the_kinetic_energy(m):
    # the kernel's ωᵀG_kω + Σ_l ω·I5[:, k, l] η̇_l against ½ uᵀ (∂M/∂η_k) u with v = 0 (the twin), and that
    # against the central difference of the twin's T (exact for the quadratic M, up to rounding)
    rng = np.random.default_rng(SEED + m)
    for _ in range(20):
        inv = _random_invariants(rng, m)
        I5 = inv[4]
        eta, omega, eta_dot = rng.normal(size=m) * rng.choice([1e-3, 1.0]), rng.normal(size=3), rng.normal(size=m)
        got = np.full(m, np.nan)
        MS.inertia_force(I5, _eta_terms(inv, eta)[2], omega, eta_dot, got)
        u = np.concatenate([np.zeros(3), omega, eta_dot])
        want = twin.kinetic_gradient(inv, eta, u)
        _close_block(got, want)
        diff = np.array([0.5 * u @ (ref_modal.mass_matrix(*inv, eta + e) - ref_modal.mass_matrix(*inv, eta - e)) @ u
                         for e in np.eye(m)]) / 2.0
        np.testing.assert_allclose(want, diff, rtol=1e-12, atol=1e-12 * np.abs(want).max())
    MS.inertia_force(I5, _eta_terms(inv, eta)[2], np.zeros(3), eta_dot, got)
    assert np.all(got == 0.0)                                  # every term carries ω


def test_constrained_rhs_matches_twin_with_and_without_the_elastic_part():
    rng = np.random.default_rng(SEED + 10)
    for m in (1, 3, 6):
        for _ in range(10):
            inv = _random_invariants(rng, m)
            eta, eta_dot, modal_f = rng.normal(size=m) * 0.1, rng.normal(size=m), rng.normal(size=m) * 10
            v_b, omega, f_b, n_b, g_b = rng.normal(size=(5, 3)) * [[1.0], [30.0], [10.0], [0.1], [9.81]]
            omega2, damp = rng.uniform(1e4, 1e8, m), rng.uniform(0, 1e3, m)
            for elastic, frozen in ((True, True), (False, True), (True, False)):
                got = np.full(6 + m, np.nan)
                S, J, G, _ = _eta_terms(inv, eta)
                MS.constrained_rhs(inv[0], inv[2], inv[4], S, J, G, eta, eta_dot, v_b, omega, f_b, n_b, g_b, modal_f,
                                   omega2, damp, elastic, True, np.full(6 + m, np.nan), got, frozen)
                want = twin.constrained_rhs(inv, eta, eta_dot, v_b, omega, f_b, n_b, g_b, modal_f, omega2, damp,
                                            elastic, frozen)
                for blk in (slice(0, 3), slice(3, 6), slice(6, None)):
                    _close_block(got[blk], want[blk])


# -- one kick and one drift against the twin -------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(SCENARIOS))
def test_modal_kick_matches_twin(name):
    """Both halves of the kick (``correct`` False: first; True: predicted and corrected), every frame form;
    rigid bodies and held components untouched."""
    model, state = _modal_model(name)
    a = model.arrays
    rng = np.random.default_rng(SEED + 20)
    worst = 0.0
    for _ in range(6):
        q, v, eta, eta_dot = _random_state(model, state, rng)
        w = _loaded_work(model, rng)
        kicked = []
        for correct in (False, True):
            v_k, ed_k = v.copy(), eta_dot.copy()
            assert MS.modal_kick(a, q, v_k, eta, ed_k, w, 0.5 * H, correct)
            v_t, ed_t = twin.kick(a, q, v, eta, eta_dot, w.body_f, w.body_t, w.modal_f, 0.5 * H, correct)
            worst = max(worst, _close_bodies(model, v_k, v_t, ed_k, ed_t))
            assert np.array_equal(v_k[0], v[0])
            for j, i in enumerate(a.modal_body):
                held = a.modal_frame_free[j] == 0
                assert np.array_equal(v_k[i, held], v[i, held])
            kicked.append(ed_k)
        # the correction is not a no-op: the velocity terms and the damping see the predicted rates
        assert np.any(kicked[0] != kicked[1])
    print(f"{name}: worst |kernel − twin| / tolerance {worst:.2g}")


@pytest.mark.parametrize("name", sorted(SCENARIOS))
def test_modal_drift_matches_twin(name):
    """Frame pose, η, and (momentum form, implicit modes) ω and η̇ after one drift."""
    model, state = _modal_model(name)
    a = model.arrays
    rng = np.random.default_rng(SEED + 30)
    w = make_work(model)
    worst = 0.0
    for _ in range(6):
        q, v, eta, eta_dot = _random_state(model, state, rng)
        q_k, v_k, e_k, ed_k = q.copy(), v.copy(), eta.copy(), eta_dot.copy()
        assert MS.modal_drift(a, q_k, v_k, e_k, ed_k, w, H)
        q_t, v_t, e_t, ed_t = twin.drift(a, q, v, eta, eta_dot, H)
        worst = max(worst, _close(q_k[:, :3], q_t[:, :3], atol=RTOL * np.abs(q_t[:, :3]).max()))
        _close(q_k[:, 3:], q_t[:, 3:], atol=4 * EPS)
        worst = max(worst, _close_bodies(model, v_k, v_t, ed_k, ed_t), _close_bodies(model, v_k, v_t, e_k, e_t))
        assert np.array_equal(q_k[0], q[0]) and np.array_equal(v_k[0], v[0])      # rigid: not the modal drift's
        for j, i in enumerate(a.modal_body):
            if not a.modal_frame_free[j].all():                 # the frame velocity and η̇ are constant over a drift
                s = slice(a.modal_off[j], a.modal_off[j + 1])
                assert np.array_equal(v_k[i], v[i]) and np.array_equal(ed_k[s], eta_dot[s])
    print(f"{name}: worst |kernel − twin| / tolerance {worst:.2g}")


def test_modal_energy_matches_twin():
    model, state = _modal_model("mixed")
    a = model.arrays
    rng = np.random.default_rng(SEED + 40)
    w = make_work(model)
    for _ in range(5):
        q, v, eta, eta_dot = _random_state(model, state, rng)
        kin, pot = MS.modal_energy(a, q, v, eta, eta_dot, w)
        want = twin.energy(a, q, v, eta, eta_dot)
        assert kin == pytest.approx(want[0], rel=RTOL) and pot == pytest.approx(want[1], rel=RTOL)


# -- what the schemes must conserve ------------------------------------------------------------------------
def test_free_drift_conserves_world_angular_momentum_to_round_off():
    """Momentum form: R π about the centre of mass (and m ṙ) are unchanged by any drift, even with hω ≈ 1
    (module docstring of the kernel); the twin's M(η) gives π."""
    model, state = _modal_model("free")
    a = model.arrays
    rng = np.random.default_rng(SEED + 50)
    w = make_work(model)
    inv = twin.invariants(a, 0)
    for h in (H, 0.01):
        q, v, eta, eta_dot = _random_state(model, state, rng)
        eta_dot *= 1e-2                                         # keeps η moderate over 20 large drifts
        turn = h * np.linalg.norm(v[1, 3:])                     # rad per drift: 6e-3 and ~0.5

        def world_momentum(q, v, eta, eta_dot):
            p = ref_modal.mass_matrix(*inv, eta)[3:6, 3:] @ np.concatenate([v[1, 3:], eta_dot])
            return ref.matrix(q[1, 3:]) @ p

        L0 = world_momentum(q, v, eta, eta_dot)
        for _ in range(20):
            assert MS.modal_drift(a, q, v, eta, eta_dot, w, h)
        assert np.abs(world_momentum(q, v, eta, eta_dot) - L0).max() < 1e-13 * np.linalg.norm(L0)
        assert turn > 0.3 or h == H


def _unloaded_step(a, q, v, eta, eta_dot, w, h):
    """One kick–drift–kick of the modal bodies alone with no contact force (w's loads zero)."""
    w.modal_f[:] = 0.0
    w.body_f[:] = 0.0
    w.body_t[:] = 0.0
    assert MS.modal_kick(a, q, v, eta, eta_dot, w, 0.5 * h, False)
    assert MS.modal_drift(a, q, v, eta, eta_dot, w, h)
    assert MS.modal_kick(a, q, v, eta, eta_dot, w, 0.5 * h, True)


def test_implicit_modes_have_the_trapezoidal_eigenvalues_and_damp_unresolved_ones():
    """Undamped modes of a fixed frame at rest, no gravity: the step map of each resolved mode (hω ≤ 2,
    hω = 2 exactly included) has the trapezoidal rule's eigenvalues λ = (1 + ia)/(1 − ia), a = hω/2 (unit
    modulus: no numerical damping; Hughes, The Finite Element Method, 2000, §9.3), to round-off; an
    unresolved mode (hω = 15) is damped critically: |λ| < 1, within 0.1 above the critically damped
    trapezoidal rule's (hω − 2)/(hω + 2) = 0.765 (measured 0.81; the augmented matrix holds (h/2)c as well,
    which makes the damping's kick stable for any coupling but damps a little less)."""
    model, state = _modal_model("fixed_implicit")
    a = model.arrays._replace(modal_damp=np.zeros(model.n_modal), gravity=np.zeros(3))
    hw = H * np.sqrt(a.modal_omega2)
    assert hw[1] == 2.0 and hw[0] < 2.0 < hw[2]
    rng = np.random.default_rng(SEED + 60)
    w = make_work(model)
    q, v, _, _ = _random_state(model, state, rng)
    v[:] = 0.0
    for k in range(3):
        columns = []
        for y0 in ((1.0, 0.0), (0.0, 1.0)):
            e, ed = np.zeros(model.n_modal), np.zeros(model.n_modal)
            e[k], ed[k] = y0
            _unloaded_step(a, q.copy(), v.copy(), e, ed, w, H)
            assert np.all(np.delete(e, k) == 0.0) and np.all(np.delete(ed, k) == 0.0)  # the modes stay apart
            columns.append((e[k], ed[k]))
        lam = np.linalg.eigvals(np.array(columns).T)
        if hw[k] <= 2.0:
            trap = (1 + 0.5j * hw[k]) / (1 - 0.5j * hw[k])
            np.testing.assert_allclose(np.sort_complex(lam), np.sort_complex([trap, np.conj(trap)]), atol=1e-7)
        else:
            crit = (hw[k] - 2.0) / (hw[k] + 2.0)
            assert crit <= np.abs(lam).max() < min(crit + 0.1, 1.0)
            print(f"hω = {hw[k]:.3g}: |λ| = {np.abs(lam).max():.4f}, critically damped trapezoidal rule {crit:.4f}")


@pytest.mark.parametrize("name", ["fixed_implicit", "fixed_implicit_I6", "driven_translation_tilt_implicit",
                                  "driven_translation_tilt_implicit_I6"])
def test_implicit_modes_keep_the_static_response_under_a_constant_force(name):
    """Kick–drift–kick with a constant modal force Q from η = Q/ω², η̇ = 0, the frame at rest: resolved and
    unresolved modes stay at their static response to round-off over 50 steps and the frame does not
    move, with unit modal mass and without it, held or free to translate and tilt (the frame coupled
    with the modes through M)."""
    model, state = _modal_model(name)
    a = model.arrays._replace(gravity=np.zeros(3))  # (the scenario's weight would add I3ᵀRᵀg to Q)
    rng = np.random.default_rng(SEED + 61)
    w = make_work(model)
    q, v, _, _ = _random_state(model, state, rng)
    v[:] = 0.0
    Q = rng.standard_normal(model.n_modal)
    eta, eta_dot = Q / a.modal_omega2, np.zeros(model.n_modal)
    w.modal_f[:] = Q
    w.body_f[:] = 0.0
    w.body_t[:] = 0.0
    for _ in range(50):
        assert MS.modal_kick(a, q, v, eta, eta_dot, w, 0.5 * H, False)
        assert MS.modal_drift(a, q, v, eta, eta_dot, w, H)
        assert MS.modal_kick(a, q, v, eta, eta_dot, w, 0.5 * H, True)
    np.testing.assert_allclose(eta, Q / a.modal_omega2, rtol=1e-12)
    assert np.abs(eta_dot).max() < 1e-12 * np.abs(Q / np.sqrt(a.modal_omega2)).max()
    assert np.abs(v).max() < 1e-12 * np.abs(Q / np.sqrt(a.modal_omega2)).max()


@pytest.mark.parametrize("name", ["driven_translation_implicit", "driven_translation_implicit_I6"])
def test_implicit_modes_leave_the_frames_momentum_alone(name):
    """A frame free to translate (no spin), implicit modes, no gravity and no forces: the elastic and
    damping forces are internal to the body, so its linear momentum m ṙ + R I3 η̇ (world) stays constant
    to round-off over 50 steps at a step that leaves two modes unresolved, while the frame and the modes
    do move."""
    model, state = _modal_model(name)
    a = model.arrays._replace(gravity=np.zeros(3))
    assert np.sum(H * np.sqrt(a.modal_omega2) > 2.0) == 2
    rng = np.random.default_rng(SEED + 62)
    w = make_work(model)
    q, v, eta, eta_dot = _random_state(model, state, rng)
    i = a.modal_body[0]
    v[i, 3:] = 0.0
    I3 = a.modal_I3[0][:, :model.n_modal]

    def momentum():
        return a.modal_mass[0] * v[i, :3] + ref.matrix(q[i, 3:]) @ (I3 @ eta_dot)

    p0, v0 = momentum(), v[i, :3].copy()
    for _ in range(50):
        _unloaded_step(a, q, v, eta, eta_dot, w, H)
        np.testing.assert_allclose(momentum(), p0, rtol=0, atol=1e-13 * a.modal_mass[0] * np.abs(v0).max())
    assert np.abs(v[i, :3] - v0).max() > 1e-3 * np.abs(v0).max()


# -- the flexible ball–groove contact ------------------------------------------------------------------------
# Binary-exact geometry: groove centre circle 62.5 mm, ball radius 2^-8 m, groove radius 2^-8 + 2^-12 m
# (conformity 0.531), so that a ball can touch with δ = 0 exactly.
R_C, Z_C = 2.0**-4, 0.0
R_BALL, F_D = 2.0**-8, 2.0**-8 + 2.0**-12
CLEAR = F_D - R_BALL                            # 2^-12 m, exact
ALPHA = math.radians(40.0)
N_SAMPLES = 24
DELTA_0 = 2e-5                                   # nominal penetration, m
FLEX_FREQS = [2e3, 2e4, 8e4]                     # Hz


def _towards_ball(th, alpha=ALPHA):
    """Unit vector from the groove's curvature centre at angle θ to the ball centre (ring frame)."""
    return np.array([-math.cos(alpha) * math.cos(th), -math.cos(alpha) * math.sin(th), -math.sin(alpha)])


def _groove_sample(rng, m, periodic=True):
    """Random D (m/√kg) and Ω (20 rad/√kg per unit) at 24 points of the groove bottom: on the full circle
    from θ = 0, or (periodic False) on the arc 0.5…2.5 rad."""
    th = 2 * np.pi * np.arange(N_SAMPLES) / N_SAMPLES if periodic else np.linspace(0.5, 2.5, N_SAMPLES)
    points = np.array([[R_C * math.cos(t), R_C * math.sin(t), Z_C] + F_D * _towards_ball(t) for t in th])
    return RacewaySample("groove", th, points, rng.normal(size=(N_SAMPLES, 3, m)),
                         20.0 * rng.normal(size=(N_SAMPLES, 3, m)), periodic)


def _ball_at(th, delta, alpha=ALPHA):
    return np.array([R_C * math.cos(th), R_C * math.sin(th), Z_C]) + (CLEAR + delta) * _towards_ball(th, alpha)


#: ball angles on the flexible groove: θ = 0 (a sample), just below 2π and just above 0 (the wrap),
#: sample 5 (2π·5/24 in floating point), and inside intervals; the last ball is 10 µm apart
FLEX_ANGLES = [0.0, 2 * np.pi - 1e-12, 1e-12, 2 * np.pi * 5 / N_SAMPLES, 1.0, 2.5, 4.0, 5.5]
FLEX_DELTAS = [DELTA_0] * 7 + [-1e-5]


def _flexible_model(undulated=False, arc=False, law=None, outer=True, gravity=(0.0, 0.0, 0.0), motion=None,
                    implicit=False, freqs=FLEX_FREQS, angles=FLEX_ANGLES, deltas=FLEX_DELTAS):
    """A modal inner ring (driven at 80 rad/s unless ``motion``) with a flexible groove, balls on it and
    (``outer``) in a rigid groove of a fixed outer ring, 15 µm in; ``arc`` adds balls on a second flexible
    groove sampled on an arc only (one at 1.5 rad inside, one at 3.0 rad beyond it)."""
    rng = np.random.default_rng(SEED + 100)
    law = law or ContactLaw(1e10, 1.5, 300.0, 1e-6, "impact", Coulomb(0.1, 0.08, 1e-3, 2e-3))
    mb = ModelBuilder(gravity_m_s2=gravity)
    ring = mb.add_modal_body("inner", _cloud_body(rng, freqs), motion=motion or Driven(80.0), implicit_modes=implicit)
    tables = dict(undulation_m=rng.uniform(-1e-5, 1e-5, 17), radial_offset_m=rng.uniform(-1e-5, 1e-5, 7)) \
        if undulated else {}
    groove = mb.add_groove(ring, R_C, Z_C, F_D, raceway=_groove_sample(rng, len(freqs)), **tables)
    if outer:
        mb.add_body("outer", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
        lam = 2 * CLEAR + DELTA_0 + 1.5e-5
        outer_groove = mb.add_groove("outer", R_C - lam * math.cos(ALPHA), Z_C - lam * math.sin(ALPHA), F_D)
    places = list(zip(angles, deltas))
    if arc:
        arc_groove = mb.add_groove(ring, R_C, Z_C, F_D, raceway=_groove_sample(rng, len(freqs), periodic=False))
        places += [(1.5, DELTA_0), (3.0, DELTA_0)]
    for k, (th, delta) in enumerate(places):
        ball = mb.add_body(f"ball{k}", 2e-3, (1.2e-8,) * 3, position_m=_ball_at(th, delta))
        mb.add_ball_groove(ball, ring, arc_groove if arc and k >= len(angles) else groove, R_BALL, law)
        if outer:
            mb.add_ball_groove(ball, "outer", outer_groove, R_BALL, law)
    return mb.finalize()


def _scene_state(model, state, rng, slow, eta_scale=3e-6, jitter=3e-6):
    """The built scene with the balls moved by ~``jitter`` and given random velocities (fast: slip of m/s; slow:
    in the friction law's transition range), then the whole scene turned and moved to a random pose;
    η with |u| ~ 5 µm and |ψ| ~ 1e-4 rad, η̇ with modal surface velocities ~ 5 mm/s."""
    q, v = state.q.copy(), state.v.copy()
    balls = [i for i, n in enumerate(model.body_names) if n.startswith("ball")]
    q[balls, :3] += rng.normal(size=(len(balls), 3)) * jitter
    scale = [1e-3] * 3 + [0.1] * 3 if slow else [0.1] * 3 + [100.0] * 3
    v[balls] = rng.normal(size=(len(balls), 6)) * scale
    turn, shift = Rotation.random(random_state=rng), rng.normal(size=3) * 0.1
    q[:, :3] = turn.apply(q[:, :3]) + shift
    q[:, 3:] = (turn * Rotation.from_quat(q[:, 3:], scalar_first=True)).as_quat(scalar_first=True)
    v[:, :3] = turn.apply(v[:, :3])
    n = model.n_modal
    return type(state)(state.t, q, v, rng.normal(size=n) * eta_scale, rng.normal(size=n) * 3e-3)


def _kernel_step(m, g, eta_ring, x, th):
    """One Gauss–Newton step of the kernel from θ: θ + (x − c')·t/|t|² with its c'(θ) and tangent t."""
    s0, s1 = m.groove_samp_off[g], m.groove_samp_off[g + 1]
    theta, periodic = m.samp_theta[s0:s1], bool(m.groove_periodic[g] == 1)
    thw = th % (2 * np.pi)  # evaluated at the wrapped angle, stepped from the given one
    i0, i1, w0, w1 = interp_index(theta, thw, periodic)
    rows = np.zeros((4, 3))
    FS._groove_rows(m.samp_disp[s0:s1], m.samp_rot[s0:s1], i0, i1, np.ascontiguousarray(eta_ring), rows)
    cx, cy, cz, tx, ty, tz = FS._deformed_groove_centre(
        theta, periodic, m.samp_point[s0:s1], rows, m.groove_rc[g], m.groove_zc[g], m.groove_h, m.groove_h_off[g],
        m.groove_h_off[g + 1], m.groove_dr, m.groove_dr_off[g], m.groove_dr_off[g + 1], thw, np.cos(thw), np.sin(thw),
        i0, i1, w0, w1)
    return th + ((x[0] - cx) * tx + (x[1] - cy) * ty + (x[2] - cz) * tz) / (tx * tx + ty * ty + tz * tz)


def kernel_groove_angle(m, g, eta_ring, x, th_ball):
    """The kernel's contact angle: two Gauss–Newton steps from the ball angle (flexible_surface._nearest_deformed_centre)."""
    return _kernel_step(m, g, eta_ring, x, _kernel_step(m, g, eta_ring, x, th_ball))


def _forces(model, st):
    w = make_work(model)
    status = FK.compute_forces(model.arrays, st.t, st.q, st.v, st.eta, st.eta_dot, w)
    assert status == (FK.STATUS_OK, -1)
    return w


def _compare_forces(model, st):
    """compute_forces against the twin at the kernel's groove angle (module docstring for tolerances).

    The penetrations agree to ATOL_M (coordinates of ~0.2 m); each force then to n K δⁿ⁻¹ ATOL_M, which
    is part of the floor of every sum it enters (body forces, moments with levers < 0.2 m, modal forces
    with |D| + |Ω| F_D per unit force); the energy to Σ F_n ATOL_M."""
    m = model.arrays
    w = _forces(model, st)
    want = ref.compute_forces(m, st.t, st.q, st.v, st.eta, st.eta_dot, kernel_groove_angle)
    fn_floor = m.pair_n * m.pair_k * np.maximum(want.delta, 0.0) ** (m.pair_n - 1.0) * ATOL_M
    per_body = np.zeros(model.n_bodies)
    np.add.at(per_body, m.pair_a, fn_floor)
    np.add.at(per_body, m.pair_b, fn_floor)
    _close(w.body_f, want.body_f, atol=(RTOL * want.body_f_scale + per_body)[:, None])
    _close(w.body_t, want.body_t, atol=(RTOL * want.body_t_scale + 0.2 * per_body)[:, None])
    _close(w.contact_delta, want.delta, atol=ATOL_M)
    _close(w.contact_fn, want.fn, atol=fn_floor)
    _close(w.contact_ft, want.ft, atol=m.pair_fric_p[:, 0] * fn_floor)
    _close_block(w.contact_slip, want.slip)
    _close(w.contact_angle, want.angle, atol=1e-14)
    _close(w.contact_theta, want.theta, atol=1e-14)
    # contact point and normal (a pair of several points: those of its most loaded one)
    _close(w.contact_point, want.point, atol=POINT_ATOL_M)
    _close(w.contact_normal, want.normal, atol=NORMAL_ATOL)
    _close(w.energy, [want.energy_contact, want.energy_bushing], atol=ATOL_M * want.fn.sum())
    per_unit = np.abs(m.samp_disp).max(initial=0.0) + F_D * np.abs(m.samp_rot).max(initial=0.0)
    _close(w.modal_f, want.modal_f, atol=RTOL * np.abs(want.modal_f).max(initial=0.0) + per_unit * fn_floor.sum())
    return w, want


def _assert_balanced(w, q):
    """Newton's third law for the rigid parts: Σ F_i = 0 and Σ (r_i × F_i + M_i) = 0 over all bodies."""
    scale = np.sum(w.contact_fn + w.contact_ft)
    assert np.abs(w.body_f.sum(axis=0)).max() < 1e-13 * scale
    assert np.abs(np.sum(np.cross(q[:, :3], w.body_f) + w.body_t, axis=0)).max() < 1e-13 * scale * 0.2


STRIP_LAW = ContactLaw(1e10, 1.5, 300.0, 1e-6, "impact", Coulomb(0.1, 0.08, 1e-3, 2e-3),
                       strips=StripTraction(7, 2e-5, 4e-3))


@pytest.mark.parametrize("undulated,law", [(False, None), (True, None), (True, STRIP_LAW)],
                         ids=["plain", "undulated", "strips"])
def test_flexible_groove_forces_match_twin_at_the_kernel_angle(undulated, law):
    """Everything after the nearest-point search — penetration, normal, the raceway's modal velocity in
    the slip, damping and friction, body forces and moments, modal forces Dᵀg + Ωᵀ((p − p_s) × g) —
    against the twin; full-circle and arc samples, balls at the wrap and on a sample. Newton's third
    law for the rigid parts: the forces on balls and rings sum to zero, and so do their moments about
    the world origin (what the ring's frame gets balances the ball; the modal forces come on top).
    ``strips``: traction over the contact ellipse in 7 strips, the slip and the spin taken against the
    section's own velocity and angular velocity, its moment in the modal force Ωᵀ(b × g + t)."""
    model, state = _flexible_model(undulated=undulated, arc=True, law=law)
    rng = np.random.default_rng(SEED + 110)
    ws = []
    for k in range(8):
        st = _scene_state(model, state, rng, slow=k % 2 == 1, jitter=3e-6 if k else 0.0)
        w, _ = _compare_forces(model, st)
        _assert_balanced(w, st.q)
        ws.append(w)
    delta = np.array([w.contact_delta for w in ws])
    slip = np.array([w.contact_slip for w in ws])[delta > 0]
    assert np.any(delta > 0) and np.any(delta <= 0)
    assert np.any(slip > 2e-3) and np.any((slip > 0) & (slip < 1e-3))
    theta = np.array([w.contact_theta for w in ws])
    assert np.all((theta >= 0.0) & (theta < 2 * np.pi))
    assert np.any(theta > 2 * np.pi - 1e-11) and np.any(theta < 1e-11)     # the corners of the unjittered state
    assert np.all(np.array([w.modal_f for w in ws]) != 0.0)


BEYOND_ARC = "ball9–inner"             # the ball at 3.0 rad, beyond the arc 0.5…2.5 rad of the second groove


@pytest.mark.parametrize("where", ["sampled", "beyond_arc"])
def test_flexible_groove_kernel_angle_is_the_nearest_point_up_to_its_tangent(where):
    """The kernel's θ_k against the exact nearest point θ* of the twin (module docstring): θ_k is θ* plus
    one Gauss–Newton step of the kernel's own tangent from θ*, to 1e-3 of the start offset; that step,
    the left-out lever term, is at most d |ψ| |∂(c − p_s)/∂θ| / |t|² with |∂(c − p_s)/∂θ| ≤ 2 F_D
    (F_D cos α plus table slopes ≤ 1e-4 m/rad) on the sampled range and ≤ r + 2 F_D beyond the ends
    of an arc (the deformation, and p_s, held there: zero deformation slope); its δ exceeds the least
    distance by |t|²Δθ²/d at most."""
    model, state = _flexible_model(undulated=True, arc=True, outer=False)
    m = model.arrays
    pairs = [c for c, name in enumerate(model.pair_names) if (name == BEYOND_ARC) == (where == "beyond_arc")]
    rng = np.random.default_rng(SEED + 120)
    worst_theta, worst_force, worst_rest = 0.0, 0.0, 0.0
    for k in range(4):
        st = _scene_state(model, state, rng, slow=False)
        w = _forces(model, st)
        exact = ref.compute_forces(m, st.t, st.q, st.v, st.eta, st.eta_dot)
        bodies = ref._Bodies(st.q, st.v)
        for c in pairs:
            g, a = m.pair_geom[c], m.pair_a[c]
            x = bodies.to_local(m.pair_b[c], bodies.r[a])
            th_ball = w.contact_theta[c]
            eta_ring = st.eta[flex.raceway_tables(m, g)[-1]]
            th_star = ref.nearest_groove_angle(m, g, eta_ring, x, th_ball)
            th_k = kernel_groove_angle(m, g, eta_ring, x, th_ball)
            predicted = _kernel_step(m, g, eta_ring, x, th_star)
            assert abs(th_k - predicted) <= 1e-3 * abs(th_ball - th_star) + 1e-15
            worst_rest = max(worst_rest, abs(th_k - predicted) / abs(th_ball - th_star))
            centre, tangent, (_, W, _) = flex.deformed_groove_centre(m, g, eta_ring, th_star)
            dist = np.linalg.norm(x - centre)
            # beyond the arc the sampled point p_s is held at the arc's end, so the lever c − p_s turns
            # with the groove: |∂(c − p_s)/∂θ| ≈ r there, not 2 F_D
            lever_slope = 2 * F_D if where == "sampled" else np.linalg.norm(tangent) + 2 * F_D
            left_out = dist * np.linalg.norm(W @ eta_ring) * lever_slope / (tangent @ tangent)
            assert abs(th_k - th_star) <= left_out + 1e-3 * abs(th_ball - th_star)
            excess = w.contact_delta[c] - exact.delta[c]
            assert -ATOL_M <= excess <= tangent @ tangent * (th_k - th_star) ** 2 / dist + ATOL_M
            worst_theta = max(worst_theta, abs(th_k - th_star))
            if exact.fn[c] > 0:
                worst_force = max(worst_force, np.abs(w.body_f[a] - exact.body_f[a]).max() / exact.fn[c])
    print(f"{where}: max |θ_k − θ*| {worst_theta:.2g} rad, |θ_k − θ_pred| / |θ_ball − θ*| ≤ {worst_rest:.2g}; "
          f"ball forces differ by {worst_force:.2g} of F_n")


def test_flexible_groove_corners_zero_penetration_and_a_ball_on_a_sample():
    """η = 0, ring at the origin: a ball at θ = 0 touching with δ = 0 exactly (no force, no modal force)
    and one 2^-16 m in (the groove point stays at θ = 0, weights 1 and 0 on sample 0, so its modal force
    is D_0ᵀg + Ω_0ᵀ((p − p_s,0) × g) of the twin); the modal rates still move the surface."""
    model, state = _flexible_model(outer=False, angles=[0.0, 0.0], deltas=[0.0, 2.0**-16])
    m = model.arrays
    st = state.copy()
    st.q[1, :3] = _ball_at(0.0, 0.0, alpha=0.0)
    st.q[2, :3] = _ball_at(0.0, 2.0**-16, alpha=0.0)
    rng = np.random.default_rng(SEED + 130)
    st.v[1:] = rng.normal(size=(2, 6)) * [0.1, 0.1, 0.1, 100, 100, 100]
    st.eta_dot = rng.normal(size=model.n_modal) * 3e-3
    assert np.all(st.eta == 0.0) and np.array_equal(st.q[0], [0, 0, 0, 1, 0, 0, 0])
    w, want = _compare_forces(model, st)
    assert w.contact_delta[0] == 0.0 and w.contact_fn[0] == 0.0 and w.contact_ft[0] == 0.0
    assert w.contact_delta[1] == 2.0**-16 and w.contact_fn[1] > 0.0
    assert not w.body_f[1].any() and not w.body_t[1].any()
    assert kernel_groove_angle(m, 0, st.eta, st.q[2, :3], 0.0) == 0.0
    # on sample 0 alone: the modal force of the force on the ring at the contact point p = x − R_BALL e_x
    D, W, P = m.samp_disp[0], m.samp_rot[0], m.samp_point[0]
    on_ring = -w.body_f[2]
    lever = st.q[2, :3] - [R_BALL, 0.0, 0.0] - P
    _close_block(w.modal_f, D.T @ on_ring + W.T @ np.cross(lever, on_ring))
    # and its slip includes the surface's modal velocity D_0 η̇ + (Ω_0 η̇) × lever
    st_rest = st.copy()
    st_rest.eta_dot[:] = 0.0
    assert _forces(model, st_rest).contact_slip[1] != w.contact_slip[1]


def test_flexible_contact_force_and_modal_force_are_minus_the_gradient_of_its_energy():
    """Work consistency, frictionless and undamped, at rest: −∂E/∂η = Q and −∂E/∂x_ball = F_ball by central
    differences (steps 1e-10 √kg and 1e-10 m: truncation (Δδ/δ)² ~ 1e-11, penetration round-off
    1e-17 m / 1e-10 m = 1e-7). Q uses the lever p − p_s of the contact point, the energy the lever
    c − p_s of c' = c + u + ψ × (c − p_s); they differ by c' − c = u + ψ × (c − p_s) across a force along
    n, a second-order term of relative size (|u| + |ψ| F_D)/F_D (≤ 5e-4 here, η ~ 3e-7 √kg; 2e-5
    measured); the nearest-point approximation adds |ψ| F_D / r ≈ 1e-6."""
    model, state = _flexible_model(outer=False, law=ContactLaw(1e10, 1.5), motion=Fixed(),
                                   angles=[0.6, 2.0, 3.3, 4.6], deltas=[DELTA_0] * 4)   # balls inside intervals
    m = model.arrays
    rng = np.random.default_rng(SEED + 140)
    base = state.copy()
    base.eta = rng.normal(size=model.n_modal) * 3e-7
    w = _forces(model, base)
    assert np.all(w.contact_fn > 0)

    def energy(d_eta=0.0, ball=None, dx=None):
        st = base.copy()
        st.eta = st.eta + d_eta
        if ball is not None:
            st.q[ball, :3] += dx
        return _forces(model, st).energy[0]

    e = 1e-10
    grad_eta = np.array([(energy(e * u) - energy(-e * u)) / (2 * e) for u in np.eye(model.n_modal)])
    tables = [flex.deformed_groove_centre(m, 0, base.eta, th)[2] for th in w.contact_theta]
    second_order = max(np.linalg.norm(D @ base.eta) + np.linalg.norm(W @ base.eta) * F_D for D, W, _ in tables) / F_D
    _close(w.modal_f, -grad_eta, rtol=0.0, atol=(second_order + 1e-6) * np.abs(w.modal_f).max())
    print(f"|Q + ∂E/∂η| / max|Q| = {np.abs(w.modal_f + grad_eta).max() / np.abs(w.modal_f).max():.2g} "
          f"(second-order bound {second_order:.2g})")
    for ball in range(1, model.n_bodies):
        grad_x = np.array([(energy(ball=ball, dx=e * u) - energy(ball=ball, dx=-e * u)) / (2 * e) for u in np.eye(3)])
        _close(w.body_f[ball], -grad_x, rtol=0.0, atol=1e-5 * np.linalg.norm(w.body_f[ball]))


# -- whole explicit steps with modal bodies -------------------------------------------------------------------
N_STEPS, H_RUN = 10, 1e-6          # s; contacts: hω ≈ 0.2; modes up to 80 kHz: hω ≤ 0.5 (1 MHz: 6.3, implicit)
RUN_RTOL = 1e-11


@pytest.mark.parametrize("frame", ["driven_translation_tilt", "driven_implicit", "translation_tilt_implicit", "strips"])
def test_explicit_run_with_a_modal_ring_matches_twin(frame):
    """run_explicit against the twin's modal_step (rigid kick and drift, modal kick and drift, forces, rigid
    kick, corrected modal kick), 10 steps of 8 balls between the flexible groove of a modal inner ring
    (driven at 80 rad/s, translating and tilting with explicit modes, or held with implicit modes and a
    1 MHz mode) and a fixed rigid outer ring, with gravity; nearest point as the kernel's. Tolerance
    1e-11 of each block (ten steps of the 1e-12 ones, whose round-off the contact dynamics pass on).
    ``translation_tilt_implicit``: the translating and tilting frame with implicit modes and the 1 MHz mode
    (the kicks then solve frame and modes together with the augmented mass). ``strips``: the translating and tilting frame
    with strip traction on every ball contact."""
    rtol = RUN_RTOL
    free = frame in ("driven_translation_tilt", "translation_tilt_implicit", "strips")
    motion = Driven(80.0, translation_free=True, tilt_free=True) if free else Driven(80.0)
    implicit = frame in ("driven_implicit", "translation_tilt_implicit")
    model, state = _flexible_model(gravity=(0.0, -9.81, -3.0), motion=motion, implicit=implicit,
                                   freqs=FLEX_FREQS + [1e6] if implicit else FLEX_FREQS,
                                   law=STRIP_LAW if frame == "strips" else None)
    m = model.arrays
    rng = np.random.default_rng(SEED + 150)
    st = _scene_state(model, state, rng, slow=False, eta_scale=1e-8)
    st.eta_dot *= 0.1
    q, v, eta, eta_dot = st.q.copy(), st.v.copy(), st.eta.copy(), st.eta_dot.copy()
    work = make_work(model)
    assert FK.compute_forces(m, st.t, q, v, eta, eta_dot, work) == (FK.STATUS_OK, -1)
    rec = make_record_buffers(model, N_STEPS)
    out = EX.run_explicit(m, q, v, eta, eta_dot, work, st.t, 0, N_STEPS, H_RUN, 1, rec, math.inf)
    assert out == (FK.STATUS_OK, -1, N_STEPS, N_STEPS)
    tq, tv, te, ted = st.q, st.v, st.eta, st.eta_dot
    forces = ref.compute_forces(m, st.t, tq, tv, te, ted, kernel_groove_angle)
    inertia = np.where(m.body_modal[:, None] >= 0, m.modal_I7[np.maximum(m.body_modal, 0)].diagonal(axis1=1, axis2=2),
                       m.body_inertia).min(axis=1)
    v_floor, w_floor, v_max, q_floor, worst = 0.0, 0.0, 0.0, 0.0, {}
    for k in range(N_STEPS):
        tq, tv, te, ted, forces = twin_step.modal_step(m, tq, tv, te, ted, forces, st.t + (k + 1) * H_RUN, H_RUN,
                                                       kernel_groove_angle)
        v_floor = v_floor + H_RUN * forces.body_f_scale / m.body_mass
        w_floor = w_floor + H_RUN * forces.body_t_scale / inertia
        v_max = np.maximum(v_max, np.linalg.norm(tv[:, :3], axis=1))
        q_floor = q_floor + H_RUN * (v_max + v_floor) + EPS / rtol * np.abs(st.q[:, :3]).max(axis=1)  # + ulp of r
        checks = {
            "v": (rec.v[k][:, :3], tv[:, :3], (np.linalg.norm(tv[:, :3], axis=1) + v_floor)[:, None]),
            "ω": (rec.v[k][:, 3:], tv[:, 3:], (np.linalg.norm(tv[:, 3:], axis=1) + w_floor)[:, None]),
            "r": (rec.q[k][:, :3] - st.q[:, :3], tq[:, :3] - st.q[:, :3], q_floor[:, None]),
            "η": (rec.eta[k], te, np.abs(te).max()),
            "η̇": (rec.eta_dot[k], ted, np.abs(ted).max()),
            "F_n": (rec.fn[k], forces.fn, forces.fn.max()),
        }
        for name, (got, want, scale) in checks.items():
            worst[name] = max(worst.get(name, 0.0), _close(got, want, atol=rtol * scale, rtol=rtol))
        _close(rec.q[k][:, 3:], tq[:, 3:], atol=(k + 1) * 4 * EPS)
    _close(work.modal_f, forces.modal_f, atol=rtol * np.abs(forces.modal_f).max())
    assert np.array_equal(q, rec.q[-1]) and np.array_equal(eta, rec.eta[-1])
    # the run is not trivial: loaded contacts, the ring's modes and frame move
    ring = model.body("inner")
    inner_pairs = forces.fn[::2][:-1]                               # the last ball is apart
    assert np.all(inner_pairs > 0) and np.all(te != st.eta) and np.all(tq[ring, 3:] != st.q[ring, 3:])
    print(frame, "worst |kernel − twin| / tolerance:", {k: f"{x:.2g}" for k, x in worst.items()})


def test_unbalance_forces_match_twin_on_rigid_and_modal_bodies():
    """The unbalance stage (mbd_core.kernels.unbalance) against the twin's: body forces, moments about the
    centres and modal forces, at a random pose, spin and deformation."""
    rng = np.random.default_rng(SEED + 7)
    mb = ModelBuilder()
    ring = mb.add_modal_body("ring", _cloud_body(rng, [200.0, 3000.0, 7000.0]),
                             motion=Driven(80.0, translation_free=True, tilt_free=True))
    disc = mb.add_body("disc", 0.5, (1e-3, 1e-3, 2e-3), omega_rad_s=(3.0, -2.0, 500.0))
    mb.add_unbalance(ring, (0.03, 0.01, 0.02), 2e-4, angle_rad=0.4, mode_shapes=rng.normal(size=(3, 3)) * 1e-2)
    mb.add_unbalance(disc, (0.0, 0.0, 0.05), 1e-4, angle_rad=-1.0)
    model, state = mb.finalize()
    q, v, eta, eta_dot = _random_state(model, state, rng)
    w = make_work(model)
    assert FK.compute_forces(model.arrays, 0.0, q, v, eta, eta_dot, w) == (FK.STATUS_OK, -1)
    want = ref.compute_forces(model.arrays, 0.0, q, v, eta, eta_dot)
    _close(w.body_f, want.body_f, atol=1e-14 * want.body_f_scale[:, None])
    _close(w.body_t, want.body_t, atol=1e-14 * want.body_t_scale[:, None])
    _close(w.modal_f, want.modal_f, atol=1e-14 * np.abs(want.modal_f).max())
    # the spin's centrifugal pull U Ω² on the rigid disc (its spin about z dominates)
    assert np.linalg.norm(w.body_f[disc]) == pytest.approx(1e-4 * np.linalg.norm(v[disc, 3:]) ** 2, rel=1e-3)
    with pytest.raises(ValueError, match="rigid; mode_shapes"):
        mb.add_unbalance(disc, (0, 0, 0), 1e-4, mode_shapes=np.zeros((3, 1)))
    with pytest.raises(ValueError, match=r"mode_shapes must be finite with shape \(3, 3\)"):
        mb.add_unbalance(ring, (0, 0, 0), 1e-4, mode_shapes=np.zeros((3, 2)))
