"""Four-point contact (gothic-arch) ball rows against an independent model and closed forms.

The independent model (``_Reference``) is written from the geometry of the two rings, not from
the solver's centre-distance vectors: for every ball and diagonal it places the curvature centres
of the moving and of the fixed ring's arc explicitly (each (f − 0.5)·D from the ball centre along
the diagonal, the radial clearance moving the two gothic arches apart radially), displaces the
moving one with the small-rotation matrix I + [θ]ₓ and the translation, takes the ball's
section plane (the ball keeps its azimuth), and computes δ = |c_m − c_f| − A, α from the
components, Q = K·δ^1.5 on the diagonal's own side (0 ≤ α ≤ shoulder), and the equilibrium
with scipy.optimize.root. Small rotations and moment arms at the reference positions are the
model's own assumptions (Harris & Kotzalas, *Advanced Concepts of Bearing Technology*, 5th ed.,
ch. 1), so the two must agree to the solvers' tolerances: 1e-6 relative is asserted (the solver
converges to 1e-12, the reference to xtol 1e-13).

Geometry of the four-point row: Amasorrain, Sagartzazu & Damián, Mech. Mach. Theory 38 (2003)
479–496 (each diagonal an angular-contact pair, curvature centres A = (f_i + f_o − 1)·D apart).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq, root

from mbd_core.quasistatic import Bearing, FourPointRow, RingLoad, solve_load_distribution
from mbd_core.quasistatic.contacts import contact_sets

TOL = 1e-6  # relative agreement asserted against the independent model (module docstring)


def _row(clearance_m: float = 0.0, moving: str = "inner", n_balls: int = 60, **kw) -> FourPointRow:
    return FourPointRow("fp", n_balls, 30e-3, 1.2, math.radians(45.0), 0.535, 0.525, moving,
                        radial_clearance_m=clearance_m, **kw)


class _Reference:
    """Independent four-point row model (module docstring)."""

    def __init__(self, row: FourPointRow):
        self.row = row
        Z, D = row.n_balls, row.ball_diameter_m
        psi = row.first_azimuth_rad + 2 * np.pi * np.arange(Z) / Z
        self.e_r = np.stack([np.cos(psi), np.sin(psi), 0 * psi], 1)
        self.e_t = np.stack([-np.sin(psi), np.cos(psi), 0 * psi], 1)
        self.e_z = np.array([0.0, 0.0, 1.0])
        sr = 1.0 if row.moving_raceway == "inner" else -1.0
        self.sr = sr
        ball = 0.5 * row.pitch_diameter_m * self.e_r + row.axial_position_m * self.e_z
        a0 = row.contact_angle_rad
        self.c_m, self.c_f = [], []  # per diagonal (+α, −α): (Z, 3) curvature centres
        for sigma in (1.0, -1.0):
            n = sr * math.cos(a0) * self.e_r + sigma * math.sin(a0) * self.e_z
            # the moving ring's arc centre lies beyond the ball centre from its contact point, the
            # fixed ring's on the other side; a radial clearance c separates the arches by c, taken
            # in the fixed ring's groove (the moving ring's moment arms are those of the nominal
            # geometry, as in the solver; the other choice moves them by c, a 1e-5 effect)
            shift = row.radial_clearance_m * sr * self.e_r
            self.c_m.append(ball + (row.conformity_moving - 0.5) * D * n)
            self.c_f.append(ball - (row.conformity_fixed - 0.5) * D * n + shift)
        self.A = (row.conformity_moving + row.conformity_fixed - 1.0) * D
        self.K = row.contact_stiffness()

    def contacts(self, q: np.ndarray):
        """Loads Q (Z, 2), angles α (Z, 2), approaches δ (Z, 2) and the generalised force (5,)."""
        d, th = q[:3], np.array([q[3], q[4], 0.0])
        Rot = np.eye(3) + np.array([[0, -th[2], th[1]], [th[2], 0, -th[0]], [-th[1], th[0], 0]])
        Q, al, de = (np.zeros((self.row.n_balls, 2)) for _ in range(3))
        F = np.zeros(3)
        M = np.zeros(3)
        lo, hi = 0.0, self.row.shoulder_angle_rad
        for j, sigma in enumerate((1.0, -1.0)):
            cm = self.c_m[j] @ Rot.T + d
            v = cm - self.c_f[j]
            v -= np.sum(v * self.e_t, 1)[:, None] * self.e_t  # the ball stays in its section plane
            L = np.linalg.norm(v, axis=1)
            delta = L - self.A
            alpha = np.arctan2(sigma * v[:, 2], self.sr * np.sum(v * self.e_r, 1))
            on = (alpha >= lo) & (alpha <= hi) & (delta > 0)
            Qj = np.where(on, self.K * np.maximum(delta, 0) ** 1.5, 0.0)
            f = -(Qj / L)[:, None] * v  # force of the balls on the moving ring
            F += f.sum(0)
            M += np.cross(self.c_m[j], f).sum(0)  # moment arms at the reference positions
            Q[:, j], al[:, j], de[:, j] = Qj, alpha, delta
        return Q, al, de, np.concatenate([F, M[:2]])

    def solve(self, load: RingLoad, q_start: np.ndarray) -> np.ndarray:
        f = load.as_array()
        Rm = 0.5 * self.row.pitch_diameter_m
        scale_q = np.array([1e-4, 1e-4, 1e-4, 1e-4 / Rm, 1e-4 / Rm])
        scale_f = max(np.linalg.norm(f * np.array([1, 1, 1, 1 / Rm, 1 / Rm])), 1.0)

        def res(y):
            r = self.contacts(y * scale_q)[3] + f
            return r * np.array([1, 1, 1, 1 / Rm, 1 / Rm]) / scale_f

        sol = root(res, q_start / scale_q, method="hybr", options={"xtol": 1e-13})
        assert np.linalg.norm(res(sol.x)) < 1e-10, sol.message
        return sol.x * scale_q


def _compare(row: FourPointRow, load: RingLoad):
    dist = solve_load_distribution(Bearing("b", (row,)), load, tolerance=1e-12)
    ref = _Reference(row)
    # the reference starts 5 % off the solver's displacement and finds its own root
    q_ref = ref.solve(load, dist.displacement * 1.05 + 1e-7)
    Q, al, _, _ = ref.contacts(q_ref)
    res = dist.rows[0]
    np.testing.assert_allclose(dist.displacement, q_ref, rtol=TOL, atol=TOL * np.abs(q_ref).max())
    np.testing.assert_allclose(res.contact_load_N, Q, rtol=TOL, atol=TOL * Q.max())
    loaded = Q > TOL * Q.max()
    np.testing.assert_allclose(res.contact_angles_rad[loaded], al[loaded], rtol=TOL)
    borderline = np.abs(Q) <= TOL * Q.max()  # a diagonal loaded to the rounding level may count either way
    n_ref = 2 * np.count_nonzero(Q > 0, axis=1)
    ok = ~borderline.any(axis=1)
    np.testing.assert_array_equal(res.n_contact_points[ok], n_ref[ok])
    return dist, Q, al


LOADS = {
    "axial": RingLoad(Fz_N=2e5),
    "radial": RingLoad(Fx_N=1e5),
    "moment": RingLoad(My_Nm=1e5),
    "combined": RingLoad(Fx_N=4e4, Fy_N=-2e4, Fz_N=-1.5e5, Mx_Nm=3e4, My_Nm=-6e4),
}


@pytest.mark.parametrize("clearance_m", [0.0, 60e-6, -15e-6])
@pytest.mark.parametrize("case", list(LOADS))
def test_diagonal_loads_and_angles_match_the_independent_model(case, clearance_m):
    dist, Q, _ = _compare(_row(clearance_m), LOADS[case])
    res = dist.rows[0]
    # load_N is the larger diagonal load of each ball
    np.testing.assert_array_equal(res.load_N, res.contact_load_N.max(axis=1))
    assert Q.max() > 0


def test_outer_moving_ring_and_offset_row_match_the_independent_model():
    row = _row(30e-6, "outer", axial_position_m=0.05, first_azimuth_rad=0.1)
    _compare(row, RingLoad(Fx_N=5e4, Fz_N=8e4, Mx_Nm=-4e4))


def test_two_to_four_contact_points_under_growing_radial_share():
    """At a fixed axial load the radial share opens a zone of four-point balls around ψ = 0 that grows
    with the radial load; the count per ball and the azimuth where it changes agree with the reference."""
    row = _row(20e-6)
    widths = []
    for Fx in (0.0, 2e4, 6e4, 1.5e5, 4e5):
        dist, Q, _ = _compare(row, RingLoad(Fx_N=Fx, Fz_N=1.5e5))
        n = dist.rows[0].n_contact_points
        four = n == 4
        widths.append(int(four.sum()))
        if four.any():
            psi = np.degrees(np.angle(np.exp(1j * dist.rows[0].azimuth_rad)))
            # the four-point zone is centred on the radial load (ψ = 0), symmetric about it
            assert np.all(np.abs(psi[four]) < 90.0)
            np.testing.assert_array_equal(four, four[(-np.arange(row.n_balls)) % row.n_balls])
    assert widths[0] == 0 and widths[-1] > 0
    assert widths == sorted(widths)


def test_pure_axial_load_closed_form():
    """Zero clearance, pure axial load: one diagonal of every ball carries Q = F_a/(Z·sin α), with
    the loaded angle from F_a = Z·K·A^1.5·sin α·(cos α0/cos α − 1)^1.5 (Harris & Kotzalas, *Rolling
    Bearing Analysis*, 5th ed., ch. 7, thrust-loaded angular-contact bearing); the other diagonal is
    unloaded (2 contact points). Tolerance 1e-8: the solver's tolerance is 1e-12."""
    row = _row(0.0)
    Fa = 3e5
    dist = solve_load_distribution(Bearing("b", (row,)), RingLoad(Fz_N=Fa), tolerance=1e-12)
    A, a0, K, Z = row.curvature_centre_distance_m, row.contact_angle_rad, row.contact_stiffness(), row.n_balls
    alpha = brentq(lambda a: Z * K * A**1.5 * math.sin(a) * (math.cos(a0) / math.cos(a) - 1) ** 1.5 - Fa,
                   a0 + 1e-12, row.shoulder_angle_rad, xtol=1e-15)
    res = dist.rows[0]
    np.testing.assert_allclose(res.contact_load_N[:, 0], Fa / (Z * math.sin(alpha)), rtol=1e-8)
    np.testing.assert_allclose(res.contact_angles_rad[:, 0], alpha, rtol=1e-8)
    assert not res.contact_load_N[:, 1].any()
    assert np.all(res.n_contact_points == 2)


def test_pure_moment_closed_form():
    """Zero clearance, pure tilting moment, many balls: each diagonal carries Q = Q_max·cos^1.5 ψ over
    its loaded half (diagonal +α where the tilt lifts the moving ring, −α on the other half), so
    M = Q_max·Z·d_m·sin α·(1/(2π))·∫_{−π/2}^{π/2} cos^2.5 ψ dψ (the two halves, each
    Σ Q·sin α·(d_m/2)·cos ψ with the sum over Z/(2π)·dψ; the single-row form of Harris & Kotzalas,
    ch. 7, moment loading, with J_m, taken over both diagonals). The approach is linear in the tilt
    only to O(δ/A), and α moves by O(δ/A) from α0: the tolerance is 3·δ_max/A (here ≈ 0.4 %)."""
    row = FourPointRow("fp", 200, 30e-3, 2.4, math.radians(45.0), 0.535, 0.525)
    M = 5e3
    dist = solve_load_distribution(Bearing("b", (row,)), RingLoad(My_Nm=M), tolerance=1e-12)
    res = dist.rows[0]
    Qmax = float(res.contact_load_N.max())
    a = float(res.contact_angles_rad.flat[np.argmax(res.contact_load_N)])
    integral = quad(lambda p: math.cos(p) ** 2.5, -math.pi / 2, math.pi / 2)[0]
    M_closed = Qmax * row.n_balls * row.pitch_diameter_m * math.sin(a) * integral / (2 * math.pi)
    tol = 3 * float(res.contact_approach_m.max()) / row.curvature_centre_distance_m
    assert tol < 0.01
    assert M_closed == pytest.approx(M, rel=tol)
    # each ball touches on one diagonal only (2 points), each diagonal carries half the balls
    loaded = res.contact_load_N > 0
    assert np.all(res.n_contact_points[res.load_N > 0] == 2)
    assert abs(int(loaded[:, 0].sum()) - int(loaded[:, 1].sum())) <= 2


def test_shoulder_unloads_the_diagonal_and_truncation_is_flagged():
    """A diagonal pushed past the shoulder angle carries nothing (the ball rides over it, as at a
    groove edge); near the shoulder the contact ellipse (±a/(f·D) about α on the arc) runs over it."""
    # with clearance the free contact angle is above α0, and a radial share tips the balls on the far
    # side beyond a 50° shoulder
    row = _row(60e-6, shoulder_angle_rad=math.radians(50.0))
    bearing = Bearing("b", (row,))
    dist, Q, al = _compare(row, RingLoad(Fx_N=1e4, Fz_N=1e4))
    res = dist.rows[0]
    de = res.contact_approach_m
    over = (al > row.shoulder_angle_rad) & (de > 0)
    assert over.any() and not res.contact_load_N[over].any()
    sets = contact_sets(bearing, dist)
    assert [s.label for s in sets] == ["inner groove, diagonal +α", "outer groove, diagonal +α",
                                       "inner groove, diagonal −α", "outer groove, diagonal −α"]
    for s, j in zip(sets, (0, 0, 1, 1)):
        np.testing.assert_array_equal(s.load_N, res.contact_load_N[:, j])
        f = row.conformity_moving if s.raceway == "inner" else row.conformity_fixed
        half = s.semi_major_m / (f * row.ball_diameter_m)
        alpha = res.contact_angles_rad[:, j]
        expected = (s.load_N > 0) & ((alpha + half > row.shoulder_angle_rad) | (alpha - half < 0.0))
        np.testing.assert_array_equal(s.truncated, expected)
    assert any(s.truncated.any() for s in sets)
    assert any("shoulder" in w or "groove edge" in w or "limit" in w for w in dist.warnings)


@pytest.mark.parametrize("field, value", [
    ("shoulder_angle_rad", math.radians(40.0)),
    ("shoulder_angle_rad", math.radians(95.0)),
    ("contact_angle_rad", 0.0),
    ("conformity_fixed", 0.5),
    ("radial_clearance_m", 1.0),
    ("n_balls", 0),
])
def test_bad_input_names_the_field(field, value):
    kw = dict(name="fp", n_balls=60, ball_diameter_m=30e-3, pitch_diameter_m=1.2)
    kw[field] = value
    with pytest.raises(ValueError, match=field.replace("_rad", "").replace("_m", "")):
        FourPointRow(**kw)


@pytest.mark.parametrize("clearance_m", [40e-6, 120e-6])
def test_clearance_is_the_free_play_of_the_gothic_arches(clearance_m):
    """A radial clearance c moves the arches apart radially, both diagonals alike. Under a small
    radial load F the balls about ψ = 0 touch on both diagonals: s = (A·cos α0 − c + x·cos ψ, ±A·sin α0)
    (the tangential part of the motion does not press the ball), Σ 2·K·(|s| − A)^1.5·(s_r/|s|)·cos ψ = F,
    so the ring moves by the free play c plus the elastic part. Under
    a small axial load every ball's +α diagonal touches: s = (A·cos α0 − c, A·sin α0 + z),
    Z·K·(|s| − A)^1.5·s_z/|s| = F; the free play is √(A² − (A·cos α0 − c)²) − A·sin α0. Both solved
    here with brentq; agreement to 1e-9 relative (the solver's tolerance 1e-12)."""
    row = _row(clearance_m)
    bearing = Bearing("b", (row,))
    A, a0, K, Z = row.curvature_centre_distance_m, row.contact_angle_rad, row.contact_stiffness(), row.n_balls
    F = 100.0

    psi = 2 * np.pi * np.arange(Z) / Z

    def radial(x):
        sr, sz = A * math.cos(a0) - clearance_m + x * np.cos(psi), A * math.sin(a0)
        L = np.hypot(sr, sz)
        return float(np.sum(2 * K * np.maximum(L - A, 0.0) ** 1.5 * sr / L * np.cos(psi))) - F

    def axial(z):
        sr, sz = A * math.cos(a0) - clearance_m, A * math.sin(a0) + z
        L = math.hypot(sr, sz)
        return Z * K * max(L - A, 0.0) ** 1.5 * sz / L - F

    z_free = math.sqrt(A**2 - (A * math.cos(a0) - clearance_m) ** 2) - A * math.sin(a0)
    x_ref = brentq(radial, clearance_m, clearance_m + 1e-4, xtol=1e-18, rtol=1e-14)
    z_ref = brentq(axial, z_free, z_free + 1e-4, xtol=1e-18, rtol=1e-14)
    q = solve_load_distribution(bearing, RingLoad(Fx_N=F), tolerance=1e-12).displacement
    assert q[0] == pytest.approx(x_ref, rel=1e-9)
    res = solve_load_distribution(bearing, RingLoad(Fz_N=F), tolerance=1e-12)
    assert res.displacement[2] == pytest.approx(z_ref, rel=1e-9)
    assert 0.0 < z_ref - z_free < 0.05 * z_free and np.all(res.rows[0].n_contact_points == 2)


def test_flexible_model_without_rings_reproduces_the_rigid_four_point_row():
    """A four-point row in the flexible-ring model with no flexible ring is the rigid-ring problem:
    the same per-diagonal loads as :func:`solve_load_distribution` (1e-9 of the largest; both solve
    to 1e-10). Flexible rings on four-point rows: tests/test_bearing_rings.py."""
    from mbd_core.quasistatic.flexible import build_flexible_model
    from mbd_core.quasistatic.flexible_solve import solve_flexible_load_distribution

    bearing = Bearing("b", (_row(),))
    load = RingLoad(Fx_N=2e4, Fz_N=-5e4, My_Nm=3e4)
    flex = solve_flexible_load_distribution(build_flexible_model(bearing), load)
    rigid = solve_load_distribution(bearing, load)
    q_f, q_r = flex.rows[0].contact_load_N, rigid.rows[0].contact_load_N
    assert np.max(np.abs(q_f - q_r)) <= 1e-9 * q_r.max()


def test_validity_warnings_name_the_diagonal():
    """A heavy axial load widens the contact ellipses of the +α diagonal past the 70° shoulder: the
    warning names the row, groove and diagonal, and agrees with the contact sets' truncation
    (ellipse ±a/(f·D) about α on the arc, Harris & Kotzalas ch. 6); the unloaded −α diagonal has none."""
    row = _row(0.0)
    bearing = Bearing("b", (row,))
    dist = solve_load_distribution(bearing, RingLoad(Fz_N=2e6))
    sets = {s.label: s for s in contact_sets(bearing, dist)}
    for raceway in ("inner", "outer"):
        s = sets[f"{raceway} groove, diagonal +α"]
        assert s.truncated.all()
        assert any(w.startswith(f"row 'fp', {raceway} groove, diagonal +α") and "[0°, 70°]" in w
                   for w in dist.warnings)
        assert not sets[f"{raceway} groove, diagonal −α"].truncated.any()
    assert not any("−α" in w for w in dist.warnings)
