"""ISO 281 load ratings and life (mbd_core.bearing.rating), DG03 case-depth factor (.case_depth)."""

import math

import numpy as np
import pytest

from mbd_core.bearing.case_depth import (
    case_depth_corrected_life_Mrev,
    case_depth_life_factor,
    core_shear_fatigue_strength_Pa,
    required_case_depth_m,
)
from mbd_core.bearing.rating import (
    BM_DEFAULTS,
    basic_rating_life_Mrev,
    equivalent_load_N,
    life_exponent,
    radial_ball_rating_N,
    radial_roller_rating_N,
    rating_life_hours,
    thrust_ball_rating_N,
    thrust_roller_rating_N,
)
from mbd_core.contact.hertz import ball_on_groove
from mbd_core.contact.subsurface import max_shear_profile_Pa, subsurface_shear
from foundation.materials import BEARING_STEEL

G = 9.80665


# --------------------------------------------------------------------------- load ratings
def test_thesis_thrust_ball_rating_116_balls():
    # Source: ISO 281:2007 thrust-ball formula (α ≠ 90°, D_w > 25.4 mm) evaluated for the
    # slewing-ring thesis bearing: Z = 116, D_w = 95.25 mm, α = 60°, b_m = 1, f_c = 36.635
    # -> C_a = 1 997 045 N. Tolerance 0.1 %.
    C = thrust_ball_rating_N(0.09525, 116, math.radians(60.0), 36.635, bm=1.0)
    assert C == pytest.approx(1_997_045.0, rel=1e-3)


def test_thesis_printed_rating_is_the_112_ball_value():
    # Source: the slewing-ring thesis prints C_a = 1 950 868 N for its "116 ball" bearing;
    # that figure is the ISO value for Z = 112 (documented error in the source). 0.1 %.
    C = thrust_ball_rating_N(0.09525, 112, math.radians(60.0), 36.635, bm=1.0)
    assert C == pytest.approx(1_950_868.0, rel=1e-3)


def test_thesis_basic_rating_life():
    # Source: slewing-ring thesis, L10 = (C_a/P_a)^3 with C_a = 1 950 868 N and
    # P_a = 5.874e6 N -> 0.036633 million revolutions. Tolerance 0.1 %.
    L10 = basic_rating_life_Mrev(1_950_868.0, 5.874e6, "ball")
    assert L10 == pytest.approx(0.036633, rel=1e-3)


def test_ball_formulas_meet_at_25_4_mm():
    # ISO 281: 3.647 is chosen so that 3.647·25.4^1.4 = 25.4^1.8 (= 25.4^0.4 ≈ 3.6470).
    # Analytic check and check of the implemented switch just below / above 25.4 mm: 0.1 %.
    assert 3.647 * 25.4**1.4 == pytest.approx(25.4**1.8, rel=1e-3)
    below = radial_ball_rating_N(0.0254, 20, 0.0, 60.0)
    above = radial_ball_rating_N(0.0254 * (1 + 1e-12), 20, 0.0, 60.0)
    assert above == pytest.approx(below, rel=1e-3)
    below = thrust_ball_rating_N(0.0254, 20, math.radians(60.0), 60.0)
    above = thrust_ball_rating_N(0.0254 * (1 + 1e-12), 20, math.radians(60.0), 60.0)
    assert above == pytest.approx(below, rel=1e-3)


def test_radial_ball_by_hand():
    # Independent re-evaluation of ISO 281:2007 6.1.1 in N and mm; tolerance 1e-12.
    # small ball: D_w = 12.7 mm, Z = 9, i = 2, α = 15°, f_c = 58.2, b_m = 1.3 (default)
    C = radial_ball_rating_N(0.0127, 9, math.radians(15.0), 58.2, n_rows=2)
    hand = 1.3 * 58.2 * (2 * math.cos(math.radians(15.0))) ** 0.7 * 9 ** (2 / 3) * 12.7**1.8
    assert C == pytest.approx(hand, rel=1e-12)
    # large ball: D_w = 40 mm, Z = 30, i = 1, α = 0, f_c = 64.0, b_m = 1.0
    C = radial_ball_rating_N(0.040, 30, 0.0, 64.0, bm=1.0)
    hand = 3.647 * 1.0 * 64.0 * 1.0**0.7 * 30 ** (2 / 3) * 40.0**1.4
    assert C == pytest.approx(hand, rel=1e-12)


def test_thrust_ball_90deg_by_hand():
    # Independent re-evaluation of ISO 281:2007 7.1.1 (α = 90°) in N and mm; 1e-12.
    C = thrust_ball_rating_N(0.030, 40, math.pi / 2, 50.0)
    hand = 3.647 * 1.3 * 50.0 * 40 ** (2 / 3) * 30.0**1.4
    assert C == pytest.approx(hand, rel=1e-12)
    C = thrust_ball_rating_N(0.010, 18, math.pi / 2, 50.0)
    hand = 1.3 * 50.0 * 18 ** (2 / 3) * 10.0**1.8
    assert C == pytest.approx(hand, rel=1e-12)


def test_radial_roller_by_hand():
    # Independent re-evaluation of ISO 281:2007 6.1.2 in N and mm; tolerance 1e-12.
    # D_we = 55 mm, L_we = 80 mm, Z = 90, i = 1, α = 0, f_c = 150.0, b_m = 1.1 (default)
    C = radial_roller_rating_N(0.055, 0.080, 90, 0.0, 150.0)
    hand = 1.1 * 150.0 * (1 * 80.0 * 1.0) ** (7 / 9) * 90 ** (3 / 4) * 55.0 ** (29 / 27)
    assert C == pytest.approx(hand, rel=1e-12)
    # tapered: i = 2, α = 12°
    a = math.radians(12.0)
    C = radial_roller_rating_N(0.020, 0.032, 24, a, 88.0, n_rows=2, bm=1.1)
    hand = 1.1 * 88.0 * (2 * 32.0 * math.cos(a)) ** (7 / 9) * 24 ** (3 / 4) * 20.0 ** (29 / 27)
    assert C == pytest.approx(hand, rel=1e-12)


def test_thrust_roller_by_hand():
    # Independent re-evaluation of ISO 281:2007 7.1.2 in N and mm; tolerance 1e-12.
    # α = 90°: D_we = 60 mm, L_we = 85 mm, Z = 120, f_c = 170.0, b_m = 1.0 (default)
    C = thrust_roller_rating_N(0.060, 0.085, 120, math.pi / 2, 170.0)
    hand = 1.0 * 170.0 * 85.0 ** (7 / 9) * 120 ** (3 / 4) * 60.0 ** (29 / 27)
    assert C == pytest.approx(hand, rel=1e-12)
    # α = 50°
    a = math.radians(50.0)
    C = thrust_roller_rating_N(0.060, 0.085, 120, a, 170.0, bm=1.15)
    hand = 1.15 * 170.0 * (85.0 * math.cos(a)) ** (7 / 9) * math.tan(a) * 120 ** (3 / 4) * 60.0 ** (29 / 27)
    assert C == pytest.approx(hand, rel=1e-12)


def test_bm_defaults_are_iso_table_1():
    # Source: ISO 281:2007 Table 1 (b_m = 1.3 radial/thrust ball, 1.1 radial roller, 1.0
    # thrust roller); the default is applied as a plain factor. Tolerance 1e-12.
    assert dict(BM_DEFAULTS) == {
        "radial_ball": 1.3,
        "thrust_ball": 1.3,
        "radial_roller": 1.1,
        "thrust_roller": 1.0,
    }
    a60 = math.radians(60.0)
    assert radial_ball_rating_N(0.01, 10, 0.0, 50.0) == pytest.approx(
        1.3 * radial_ball_rating_N(0.01, 10, 0.0, 50.0, bm=1.0), rel=1e-12
    )
    assert thrust_ball_rating_N(0.01, 10, a60, 50.0) == pytest.approx(
        1.3 * thrust_ball_rating_N(0.01, 10, a60, 50.0, bm=1.0), rel=1e-12
    )
    assert radial_roller_rating_N(0.01, 0.01, 10, 0.0, 50.0) == pytest.approx(
        1.1 * radial_roller_rating_N(0.01, 0.01, 10, 0.0, 50.0, bm=1.0), rel=1e-12
    )
    assert thrust_roller_rating_N(0.01, 0.01, 10, a60, 50.0) == pytest.approx(
        1.0 * thrust_roller_rating_N(0.01, 0.01, 10, a60, 50.0, bm=1.0), rel=1e-12
    )


# --------------------------------------------------------------------------- life
def test_life_exponents_and_hours():
    # ISO 281:2007 6.2/7.2: p = 3 (ball), 10/3 (roller); L_h = 1e6·L/(60 n). Hand values, 1e-12.
    assert life_exponent("ball") == 3.0
    assert life_exponent("roller") == pytest.approx(10 / 3, rel=1e-15)
    assert basic_rating_life_Mrev(2.0e5, 1.0e5, "ball") == pytest.approx(8.0, rel=1e-12)
    assert basic_rating_life_Mrev(2.0e5, 1.0e5, "roller") == pytest.approx(2 ** (10 / 3), rel=1e-12)
    # 1 million revolutions at 1000 r/min = 1e6/1000 min = 1000/60 h
    assert rating_life_hours(1.0, 1000.0) == pytest.approx(1000.0 / 60.0, rel=1e-12)
    # thesis L10 at 1 r/min: 0.036633e6 min
    assert rating_life_hours(0.036633, 1.0) == pytest.approx(0.036633e6 / 60.0, rel=1e-12)


def test_equivalent_load():
    # ISO 281:2007 6.2.2: P = X F_r + Y F_a; hand value, 1e-12.
    assert equivalent_load_N(10_000.0, 4_000.0, 0.56, 1.8) == pytest.approx(
        0.56 * 10_000.0 + 1.8 * 4_000.0, rel=1e-12
    )


# --------------------------------------------------------------------------- case depth
def _johnson_tau_max(p0, a, z, nu):
    """Axisymmetric Hertz stresses on the axis (Johnson, Contact Mechanics, eq. 3.45)."""
    c = z / a
    sr = -p0 * ((1 + nu) * (1 - c * math.atan(1 / c)) - 0.5 / (1 + c * c))
    sz = -p0 / (1 + c * c)
    return abs(sr - sz) / 2


def test_core_shear_fatigue_strength():
    # DG03: τ_f = 0.6·τ_y; τ_y = 0.425·UTS (Sague–Rumbarger) or 0.5·σ_y (Tresca).
    # Thesis value 0.6 × 330 MPa = 198 MPa. Hand values, 1e-12.
    assert core_shear_fatigue_strength_Pa(core_shear_yield_Pa=330e6) == pytest.approx(198e6, rel=1e-12)
    assert core_shear_fatigue_strength_Pa(core_uts_Pa=900e6) == pytest.approx(0.6 * 0.425 * 900e6, rel=1e-12)
    assert core_shear_fatigue_strength_Pa(core_yield_Pa=700e6) == pytest.approx(0.6 * 0.5 * 700e6, rel=1e-12)


def test_required_case_depth_circular_contact_against_johnson():
    # Independent check: at the returned depth h the axisymmetric closed form of Johnson
    # (eq. 3.45) gives τ_max(1.1 h) = τ_f (1e-6 relative), with 1.1 h beyond the τ_max peak
    # (≈ 0.48 a for ν = 0.3, Johnson §3.4). A_cd (uncapped) there is 1 to 1e-6.
    p0, a, nu = 2.0e9, 2.0e-3, 0.3
    tau_f = 0.6 * 330e6
    h = required_case_depth_m(p0, a, a, nu, tau_f)
    z = 1.1 * h
    assert z > 0.48 * a
    assert _johnson_tau_max(p0, a, z, nu) == pytest.approx(tau_f, rel=1e-6)
    assert case_depth_life_factor(p0, a, a, h, nu, tau_f, cap=False) == pytest.approx(1.0, rel=1e-6)


def test_case_depth_factor_circular_by_hand():
    # A_cd = τ_f/τ_max(1.1 h), with τ_max from Johnson eq. 3.45 evaluated in the test;
    # capped at 1 by default. Tolerance 1e-9 (same closed form, different code).
    p0, a, nu, tau_f = 2.5e9, 1.5e-3, 0.3, 250e6
    for h in (0.3e-3, 1.0e-3, 2.0e-3, 6.0e-3):
        raw = tau_f / _johnson_tau_max(p0, a, 1.1 * h, nu)
        assert case_depth_life_factor(p0, a, a, h, nu, tau_f, cap=False) == pytest.approx(raw, rel=1e-9)
        assert case_depth_life_factor(p0, a, a, h, nu, tau_f) == pytest.approx(min(raw, 1.0), rel=1e-9)


def test_required_case_depth_elliptical_contact_and_monotonicity():
    # Elliptical contact from Hertz theory (a ball in a groove): at the returned h,
    # τ_max(1.1 h) = τ_f to 1e-6 (definition of the root), and A_cd is monotone
    # non-decreasing with h beyond the depth of the τ_max peak (τ_max decays with depth).
    c = ball_on_groove(0.025, 0.52, 0.15, math.radians(20.0), "inner", BEARING_STEEL, BEARING_STEEL)
    Q = 12_000.0
    a, b = (float(x) for x in c.semi_axes_m(Q))
    p0 = float(c.max_pressure_Pa(Q))
    nu = BEARING_STEEL.nu
    tau_f = 0.6 * 0.425 * 1000e6
    peak = subsurface_shear(p0, a, b, nu)
    assert tau_f < peak.tau_max_Pa
    h = required_case_depth_m(p0, a, b, nu, tau_f)
    assert 1.1 * h > peak.depth_tau_max_m
    assert float(max_shear_profile_Pa(p0, a, b, 1.1 * h, nu)) == pytest.approx(tau_f, rel=1e-6)
    depths = np.linspace(peak.depth_tau_max_m / 1.1, 5 * h, 200)
    for cap in (True, False):
        acd = case_depth_life_factor(p0, a, b, depths, nu, tau_f, cap=cap)
        assert np.all(np.diff(acd) >= -1e-12)
    acd = case_depth_life_factor(p0, a, b, depths, nu, tau_f)
    assert np.all(acd[depths < h * (1 - 1e-6)] < 1.0)
    assert np.all(acd[depths > h * (1 + 1e-6)] == 1.0)


def test_required_case_depth_zero_when_core_never_governs():
    # Analytic: τ_f above the peak τ_max (≈ 0.31 p0 for a circular contact, Johnson §3.4)
    # -> A_cd = 1 at any depth and no case depth is required.
    p0, a, nu = 1.0e9, 1.0e-3, 0.3
    assert required_case_depth_m(p0, a, a, nu, 0.40 * p0) == 0.0


def test_thesis_contact_case_depth():
    # Slewing-ring thesis contact: ball Ø95.25 mm, inner groove f = 0.525, pitch 6.69 m,
    # α = 60°, E = 207 GPa, ν = 0.29, Q = 4.24 t·g, τ_f = 0.6 × 330 MPa = 198 MPa.
    # The thesis reports a required case depth of 4.8 mm. This code gives h = 4.36 mm
    # (1.1 h = 4.80 mm): the thesis figure matches the depth at which τ_max = τ_f, not the
    # case depth h with the 1.1 factor, so the 4.8 mm figure is not asserted (disagreement
    # 9 % > 5 %). Asserted here: the root property τ_max(1.1 h) = τ_f (1e-6) and, with the
    # capped factor, A_cd = 1 for any deeper case (definition, 1e-12).
    c = ball_on_groove(0.09525, 0.525, 6.69, math.radians(60.0), "inner", BEARING_STEEL, BEARING_STEEL)
    Q = 4.24e3 * G
    a, b = (float(x) for x in c.semi_axes_m(Q))
    p0 = float(c.max_pressure_Pa(Q))
    tau_f = core_shear_fatigue_strength_Pa(core_shear_yield_Pa=330e6)
    h = required_case_depth_m(p0, a, b, BEARING_STEEL.nu, tau_f)
    assert float(max_shear_profile_Pa(p0, a, b, 1.1 * h, BEARING_STEEL.nu)) == pytest.approx(tau_f, rel=1e-6)
    assert case_depth_life_factor(p0, a, b, 1.2 * h, BEARING_STEEL.nu, tau_f) == pytest.approx(1.0, abs=1e-12)
    # the thesis' 4.8 mm is reproduced as the depth where τ_max falls to τ_f (measured 4.801 mm), 1 %
    assert 1.1 * h == pytest.approx(4.8e-3, rel=1e-2)


def test_corrected_life():
    # DG03: L = A_cd · L10. Hand value, 1e-12.
    assert case_depth_corrected_life_Mrev(0.036633, 0.5) == pytest.approx(0.0183165, rel=1e-12)


# --------------------------------------------------------------------------- validation
@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: radial_ball_rating_N(-0.01, 10, 0.0, 50.0), "ball_diameter_m"),
        (lambda: radial_ball_rating_N(0.01, 0, 0.0, 50.0), "n_balls"),
        (lambda: radial_ball_rating_N(0.01, 10, 0.0, 50.0, n_rows=0), "n_rows"),
        (lambda: radial_ball_rating_N(0.01, 10, math.radians(50.0), 50.0), "contact_angle_rad"),
        (lambda: radial_ball_rating_N(0.01, 10, 0.0, 0.0), "f_c"),
        (lambda: radial_ball_rating_N(0.01, 10, 0.0, 50.0, bm=-1.0), "bm"),
        (lambda: thrust_ball_rating_N(0.01, 10, math.radians(30.0), 50.0), "contact_angle_rad"),
        (lambda: thrust_ball_rating_N(0.01, 10, math.radians(95.0), 50.0), "contact_angle_rad"),
        (lambda: thrust_ball_rating_N(0.01, 10.5, math.radians(60.0), 50.0), "n_balls"),
        (lambda: thrust_ball_rating_N(0.01, 10, math.radians(60.0), -3.0), "f_c"),
        (lambda: radial_roller_rating_N(0.01, 0.0, 10, 0.0, 50.0), "roller_effective_length_m"),
        (lambda: radial_roller_rating_N(0.01, 0.01, 0, 0.0, 50.0), "n_rollers"),
        (lambda: thrust_roller_rating_N(-0.01, 0.01, 10, math.pi / 2, 50.0), "roller_diameter_m"),
        (lambda: thrust_roller_rating_N(0.01, 0.01, 10, math.pi / 2, float("nan")), "f_c"),
        (lambda: basic_rating_life_Mrev(1e5, 0.0, "ball"), "equivalent_load_N"),
        (lambda: basic_rating_life_Mrev(1e5, 1e4, "needle"), "element"),
        (lambda: rating_life_hours(1.0, 0.0), "speed_rpm"),
        (lambda: equivalent_load_N(-1.0, 0.0, 1.0, 0.0), "radial_load_N"),
        (lambda: core_shear_fatigue_strength_Pa(), "exactly one"),
        (lambda: core_shear_fatigue_strength_Pa(core_uts_Pa=1e9, core_yield_Pa=8e8), "exactly one"),
        (lambda: core_shear_fatigue_strength_Pa(core_uts_Pa=-1e9), "ultimate_tensile_strength_Pa"),
        (lambda: case_depth_life_factor(1e9, 1e-3, 1e-3, -1e-3, 0.3, 2e8), "case_depth_m"),
        (lambda: case_depth_life_factor(1e9, 1e-3, 2e-3, 1e-3, 0.3, 2e8), "semi_minor_m"),
        (lambda: required_case_depth_m(1e9, 1e-3, 1e-3, 0.3, 0.0), "core_shear_fatigue_Pa"),
        (lambda: required_case_depth_m(0.0, 1e-3, 1e-3, 0.3, 2e8), "p0_Pa"),
    ],
)
def test_validation_names_field(call, field):
    with pytest.raises(ValueError, match=field):
        call()
