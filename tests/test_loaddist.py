"""Quasi-static load distribution with rigid rings, against classical results and independent solutions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from cases.catalog import slewing_ring, three_row_roller
from mbd_core.quasistatic import (
    BallRow,
    Bearing,
    LoadDistributionError,
    RingLoad,
    RollerRow,
    solve_load_distribution,
)


def radial_ball_bearing(n_balls: int, gap_m: float = 0.0) -> Bearing:
    row = BallRow("balls", n_balls, 12.7e-3, 0.25, 0.0, 0.52, 0.52, "inner", 1, radial_clearance_m=gap_m)
    return Bearing("radial ball", (row,))


def radial_roller_bearing(n_rollers: int, gap_m: float = 0.0, n_slices: int = 10) -> Bearing:
    row = RollerRow("rollers", n_rollers, 10e-3, 10e-3, 0.25, "radial", 1, gap_m=gap_m, n_slices=n_slices)
    return Bearing("radial roller", (row,))


# --- Stribeck: Q_max·Z/F_r at zero clearance -------------------------------------------------

@pytest.mark.parametrize("n_balls", [16, 20, 40])
def test_stribeck_ball(n_balls):
    """Stribeck (1901): Q_max·Z/F_r = 4.37 for point contact, zero clearance (Harris & Kotzalas,
    Rolling Bearing Analysis, J_r(ε = 0.5) = 0.2288 → 1/J_r = 4.37), tolerance ±0.03 (issue)."""
    F = 5000.0
    res = solve_load_distribution(radial_ball_bearing(n_balls), RingLoad(Fx_N=F))
    assert res.rows[0].max_load_N * n_balls / F == pytest.approx(4.37, abs=0.03)


@pytest.mark.parametrize("n_rollers", [16, 20, 40])
def test_stribeck_roller(n_rollers):
    """Line contact (exponent 10/9): Q_max·Z/F_r = 4.08 (Harris & Kotzalas, J_r(0.5) = 0.2453), ±0.03."""
    F = 5000.0
    res = solve_load_distribution(radial_roller_bearing(n_rollers), RingLoad(Fx_N=F))
    assert res.rows[0].max_load_N * n_rollers / F == pytest.approx(4.08, abs=0.03)
    # no axial stiffness and no axial load: z held, reported
    assert res.held_dofs == ("z",)


def _radial_reference(n: int, K: float, expo: float, gap: float, F: float) -> np.ndarray:
    """Independent solution of a radially loaded single row with clearance (Harris ch. 7):
    δ_ψ = δ_r·cos ψ − gap, Q = K·δ_ψ^n, Σ Q cos ψ = F_r; solved for δ_r by bracketing."""
    psi = 2 * np.pi * np.arange(n) / n

    def unbalance(dr):
        d = np.maximum(dr * np.cos(psi) - gap, 0.0)
        return np.sum(K * d**expo * np.cos(psi)) - F

    dr = brentq(unbalance, gap, gap + 1e-2, xtol=1e-18, rtol=1e-15)
    return K * np.maximum(dr * np.cos(psi) - gap, 0.0) ** expo


@pytest.mark.parametrize("gap_m", [0.0, 5e-6, 20e-6])
def test_radial_ball_row_matches_independent_solution(gap_m):
    """Ball loads with clearance equal the 1-D reference solution to 1e-8 (same physics, separate code)."""
    b = radial_ball_bearing(20, gap_m)
    res = solve_load_distribution(b, RingLoad(Fx_N=8000.0))
    ref = _radial_reference(20, b.rows[0].contact_stiffness(), 1.5, gap_m, 8000.0)
    np.testing.assert_allclose(res.rows[0].load_N, ref, rtol=1e-8, atol=1e-8 * ref.max())


def test_clearance_raises_stribeck_ratio():
    """Positive clearance concentrates the load (Harris: ε < 0.5 ⇒ Q_max·Z/F_r > 4.37)."""
    F, n = 8000.0, 20
    ratios = [solve_load_distribution(radial_ball_bearing(n, g), RingLoad(Fx_N=F)).rows[0].max_load_N * n / F
              for g in (0.0, 5e-6, 20e-6)]
    assert ratios[0] < ratios[1] < ratios[2]
    assert ratios[2] > 4.37 + 0.3
    roller = [solve_load_distribution(radial_roller_bearing(n, g), RingLoad(Fx_N=F)).rows[0].max_load_N * n / F
              for g in (0.0, 2e-6)]
    assert roller[1] > roller[0] + 0.1


# --- slewing ring under pure axial load ------------------------------------------------------

def _thrust_ball_reference(row: BallRow, Fa: float) -> tuple[float, float]:
    """Angular-contact ball under a centric axial load (Harris & Kotzalas, ch. 7): with
    A = (f_i + f_o − 1)D, the moving groove centre moves δ_a axially, α = atan((A sin α0 + δ_a)/(A cos α0)),
    δ = A·(cos α0/cos α − 1), Q = K δ^1.5, Z·Q·sin α = Fa. Returns (Q, α)."""
    A, a0, K, Z = row.curvature_centre_distance_m, row.contact_angle_rad, row.contact_stiffness(), row.n_balls

    def alpha(da):
        return math.atan2(A * math.sin(a0) + da, A * math.cos(a0))

    def unbalance(da):
        a = alpha(da)
        return Z * K * (A * (math.cos(a0) / math.cos(a) - 1.0)) ** 1.5 * math.sin(a) - Fa

    da = brentq(unbalance, 0.0, A, xtol=1e-16, rtol=1e-15)
    a = alpha(da)
    return K * (A * (math.cos(a0) / math.cos(a) - 1.0)) ** 1.5, a


@pytest.mark.parametrize("variant", ["full", "1m", "2m"])
def test_slewing_ring_axial_load_uniform(variant):
    """Pure axial load: every ball carries Fa/(Z·sin α) within 0.1 % (issue; thesis study (a)),
    with α the loaded contact angle; load and angle equal the independent single-ball solution."""
    case = slewing_ring(variant)
    row = case.bearing.rows[0]
    Fa = -case.default_load.Fz_N
    res = solve_load_distribution(case.bearing, case.default_load)
    r = res.rows[0]
    assert np.ptp(r.load_N) <= 1e-9 * r.load_N.mean()
    assert r.n_unloaded == 0
    expected = Fa / (row.n_balls * np.sin(r.contact_angle_rad))
    np.testing.assert_allclose(r.load_N, expected, rtol=1e-3)
    Q_ref, a_ref = _thrust_ball_reference(row, Fa)
    np.testing.assert_allclose(r.load_N, Q_ref, rtol=1e-8)
    np.testing.assert_allclose(r.contact_angle_rad, a_ref, rtol=1e-8)


def test_full_scale_contact_angle_rise():
    """Under the 503 t dead load the contact angle rises above the nominal 60°; the load per ball is
    then below Fa/(Z sin 60°). Figures: α = 60.94°, Q = 48.69 kN vs 49.14 kN (−0.92 %),
    from the independent single-ball solution above (rtol 1e-8 there)."""
    case = slewing_ring("full")
    res = solve_load_distribution(case.bearing, case.default_load)
    r = res.rows[0]
    assert math.degrees(r.contact_angle_rad[0]) == pytest.approx(60.936, abs=0.002)
    nominal = -case.default_load.Fz_N / (116 * math.sin(math.radians(60)))
    assert r.load_N[0] / nominal - 1.0 == pytest.approx(-0.0092, abs=0.0002)


# --- three-row roller bearing: equilibrium recomputed from the element loads --------------------

def _resultant_from_slices(bearing: Bearing, res) -> np.ndarray:
    """(Fx, Fy, Fz, Mx, My) on the moving ring rebuilt from the reported slice loads with the slice
    geometry of ISO/TS 16281 written out here independently of the solver's arrays."""
    total = np.zeros(5)
    for row, out in zip(bearing.rows, res.rows):
        ns = row.n_slices
        x = -0.5 * row.roller_length_m + (np.arange(ns) + 0.5) * row.roller_length_m / ns
        for j, psi in enumerate(out.azimuth_rad):
            er = np.array([math.cos(psi), math.sin(psi), 0.0])
            ez = np.array([0.0, 0.0, 1.0])
            for k in range(ns):
                if row.orientation == "radial":
                    p = 0.5 * row.pitch_diameter_m * er + (row.axial_position_m + x[k]) * ez
                    n = row.load_sign * er
                else:
                    p = (0.5 * row.pitch_diameter_m + x[k]) * er + row.axial_position_m * ez
                    n = row.load_sign * ez
                F = -out.slice_load_N[j, k] * n
                M = np.cross(p, F)
                total += np.array([F[0], F[1], F[2], M[0], M[1]])
    return total


def test_three_row_combined_load_equilibrium():
    """Force and moment equilibrium of the solution within 1e-6 relative (issue acceptance), with the
    resultant rebuilt from the reported slice loads."""
    case = three_row_roller()
    load = RingLoad(Fx_N=4e5, Fy_N=-1.3e6, Fz_N=1.5e6, Mx_Nm=3.0e6, My_Nm=-1.0e6)
    res = solve_load_distribution(case.bearing, load)
    resultant = _resultant_from_slices(case.bearing, res)
    f_ext = load.as_array()
    np.testing.assert_allclose(resultant[:3] + f_ext[:3], 0.0, atol=1e-6 * np.linalg.norm(f_ext[:3]))
    np.testing.assert_allclose(resultant[3:] + f_ext[3:], 0.0, atol=1e-6 * np.linalg.norm(f_ext[3:]))
    # the thrust is carried by the front row, the moment puts some load on the rear row
    front, rear = res.row("front thrust"), res.row("rear thrust")
    assert front.load_N.sum() > rear.load_N.sum() > 0.0


def test_tilt_loads_one_roller_end_more():
    """A tilting moment on a radial roller row loads the slices at one end of the most loaded
    roller more than at the other; without it the slices share the load equally (straight roller)."""
    b = radial_roller_bearing(30, n_slices=12)
    flat = solve_load_distribution(b, RingLoad(Fx_N=2e4)).rows[0]
    i = int(np.argmax(flat.load_N))
    np.testing.assert_allclose(flat.slice_load_N[i], flat.slice_load_N[i].mean(), rtol=1e-9)
    tilted = solve_load_distribution(b, RingLoad(Fx_N=2e4, My_Nm=40.0)).rows[0]
    s = tilted.slice_load_N[int(np.argmax(tilted.load_N))]
    assert np.all(np.diff(s) > 0.0) or np.all(np.diff(s) < 0.0)
    assert max(s[0], s[-1]) > 1.5 * min(s[0], s[-1])


# --- errors -----------------------------------------------------------------------------------

def test_lifting_load_has_no_equilibrium():
    """An upward load lifts the top race off the single-row slewing ring: a clear error."""
    case = slewing_ring("full")
    with pytest.raises(LoadDistributionError, match="cannot carry"):
        solve_load_distribution(case.bearing, RingLoad(Fz_N=1e5))


def test_load_on_unsupported_dof_is_named():
    with pytest.raises(LoadDistributionError, match="Fz_N"):
        solve_load_distribution(radial_roller_bearing(20), RingLoad(Fx_N=1e3, Fz_N=10.0))


@pytest.mark.parametrize(
    "kwargs, field",
    [
        (dict(conformity_moving=0.5), "conformity_moving"),
        (dict(ball_diameter_m=-1e-3), "ball_diameter_m"),
        (dict(n_balls=0), "n_balls"),
        (dict(contact_angle_rad=2.0), "contact_angle"),
        (dict(axial_sign=0), "axial_sign"),
    ],
)
def test_ball_row_validation_names_field(kwargs, field):
    base = dict(name="r", n_balls=20, ball_diameter_m=12.7e-3, pitch_diameter_m=0.25, contact_angle_rad=0.0,
                conformity_moving=0.52, conformity_fixed=0.52)
    base.update(kwargs)
    with pytest.raises(ValueError, match=field):
        BallRow(**base)


def test_load_validation_names_field():
    with pytest.raises(ValueError, match="Mx_Nm"):
        RingLoad(Mx_Nm=float("nan"))


def test_tipping_moment_has_no_equilibrium():
    """A single-row angular-contact ring cannot carry a tilting moment above W·R (the resultant of the
    ball loads must stay inside the pitch circle: statics). Below it, equilibrium with lift-off on the
    light side; above it, the balls would have to run over the groove edge: a clear error."""
    case = slewing_ring("full")
    W = -case.default_load.Fz_N
    R = 0.5 * case.bearing.rows[0].pitch_diameter_m
    res = solve_load_distribution(case.bearing, RingLoad(Fz_N=-W, Mx_Nm=0.9 * W * R))
    r = res.rows[0]
    assert 0 < r.n_unloaded < 116
    assert np.all((r.contact_angle_rad[~r.unloaded] >= 0.0) & (r.contact_angle_rad[~r.unloaded] <= np.pi / 2))
    with pytest.raises(LoadDistributionError, match="cannot carry"):
        solve_load_distribution(case.bearing, RingLoad(Fz_N=-W, Mx_Nm=1.2 * W * R))
