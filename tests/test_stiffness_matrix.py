"""The bearing's 5×5 tangent stiffness at the operating point, against finite differences.

Reference: the central finite difference of the displacement–load relation F(q) = −reaction(q)
(the load that holds the moving ring at q), K_fd[:, j] = (F(q + h·e_j) − F(q − h·e_j))/(2h). Its
truncation error of an element of approach δ ≫ h is O((h/δ)²) of its own stiffness, which
shrinks as δ^(n−1): with h = 1e-6 of the largest approach δ_max (rotations: that over the
largest pitch radius) the worst element, at δ ≥ 10·h (checked: at δ = 0 the load law changes its
form), contributes < 1e-6 of the total; the rounding error is ε·ℓ/h ≲ 1e-7 with ℓ ≤ 1e-3 m the
lengths δ is computed from. So K must equal K_fd to 1e-5 relative (entries scaled to force/length units by
the largest pitch radius R: S⁻¹·K·S⁻¹, S = diag(1, 1, 1, R, R), against the largest of them),
and be symmetric to 1e-9 (it is the Hessian of the potential energy).

The equilibrium at which it is taken is checked to 1e-9 relative, with the residual recomputed
from the element forces: the solver's default tolerance 1e-10 (relative to max(|load|, Σ element
loads)) guarantees that.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cases.catalog import three_row_roller
from mbd_core.quasistatic import (
    BallRow,
    Bearing,
    FourPointRow,
    RingLoad,
    RollerRow,
    solve_load_distribution,
    stiffness_matrix,
)
from mbd_core.quasistatic.solver import _Problem, _scaling


def _bearings():
    deg = math.radians
    yield "deep groove", Bearing("dg", (BallRow("b", 14, 12e-3, 80e-3, 0.0, 0.52, 0.53, radial_clearance_m=5e-6),)), \
        RingLoad(Fx_N=3000.0, Fy_N=-1000.0, Fz_N=800.0)
    yield "angular contact", Bearing("ac", (BallRow("b", 16, 12e-3, 80e-3, deg(40), 0.52, 0.53),)), \
        RingLoad(Fx_N=1500.0, Fz_N=4000.0, My_Nm=20.0)
    yield "angular contact double row", Bearing("acd", (
        BallRow("a", 20, 15e-3, 0.12, deg(30), 0.52, 0.53, axial_sign=1, axial_position_m=-0.012,
                diametral_clearance_m=-4e-6),
        BallRow("b", 20, 15e-3, 0.12, deg(30), 0.52, 0.53, axial_sign=-1, axial_position_m=0.012,
                diametral_clearance_m=-4e-6, first_azimuth_rad=0.05))), \
        RingLoad(Fx_N=6000.0, Fy_N=2000.0, Fz_N=-3000.0, Mx_Nm=-60.0, My_Nm=90.0)
    # α0 = 80°: at exactly 90° any lateral shift carries half the balls past the groove's 90° edge
    yield "thrust", Bearing("th", (BallRow("b", 18, 10e-3, 0.1, deg(80), 0.53, 0.53),)), \
        RingLoad(Fz_N=5000.0, Mx_Nm=40.0, My_Nm=-25.0)
    yield "four-point", Bearing("fp", (FourPointRow("b", 80, 30e-3, 1.6, deg(45), 0.535, 0.525,
                                                    radial_clearance_m=20e-6),)), \
        RingLoad(Fx_N=6e4, Fy_N=-3e4, Fz_N=1.2e5, Mx_Nm=2e4, My_Nm=-5e4)
    roller = three_row_roller()
    yield "three-row roller", roller.bearing, RingLoad(Fy_N=-1.1e6, Fz_N=1.3e6, Mx_Nm=2.6e6, My_Nm=4e5)


CASES = {name: (b, load) for name, b, load in _bearings()}


def _force(prob: _Problem, q: np.ndarray) -> np.ndarray:
    return -prob.reaction(q, jacobian=False)[0]


def _element_approaches(prob: _Problem, q: np.ndarray) -> np.ndarray:
    from mbd_core.quasistatic.solver import ball_forces, slice_forces

    _, db, _, _, _ = ball_forces(prob.balls, prob.B_balls, q, jacobian=False)
    _, ds, _, _ = slice_forces(prob.slices, prob.w_slices, q, jacobian=False)
    return np.concatenate([db, ds])


@pytest.mark.parametrize("name", list(CASES))
def test_stiffness_matrix_is_the_derivative_of_the_load(name):
    bearing, load = CASES[name]
    dist = solve_load_distribution(bearing, load)
    prob = _Problem(bearing)
    q = dist.displacement
    S = _scaling(bearing)
    # equilibrium, recomputed from the element forces
    Qsum = sum(float(r.load_N.sum()) for r in dist.rows)
    scale = max(np.linalg.norm(load.as_array() / S), Qsum)
    assert np.linalg.norm((load.as_array() - _force(prob, q)) / S) <= 1e-9 * scale

    K = stiffness_matrix(bearing, dist)
    np.testing.assert_array_equal(K, dist.stiffness)
    delta = _element_approaches(prob, q)
    h_len = 1e-6 * float(delta.max())
    assert np.min(np.abs(delta)) > 10 * h_len, "an element is at the edge of contact: choose another load"
    K_fd = np.zeros((5, 5))
    for j in range(5):
        h = h_len / S[j]
        e = np.zeros(5)
        e[j] = h
        K_fd[:, j] = (_force(prob, q + e) - _force(prob, q - e)) / (2 * h)
    held = [i for i, n in enumerate(("x", "y", "z", "rot_x", "rot_y")) if n in dist.held_dofs]
    K_fd[:, held] = 0.0  # a held DOF is no unknown; its column is zero in K by definition
    K_fd[held, :] = 0.0
    Ks, Kfs = K / S[:, None] / S[None, :], K_fd / S[:, None] / S[None, :]
    big = np.abs(Ks).max()
    assert np.abs(Ks - Kfs).max() <= 1e-5 * big
    assert np.abs(Ks - Ks.T).max() <= 1e-9 * big
    # positive definite on the supported DOFs (a stable equilibrium)
    free = [i for i in range(5) if i not in held]
    assert np.linalg.eigvalsh(0.5 * (Ks + Ks.T)[np.ix_(free, free)]).min() > 0


def test_stiffness_in_the_result_dictionary_with_units():
    bearing, load = CASES["four-point"]
    d = solve_load_distribution(bearing, load).to_dict()["stiffness_matrix"]
    assert d["units"][0][0] == "N/m" and d["units"][0][3] == "N/rad"
    assert d["units"][3][0] == "N·m/m" and d["units"][4][4] == "N·m/rad"
    assert d["rows"] == ["Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm"]
    assert np.array(d["values"]).shape == (5, 5)


def test_axial_stiffness_of_a_thrust_row_closed_form():
    """Pure axial load on a thrust row (α = 90°): every ball Q = F/Z, δ = (Q/K)^(2/3), so
    K_zz = Z·1.5·K·δ^0.5 = 1.5·F/δ (Harris & Kotzalas, ch. 7: Q = K·δ^1.5), to 1e-9."""
    row = BallRow("b", 18, 10e-3, 0.1, math.radians(90), 0.53, 0.53)
    F = 5000.0
    dist = solve_load_distribution(Bearing("th", (row,)), RingLoad(Fz_N=F), tolerance=1e-12)
    delta = (F / row.n_balls / row.contact_stiffness()) ** (2 / 3)
    assert dist.stiffness[2, 2] == pytest.approx(1.5 * F / delta, rel=1e-9)


def test_mismatched_distribution_is_named():
    bearing, load = CASES["thrust"]
    other, _ = CASES["four-point"]
    dist = solve_load_distribution(bearing, load)
    with pytest.raises(ValueError, match="dist"):
        stiffness_matrix(other, dist)
