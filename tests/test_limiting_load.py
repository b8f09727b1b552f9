"""Limiting load curve against an independent rigid-ring ball model and the pure-axial closed form.

The independent model (written here in scalar components, after Harris & Kotzalas, *Advanced
Concepts of Bearing Technology*, 5th ed., ch. 1, "rigid rings"): the moving ring moves by x
(radial, along the x axis), z (axial) and tilts by θ about y. The moving groove's curvature
centre of the ball at ψ, on the locus radius R_m = d_m/2 + (f_m − ½)·D·cos α0 at height
z_m = ±(f_m − ½)·D·sin α0, moves radially by (x + θ·z_m)·cos ψ and axially by z − θ·R_m·cos ψ.
The centre-distance components are A·cos α0 + radial and ±A·sin α0 + axial, the approach is
their length less A, Q = K·δ^1.5 while the loaded angle stays on its groove side. Equilibrium in
(Fx, Fz, My) is solved by ``scipy.optimize.root``; the scale of a ray at which the largest ball
load reaches the load at p0 = 4.2 GPa (ISO 76) by ``scipy.optimize.brentq``. A four-point row is
two such diagonals per ball (±α0).
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq, root

from mbd_core.bearing.limiting_load import limiting_load_curve
from mbd_core.contact.hertz import ball_on_groove
from mbd_core.quasistatic import BallRow, Bearing, FourPointRow, RingLoad, solve_load_distribution

P_LIM = 4.2e9


class Model:
    def __init__(self, row, signs, angle_max_rad):
        self.row, self.signs, self.amax = row, signs, angle_max_rad
        Z, D = row.n_balls, row.ball_diameter_m
        self.psi = 2 * np.pi * np.arange(Z) / Z
        self.A, self.K, self.a0 = row.curvature_centre_distance_m, row.contact_stiffness(), row.contact_angle_rad
        self.R_m = row.pitch_diameter_m / 2 + (row.conformity_moving - 0.5) * D * math.cos(self.a0)
        self.h_m = (row.conformity_moving - 0.5) * D * math.sin(self.a0)
        # ball load at p0 = 4.2 GPa on the more curved (inner) and the outer groove: Q ∝ p0^3
        q = []
        for rw, f in (("inner", row.conformity_moving), ("outer", row.conformity_fixed)):
            c = ball_on_groove(D, f, row.pitch_diameter_m, self.a0, rw)
            q.append(1e3 * (P_LIM / float(c.max_pressure_Pa(1e3))) ** 3)
        self.q_lim = min(q)

    def loads(self, y):
        x, z, th = y
        c = np.cos(self.psi)
        F = np.zeros(3)
        Qs = []
        for sg in self.signs:
            zm = sg * self.h_m
            sr = self.A * math.cos(self.a0) + (x + th * zm) * c
            sz = sg * self.A * math.sin(self.a0) + z - th * self.R_m * c
            L = np.hypot(sr, sz)
            alpha = np.arctan2(sg * sz, sr)
            d = np.where((alpha >= 0) & (alpha <= self.amax), np.maximum(L - self.A, 0.0), 0.0)
            Q = self.K * d**1.5
            F += [np.sum(Q * sr / L * c), np.sum(Q * sz / L), np.sum(Q * (zm * sr / L * c - self.R_m * c * sz / L))]
            Qs.append(Q)
        return F, np.concatenate(Qs)

    def solve(self, Fa, M, y0, Fr=0.0):
        scale = self.A * np.array([1.0, 1.0, 1.0 / self.R_m])  # unknowns of order 1
        norm = max(abs(Fa), abs(M) / self.R_m, abs(Fr))
        sol = root(lambda y: (self.loads(y * scale)[0] - [Fr, Fa, M]) / norm, np.asarray(y0) / scale,
                   method="hybr", options={"xtol": 1e-13})
        assert np.linalg.norm(sol.fun) < 1e-9, sol.message  # equilibrium to 1e-9 of the load
        return sol.x * scale

    def limit_point(self, Fa, M, y0, Fr=0.0):
        """(F_a, M) on the ray through (Fa, M) at the fixed radial force Fr where max Q = Q_lim, own
        root finder."""
        state = {"y": np.asarray(y0, dtype=float)}

        def g(lam):
            y = self.solve(lam * Fa, lam * M, state["y"] * lam ** (2 / 3), Fr)
            return self.loads(y)[1].max() / self.q_lim - 1.0

        lam = brentq(g, 0.9, 1.1, xtol=1e-12)
        return lam * Fa, lam * M


def _library_start(bearing, Fa, M, Fr=0.0):
    q = solve_load_distribution(bearing, RingLoad(Fx_N=Fr, Fz_N=Fa, My_Nm=M)).displacement
    return q[[0, 2, 4]]


def _check_points(bearing, model, curve, n_min):
    checked = 0
    for Fa, M, ok, eq in zip(curve.axial_N, curve.moment_Nm, curve.carried, curve.equilibrium_limited):
        if not ok or eq:
            continue
        Fr = curve.radial_N
        Fa_ref, M_ref = model.limit_point(Fa, M, _library_start(bearing, Fa, M, Fr), Fr)
        # the point's distance from the origin in the (F_a, 4M/d_m) plane: the same physics written
        # twice, so equal to Brent's rtol 1e-7 and the equilibrium tolerances (1e-8): 1e-6 (measured
        # 4e-9), far inside the 0.5 % a catalogue curve needs
        scale = 4.0 / model.row.pitch_diameter_m
        assert math.hypot(Fa, M * scale) == pytest.approx(math.hypot(Fa_ref, M_ref * scale), rel=1e-6)
        checked += 1
    assert checked >= n_min


def test_angular_contact_row_curve_matches_the_independent_model():
    row = BallRow("acbb", 40, 20e-3, 0.5, math.radians(60.0), 0.53, 0.53)
    bearing = Bearing("acbb", (row,))
    curve = limiting_load_curve(bearing, n_rays=12)
    assert curve.criterion.startswith("s0 = 1")
    model = Model(row, (1,), math.pi / 2)
    _check_points(bearing, model, curve, 5)
    # a single angular-contact row: only F_a > 0, and no nearly pure moment
    assert np.all(curve.axial_N[curve.carried] > 0)
    assert not curve.carried.all()
    # pure-axial end point: F_a = Z·Q_lim·sin α, cos α = A cos α0/(A + δ), δ = (Q_lim/K)^(2/3) (exact
    # in the model; Brent's rtol 1e-7)
    i0 = int(np.argmin(np.abs(curve.ray_angle_rad)))
    assert curve.ray_angle_rad[i0] == 0.0
    d = (model.q_lim / model.K) ** (2 / 3)
    alpha = math.acos(model.A * math.cos(model.a0) / (model.A + d))
    assert curve.axial_N[i0] == pytest.approx(40 * model.q_lim * math.sin(alpha), rel=1e-6)
    assert curve.moment_Nm[i0] == 0.0


def test_four_point_pitch_bearing_curve_is_closed_and_matches_the_independent_model():
    row = FourPointRow("fp", 200, 45e-3, 3.0, math.radians(45.0), 0.53, 0.53)
    bearing = Bearing("pitch", (row,))
    curve = limiting_load_curve(bearing, n_rays=8)
    assert curve.carried.all()  # both signs of F_a and M: closed around the origin
    assert (curve.axial_N > 1).any() and (curve.axial_N < -1).any()
    assert (curve.moment_Nm > 1).any() and (curve.moment_Nm < -1).any()
    model = Model(row, (1, -1), row.shoulder_angle_rad)
    _check_points(bearing, model, curve, 5)
    # symmetric arches: +F_a and −F_a limits alike (Brent's rtol)
    assert curve.axial_N[0] == pytest.approx(-curve.axial_N[4], rel=1e-6)
    d = curve.to_dict()
    assert d["axial_N"] == curve.axial_N.tolist() and d["ray_angle_deg"][2] == pytest.approx(90.0, rel=1e-12)


def test_fixed_radial_force_matches_the_independent_model():
    row = FourPointRow("fp", 60, 25e-3, 1.0)
    bearing = Bearing("fp", (row,))
    Fr = 2e5
    curve = limiting_load_curve(bearing, n_rays=6, radial_N=Fr)
    assert curve.radial_N == Fr and curve.carried.all()
    _check_points(bearing, Model(row, (1, -1), row.shoulder_angle_rad), curve, 5)
    # a radial force uses up part of the capacity: the pure-axial limit shrinks
    assert curve.axial_N[0] < limiting_load_curve(bearing, n_rays=6).axial_N[0]


def test_ray_ends_where_the_balls_reach_the_groove_shoulder():
    from mbd_core.bearing.limiting_load import Criterion, ray_limit

    row = FourPointRow("fp", 60, 25e-3, 1.0, shoulder_angle_rad=math.radians(50.0))
    bearing = Bearing("fp", (row,))
    # a pressure limit never reached: the axial ray ends where α reaches the shoulder, cos α_sh =
    # A·cos α0/(A + δ), F_a = Z·K·δ^1.5·sin α_sh (rigid rings, all balls alike); the end of equilibrium
    # is located to 1e-4 of the scale
    lam, who, by_equilibrium = ray_limit(bearing, np.zeros(5), np.array([0, 0, 1e5, 0, 0.0]),
                                         Criterion(pressure_limit_Pa=20e9))
    A, K, a0, a_sh = row.curvature_centre_distance_m, row.contact_stiffness(), row.contact_angle_rad, math.radians(50)
    d = A * (math.cos(a0) / math.cos(a_sh) - 1)
    assert by_equilibrium and who[1] == "inner groove, diagonal +α"
    assert lam * 1e5 == pytest.approx(60 * K * d**1.5 * math.sin(a_sh), rel=2e-4)
    assert lam * 1e5 <= 60 * K * d**1.5 * math.sin(a_sh)


def test_pressure_limit_criterion_and_s0_scale_the_allowed_pressure():
    row = BallRow("acbb", 40, 20e-3, 0.5, math.radians(60.0), 0.53, 0.53)
    bearing = Bearing("acbb", (row,))
    a = limiting_load_curve(bearing, n_rays=4, s0=2.0)
    b = limiting_load_curve(bearing, n_rays=4, pressure_limit_Pa=P_LIM * 2.0 ** (-1 / 3))
    # s0 = 2 for point contacts is p_allow = p_lim·2^(-1/3) (ISO 76, Q ∝ p0^3)
    np.testing.assert_allclose(a.axial_N[a.carried], b.axial_N[b.carried], rtol=1e-6)
    assert "GPa" in b.criterion


@pytest.mark.parametrize("kw, key", [({"n_rays": 2}, "n_rays"), ({"s0": 0.0}, "s0"),
                                     ({"pressure_limit_Pa": -1.0}, "pressure_limit_Pa"),
                                     ({"radial_N": math.nan}, "radial_N")])
def test_bad_input_names_the_key(kw, key):
    row = BallRow("acbb", 40, 20e-3, 0.5, math.radians(60.0), 0.53, 0.53)
    with pytest.raises(ValueError, match=key):
        limiting_load_curve(Bearing("acbb", (row,)), **kw)


def test_plot_shows_the_curve_in_kn_and_knm(tmp_path):
    from cases.bearing_plots import limiting_load_curve_xy, plot_limiting_load_curve

    row = FourPointRow("fp", 60, 25e-3, 1.0)
    curve = limiting_load_curve(Bearing("fp", (row,)), n_rays=6)
    M, F = limiting_load_curve_xy(curve)
    # closed all round: the first point repeated, values in kN·m and kN (exact unit conversion)
    np.testing.assert_allclose(M[:-1], curve.moment_Nm / 1e3, rtol=0, atol=1e-12)
    np.testing.assert_allclose(F[:-1], curve.axial_N / 1e3, rtol=0, atol=1e-12)
    assert (M[-1], F[-1]) == (M[0], F[0])
    out = plot_limiting_load_curve(curve, tmp_path / "llc.png", "fp")
    assert out.stat().st_size > 10_000
