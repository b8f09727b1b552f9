"""Ball rows at speed: centrifugal force and gyroscopic moment in the quasi-static solution.

References:
- at rest the per-ball solution must be the project's static load distribution
  (:func:`mbd_core.quasistatic.solve_load_distribution`, whose ball model eliminates the ball centre:
  an independent implementation of the same contacts);
- at speed, an independent solution written here in the classical form of Jones' race-control model
  (Jones, Trans. ASME J. Basic Eng. 82 (1960) 309; Harris & Kotzalas, Advanced Concepts of Bearing
  Technology, 5th ed., ch. 3): unknowns X1, X2 (ball centre from the outer groove's curvature centre,
  axial and radial) and the inner ring's axial displacement, all balls alike under a pure thrust;
  Jones' closed forms for the spin-axis angle tan β = sin α_o/(cos α_o + γ), the rolling speeds about
  that axis, F_c = ½ m d_m ω_m² and M_g = J ω_R ω_m sin β held at the outer race. The friction there
  supplies the moment ω_m e_z × J Ω (steady precession), i.e. a force (2M_g/D)(sin α_o, −cos α_o) on
  the ball in (radial, axial).
"""

import math

import numpy as np
import pytest
from scipy.optimize import fsolve

from mbd_core.contact.hertz import ball_on_groove
from mbd_core.quasistatic import Bearing, BallRow, RingLoad, solve_load_distribution
from mbd_core.quasistatic.high_speed import solve_high_speed_row

# a 218-size angular-contact bearing (Harris' example dimensions): 16 balls of 22.23 mm on d_m = 125.3 mm,
# f = 0.5232 both, α0 = 40°, steel; 22.25 kN thrust
ROW = BallRow("218", 16, 22.23e-3, 125.3e-3, math.radians(40), 0.5232, 0.5232, "inner", axial_sign=1)
THRUST_N = 22250.0


def _jones_thrust(row, thrust_N, omega_i):
    """(Q_i, Q_o, α_i, α_o) of every ball under a pure thrust at ω_i, Jones/Harris form (module docstring)."""
    D, dm, f = row.ball_diameter_m, row.pitch_diameter_m, row.conformity_moving
    A = (row.conformity_moving + row.conformity_fixed - 1.0) * D
    a0 = row.contact_angle_rad
    gam = D / dm
    m = math.pi / 6 * D**3 * row.ball_material.density_kg_m3
    J = 0.1 * m * D * D
    K_i = ball_on_groove(D, f, dm, a0, "inner").stiffness_N_per_m1p5
    K_o = ball_on_groove(D, row.conformity_fixed, dm, a0, "outer").stiffness_N_per_m1p5

    def state(x):
        X1, X2, da = x
        A1, A2 = A * math.sin(a0) + da, A * math.cos(a0)
        Lo, Li = math.hypot(X1, X2), math.hypot(A1 - X1, A2 - X2)
        do, di = Lo - (row.conformity_fixed - 0.5) * D, Li - (f - 0.5) * D
        so, co, si, ci = X1 / Lo, X2 / Lo, (A1 - X1) / Li, (A2 - X2) / Li
        Qo, Qi = K_o * max(do, 0) ** 1.5, K_i * max(di, 0) ** 1.5
        ao, ai = math.atan2(so, co), math.atan2(si, ci)
        beta = math.atan2(so, co + gam)
        # rolling about the spin axis at both contacts (cage frame): ω_m r_o = ω'(D/2)cos(α_o − β), etc.
        ro, ri = 1 + gam * co, 1 - gam * ci
        wm = omega_i * (ri / math.cos(ai - beta)) / (ro / math.cos(ao - beta) + ri / math.cos(ai - beta))
        wR = wm * ro / (gam * math.cos(ao - beta))
        Fc = 0.5 * m * dm * wm**2
        Mg = J * wR * wm * math.sin(beta)
        return Qi, Qo, si, ci, so, co, Fc, Mg, ai, ao

    def eqs(x):
        Qi, Qo, si, ci, so, co, Fc, Mg, _, _ = state(x)
        return [(Qi * si - Qo * so - 2 * Mg / D * co) / thrust_N,
                (Qi * ci - Qo * co + 2 * Mg / D * so + Fc) / thrust_N,
                (row.n_balls * Qi * si - thrust_N) / thrust_N]

    x0 = [(row.conformity_fixed - 0.5) * D * math.sin(a0), (row.conformity_fixed - 0.5) * D * math.cos(a0), 1e-5]
    x, info, ok, msg = fsolve(eqs, x0, xtol=1e-13, full_output=True)
    assert ok == 1, msg
    Qi, Qo, _, _, _, _, _, _, ai, ao = state(x)
    return Qi, Qo, ai, ao


def test_at_rest_it_is_the_static_distribution():
    # combined load: every ball's load and contact angle as the static solver's, to 1e-7
    load = RingLoad(Fx_N=3000.0, Fz_N=THRUST_N, My_Nm=50.0)
    static = solve_load_distribution(Bearing("b", (ROW,)), load).rows[0]
    hs = solve_high_speed_row(ROW, load, 0.0)
    np.testing.assert_allclose(hs.inner_load_N, static.load_N, rtol=1e-7, atol=1e-7 * static.load_N.max())
    np.testing.assert_allclose(hs.outer_load_N, static.load_N, rtol=1e-7, atol=1e-7 * static.load_N.max())
    np.testing.assert_allclose(hs.inner_angle_rad, static.contact_angle_rad, atol=1e-7)


@pytest.mark.parametrize("rpm", [5000.0, 10000.0, 20000.0])
def test_thrust_at_speed_against_jones(rpm):
    # outer-race load and both contact angles against the Jones/Harris form within 1 % (the module takes
    # the ball centre's true radius and contact points; the classical form d_m/2: they differ ~1e-3)
    omega = rpm * 2 * math.pi / 60
    hs = solve_high_speed_row(ROW, RingLoad(Fz_N=THRUST_N), omega)
    Qi, Qo, ai, ao = _jones_thrust(ROW, THRUST_N, omega)
    static = solve_load_distribution(Bearing("b", (ROW,)), RingLoad(Fz_N=THRUST_N)).rows[0]
    assert np.ptp(hs.outer_load_N) < 1e-9 * Qo                     # all balls alike
    assert hs.outer_load_N[0] == pytest.approx(Qo, rel=0.01)
    assert hs.inner_load_N[0] == pytest.approx(Qi, rel=0.01)
    # the contact-angle changes from rest, within 1 % of the reference's change
    a_rest = static.contact_angle_rad[0]
    assert hs.outer_angle_rad[0] - a_rest == pytest.approx(ao - a_rest, rel=0.01)
    assert hs.inner_angle_rad[0] - a_rest == pytest.approx(ai - a_rest, rel=0.01)


def test_outer_control_reproduces_jones_spin_axis():
    # the spin axis relative to the cage: tan β = sin α_o/(cos α_o + D/d_m), from the three linear conditions
    omega = 15000 * 2 * math.pi / 60
    hs = solve_high_speed_row(ROW, RingLoad(Fz_N=THRUST_N), omega)
    w_rel = hs.spin_rad_s[0] - np.array([0.0, hs.orbit_speed_rad_s[0]])     # Ω − ω_m e_z: (r, z)
    beta = math.atan2(abs(w_rel[0]), abs(w_rel[1]))
    ao = hs.outer_angle_rad[0]
    gam = ROW.ball_diameter_m / (2 * 0.5 * ROW.pitch_diameter_m)
    assert beta == pytest.approx(math.atan2(math.sin(ao), math.cos(ao) + gam), rel=2e-3)


def test_bad_input():
    with pytest.raises(ValueError, match="control"):
        solve_high_speed_row(ROW, RingLoad(Fz_N=THRUST_N), 100.0, control="cage")
    with pytest.raises(ValueError, match="moving raceway"):
        solve_high_speed_row(BallRow("o", 16, 22.23e-3, 125.3e-3, 0.7, 0.52, 0.52, "outer"), RingLoad(Fz_N=1e3), 1.0)


def test_radial_load_at_speed_unloaded_balls_ride_the_outer_race():
    # a deep-groove row (α0 = 0) under radial load at 20 000 rev/min: balls out of the load zone touch
    # only the outer race, at its groove bottom, pressed by their centrifugal force alone
    # (F_c = m ω_c² r_b, ω_c the cage speed: Q_o = F_c to 1e-6); the returned inner-contact loads
    # balance the load (equilibrium written out here from Q_i and α_i)
    row = BallRow("dg", 12, 12e-3, 60e-3, 0.0, 0.52, 0.53, "inner", diametral_clearance_m=10e-6)
    load = RingLoad(Fx_N=3000.0)
    hs = solve_high_speed_row(row, load, 20000 * math.pi / 30)
    free = hs.inner_load_N == 0.0
    assert 3 <= free.sum() <= 9
    np.testing.assert_allclose(hs.outer_load_N[free], hs.centrifugal_N[free], rtol=1e-6)
    np.testing.assert_allclose(hs.outer_angle_rad[free], 0.0, atol=1e-6)
    assert np.ptp(hs.orbit_speed_rad_s[free]) < 1e-9 * hs.orbit_speed_rad_s[0]      # carried by one cage
    Fx = np.sum(hs.inner_load_N * np.cos(hs.inner_angle_rad) * np.cos(hs.azimuth_rad))
    Fy = np.sum(hs.inner_load_N * np.cos(hs.inner_angle_rad) * np.sin(hs.azimuth_rad))
    assert Fx == pytest.approx(3000.0, rel=1e-5) and abs(Fy) < 1e-5 * 3000.0
    assert np.all(hs.outer_load_N >= hs.inner_load_N)                                # F_c adds outside


def test_combined_load_at_speed_balances_and_balls_wedge_out():
    # 218 bearing, 8 kN radial + 3 kN thrust at 10 000 rev/min: the inner-contact forces balance the load
    # (radial and axial, written out here) and the unloaded side's balls carry F_c on the outer race
    load = RingLoad(Fx_N=8000.0, Fz_N=3000.0)
    hs = solve_high_speed_row(ROW, load, 10000 * math.pi / 30)
    Q, a, psi = hs.inner_load_N, hs.inner_angle_rad, hs.azimuth_rad
    assert np.sum(Q * np.cos(a) * np.cos(psi)) == pytest.approx(8000.0, rel=1e-5)
    assert np.sum(Q * np.sin(a)) == pytest.approx(3000.0, rel=1e-5)
    free = Q == 0.0
    assert free.sum() >= 3
    np.testing.assert_allclose(hs.outer_load_N[free], hs.centrifugal_N[free], rtol=1e-3)


def test_dynamics_lies_between_the_race_control_limits():
    # an independent check of the centrifugal and gyroscopic terms (and of the friction couple's sign):
    # the same bearing in the multibody dynamics (balls as rigid bodies under Newton–Euler, Coulomb
    # friction at both contacts, a cage), settled at 10 000 rev/min under the thrust, carries mean ball
    # loads between the quasi-static inner- and outer-race-control solutions (measured: Q_i 1821 N in
    # [1802, 1849], Q_o 2253 N in [2221, 2307]), below the solution without the gyroscopic couple
    # (1905 / 2364 N): the friction shares the couple between the races
    from mbd_core.contact.friction import Coulomb
    from mbd_core.multibody import Driven, Fixed, ModelBuilder, simulate
    from mbd_core.multibody.bearings import add_ball_row, set_rolling_velocities
    from mbd_core.multibody.statics import static_equilibrium

    omega = 10000 * math.pi / 30
    b = ModelBuilder()
    inner = b.add_body("inner ring", 2.0, (2e-3, 2e-3, 4e-3), motion=Driven(omega, translation_free=True))
    outer = b.add_body("outer ring", 2.0, (2e-3, 2e-3, 4e-3), motion=Fixed())
    balls = add_ball_row(b, ROW, inner, outer, friction=Coulomb(0.1, 0.08, 0.05, 0.1), damping_N_s_m=500.0,
                         cage_mass_kg=0.2)
    b.add_force(inner, (0.0, 0.0, THRUST_N))
    model, state = b.finalize()
    state = static_equilibrium(model, state).state
    set_rolling_velocities(model, state, balls.elements, inner, other_ring=outer)
    run = simulate(model, state, 0.03, record_every=50)
    late = run["t"] > 0.02
    q_i = run["fn"][late][:, list(balls.moving_pairs)].mean()
    q_o = run["fn"][late][:, list(balls.fixed_pairs)].mean()
    lo, hi = (solve_high_speed_row(ROW, RingLoad(Fz_N=THRUST_N), omega, control=c) for c in ("inner", "outer"))
    assert lo.inner_load_N[0] < q_i < hi.inner_load_N[0]
    assert lo.outer_load_N[0] < q_o < hi.outer_load_N[0]


def test_stiffness_at_rest_is_the_static_one_and_softens_axially_at_speed():
    # at rest the operating-point stiffness (central differences, balls settled) equals the static
    # solver's analytic tangent stiffness within 1e-4 of its largest entry; at speed the centrifugal
    # force unloads the inner contacts and the axial stiffness falls (Harris & Kotzalas, Advanced
    # Concepts, ch. 3: high-speed angular-contact bearings lose axial stiffness)
    load = RingLoad(Fx_N=3000.0, Fz_N=THRUST_N)
    static = solve_load_distribution(Bearing("b", (ROW,)), load)
    K0 = solve_high_speed_row(ROW, load, 0.0).stiffness
    scale = np.abs(static.stiffness).max(axis=0)
    assert np.all(np.abs(K0 - static.stiffness) <= 1e-4 * scale[None, :])
    K = solve_high_speed_row(ROW, load, 15000 * math.pi / 30).stiffness
    assert K[2, 2] < 0.95 * K0[2, 2]
