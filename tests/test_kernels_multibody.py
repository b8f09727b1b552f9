"""The whole force stage of the multibody kernels against its numpy twin in tests/reference/multibody.py,
on seeded random and corner inputs, plus the balance laws it must satisfy (Newton's third law, moment
balance, bushing torque = −∂E/∂φ). The element contact geometry, load splines and rotations:
tests/test_kernels_elements.py.

Tolerances, kernel against twin: rtol 1e-12, plus an absolute floor where a value is a small
difference or a sum of terms of both signs:

* penetrations and contact points: 1e-16 m, a few ulp of coordinates of ~0.05 m;
* body forces and moments: 1e-12 × Σ|terms| of that body (the twin's body_f_scale, body_t_scale);
* contact forces, friction forces, slip: 1e-12 × the largest entry of the array (a contact that just
  touches has a penetration, hence a force, with few significant digits);
* unit vectors and angles: 1e-15, 1e-14.

(The roller end nearly parallel to its rib, computed to ρ ε/|u| only: tests/test_kernels_elements.py;
the roller model here stays out of that range.)
"""

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from mbd_core.contact.friction import Coulomb, DrebFalling, Kragelskii
from mbd_core.kernels import explicit as EX
from mbd_core.kernels import forces as FK
from mbd_core.kernels.roller_slices import (
    RACEWAY_INNER_CYLINDER,
    RACEWAY_OUTER_CYLINDER,
    RACEWAY_PLANE_DOWN,
    RACEWAY_PLANE_UP,
)
from mbd_core.multibody import ContactLaw, Fixed, ModelBuilder, quat_from_axis_angle, quat_z_to
from mbd_core.multibody.parts import StripTraction
from mbd_core.multibody.model import make_work
from mbd_core.squeeze_film import SqueezeFilmDamper
from mbd_core.squeeze_film.force_table import tabulate
from tests.kernel_checks import (ATOL_M, NORMAL_ATOL, POINT_ATOL_M, RTOL, SEED, close as _close,
                                 close_scaled as _close_scaled, random_quat as _random_quat)
from tests.reference import multibody as ref


# -- models -------------------------------------------------------------------------------------
R_PITCH, R_BALL, CONFORMITY = 0.03, 0.0075, 0.52
ALPHA = math.radians(15)
DELTA_0 = 3e-5                    # nominal ball–groove penetration, m


SFD_TABLE = tabulate(SqueezeFilmDamper(0.04, 0.01, 5e-5, 0.01), "short", n_eps=9, n_psi=24)


def _ball_bearing(external=True, strips=None):
    """Fixed outer ring, free inner ring, cage, 6 balls in three touching pairs; Coulomb, Kragelskii and
    DREB friction; gravity, a constant force and a load history unless ``external`` is False. The inner
    ring is built turned by 0.3 rad, so the outer–inner bushing rests at q_ref ≠ 1. ``strips``: the
    ball–groove traction over the contact ellipse in that many strips (a = 2e-5 m·F_n^(1/3),
    deformed surface radius 4 mm)."""
    rng = np.random.default_rng(SEED + 100)
    mb = ModelBuilder(gravity_m_s2=(0.0, -9.81, -3.0) if external else (0.0, 0.0, 0.0))
    mb.add_body("outer", 0.4, (2e-4, 2e-4, 4e-4), motion=Fixed())
    mb.add_body("inner", 0.3, (1e-4, 1e-4, 2e-4), orientation=quat_from_axis_angle((0, 0, 1), 0.3),
                omega_rad_s=(0, 0, 150.0))
    mb.add_body("cage", 0.02, (1e-5, 1e-5, 2e-5), orientation=quat_from_axis_angle((0, 0, 1), -0.2))
    half = math.asin((2 * R_BALL - 1e-5) / (2 * R_PITCH))     # neighbours in a pair 10 µm into each other
    angles = [0.0, 2 * half, 2 * math.pi / 3, 2 * math.pi / 3 + 2 * half, 4 * math.pi / 3, 4 * math.pi / 3 + 2 * half]
    radii = R_PITCH + np.array([0.0, 0.0, 0.0, 4e-5, -4e-5, 0.0])   # balls 3, 4: off one groove
    balls = []
    for i, phi in enumerate(angles):
        position = (radii[i] * math.cos(phi), radii[i] * math.sin(phi), 0.0)
        balls.append(mb.add_body(f"ball{i}", 3.4e-3, (7.7e-8,) * 3, position,
                                 orientation=_random_quat(rng), omega_rad_s=rng.normal(size=3) * 100))
    rho = (2 * CONFORMITY - 1) * R_BALL + DELTA_0
    f_d = 2 * CONFORMITY * R_BALL
    outer_groove = mb.add_groove("outer", R_PITCH - rho * math.cos(ALPHA), -rho * math.sin(ALPHA), f_d,
                                 undulation_m=rng.uniform(-1e-5, 1e-5, 17), radial_offset_m=rng.uniform(-1e-5, 1e-5, 7))
    inner_groove = mb.add_groove("inner", R_PITCH + rho * math.cos(ALPHA), rho * math.sin(ALPHA), f_d,
                                 undulation_m=rng.uniform(-1e-5, 1e-5, 5), radial_offset_m=rng.uniform(-1e-5, 1e-5, 12))
    coulomb = ContactLaw(6e9, 1.5, 300.0, 1e-6, "impact", Coulomb(0.1, 0.08, 1e-3, 2e-3))
    kragelskii = ContactLaw(8e9, 1.5, 0.4, 1e-6, "hunt_crossley", Kragelskii(0.02, 0.5, 12.0, 0.01))
    falling = ContactLaw(2e8, 1.5, 50.0, 1e-5, "impact", DrebFalling(0.1, 0.01))
    pocket_push = [2e-5, -1e-5, 3e-5, 1e-5, -5e-5, 2e-5]      # pocket offsets beyond the clearance, m
    clearance = 2e-4
    groove_laws = (coulomb, kragelskii)
    if strips:
        groove_laws = tuple(ContactLaw(l.stiffness, l.exponent, l.damping, l.d_max_m, l.model, l.friction,
                                       strips=StripTraction(strips, 2e-5, 4e-3)) for l in groove_laws)
    for i, (b, phi) in enumerate(zip(balls, angles)):
        mb.add_ball_groove(b, "outer", outer_groove, R_BALL, groove_laws[0])
        mb.add_ball_groove(b, "inner", inner_groove, R_BALL, groove_laws[1])
        mb.add_ball_ball(b, balls[(i + 1) % 6], R_BALL, R_BALL, coulomb if i % 2 else falling)
        shift = (-1) ** i * (clearance + pocket_push[i]) / R_PITCH
        pocket = mb.add_pocket("cage", "cylinder", phi + 0.2 + shift, R_PITCH, 0.0, clearance)
        mb.add_element_pocket(b, "cage", pocket, R_BALL, kragelskii if i % 2 else falling)
    mb.add_bushing("outer", "inner", (0.0, 0.001, 0.01), (2e7, 2e7, 5e7, 3e3, 3e3, 50.0),
                   (1e3, 1e3, 2e3, 0.5, 0.5, 0.1))
    # a squeeze film between the rings: the bore 20 µm off the inner ring's centre (ε ≈ 0.4), axis tilted
    mb.add_squeeze_film("inner", "outer", SFD_TABLE, bore_center_m=(2e-5, 0.0, 1e-3), axis=(0.05, 0.0, 1.0))
    if external:
        mb.add_force("inner", (30.0, -200.0, 500.0), (1.0, -2.0, 0.5))
        mb.add_drag(balls[0], 0.05, 0.3)                          # fluid drag, linear and quadratic
        mb.add_drag("cage", 0.2)
        mb.add_load_history("inner", [0.0, 0.01, 0.025, 0.04], rng.normal(size=(4, 6)) * [300, 300, 500, 3, 3, 1])
    return mb.finalize()


R_ROLLER, L_ROLLER, EDGE, N_SLICES = 0.006, 0.012, 1e-3, 8
R_THRUST, L_THRUST, EDGE_THRUST, RT_THRUST, Z_THRUST = 0.005, 0.01, 8e-4, 0.045, 0.03
R_ROW = 0.04                      # pitch radius of the radial row, m
SURFACE_CODES = {"inner_cylinder": RACEWAY_INNER_CYLINDER, "outer_cylinder": RACEWAY_OUTER_CYLINDER,
                 "plane_up": RACEWAY_PLANE_UP, "plane_down": RACEWAY_PLANE_DOWN}


def _rib_for(kind, center, axis, radius, length, sign, edge, depth_m):
    """Radius or height of a rib of ``kind`` that this roller end (ring frame = world) penetrates by depth_m."""
    d0, _, _ = ref.roller_end(center, axis, radius, length, sign, edge, SURFACE_CODES[kind], 0.0)
    return depth_m - d0 if kind in ("inner_cylinder", "plane_up") else d0 - depth_m


def _roller_bearing():
    """Fixed outer ring, free inner ring and cage; 4 radial rollers (axis z) on crowned line contacts
    with cylinders and on plane ribs, 3 thrust rollers (axis radial) on planes with cylinder ribs, all
    in slot pockets. Roller 0 is exactly parallel to its ribs, which sit on the fixed ring
    (degenerate projection, u = 0). The others are built skewed by 0.15–0.25 rad, so that their rim
    contact points are computed to full precision (|u| ≳ 0.15; see
    test_roller_end_matches_twin_on_tilted_rollers for the accuracy ρ ε/|u| at small tilts). Rib
    heights/radii and slot clearances are set per contact for a few µm of penetration in the built pose."""
    rng = np.random.default_rng(SEED + 200)
    d0 = 2e-5                     # raceway preload, m
    mb = ModelBuilder()
    mb.add_body("outer", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    mb.add_body("inner", 0.8, (6e-4, 6e-4, 1e-3), omega_rad_s=(0, 0, 100.0))
    mb.add_body("cage", 0.1, (5e-5, 5e-5, 1e-4))
    crown = 4e-6 * ((np.arange(N_SLICES) + 0.5) / N_SLICES * 2 - 1) ** 2
    s_in = mb.add_surface("inner", "inner_cylinder", R_ROW - R_ROLLER + d0)
    s_out = mb.add_surface("outer", "outer_cylinder", R_ROW + R_ROLLER - d0)
    t_low = mb.add_surface("inner", "plane_up", Z_THRUST - R_THRUST + d0)
    t_up = mb.add_surface("outer", "plane_down", Z_THRUST + R_THRUST - d0)
    race = ContactLaw(1e9, 10 / 9, 500.0, 1e-6, "impact", Kragelskii(0.02, 0.5, 12.0, 0.01))
    race_c = ContactLaw(1e9, 10 / 9, 800.0, 2e-6, "impact", Coulomb(0.12, 0.08, 1e-3, 2e-3))
    rib = ContactLaw(5e9, 1.5, 0.3, 1e-6, "hunt_crossley", DrebFalling(0.08, 0.01))
    pocket_law = ContactLaw(1e8, 1.5, 20.0, 1e-5, "impact", Coulomb(0.1, 0.05, 1e-3, 2e-3))

    def rollers(phis, place):
        for i, phi in enumerate(phis):
            e_r = np.array([math.cos(phi), math.sin(phi), 0.0])
            skew = 0.0 if (place == "radial" and i == 0) else rng.choice([-1, 1]) * rng.uniform(0.15, 0.25)
            if place == "radial":
                center, turn = R_ROW * e_r, Rotation.from_rotvec(skew * e_r)
            else:
                center = RT_THRUST * e_r + [0, 0, Z_THRUST]
                turn = Rotation.from_rotvec([0, 0, skew]) * Rotation.from_quat(quat_z_to(e_r), scalar_first=True)
            axis = turn.apply([0.0, 0.0, 1.0])
            r = mb.add_body(f"{place}{i}", 0.02, (2e-7, 2e-7, 3e-7), center,
                            orientation=turn.as_quat(scalar_first=True), omega_rad_s=(0, 0, -300.0))
            yield i, r, phi, center, axis, skew

    for i, r, phi, center, axis, skew in rollers([0.0, 1.6, 3.1, 4.8], "radial"):
        mb.add_roller_raceway(r, "inner", s_in, R_ROLLER, L_ROLLER, race, N_SLICES, crown, name=f"r{i} inner race")
        mb.add_roller_raceway(r, "outer", s_out, R_ROLLER, L_ROLLER, race_c, N_SLICES, crown, name=f"r{i} outer race")
        for sign, kind, ring in ((1, "plane_down", "outer"), (-1, "plane_up", "outer" if i == 0 else "inner")):
            value = _rib_for(kind, center, axis, R_ROLLER, L_ROLLER, sign, EDGE, rng.uniform(-5e-6, 2e-5))
            mb.add_roller_rib(r, ring, mb.add_surface(ring, kind, value), R_ROLLER, L_ROLLER, sign, EDGE, rib,
                              name=f"r{i} rib {sign:+d}")
        # slot: both ends of a skewed roller reach a face ((L/2) sin ψ off the centre plane); roller 0 is shifted
        reach = 0.5 * L_ROLLER * abs(math.sin(skew))
        clearance = reach + 1e-4 if i == 0 else reach - [0.0, -1e-5, 1.5e-5, 5e-6][i]
        shift = (clearance + 1e-5) / R_ROW if i == 0 else 0.0
        mb.add_element_pocket(r, "cage", mb.add_pocket("cage", "slot", phi + shift, R_ROW, 0.0, clearance),
                              R_ROLLER, pocket_law, L_ROLLER)
    for i, r, phi, center, axis, skew in rollers([0.7, 2.9, 5.0], "thrust"):
        mb.add_roller_raceway(r, "inner", t_low, R_THRUST, L_THRUST, race_c, N_SLICES, crown, name=f"t{i} lower race")
        mb.add_roller_raceway(r, "outer", t_up, R_THRUST, L_THRUST, race, N_SLICES, crown, name=f"t{i} upper race")
        for sign, kind, ring in ((-1, "inner_cylinder", "inner"), (1, "outer_cylinder", "outer")):
            value = _rib_for(kind, center, axis, R_THRUST, L_THRUST, sign, EDGE_THRUST, rng.uniform(-5e-6, 2e-5))
            mb.add_roller_rib(r, ring, mb.add_surface(ring, kind, value), R_THRUST, L_THRUST, sign, EDGE_THRUST, rib,
                              name=f"t{i} rib {sign:+d}")
        clearance = 0.5 * L_THRUST * abs(math.sin(skew)) - [-1e-5, 1e-5, 2e-5][i]
        mb.add_element_pocket(r, "cage", mb.add_pocket("cage", "slot", phi, RT_THRUST, Z_THRUST, clearance),
                              R_THRUST, pocket_law, L_THRUST)
    return mb.finalize()


def _perturbed(model, state, rng, dx, dphi, v_scale, keep_orientation=(), slow=False):
    """State with every movable body shifted by ~dx, turned by ~dphi and given random velocities
    (added to the built ones, or replacing them when ``slow``)."""
    q, v = state.q.copy(), np.zeros_like(state.v) if slow else state.v.copy()
    for i in range(model.n_bodies):
        if not model.arrays.body_free[i].any():
            continue
        q[i, :3] += rng.normal(size=3) * dx
        if i not in keep_orientation:
            turned = Rotation.from_rotvec(rng.normal(size=3) * dphi) * Rotation.from_quat(q[i, 3:], scalar_first=True)
            q[i, 3:] = turned.as_quat(scalar_first=True)
        v[i] += rng.normal(size=6) * v_scale
    return type(state)(state.t, q, v)


def _forces(model, state):
    w = make_work(model)
    status, index = FK.compute_forces(model.arrays, state.t, state.q, state.v, state.eta, state.eta_dot, w)
    assert (status, index) == (FK.STATUS_OK, -1)
    return w


def _compare_with_twin(model, state):
    """compute_forces against the twin: body sums to rtol × Σ|terms| (their round-off scale), contact
    forces relative to the largest of the array, penetrations to rtol plus ATOL_M."""
    w = _forces(model, state)
    want = ref.compute_forces(model.arrays, state.t, state.q, state.v)
    _close(w.body_f, want.body_f, atol=RTOL * want.body_f_scale[:, None])
    _close(w.body_t, want.body_t, atol=RTOL * want.body_t_scale[:, None])
    _close(w.contact_delta, want.delta, atol=ATOL_M)
    for name in ("fn", "ft", "slip"):
        _close_scaled(getattr(w, f"contact_{name}"), getattr(want, name))
    _close(w.contact_angle, want.angle, atol=1e-14)
    _close(w.contact_theta, want.theta, atol=1e-14)
    # contact point and normal (a pair of several points: those of its most loaded one)
    _close(w.contact_point, want.point, atol=POINT_ATOL_M)
    _close(w.contact_normal, want.normal, atol=NORMAL_ATOL)
    _close(w.energy, [want.energy_contact, want.energy_bushing])
    return w


def _random_states(model, state, rng, n, dx, dphi, keep_orientation=()):
    """n states: alternately fast (slip of m/s) and slow (slip in the friction laws' transition range)."""
    for k in range(n):
        slow = k % 2 == 1
        scale = np.array([1e-3] * 3 + [0.1] * 3) if slow else np.array([0.1] * 3 + [100.0] * 3)
        st = _perturbed(model, state, rng, dx, dphi, scale, keep_orientation, slow)
        st.t = rng.uniform(-0.01, 0.05)                          # before, inside and after the load history
        yield st


def _mix_checks(ws, model):
    """The states exercise what they are meant to: contacts in penetration and out, slipping fast and slowly."""
    delta = np.array([w.contact_delta for w in ws])
    slip = np.array([w.contact_slip for w in ws])[delta > 0]
    for kind in set(model.pair_kinds) - {"roller_raceway"}:       # raceways: some slices are always loaded
        sel = delta[:, model.pairs_of(kind)]
        assert np.any(sel > 0) and np.any(sel <= 0), kind
    assert np.any(slip > 2e-3) and np.any((slip > 0) & (slip < 1e-3))


# -- the force stage against its twin ------------------------------------------------------------
def test_contact_force_matches_twin_is_zero_when_touching_and_reverses_friction_with_slip():
    model, state = _ball_bearing()
    m = model.arrays
    rng = np.random.default_rng(SEED + 8)
    st = _perturbed(model, state, rng, 1e-5, 1e-3, np.array([0.1] * 3 + [100.0] * 3))
    q, v = st.q, st.v
    for c in range(model.n_pairs):
        a, b = m.pair_a[c], m.pair_b[c]
        normal = Rotation.random(random_state=rng).apply([0.0, 0.0, 1.0])
        p = q[a, :3] - R_BALL * normal
        args = (m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c], m.pair_dmax[c], m.pair_fric[c])
        for delta in (rng.uniform(1e-7, 5e-5), 0.0, -1e-6):        # penetrating, touching, apart
            bf, bt = np.zeros((model.n_bodies, 3)), np.zeros((model.n_bodies, 3))
            got = FK.contact_force(q, v, bf, bt, m.pair_fric_p, c, a, b, *args, delta, *normal, *p)
            fn, slip, ft, e, force = ref.contact_force(m, q, v, c, delta, normal, p)
            _close(np.array(got), [fn, slip, ft, e], atol=0)
            _close(bf[a], force, atol=1e-12 * fn)
            _close(bf[b], -force, atol=1e-12 * fn)
            _close(bt[a], np.cross(p - q[a, :3], force), atol=1e-13 * fn)
            _close(bt[b], -np.cross(p - q[b, :3], force), atol=1e-13 * fn)
            if delta <= 0:
                assert got == (0.0, 0.0, 0.0, 0.0) and not bf.any() and not bt.any()
        # reversed slip (all velocities reversed, no damping): same normal force, friction reversed
        delta = 2e-5
        undamped = (m.pair_law[c], m.pair_k[c], m.pair_n[c], 0.0, m.pair_dmax[c], m.pair_fric[c])
        forces = []
        for sign in (1.0, -1.0):
            bf, bt = np.zeros((model.n_bodies, 3)), np.zeros((model.n_bodies, 3))
            got = FK.contact_force(q, sign * v, bf, bt, m.pair_fric_p, c, a, b, *undamped, delta, *normal, *p)
            forces.append((got, bf[a] - got[0] * normal))
        (g1, t1), (g2, t2) = forces
        assert g1 == pytest.approx(g2, rel=1e-14) and g1[2] > 0.0
        _close(t2, -t1, atol=1e-14 * g1[2])
        assert t1 @ (ref.point_velocity(q[a], v[a], p) - ref.point_velocity(q[b], v[b], p)) < 0   # opposes slip


@pytest.mark.parametrize("strips", [None, 7])
def test_ball_bearing_forces_match_twin(strips):
    model, state = _ball_bearing(strips=strips)
    rng = np.random.default_rng(SEED + 9)
    ws = [_compare_with_twin(model, st) for st in _random_states(model, state, rng, 8, 1e-5, 3e-4)]
    _mix_checks(ws, model)
    # corners: ball 0 at θ = 0 exactly on the outer groove, ball 1 just below 2π on the inner groove
    # (inner ring turned to just past it), at the knots and ends of the load history, and at rest
    corner = state.copy()
    ball1 = state.q[model.body("ball1")]
    corner.q[model.body("inner"), 3:] = quat_from_axis_angle((0, 0, 1), math.atan2(ball1[1], ball1[0]) + 1e-12)
    for t in (0.0, 0.01, 0.04, 0.1, -1.0):
        corner.t = t
        w = _compare_with_twin(model, corner)
    ball0_outer, ball1_inner = model.pair_names.index("ball0–outer"), model.pair_names.index("ball1–inner")
    assert w.contact_theta[ball0_outer] == 0.0
    assert 2 * math.pi - 2e-12 < w.contact_theta[ball1_inner] < 2 * math.pi
    corner.v[:] = 0.0
    w = _compare_with_twin(model, corner)
    assert np.all(w.contact_slip == 0.0) and np.all(w.contact_ft == 0.0)     # no slip, no friction


def test_roller_bearing_forces_match_twin():
    model, state = _roller_bearing()
    rng = np.random.default_rng(SEED + 10)
    radial0 = model.body("radial0")
    ws = [_compare_with_twin(model, st)
          for st in _random_states(model, state, rng, 8, 3e-6, 1e-4, keep_orientation=(radial0,))]
    _mix_checks(ws, model)
    ws.append(_compare_with_twin(model, state))                          # as built
    for w in ws:                                                         # ribs of roller 0: parallel ends
        for c in (model.pair_names.index("r0 rib +1"), model.pair_names.index("r0 rib -1")):
            assert w.contact_angle[c] == 0.0


def test_kinetic_energy_matches_twin():
    model, _ = _ball_bearing()
    rng = np.random.default_rng(SEED + 6)
    v = rng.normal(size=(model.n_bodies, 6)) * [0.1, 0.1, 0.1, 200, 200, 200]
    m = model.arrays
    want = ref.kinetic_energy(m.body_mass, m.body_inertia, v)
    assert EX.kinetic_energy(m.body_mass, m.body_inertia, v) == pytest.approx(want, rel=1e-13)


# -- balance laws ------------------------------------------------------------------------------------
def _assert_balanced(model, w, q):
    """Σ F_i = 0 and Σ (r_i × F_i + M_i) = 0 over all bodies (fixed ones included), to round-off."""
    scale = np.sum(w.contact_fn + w.contact_ft) + np.abs(w.body_f).sum()
    assert np.abs(w.body_f.sum(axis=0)).max() < 1e-13 * scale
    total_moment = np.sum(np.cross(q[:, :3], w.body_f) + w.body_t, axis=0)
    assert np.abs(total_moment).max() < 1e-13 * scale * 0.1            # lever arms ≤ 0.1 m


@pytest.mark.parametrize("builder", ["ball", "ball-strips", "roller"])
def test_internal_forces_obey_action_reaction_and_moment_balance(builder):
    model, state = (_roller_bearing() if builder == "roller"
                    else _ball_bearing(external=False, strips=5 if builder == "ball-strips" else None))
    assert not model.arrays.body_force.any() and model.arrays.load_body.size == 0
    rng = np.random.default_rng(SEED + 11)
    for st in _random_states(model, state, rng, 6, 1e-5 if builder == "ball" else 3e-6, 3e-4):
        w = _forces(model, st)
        assert np.sum(w.contact_fn > 0) > model.n_pairs // 2
        _assert_balanced(model, w, st.q)


def test_bushing_force_and_torque_are_minus_the_gradient_of_its_energy():
    # Bodies built in different orientations (q_ref ≠ 1). Translating b by x or turning it by a small
    # world rotation θ about its centre (the bushing point) changes the energy E; F_b = −∂E/∂x and
    # M_b = −∂E/∂θ (to O(|θ|) relative, the small-angle form of the rotation vector).
    rng = np.random.default_rng(SEED + 12)
    mb = ModelBuilder()
    mb.add_body("a", 1.0, (1.0, 1.0, 1.0), (0.1, 0.0, 0.0), orientation=_random_quat(rng), motion=Fixed())
    mb.add_body("b", 1.0, (1.0, 1.0, 1.0), (0.0, 0.2, 0.1), orientation=_random_quat(rng))
    mb.add_bushing("a", "b", (0.0, 0.2, 0.1), (1e6, 2e6, 3e6, 1e2, 2e2, 3e2))
    model, state = mb.finalize()
    assert abs(model.arrays.bush_q_ref[0, 0]) < 0.99
    base = state.copy()
    base.q[1, :3] += rng.normal(size=3) * 1e-5
    base.q[1, 3:] = (Rotation.from_rotvec(rng.normal(size=3) * 1e-4)
                     * Rotation.from_quat(base.q[1, 3:], scalar_first=True)).as_quat(scalar_first=True)
    w = _forces(model, base)
    f_b, m_b = w.body_f[1].copy(), w.body_t[1].copy()

    def energy(dx=np.zeros(3), dtheta=np.zeros(3)):
        st = base.copy()
        st.q[1, :3] += dx
        st.q[1, 3:] = (Rotation.from_rotvec(dtheta) * Rotation.from_quat(st.q[1, 3:], scalar_first=True)).as_quat(
            scalar_first=True)
        return _forces(model, st).energy[1]

    h_x, h_t, eye = 1e-7, 1e-7, np.eye(3)
    grad_x = np.array([(energy(dx=h_x * e) - energy(dx=-h_x * e)) / (2 * h_x) for e in eye])
    grad_t = np.array([(energy(dtheta=h_t * e) - energy(dtheta=-h_t * e)) / (2 * h_t) for e in eye])
    _close(f_b, -grad_x, rtol=1e-6, atol=1e-6 * np.abs(f_b).max())
    _close(m_b, -grad_t, rtol=2e-3, atol=2e-3 * np.abs(m_b).max())     # the force acts at b's centre
