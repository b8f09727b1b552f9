"""Rating life from the load distribution against ISO 281's calibration cases and Palmgren–Miner.

References: ISO/TR 1281-1 (explanatory notes on ISO 281): the catalogue rating of a radial ball
bearing is the Lundberg–Palmgren ring lives of a bearing without clearance under a radial load
(load zone ε = 0.5), C_r = Z·J_r·((Q_ci/J_1)^(−10/3) + (Q_ce/J_2)^(−10/3))^(−0.3) with
J_r = (1/2π)∫cos^2.5 ψ, J_1 = ((1/2π)∫cos^4.5 ψ)^(1/3), J_2 = ((1/2π)∫cos^5 ψ)^(3/10) over the load
zone, rounded in ISO 281 to C_r = 0.407·Z·Q_ci·(1 + (1.04·Q_ci/Q_ce)^(10/3))^(−0.3); L10 = (C/P)^3.
A thrust row under a centric load loads every ball alike: C_a = Z·(Q_ci^(−10/3) + Q_ce^(−10/3))^(−0.3)
for α = 90°. A thrust roller row likewise loads every lamina with q = F_a/(Z·n_s); ISO/TS 16281's
laminae (q_c = Q_c·n_s^(−7/9), L_k = (q_c/q)^4, e = 9/8, two raceways of n_s laminae) then give
L = (2·n_s·(q_c/q)^(−9/2))^(−8/9) = 2^(−8/9)·(Z·Q_c/F_a)^4 whatever n_s. Spectra: Palmgren–Miner,
L = 1/Σ(t_i/L_i) (ISO 281:2007, 9.5).
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from mbd_core.bearing.distribution_life import (
    ball_contact_rating_N,
    roller_contact_rating_N,
    combined_life,
    equivalent_contact_load_N,
    rating_life,
    spectrum_rating_life,
)
from mbd_core.bearing.rating import basic_rating_life_Mrev
from mbd_core.quasistatic import BallRow, Bearing, FourPointRow, RingLoad, RollerRow, solve_load_distribution


def _dgbb(Z=16):
    row = BallRow("dgbb", Z, 12e-3, 80e-3, 0.0, 0.52, 0.53)
    return Bearing("dgbb", (row,)), row


def _ratings(row):
    qi = ball_contact_rating_N(row.ball_diameter_m, row.conformity_moving, row.pitch_diameter_m,
                               row.contact_angle_rad, row.n_balls, "inner")
    qe = ball_contact_rating_N(row.ball_diameter_m, row.conformity_fixed, row.pitch_diameter_m,
                               row.contact_angle_rad, row.n_balls, "outer")
    return qi, qe


def test_radial_ball_row_reproduces_the_iso281_catalogue_life():
    bearing, row = _dgbb()
    Fr = 4000.0
    life = rating_life(bearing, solve_load_distribution(bearing, RingLoad(Fx_N=Fr)), rotating_ring="moving")
    qi, qe = _ratings(row)

    def zone(n):
        return quad(lambda p: math.cos(p) ** n, -math.pi / 2, math.pi / 2)[0] / (2 * math.pi)

    Jr, J1, J2 = zone(2.5), zone(4.5) ** (1 / 3), zone(5.0) ** 0.3
    C_integral = row.n_balls * Jr * ((qi / J1) ** (-10 / 3) + (qe / J2) ** (-10 / 3)) ** -0.3
    # discrete 16 balls against the continuous load zone: 0.5 % (measured 0.14 %)
    assert life.life_Mrev == pytest.approx(basic_rating_life_Mrev(C_integral, Fr, "ball"), rel=5e-3)
    C_iso = 0.407 * row.n_balls * qi * (1 + (1.04 * qi / qe) ** (10 / 3)) ** -0.3
    # ISO 281's rounded 0.407 and 1.04 (J_r/J_1 = 0.4068, J_2/J_1 = 1.0443) add 0.3 %: 1 % in all
    assert life.life_Mrev == pytest.approx(basic_rating_life_Mrev(C_iso, Fr, "ball"), rel=1e-2)
    assert life.rows[0].deciding == "inner groove"


def test_thrust_row_under_axial_load_gives_ca_over_fa_cubed():
    row = BallRow("thrust", 24, 15e-3, 0.2, math.pi / 2, 0.54, 0.54)
    bearing = Bearing("thrust", (row,))
    Fa = 5e4
    dist = solve_load_distribution(bearing, RingLoad(Fz_N=Fa))
    np.testing.assert_allclose(dist.rows[0].load_N, Fa / 24, rtol=1e-8)
    life = rating_life(bearing, dist)
    qi, qe = _ratings(row)
    Ca = 24 * (qi ** (-10 / 3) + qe ** (-10 / 3)) ** -0.3
    assert life.life_Mrev == pytest.approx((Ca / Fa) ** 3, rel=1e-7)  # solver tolerance, all balls alike


def test_load_spectrum_is_palmgren_miner_of_the_single_loads():
    row = BallRow("thrust", 24, 15e-3, 0.2, math.pi / 2, 0.54, 0.54)
    bearing = Bearing("thrust", (row,))
    qi, qe = _ratings(row)
    Ca = 24 * (qi ** (-10 / 3) + qe ** (-10 / 3)) ** -0.3
    loads, shares = [RingLoad(Fz_N=3e4), RingLoad(Fz_N=8e4)], [3.0, 1.0]
    life = spectrum_rating_life(bearing, loads, shares)
    by_hand = 1.0 / (0.75 / (Ca / 3e4) ** 3 + 0.25 / (Ca / 8e4) ** 3)
    assert life.rows[0].life_Mrev == pytest.approx(by_hand, rel=1e-7)


def test_rotating_ring_choice_and_four_point_sets():
    bearing, _ = _dgbb()
    dist = solve_load_distribution(bearing, RingLoad(Fx_N=4000.0))
    inner_turns, outer_turns = rating_life(bearing, dist, "moving"), rating_life(bearing, dist, "fixed")
    # a ring stationary relative to the load sees its peak ball every time: w = 10/3 > 3, shorter life
    assert inner_turns.rows[0].set_life_Mrev[0] > outer_turns.rows[0].set_life_Mrev[0]
    Q = dist.rows[0].load_N
    assert inner_turns.rows[0].set_equivalent_load_N[0] == pytest.approx(np.mean(Q**3) ** (1 / 3), rel=1e-12)
    fp = Bearing("fp", (FourPointRow("fp", 60, 25e-3, 1.0),))
    life = rating_life(fp, solve_load_distribution(fp, RingLoad(Fz_N=1e5, My_Nm=5e4)))
    assert len(life.rows[0].set_labels) == 4
    assert life.life_Mrev == pytest.approx(combined_life(life.rows[0].set_life_Mrev), rel=1e-12)
    assert life.life_Mrev < min(life.rows[0].set_life_Mrev)
    d = life.to_dict()
    assert d["life_Mrev"] == life.life_Mrev
    assert [c["life_Mrev"] for c in d["rows"][0]["contact_sets"]] == list(life.rows[0].set_life_Mrev)


def test_a_iso_scales_and_bad_input_names_the_key():
    bearing, _ = _dgbb()
    dist = solve_load_distribution(bearing, RingLoad(Fx_N=4000.0))
    assert rating_life(bearing, dist, a_iso=2.5).life_Mrev == pytest.approx(2.5 * rating_life(bearing, dist).life_Mrev)
    with pytest.raises(ValueError, match="rotating_ring"):
        rating_life(bearing, dist, rotating_ring="inner")
    with pytest.raises(ValueError, match="time_shares"):
        spectrum_rating_life(bearing, [RingLoad(Fx_N=1.0)], [1.0, 2.0])
    with pytest.raises(ValueError, match="a_iso"):
        rating_life(bearing, dist, a_iso=0.0)
    assert equivalent_contact_load_N(np.zeros(4), True) == 0.0


@pytest.mark.parametrize("n_slices", [10, 25])
def test_thrust_roller_row_laminae_give_the_closed_form(n_slices):
    row = RollerRow("trb", 30, 20e-3, 30e-3, 0.5, "thrust", n_slices=n_slices)
    bearing = Bearing("trb", (row,))
    Fa = 4e5
    dist = solve_load_distribution(bearing, RingLoad(Fz_N=Fa))
    np.testing.assert_allclose(dist.rows[0].slice_load_N, Fa / (30 * n_slices), rtol=1e-8)
    life = rating_life(bearing, dist)
    # Q_c of a thrust line contact (γ = 0): 552·b_m·(D/d_m)^(2/9)·D^(29/27)·L^(7/9)·Z^(−1/4), N and mm, b_m = 1.0
    Qc = 552.0 * 1.0 * (20 / 500) ** (2 / 9) * 20 ** (29 / 27) * 30 ** (7 / 9) * 30**-0.25
    assert roller_contact_rating_N(20e-3, 30e-3, 0.5, math.pi / 2, 30, "inner", 1.0) == pytest.approx(Qc, rel=1e-12)
    # closed form above; laminae equal to the solver's tolerance: 1e-6
    assert life.life_Mrev == pytest.approx(2 ** (-8 / 9) * (30 * Qc / Fa) ** 4, rel=1e-6)


def test_radial_roller_row_rotating_ring_and_spectrum():
    row = RollerRow("crb", 16, 10e-3, 10e-3, 70e-3, n_slices=10)
    bearing = Bearing("crb", (row,))
    d1, d2 = (solve_load_distribution(bearing, RingLoad(Fx_N=F)) for F in (5e3, 1e4))
    moving, fixed = rating_life(bearing, d1, "moving"), rating_life(bearing, d1, "fixed")
    # the inner raceway turning relative to the load (w = 4) outlives it standing (w = 9/2)
    assert moving.rows[0].set_life_Mrev[0] > fixed.rows[0].set_life_Mrev[0]
    # the rows' laminae in series: the row is shorter-lived than either raceway, e = 9/8
    L_in, L_out = moving.rows[0].set_life_Mrev
    assert moving.life_Mrev == pytest.approx((L_in ** (-9 / 8) + L_out ** (-9 / 8)) ** (-8 / 9), rel=1e-12)
    # a spectrum of one load is that load; of two, Miner per lamina lies between the two lives
    one = spectrum_rating_life(bearing, [RingLoad(Fx_N=5e3)], [1.0])
    assert one.life_Mrev == pytest.approx(moving.life_Mrev, rel=1e-12)
    two = spectrum_rating_life(bearing, [RingLoad(Fx_N=5e3), RingLoad(Fx_N=1e4)], [0.5, 0.5])
    assert rating_life(bearing, d2).life_Mrev < two.life_Mrev < moving.life_Mrev
