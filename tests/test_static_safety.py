"""Static safety factor s0 per row against closed forms of the rigid-ring load distribution.

References: ISO 76:2006 (C0 at p0 = 4.2 GPa, s0 = C0/P0); for a radial ball row without
clearance under a radial load the ball approaches are δ_r·cos ψ, so Q = Q_max·cos^1.5 ψ and
F_r = Q_max·Σ cos^2.5 ψ over the loaded half (Harris & Kotzalas, *Rolling Bearing Analysis*,
5th ed., ch. 7; Stribeck's Z/Σ cos^2.5 ψ ≈ 4.37); for a thrust row under a centric axial load every
ball carries F_a/(Z·sin α) at the loaded angle cos α = A·cos α0/(A + δ).
"""

import math

import numpy as np
import pytest

from mbd_core.bearing.static_safety import (
    ball_row_equivalent_static_load_N,
    ball_row_static_rating_N,
    contact_load_at_pressure_N,
    row_forces_N,
    static_safety,
)
from mbd_core.contact.hertz import ball_on_groove
from mbd_core.quasistatic import BallRow, Bearing, FourPointRow, RingLoad, solve_load_distribution

P_LIM = 4.2e9  # ISO 76 ball bearings


def _q_lim(row: BallRow, raceway: str, f: float) -> float:
    """Ball load at p0 = 4.2 GPa: p0 = 3Q/(2πab) ∝ Q^(1/3), from one evaluation at 1 kN."""
    c = ball_on_groove(row.ball_diameter_m, f, row.pitch_diameter_m, row.contact_angle_rad, raceway)
    return 1e3 * (P_LIM / float(c.max_pressure_Pa(1e3))) ** 3


def test_radial_row_s0_and_the_iso76_rating_differ_by_stribecks_factor():
    row = BallRow("dgbb", 16, 12e-3, 80e-3, 0.0, 0.52, 0.53)
    bearing = Bearing("dgbb", (row,))
    Fr = 4000.0
    (res,) = static_safety(bearing, solve_load_distribution(bearing, RingLoad(Fx_N=Fr)))
    psi = 2 * np.pi * np.arange(16) / 16
    c = np.cos(psi[np.cos(psi) > 0])
    q_max = Fr / np.sum(c**2.5)
    q_lim = min(_q_lim(row, "inner", 0.52), _q_lim(row, "outer", 0.53))
    # s0 = Q_lim/Q_max: Q ∝ p0^3; solver tolerance 1e-8 relative
    assert res.s0 == pytest.approx(q_lim / q_max, rel=1e-6)
    assert res.contact == "inner groove" and res.element == 0
    s0_iso = ball_row_static_rating_N(row) / ball_row_equivalent_static_load_N(row, Fr, 0.0)
    # ISO 76 assumes Q_max = 5 F_r/Z (clearance); without clearance Z/Σcos^2.5 ψ (4.37 for many balls):
    # the ratio is 5·Σcos^2.5/Z exactly, 5/4.37 within 1 % (discrete Z = 16)
    assert res.s0 / s0_iso == pytest.approx(5 * np.sum(c**2.5) / 16, rel=1e-6)
    assert res.s0 / s0_iso == pytest.approx(5 / 4.37, rel=1e-2)


def test_thrust_row_s0_agrees_with_c0_over_p0_up_to_the_loaded_angle():
    row = BallRow("thrust", 30, 20e-3, 0.4, math.radians(60.0), 0.53, 0.53)
    bearing = Bearing("thrust", (row,))
    Fa = 2e5
    dist = solve_load_distribution(bearing, RingLoad(Fz_N=Fa))
    (res,) = static_safety(bearing, dist)
    # loaded angle from the groove geometry: Q = K δ^1.5 and F_a = Z Q sin α, cos α = A cos α0/(A + δ)
    A, K, a0 = row.curvature_centre_distance_m, row.contact_stiffness(), row.contact_angle_rad
    from scipy.optimize import brentq

    delta = brentq(lambda d: 30 * K * d**1.5 * math.sqrt(1 - (A * math.cos(a0) / (A + d)) ** 2) - Fa, 1e-9, A)
    alpha = math.acos(A * math.cos(a0) / (A + delta))
    q_lim = min(_q_lim(row, "inner", 0.53), _q_lim(row, "outer", 0.53))
    assert res.s0 == pytest.approx(q_lim * 30 * math.sin(alpha) / Fa, rel=1e-6)
    fr, fa = row_forces_N(dist, "thrust")
    assert fa == pytest.approx(Fa, rel=1e-8) and fr < 1e-6 * Fa
    s0_iso = ball_row_static_rating_N(row) / ball_row_equivalent_static_load_N(row, fr, fa)
    # all balls alike: the two differ only by sin α / sin α0 (the contact angle grows under load)
    assert res.s0 / s0_iso == pytest.approx(math.sin(alpha) / math.sin(a0), rel=1e-6)
    assert abs(res.s0 / s0_iso - 1) < 0.02


def test_four_point_row_names_the_deciding_diagonal():
    row = FourPointRow("fp", 60, 25e-3, 1.0)
    bearing = Bearing("fp", (row,))
    (down,) = static_safety(bearing, solve_load_distribution(bearing, RingLoad(Fz_N=-3e5)))
    (up,) = static_safety(bearing, solve_load_distribution(bearing, RingLoad(Fz_N=3e5)))
    assert "diagonal −α" in down.contact and "diagonal +α" in up.contact
    # symmetric gothic arches: the same s0 either way (solver tolerance)
    assert down.s0 == pytest.approx(up.s0, rel=1e-6)
    assert down.max_pressure_Pa == pytest.approx(P_LIM * down.s0 ** (-1 / 3), rel=1e-12)
    assert down.to_dict()["s0"] == down.s0 and down.to_dict()["contact"] == down.contact


def test_contact_load_at_pressure_is_hertz_cube_law():
    c = ball_on_groove(20e-3, 0.53, 0.4, 0.5, "inner")
    q = contact_load_at_pressure_N(c, 3e9)
    assert float(c.max_pressure_Pa(q)) == pytest.approx(3e9, rel=1e-12)
    with pytest.raises(ValueError, match="pressure_Pa"):
        contact_load_at_pressure_N(c, -1.0)


def test_bad_static_load_input_names_the_field():
    row = BallRow("dgbb", 16, 12e-3, 80e-3, 0.0, 0.52, 0.53)
    with pytest.raises(ValueError, match="X0"):
        ball_row_equivalent_static_load_N(row, 1.0, 1.0, X0=-1.0)
    with pytest.raises(ValueError, match="row"):
        ball_row_static_rating_N(FourPointRow("fp", 60, 25e-3, 1.0))


def test_roller_rows_agree_with_iso76_printed_constants():
    from mbd_core.bearing.static_safety import classical_static_safety, roller_row_static_rating_N
    from mbd_core.quasistatic import RollerRow

    # ISO 76: C0a = 220·Z·L·D (thrust, α = 90°), C0r = 44·(1 − D/d_m)·Z·L·D (radial, α = 0), N and mm;
    # the constants are 16e18·π/E' rounded for E = 207 GPa, ν = 0.3; ν = 0.29 here gives 222.4: 1.5 %
    thrust = RollerRow("trb", 30, 20e-3, 30e-3, 0.5, "thrust", n_slices=10)
    assert roller_row_static_rating_N(thrust) == pytest.approx(220 * 30 * 30 * 20, rel=1.5e-2)
    radial = RollerRow("crb", 16, 10e-3, 10e-3, 70e-3, n_slices=10)
    assert roller_row_static_rating_N(radial) == pytest.approx(44 * (1 - 10 / 70) * 16 * 10 * 10, rel=1.5e-2)
    # a thrust row under a centric load: every slice alike, s0 = (4 GPa/p0)^2 is exactly C0a/F_a
    bearing = Bearing("trb", (thrust,))
    dist = solve_load_distribution(bearing, RingLoad(Fz_N=4e5))
    (res,) = static_safety(bearing, dist)
    fr, fa = row_forces_N(dist, "trb")
    assert res.s0 == pytest.approx(classical_static_safety(thrust, fr, fa), rel=1e-7)  # solver tolerance
    with pytest.raises(ValueError, match="fp"):
        classical_static_safety(FourPointRow("fp", 60, 25e-3, 1.0), 1.0, 1.0)
