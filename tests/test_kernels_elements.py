"""Element contact geometry, load splines, rotations, kinetic energy and bushing rotations of the
multibody kernels against their numpy twins (tests/reference/multibody.py), on seeded random and corner
inputs. Tolerances: tests/test_kernels_multibody.py (module docstring).

A roller end nearly parallel to its rib is the exception: its rim point is computed to ρ ε/|u| only
(test_roller_end_matches_twin_on_tilted_rollers); the roller model stays out of that range.
"""

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.spatial.transform import Rotation

from mbd_core.kernels import element_contacts as EC
from mbd_core.kernels import explicit as EX
from mbd_core.kernels import forces as FK
from mbd_core.kernels.roller_slices import (
    RACEWAY_INNER_CYLINDER,
    RACEWAY_OUTER_CYLINDER,
    RACEWAY_PLANE_DOWN,
    RACEWAY_PLANE_UP,
)
from mbd_core.kernels.splines import spline_value
from mbd_core.multibody import quat_from_axis_angle
from tests.kernel_checks import ATOL_M, SEED, close as _close, close_scaled as _close_scaled, random_quat as _random_quat
from tests.reference import multibody as ref


# -- element contact geometry -----------------------------------------------------------------------
def _geometry_close(got, want):
    """(δ, m, p) of a kernel against the twin's (δ, m, p)."""
    _close(got[0], want[0], atol=ATOL_M)
    _close(np.array(got[1:4]), want[1], atol=1e-15)
    _close(np.array(got[4:7]), want[2], atol=ATOL_M)


def test_ball_ball_matches_twin_on_random_and_touching_spheres():
    rng = np.random.default_rng(SEED)
    for _ in range(200):
        xa = rng.uniform(-0.1, 0.1, 3)
        ra, rb = rng.uniform(1e-3, 0.02, 2)
        xb = xa + (ra + rb + rng.uniform(-1e-4, 1e-4)) * Rotation.random(random_state=rng).apply([1.0, 0, 0])
        _geometry_close(EC.ball_ball(xa, xb, ra, rb), ref.ball_ball(xa, xb, ra, rb))
    # touching exactly (δ = 0 in floating point): 0.25 = 0.125 + 0.125, all exact binary numbers
    xa, xb = np.array([0.5, 0.25, 0.0]), np.array([0.25, 0.25, 0.0])
    got = EC.ball_ball(xa, xb, 0.125, 0.125)
    assert got[0] == 0.0
    _geometry_close(got, ref.ball_ball(xa, xb, 0.125, 0.125))
    # coincident centres: no normal exists; the kernel reports no contact instead of a NaN
    got = EC.ball_ball(xa, xa, 0.1, 0.1)
    assert got[0] == -math.inf and np.all(np.isfinite(got[1:]))


def _roller_pose(rng, kind):
    """A roller near its raceway position: axis z for plane ribs, radial for cylinder ribs; tilted."""
    th = rng.uniform(0, 2 * np.pi)
    e_r = np.array([math.cos(th), math.sin(th), 0.0])
    if kind in (RACEWAY_PLANE_UP, RACEWAY_PLANE_DOWN):
        center, axis = 0.04 * e_r + [0, 0, rng.normal(0, 1e-4)], np.array([0.0, 0.0, 1.0])
    else:
        center, axis = 0.045 * e_r + [0, 0, 0.03], e_r
    axis = axis + rng.normal(size=3) * rng.choice([1e-6, 1e-3, 0.1])
    return center + rng.normal(size=3) * 1e-5, axis / np.linalg.norm(axis)


# rib surfaces: (kind, value) that the end (sign) of a roller of radius 6 mm, length 12 mm touches
RIBS = [(RACEWAY_PLANE_DOWN, 0.006 - 1e-5, 1.0), (RACEWAY_PLANE_UP, -0.006 + 1e-5, -1.0),
        (RACEWAY_INNER_CYLINDER, 0.045 - 0.006 + 1e-5, -1.0), (RACEWAY_OUTER_CYLINDER, 0.045 + 0.006 - 1e-5, 1.0)]


@pytest.mark.parametrize("kind,value,sign", RIBS)
def test_roller_end_matches_twin_on_tilted_rollers(kind, value, sign):
    rng = np.random.default_rng(SEED + kind)
    radius, length, edge = 0.006, 0.012, 0.001
    for _ in range(100):
        center, axis = _roller_pose(rng, kind)
        point = np.empty(3)
        delta, mx, my, mz = EC.roller_end(center, axis, radius, length, sign, edge, kind, value, point)
        want = ref.roller_end(center, axis, radius, length, sign, edge, kind, value)
        # When the end is nearly parallel to the rib, u = d − (d·a) a is small and its direction is set
        # to ~ε/|u| only: the rim point moves by ρ ε/|u| (the kernel's u/|u| also gets an axial part
        # of that size, which changes δ), and a cylinder's normal e_r(p) turns by that over r(p).
        d = ref.into_surface(kind, center + sign * (0.5 * length - edge) * axis)
        atol = ATOL_M + 8 * np.finfo(float).eps * (radius - edge) / np.linalg.norm(d - (d @ axis) * axis)
        _close(delta, want[0], atol=atol)
        _close(np.array([mx, my, mz]), want[1], atol=1e-15 + atol / np.hypot(*want[2][:2]))
        _close(point, want[2], atol=atol)


@pytest.mark.parametrize("kind,value,sign", RIBS)
def test_roller_end_parallel_to_rib_touches_at_the_end_face_centre(kind, value, sign):
    # Degenerate projection (u = 0): the end face is parallel to the rib, so the contact point is the
    # centre of the end face c + σ (L/2) a and δ its depth. Exact binary numbers make δ = 0 exactly.
    radius, length, edge = 0.25, 1.0, 0.125
    if kind in (RACEWAY_PLANE_UP, RACEWAY_PLANE_DOWN):
        center, axis, value = np.array([3.0, 2.0, 0.0]), np.array([0.0, 0.0, 1.0]), 0.5 * sign
    else:
        center, axis, value = np.array([4.0, 0.0, 0.0]), np.array([1.0, 0.0, 0.0]), 4.0 + 0.5 * sign
    point = np.empty(3)
    got = EC.roller_end(center, axis, radius, length, sign, edge, kind, value, point)
    want = ref.roller_end(center, axis, radius, length, sign, edge, kind, value)
    _geometry_close((*got, *point), want)
    assert got[0] == 0.0                                            # touching
    assert point == pytest.approx(center + sign * 0.5 * length * axis, abs=0.0)
    assert np.array(got[1:]) == pytest.approx(-sign * axis, abs=0.0)   # pushes the roller back along its axis


def test_roller_end_tilted_towards_a_plane_rib_touches_on_the_rim():
    # A roller tilted by γ about x touches the rib z = Z on the rim torus: the deepest point is
    # e + ρ u + r_e ẑ with e the end's torus centre, so δ = e_z + ρ sin γ + r_e − Z.
    radius, length, edge, g = 0.006, 0.012, 0.001, 1e-3
    axis = np.array([0.0, -math.sin(g), math.cos(g)])
    center = np.array([0.04, 0.0, 0.0])
    point = np.empty(3)
    delta, *_ = EC.roller_end(center, axis, radius, length, 1.0, edge, RACEWAY_PLANE_DOWN, 0.006, point)
    e_z = (0.5 * length - edge) * math.cos(g)
    # δ ≈ 5 µm; absolute accuracy ρ ε / sin γ (see the random test above)
    assert delta == pytest.approx(e_z + (radius - edge) * math.sin(g) + edge - 0.006, rel=1e-12,
                                  abs=8 * np.finfo(float).eps * (radius - edge) / math.sin(g))


def test_pocket_cylinder_matches_twin_on_random_corner_and_centred_balls():
    rng = np.random.default_rng(SEED + 1)
    r_p, z_p, radius = 0.03, 0.001, 0.0075
    for angle in np.concatenate([rng.uniform(0, 2 * np.pi, 100), [0.0, 2 * np.pi - 1e-12, -0.0]]):
        for clearance in (2e-4, 0.0):                              # with and without clearance (zero gap)
            x = np.array([r_p * math.cos(angle), r_p * math.sin(angle), z_p]) + rng.normal(size=3) * 3e-4
            _geometry_close(EC.pocket_cylinder(x, radius, angle, r_p, z_p, clearance),
                            ref.pocket_cylinder(x, radius, angle, r_p, z_p, clearance))
    # ball exactly at the pocket centre, and moved along the pocket axis only: δ = −c_p, no normal
    for x in ([0.03, 0.0, 0.001], [0.031, 0.0, 0.001]):
        got = EC.pocket_cylinder(np.array(x), radius, 0.0, r_p, z_p, 2e-4)
        _geometry_close(got, ref.pocket_cylinder(np.array(x), radius, 0.0, r_p, z_p, 2e-4))
        assert got[0] == -2e-4 and got[1:4] == (0.0, 0.0, 0.0)
    # touching: centre moved by exactly the clearance along e_t at φ = 0 (exact binary numbers)
    got = EC.pocket_cylinder(np.array([0.5, 0.25, 0.0]), 0.125, 0.0, 0.5, 0.0, 0.25)
    assert got[0] == 0.0 and got[1:4] == (0.0, -1.0, 0.0) and got[4:] == (0.5, 0.375, 0.0)


def test_pocket_slot_matches_twin_and_reverses_its_normal_across_the_pocket():
    rng = np.random.default_rng(SEED + 2)
    r_p, z_p, radius = 0.04, 0.0, 0.006
    for angle in np.concatenate([rng.uniform(0, 2 * np.pi, 100), [0.0, 2 * np.pi - 1e-12]]):
        for clearance in (1e-4, 0.0):
            e_t = np.array([-math.sin(angle), math.cos(angle), 0.0])
            base = np.array([r_p * math.cos(angle), r_p * math.sin(angle), 0.003])
            e_r = np.array([math.cos(angle), math.sin(angle), 0.0])
            u = rng.uniform(1e-6, 3e-4)
            off = rng.uniform(-1e-3, 1e-3) * e_r + [0.0, 0.0, rng.uniform(-3e-3, 3e-3)]  # along the faces
            for side in (1.0, -1.0):                             # element against either face
                xs = base + off + side * u * e_t
                got = EC.pocket_slot(xs, radius, angle, r_p, z_p, clearance)
                _geometry_close(got, ref.pocket_slot(xs, radius, angle, r_p, z_p, clearance))
                assert np.array(got[1:4]) == pytest.approx(-side * e_t, abs=1e-15)
    # centred (u = 0 exactly, zero gap): touching, δ = 0; the normal is then a convention (either face)
    got = EC.pocket_slot(np.array([0.5, 0.0, 0.0]), 0.125, 0.0, 0.5, 0.0, 0.0)
    assert got[0] == 0.0 and abs(got[2]) == 1.0


# -- load splines ------------------------------------------------------------------------------
def test_spline_value_matches_cubic_spline_inside_at_knots_and_beyond_the_ends():
    rng = np.random.default_rng(SEED + 3)
    histories = []
    for n in (2, 3, 7):
        t = np.cumsum(rng.uniform(0.005, 0.1, n)) - 0.05
        histories.append((t, rng.normal(size=(n, 6)) * [1e3, 1e3, 5e3, 10, 10, 50]))
    # stored as the builder stores them: knots and PPoly coefficients (n_k, 4, 6), one zero row per load end
    knot_t = np.concatenate([t for t, _ in histories])
    coef = np.concatenate([np.concatenate([np.transpose(CubicSpline(t, f, axis=0).c, (1, 0, 2)), np.zeros((1, 4, 6))])
                           for t, f in histories])
    start = 0
    for t, f in histories:
        stop = start + t.size
        times = np.concatenate([rng.uniform(t[0] - 0.05, t[-1] + 0.05, 100), t,
                                [np.nextafter(t[-1], -np.inf), np.nextafter(t[0], np.inf), t[0] - 10.0, t[-1] + 10.0]])
        out = np.empty(6)
        for tt in times:
            spline_value(knot_t, coef, start, stop, tt, out)
            _close_scaled(out, ref.spline_value(t, f, tt))
        spline_value(knot_t, coef, start, stop, t[-1] + 1.0, out)     # held at the last tabulated load
        _close_scaled(out, f[-1])
        spline_value(knot_t, coef, start, stop, t[0] - 1.0, out)      # and at the first before the start
        assert np.all(out == f[0])
        start = stop


# -- rotations, spin, energy ----------------------------------------------------------------------------
def _random_poses(rng, n):
    q = np.empty((n, 7))
    q[:, :3] = rng.normal(size=(n, 3)) * 0.1
    q[:, 3:] = Rotation.random(n, random_state=rng).as_quat(scalar_first=True)
    q[0, 3:] = [1.0, 0.0, 0.0, 0.0]                               # identity
    q[1, 3:] = np.concatenate([[0.0], quat_from_axis_angle(rng.normal(size=3), math.pi)[1:]])   # half turn, w = 0
    q[2, 3:] = -q[3, 3:]                                          # the other cover of a rotation
    return q


def test_rotate_rotate_back_and_point_velocity_match_rotation_matrices():
    rng = np.random.default_rng(SEED + 4)
    q = _random_poses(rng, 40)
    v = rng.normal(size=(40, 6)) * [0.5, 0.5, 0.5, 300, 300, 300]
    for i in range(40):
        x = rng.normal(size=3)
        _close(FK.rotate(q, i, *x), ref.rotate(q[i], x), atol=1e-15)
        _close(FK.rotate_back(q, i, *x), ref.rotate_back(q[i], x), atol=1e-15)
        _close(FK.rotate_back(q, i, *FK.rotate(q, i, *x)), x, atol=1e-15)
        p = q[i, :3] + rng.normal(size=3) * 0.05
        _close_scaled(FK.point_velocity(q, v, i, *p), ref.point_velocity(q[i], v[i], p))
    assert FK.rotate(q, 2, 1.0, 2.0, 3.0) == pytest.approx(FK.rotate(q, 3, 1.0, 2.0, 3.0), rel=1e-15)


def test_spin_turns_by_h_omega_about_the_body_axis_and_keeps_a_unit_quaternion():
    rng = np.random.default_rng(SEED + 5)
    q = _random_poses(rng, 30)
    for i in range(30):
        omega, h = rng.normal(size=3) * rng.choice([1e-3, 1.0, 300.0]), rng.uniform(1e-6, 1e-2)
        before = q[i, 3:].copy()
        EX._spin(q, i, *omega, h)
        _close(ref.matrix(q[i, 3:]), ref.spin(before, omega, h), atol=1e-15)
        assert np.linalg.norm(q[i, 3:]) == pytest.approx(1.0, abs=1e-15)
    before = q[5].copy()
    EX._spin(q, 5, 0.0, 0.0, 0.0, 1e-3)                           # no rotation: untouched
    assert np.all(q[5] == before)


def test_bushing_rotation_is_the_rotation_vector_of_b_relative_to_its_rest_pose_in_a_frame():
    # b at rest relative to a: q_b = q_a q_ref; turning b by a small world rotation φ gives R_aᵀ φ + O(φ²)
    rng = np.random.default_rng(SEED + 7)
    for _ in range(50):
        qa, q_ref = _random_quat(rng), _random_quat(rng)
        phi = rng.normal(size=3) * 1e-4
        rest = Rotation.from_quat(qa, scalar_first=True) * Rotation.from_quat(q_ref, scalar_first=True)
        qb = (Rotation.from_rotvec(phi) * rest).as_quat(scalar_first=True)
        got = np.array(FK._small_rotation(qa, qb, q_ref))
        # e_vec is small but comes from products of unit quaternions: absolute round-off ~ε
        _close(got, ref.small_rotation(qa, qb, q_ref), atol=1e-15)
        _close(got, ref.matrix(qa).T @ phi, rtol=1e-7, atol=0)
