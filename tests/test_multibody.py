"""The rigid multibody core against references: the quasi-static load distribution (an
independent solver, mbd_core.quasistatic), rolling kinematics without slip, conservation laws,
order of accuracy, and its behaviour when a run is set up wrongly or diverges."""

import dataclasses
import math

import numpy as np
import pytest

from mbd_core.bearing import rolling_kinematics
from mbd_core.contact.friction import Coulomb, DrebLinear
from mbd_core.multibody import (
    ContactLaw,
    DivergenceError,
    Driven,
    Fixed,
    ModelBuilder,
    State,
    StepTooLargeError,
    evaluate_forces,
    read_run,
    simulate,
    stable_timestep,
)
from mbd_core.multibody.bearings import add_ball_row, add_roller_row, set_rolling_velocities
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.quasistatic import BallRow, Bearing, RingLoad, RollerRow, solve_load_distribution

G = 9.81
# The 1 m model of the slewing ring: 16 balls Ø95.25 mm at 60°, f = 0.525, dead load 68.9 t.
SLEWING_ROW = BallRow("balls", 16, 95.25e-3, 1.0, math.radians(60), 0.525, 0.525, "inner", axial_sign=-1)


def slewing_model(row, load: RingLoad, damping=2e4, cage_mass_kg=None, friction=None):
    b = ModelBuilder()
    top = b.add_body("top race", 500.0, (100.0, 100.0, 200.0))
    bottom = b.add_body("bottom race", 500.0, (100.0, 100.0, 200.0), motion=Fixed())
    bodies = add_ball_row(b, row, top, bottom, damping_N_s_m=damping, d_max_m=1e-5, cage_mass_kg=cage_mass_kg,
                          friction=friction,
                          pocket_clearance_m=0.2e-3, cage_stiffness_N_per_m=1e8)
    if cage_mass_kg is not None:  # the cage is centred on the fixed ring (land guidance)
        b.add_bushing(bottom, bodies.cage, (0.0, 0.0, 0.0), (1e8, 1e8, 0, 0, 0, 0), (1e4, 1e4, 0, 0, 0, 0))
    b.add_force(top, (load.Fx_N, load.Fy_N, load.Fz_N), (load.Mx_Nm, load.My_Nm, 0.0))
    model, state = b.finalize()
    return model, state, bodies


def test_thrust_slewing_ring_settles_to_the_quasistatic_ball_loads():
    load = RingLoad(Fz_N=-68.9e3 * G)
    qs = solve_load_distribution(Bearing("slewing", (SLEWING_ROW,)), load).rows[0].load_N
    model, state, bodies = slewing_model(SLEWING_ROW, load)
    moving = list(bodies.moving_pairs)
    # the model's own static equilibrium equals the independent quasi-static solver
    eq = static_equilibrium(model, state)
    fn_static = evaluate_forces(model, eq.state).contact_fn[moving]
    assert np.max(np.abs(fn_static / qs - 1)) < 1e-6
    # Q = F/(Z sin α) at the loaded contact angle (thesis' Q = (F + W)/(Z sin α)), through the solver
    assert qs.mean() == pytest.approx(-load.Fz_N / (16 * math.sin(np.mean(
        solve_load_distribution(Bearing("s", (SLEWING_ROW,)), load).rows[0].contact_angle_rad))), rel=1e-9)
    # dynamics from the unloaded, touching start with the load applied at once: settles within 0.5 %
    out = simulate(model, state, 0.3, record_every=200)
    fn_dyn = out["fn"][-1, moving]
    assert np.max(np.abs(fn_dyn / qs - 1)) < 5e-3
    # and the balls push on both races equally (equilibrium of each ball)
    assert np.allclose(out["fn"][-1, list(bodies.fixed_pairs)], fn_dyn, rtol=1e-3)


def test_radial_load_with_clearance_matches_quasistatic_per_ball():
    row = dataclasses.replace(SLEWING_ROW, radial_clearance_m=0.05e-3, diametral_clearance_m=None)
    load = RingLoad(Fx_N=0.15 * 68.9e3 * G, Fz_N=-68.9e3 * G)
    qs = solve_load_distribution(Bearing("slewing", (row,)), load).rows[0].load_N
    assert qs.min() < 0.5 * qs.max()  # a real distribution, not a uniform one
    # A cage centred on the fixed ring keeps the balls evenly spaced, as the quasi-static solution
    # assumes (without one there is no equilibrium: the balls of the less loaded side drift along the
    # groove). The contact lines of a single angular-contact row meet at one point of the axis, so
    # the ring's rocking about it is nearly free; normal damping hardly sees it and Coulomb friction
    # would stick at a history-dependent state. A viscous traction (DREB κ = B·u) damps it and
    # vanishes at rest, so the dynamic steady state is the frictionless equilibrium.
    model, state, bodies = slewing_model(row, load, cage_mass_kg=20.0, friction=DrebLinear(0.2))
    moving = list(bodies.moving_pairs)
    scale = np.maximum(qs, 0.02 * qs.max())  # 2 % of the largest load where a ball is unloaded
    eq = static_equilibrium(model, state).state
    assert np.max(np.abs(evaluate_forces(model, eq).contact_fn[moving] - qs) / scale) < 0.02
    # dynamics from the unloaded, touching start: the steady state, per ball
    out = simulate(model, state, 3.0, record_every=2000)
    assert np.max(np.abs(out["fn"][-1, moving] - qs) / scale) < 0.02


def test_start_from_static_equilibrium_has_no_shock():
    load = RingLoad(Fz_N=-68.9e3 * G)
    model, state, bodies = slewing_model(SLEWING_ROW, load)
    eq = static_equilibrium(model, state).state
    f0 = evaluate_forces(model, eq).contact_fn.copy()
    out = simulate(model, eq, 0.02, record_every=50)
    assert np.max(np.abs(out["fn"] - f0)) < 1e-6 * f0.max()


def _angular_contact_bearing(friction, omega_i):
    row = BallRow("balls", 12, 12e-3, 0.1, math.radians(30), 0.52, 0.52, "inner", axial_sign=1)
    b = ModelBuilder()
    inner = b.add_body("inner ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Driven(omega_i, translation_free=True))
    outer = b.add_body("outer ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    bodies = add_ball_row(b, row, inner, outer, friction=friction, damping_N_s_m=200.0, d_max_m=1e-6,
                          cage_mass_kg=0.05, pocket_clearance_m=0.2e-3, cage_stiffness_N_per_m=2e6)
    # the cage is centred on the outer ring (land guidance), so it does not whirl
    b.add_bushing(outer, bodies.cage, (0.0, 0.0, 0.0), (1e6, 1e6, 0, 0, 0, 0), (50.0, 50.0, 0, 0, 0, 0))
    b.add_force(inner, (0.0, 0.0, 2000.0))
    model, state = b.finalize()
    return row, model, state, bodies, inner


def _mean_spin_relative_to_cage(out, balls, cage, normals_axis):
    """Mean |ω_ball − ω_cage| component normal to the contact line, over the last half of the run."""
    from scipy.spatial.transform import Rotation

    half = len(out["t"]) // 2
    spins = []
    for k in range(half, len(out["t"])):
        qc = out["q"][k, cage, 3:]
        wc = Rotation.from_quat(qc[[1, 2, 3, 0]]).apply(out["v"][k, cage, 3:])
        for e in balls:
            r = Rotation.from_quat(out["q"][k, e, [4, 5, 6, 3]])
            w = r.apply(out["v"][k, e, 3:]) - wc
            u = normals_axis(out["q"][k, e, :3])
            spins.append(np.linalg.norm(w - (w @ u) * u))
    return float(np.mean(spins))


def test_ball_bearing_kinematics_match_no_slip_formulas():
    omega_i = 2 * math.pi * 1000 / 60
    # the regularised Coulomb law needs some micro-slip to carry traction (the balls' gyroscopic
    # moment): its transition speed must be small against the rolling speed (here 0.2 % of 4.6 m/s)
    row, model, state, bodies, inner = _angular_contact_bearing(Coulomb(0.1, 0.08, 0.01, 0.02), omega_i)
    eq = static_equilibrium(model, state).state
    out = simulate(model, eq, 0.15, record_every=100)
    alpha = float(np.mean(out["angle"][-1, list(bodies.moving_pairs)]))
    kin = rolling_kinematics(row.ball_diameter_m, row.pitch_diameter_m, alpha, row.n_balls, omega_i, 0.0)
    half = len(out["t"]) // 2
    cage_speed = np.mean(out["v"][half:, bodies.cage, 5])
    # Harris & Kotzalas, Essential Concepts, eq. 8.24: ω_c = ω_i (1 − γ)/2, γ = D cos α / d_m
    assert cage_speed == pytest.approx(kin.cage_speed_rad_s, rel=0.01)
    orbit = np.mean([np.cross(out["q"][-1, e, :3], out["v"][-1, e, :3])[2] / (row.pitch_diameter_m / 2) ** 2
                     for e in bodies.elements])
    assert orbit == pytest.approx(kin.cage_speed_rad_s, rel=0.01)

    def contact_line(x):  # unit vector along the loaded contact line at the ball (ring frame = world)
        e_r = np.array([x[0], x[1], 0.0]) / math.hypot(x[0], x[1])
        return math.cos(alpha) * e_r + math.sin(alpha) * np.array([0.0, 0.0, 1.0])

    spin = _mean_spin_relative_to_cage(out, bodies.elements, bodies.cage, contact_line)
    # ω_R = (d_m / 2D)(1 − γ²) ω_i relative to the cage (eq. 8.31), for the component normal to the
    # contact line (the spin about the line itself is free with point contacts)
    assert spin == pytest.approx(kin.element_speed_magnitude_rad_s, rel=0.01)


def test_cylindrical_roller_bearing_kinematics_match_no_slip_formulas():
    omega_i = 2 * math.pi * 600 / 60
    row = RollerRow("rollers", 14, 10e-3, 10e-3, 0.08, "radial", load_sign=1, gap_m=-5e-6, n_slices=6)
    b = ModelBuilder()
    inner = b.add_body("inner ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Driven(omega_i, translation_free=True))
    outer = b.add_body("outer ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    bodies = add_roller_row(b, row, inner, outer, friction=Coulomb(0.1, 0.08, 0.05, 0.1), damping_N_s_m=20.0,
                            rib_clearance_m=0.1e-3, cage_mass_kg=0.04, pocket_clearance_m=0.2e-3,
                            cage_stiffness_N_per_m=2e6)
    b.add_force(inner, (1000.0, 0.0, 0.0))
    model, state = b.finalize()
    eq = static_equilibrium(model, state).state
    out = simulate(model, eq, 0.15, record_every=100)
    kin = rolling_kinematics(row.roller_diameter_m, row.pitch_diameter_m, 0.0, row.n_rollers, omega_i, 0.0)
    half = len(out["t"]) // 2
    assert np.mean(out["v"][half:, bodies.cage, 5]) == pytest.approx(kin.cage_speed_rad_s, rel=0.01)
    # roller spin about its own axis (body z) relative to the cage (the axes are parallel)
    spin = np.mean(out["v"][half:, list(bodies.elements), 5] - out["v"][half:, bodies.cage, 5][:, None])
    assert spin == pytest.approx(kin.element_speed_rad_s, rel=0.01)


def _free_bearing(preload_m=-20e-6, caged=True):
    """Both rings free; two preloaded rows of 8 balls (back to back, so the preload is held
    inside the bearing) in free cages; no friction, no damping; the inner ring spinning and shaking."""
    rows = [BallRow(name, 8, 12e-3, 0.1, math.radians(30), 0.52, 0.52, "inner", axial_sign=sign, radial_clearance_m=preload_m,
                    axial_position_m=z) for name, sign, z in (("row A", 1, -0.01), ("row B", -1, 0.01))]
    b = ModelBuilder()
    inner = b.add_body("inner ring", 0.4, (4e-4, 4e-4, 7e-4), velocity_m_s=(0.0, 0.0, 0.001),
                       omega_rad_s=(0.05, 0.0, 40.0))
    outer = b.add_body("outer ring", 0.6, (1e-3, 1e-3, 1.8e-3))
    bodies = [add_ball_row(b, row, inner, outer, cage_mass_kg=0.02 if caged else None, pocket_clearance_m=0.1e-3,
                           cage_stiffness_N_per_m=1e6) for row in rows]
    model, state = b.finalize()
    eq = static_equilibrium(model, dataclasses.replace(state, v=np.zeros_like(state.v))).state
    eq.v[:] = state.v
    return model, eq, bodies[0]


def _energy(model, out, k):
    a = model.arrays
    st = State(out["t"][k], out["q"][k].copy(), out["v"][k].copy())
    w = evaluate_forces(model, st)
    kinetic = 0.5 * np.sum(a.body_mass * np.sum(st.v[:, :3] ** 2, axis=1)) + 0.5 * np.sum(a.body_inertia * st.v[:, 3:] ** 2)
    return kinetic + w.energy[0]


def _momenta(model, out, k):
    from scipy.spatial.transform import Rotation

    a = model.arrays
    p = np.sum(a.body_mass[:, None] * out["v"][k, :, :3], axis=0)
    L = np.zeros(3)
    for i in range(model.n_bodies):
        R = Rotation.from_quat(out["q"][k, i, [4, 5, 6, 3]])
        L += np.cross(out["q"][k, i, :3], a.body_mass[i] * out["v"][k, i, :3]) + R.apply(a.body_inertia[i] * out["v"][k, i, 3:])
    return p, L


def test_free_bearing_conserves_energy_and_momentum_over_1e5_steps():
    model, state, bodies = _free_bearing()
    h = stable_timestep(model, state).timestep_s  # the automatic step
    out = simulate(model, state, state.t + 1e5 * h, timestep_s=h, record_every=5000)
    assert len(out["t"]) == 21
    e = np.array([_energy(model, out, k) for k in range(len(out["t"]))])
    # symplectic integrator: bounded energy error, no drift (acceptance: < 1e-4 relative)
    assert np.max(np.abs(e / e[0] - 1)) < 1e-4
    p0, L0 = _momenta(model, out, 0)
    p1, L1 = _momenta(model, out, -1)
    scale_p = np.sum(model.arrays.body_mass[:, None] * np.abs(out["v"][0, :, :3]))
    assert np.max(np.abs(p1 - p0)) < 1e-11 * scale_p
    assert np.max(np.abs(L1 - L0)) < 1e-10 * np.linalg.norm(L0)


def test_explicit_integrator_is_second_order():
    # without cages: the smooth Hertz contacts only (the pockets' clearance makes contact events)
    model, state, bodies = _free_bearing(caged=False)
    h0 = stable_timestep(model, state).timestep_s / 2
    t_end = state.t + 200 * h0

    def final(h):
        s = state.copy()
        simulate(model, s, t_end, timestep_s=h, record_every=10**9)
        return np.concatenate([s.q[:, :3].ravel(), h0 * s.v[:, :3].ravel()])

    ref = final(h0 / 64)
    errs = [np.max(np.abs(final(h0 / 2**k) - ref)) for k in range(4)]
    # velocity Verlet is second order (Hairer, Lubich & Wanner, GNI, ch. II.1); measured 2.18, 2.04, 2.03
    order = np.polyfit(np.log(2.0 ** -np.arange(4)), np.log(errs), 1)[0]
    assert 1.9 < order < 2.2, (errs, order)


def test_a_step_above_the_limit_is_refused_with_the_reason():
    model, state, _ = slewing_model(SLEWING_ROW, RingLoad(Fz_N=-68.9e3 * G))
    lim = stable_timestep(model, state)
    assert "contacts of body" in lim.reason
    with pytest.raises(StepTooLargeError, match="exceeds the explicit stability limit"):
        simulate(model, state, 0.01, timestep_s=2 * lim.limit_s)


def test_an_unstable_run_stops_with_the_cause_and_writes_no_nan(tmp_path):
    model, state, _ = slewing_model(SLEWING_ROW, RingLoad(Fz_N=-68.9e3 * G), damping=0.0)
    lim = stable_timestep(model, state)
    with pytest.raises(DivergenceError, match="at contact|ran away|non-finite") as err:
        simulate(model, state, 0.2, timestep_s=6 * lim.limit_s, folder=tmp_path / "run", allow_unstable=True,
                 record_every=1, chunk_samples=50)
    assert "t =" in str(err.value) or "t ≈" in str(err.value)
    rec = read_run(tmp_path / "run")
    assert rec["status"].startswith("failed")
    for key in ("q", "v", "fn", "delta"):
        assert np.all(np.isfinite(rec[key]))


def test_an_interrupted_run_resumes_to_the_same_result(tmp_path):
    model, state, _ = slewing_model(SLEWING_ROW, RingLoad(Fz_N=-68.9e3 * G))
    h = stable_timestep(model, state).timestep_s
    whole = simulate(model, state.copy(), 3000 * h, timestep_s=h, folder=tmp_path / "a", record_every=20,
                     chunk_samples=10)
    first = state.copy()
    simulate(model, first, 1400 * h, timestep_s=h, folder=tmp_path / "b", record_every=20, chunk_samples=10)
    assert read_run(tmp_path / "b")["status"] == "complete"
    resumed = simulate(model, state.copy(), 3000 * h, folder=tmp_path / "b", record_every=20,
                       chunk_samples=10, resume=True)  # the recorded step
    assert resumed["t"].shape == whole["t"].shape
    for key in ("t", "q", "v", "fn", "delta", "slip"):
        np.testing.assert_array_equal(resumed[key], whole[key])


def test_rolling_velocities_leave_no_slip_at_the_raceways():
    omega_i = 2 * math.pi * 1000 / 60
    row, model, state, bodies, inner = _angular_contact_bearing(None, omega_i)
    eq = static_equilibrium(model, state).state
    set_rolling_velocities(model, eq, bodies.elements, inner, other_ring=1)
    w = evaluate_forces(model, eq)
    raceway = list(bodies.moving_pairs) + list(bodies.fixed_pairs)
    # the contact points move with both raceways (slip relative to a surface speed of ~4.6 m/s)
    assert np.max(w.contact_slip[raceway]) < 1e-9
    # and the balls orbit at the no-slip cage speed ω_i (1 − γ)/2 at their loaded contact angle
    alpha = float(np.mean(w.contact_angle[list(bodies.moving_pairs)]))
    kin = rolling_kinematics(row.ball_diameter_m, row.pitch_diameter_m, alpha, row.n_balls, omega_i, 0.0)
    x, v = eq.q[bodies.elements[0], :3], eq.v[bodies.elements[0], :3]
    assert np.cross(x, v)[2] / (x[0] ** 2 + x[1] ** 2) == pytest.approx(kin.cage_speed_rad_s, rel=1e-6)


def test_rolling_velocities_leave_no_spin_about_nearly_collinear_contacts():
    """A ball whose two contact normals are 0.1° off collinear (here moved 0.5 µm across its contact
    line; on a modal ring the deformed groove does it) may spin about the line through its contacts
    without moving them; the no-slip conditions barely fix that spin. It is set to zero: before, the
    misalignment alone fixed it, at 100× the rolling speed on the 1 m slewing ring with a modal top,
    and the ball orbit then ran 1.8 % slow. Reference: the classical rolling kinematics (Harris &
    Kotzalas, Essential Concepts, ch. 8) at the loaded contact angle, and a spin of the order of
    the rolling speed."""
    omega_i = 2 * math.pi * 1000 / 60
    row, model, state, bodies, inner = _angular_contact_bearing(None, omega_i)
    eq = static_equilibrium(model, state).state
    w = evaluate_forces(model, eq)
    alpha = float(np.mean(w.contact_angle[list(bodies.moving_pairs)]))
    for e in bodies.elements:  # 0.5 µm across the contact line, in the meridian plane
        x = eq.q[e, :3]
        er = np.array([x[0], x[1], 0.0]) / math.hypot(x[0], x[1])
        eq.q[e, :3] = x + 0.5e-6 * (math.sin(alpha) * er + math.cos(alpha) * np.array([0.0, 0.0, 1.0]))
    set_rolling_velocities(model, eq, bodies.elements, inner, other_ring=1)
    kin = rolling_kinematics(row.ball_diameter_m, row.pitch_diameter_m, alpha, row.n_balls, omega_i, 0.0)
    e = bodies.elements[0]
    x, v = eq.q[e, :3], eq.v[e, :3]
    assert np.cross(x, v)[2] / (x[0] ** 2 + x[1] ** 2) == pytest.approx(kin.cage_speed_rad_s, rel=1e-3)
    # ω (world) of the ball against the rolling speed ω_i·d_m/D of the classical kinematics
    from scipy.spatial.transform import Rotation

    qb = eq.q[e, 3:]
    omega = Rotation.from_quat([qb[1], qb[2], qb[3], qb[0]]).apply(eq.v[e, 3:])
    assert np.linalg.norm(omega) < 2.0 * omega_i * row.pitch_diameter_m / row.ball_diameter_m


def test_bad_input_is_rejected_naming_the_field():
    b = ModelBuilder()
    with pytest.raises(ValueError, match="mass_kg"):
        b.add_body("ring", -1.0, (1, 1, 1))
    with pytest.raises(ValueError, match="inertia_kg_m2"):
        b.add_body("ring", 1.0, (1, 0, 1))
    ring = b.add_body("ring", 10.0, (1, 1, 2))
    ball = b.add_body("ball", 0.1, (1e-6,) * 3)
    with pytest.raises(ValueError, match="exists already"):
        b.add_body("ring", 1.0, (1, 1, 1))
    g = b.add_groove(ring, 0.5, 0.0, 0.0105)
    with pytest.raises(ValueError, match="groove radius"):
        b.add_ball_groove(ball, ring, g, 0.011, ContactLaw(1e10))
    with pytest.raises(ValueError, match="no body named 'cage'"):
        b.add_ball_groove(ball, "cage", g, 0.01, ContactLaw(1e10))
    with pytest.raises(ValueError, match="stiffness"):
        ContactLaw(-1e10)
    with pytest.raises(ValueError, match="times_s"):
        b.add_load_history(ring, [0.0, 0.2, 0.1], np.zeros((3, 6)))
    with pytest.raises(ValueError, match="cannot touch itself"):
        b.add_ball_ball(ball, ball, 0.01, 0.01, ContactLaw(1e10))


def test_static_equilibrium_carries_a_caged_bearing_under_gravity():
    b = ModelBuilder(gravity_m_s2=(0.0, 0.0, -9.81))
    row = BallRow("balls", 12, 12e-3, 0.1, math.radians(30), 0.52, 0.52, "inner", axial_sign=1)
    inner = b.add_body("inner ring", 1.0, (1e-3, 1e-3, 2e-3))
    outer = b.add_body("outer ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    bodies = add_ball_row(b, row, inner, outer, cage_mass_kg=0.05, cage_stiffness_N_per_m=2e6)
    b.add_force(inner, (0.0, 0.0, 2000.0))
    model, state = b.finalize()
    eq = static_equilibrium(model, state)
    w = evaluate_forces(model, eq.state)
    # the cage hangs in its pocket clearance (0.5 mm) on the balls: the pocket forces carry its weight
    assert eq.state.q[bodies.cage, 2] < -0.4e-3
    assert np.abs(w.body_f[bodies.cage]).max() < 1e-3 * 0.05 * 9.81  # residual < 0.1 % of its weight
    # the outer ring carries the load on the inner ring less the weight of everything it holds
    weight = 9.81 * (1.0 + 12 * model.arrays.body_mass[bodies.elements[0]] + 0.05)
    axial = sum(w.contact_fn[c] * math.sin(w.contact_angle[c]) for c in bodies.fixed_pairs)
    assert axial == pytest.approx(2000.0 - weight, rel=1e-6)


@pytest.mark.parametrize("load_sign", [1, -1])
def test_thrust_roller_ribs_sit_beyond_both_roller_ends(load_sign):
    """A thrust roller (axis radial) between ribs on the moving ring: at its nominal place each end is
    c/2 from its rib (penetration −c/2), and moved outward by u the outer end's penetration is
    u − c/2 and the inner end's −u − c/2 (geometry: ends at R ± L/2, ribs at R ± (L/2 + c/2))."""
    c, u = 0.4e-3, 0.1e-3
    row = RollerRow("thrust", 12, 20e-3, 20e-3, 0.3, "thrust", load_sign=load_sign, gap_m=10e-6, n_slices=4)
    b = ModelBuilder()
    inner = b.add_body("inner ring", 1.0, (1e-2, 1e-2, 2e-2), motion=Fixed())
    outer = b.add_body("outer ring", 1.0, (1e-2, 1e-2, 2e-2), motion=Fixed())
    bodies = add_roller_row(b, row, inner, outer, rib_clearance_m=c)
    model, state = b.finalize()
    ribs = np.array(bodies.other_pairs).reshape(len(bodies.elements), 2)  # (end +, end −) per roller
    w = evaluate_forces(model, state)
    np.testing.assert_allclose(w.contact_delta[ribs], -c / 2, atol=1e-12)
    e = bodies.elements[3]
    x = state.q[e, :3]
    state.q[e, :3] = x + u * np.array([x[0], x[1], 0.0]) / math.hypot(x[0], x[1])
    w = evaluate_forces(model, state)
    np.testing.assert_allclose(w.contact_delta[ribs[3]], [u - c / 2, -u - c / 2], atol=1e-12)


@pytest.mark.parametrize("orientation", ["radial", "thrust"])
def test_rolling_velocities_of_rollers_with_ribs(orientation):
    """set_rolling_velocities on roller rows held by ribs (which must not count as raceways):
    radial row, no-slip kinematics ω_c = ω_i (1 − γ)/2 and zero slip at every slice (Harris &
    Kotzalas, Essential Concepts, ch. 8); thrust row (axis radial), ω_c = ω_i/2 and spin
    ω_s = −ω_i R / (2 r) about the roller's own axis, no slip at the pitch radius (the slices away
    from it spin-slip, as on any cylindrical thrust roller)."""
    omega_i = 2 * math.pi * 100 / 60
    R, D = 0.15, 20e-3
    row = RollerRow("row", 12, D, 20e-3, 2 * R, orientation, load_sign=1, gap_m=10e-6, n_slices=4)
    b = ModelBuilder()
    inner = b.add_body("inner ring", 1.0, (1e-2, 1e-2, 2e-2), motion=Driven(omega_i))
    outer = b.add_body("outer ring", 1.0, (1e-2, 1e-2, 2e-2), motion=Fixed())
    bodies = add_roller_row(b, row, inner, outer, rib_clearance_m=0.2e-3)
    model, state = b.finalize()
    set_rolling_velocities(model, state, bodies.elements, inner, other_ring=outer)
    w = evaluate_forces(model, state)
    e = bodies.elements[5]
    x, v = state.q[e, :3], state.v[e, :3]
    orbit = np.cross(x, v)[2] / (x[0] ** 2 + x[1] ** 2)
    from scipy.spatial.transform import Rotation

    R_e = Rotation.from_quat(state.q[e, [4, 5, 6, 3]])
    omega_world = R_e.apply(state.v[e, 3:])
    axis = R_e.apply([0.0, 0.0, 1.0])
    spin = omega_world - orbit * np.array([0.0, 0.0, 1.0])
    np.testing.assert_allclose(np.cross(spin, axis), 0.0, atol=1e-9 * omega_i * R / D)  # about its own axis only
    if orientation == "radial":
        kin = rolling_kinematics(D, 2 * R, 0.0, 12, omega_i, 0.0)
        assert orbit == pytest.approx(kin.cage_speed_rad_s, rel=1e-9)
        assert np.max(np.abs(w.contact_slip[list(bodies.moving_pairs) + list(bodies.fixed_pairs)])) < 1e-9
    else:
        assert orbit == pytest.approx(omega_i / 2, rel=1e-9)
        assert abs(spin @ axis) == pytest.approx(omega_i * R / D, rel=1e-9)
