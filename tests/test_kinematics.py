"""Rolling kinematics without slip and defect frequencies (mbd_core.bearing.kinematics)."""

import math

import numpy as np
import pytest

from mbd_core.bearing.kinematics import (
    RollingKinematics,
    cage_speed_rad_s,
    element_speed_magnitude_rad_s,
    element_speed_rad_s,
    pitch_ratio,
    rad_s_to_rpm,
    rolling_kinematics,
    rpm_to_rad_s,
)

INCH = 0.0254


# --------------------------------------------------------------------------- published values
def test_wind_main_bearing_radial_roller_speed():
    # Source: wind main bearing paper (12 MW three-row roller main bearing, ADAMS multibody
    # study): radial rollers Ø55 mm on pitch Ø1963 mm, inner ring 30 r/min, outer ring fixed,
    # roller speed relative to the cage 535 r/min. Tolerance 0.5 % (figure printed to 3 digits).
    w_r = element_speed_magnitude_rad_s(0.055, 1.963, 0.0, inner_speed_rad_s=rpm_to_rad_s(30.0))
    assert rad_s_to_rpm(w_r) == pytest.approx(535.0, rel=5e-3)


def test_wind_main_bearing_thrust_roller_speed():
    # Source: same paper: thrust rollers Ø60 mm on pitch Ø2182 mm (α = 90°), inner ring
    # 30 r/min, outer ring fixed -> 545.5 r/min relative to the cage. Tolerance 0.5 %.
    k = rolling_kinematics(0.060, 2.182, math.pi / 2, 40, inner_speed_rad_s=rpm_to_rad_s(30.0))
    assert rad_s_to_rpm(k.element_speed_magnitude_rad_s) == pytest.approx(545.5, rel=5e-3)


@pytest.mark.parametrize(
    "ball_in, pitch_in, n_balls, published",
    [
        # Case Western Reserve University Bearing Data Center, "bearing information" page:
        # drive-end SKF 6205-2RS JEM and fan-end SKF 6203-2RS JEM, defect frequencies as
        # multiples of the running speed (BPFI, BPFO, FTF, "rolling element" = 2·BSF).
        (0.3126, 1.537, 9, (5.4152, 3.5848, 0.39828, 4.7135)),
        (0.2656, 1.122, 8, (4.9469, 3.0530, 0.3817, 3.9874)),
    ],
)
def test_cwru_published_defect_orders(ball_in, pitch_in, n_balls, published):
    # Inner ring at 1 Hz, outer ring fixed, α = 0, so the frequencies in Hz are the orders.
    # Tolerance 2.5e-4 relative: the table is printed to 4-5 significant figures.
    k = rolling_kinematics(ball_in * INCH, pitch_in * INCH, 0.0, n_balls, inner_speed_rad_s=2 * math.pi)
    bpfi, bpfo, ftf, ball_2x = published
    assert k.bpfi_Hz == pytest.approx(bpfi, rel=2.5e-4)
    assert k.bpfo_Hz == pytest.approx(bpfo, rel=2.5e-4)
    assert k.ftf_Hz == pytest.approx(ftf, rel=2.5e-4)
    assert k.bsf_2x_Hz == pytest.approx(ball_2x, rel=2.5e-4)
    assert k.bsf_Hz == pytest.approx(ball_2x / 2.0, rel=2.5e-4)


# --------------------------------------------------------------------------- identities
@pytest.mark.parametrize("alpha_deg", [0.0, 25.0, 45.0, 60.0, 90.0])
@pytest.mark.parametrize("w_i, w_o", [(10.0, 0.0), (0.0, -7.0), (3.0, 11.0), (-4.0, 2.5)])
def test_no_slip_at_both_raceway_contacts(alpha_deg, w_i, w_o):
    # Independent derivation (pure rolling): in the cage frame the raceway contact points lie
    # at radii r_i,o = (d_m ∓ D cos α)/2 from the bearing axis and D/2 from the element's
    # rolling axis; the surface speeds must match: (ω_i − ω_c) r_i = −ω_R D/2 and
    # (ω_o − ω_c) r_o = +ω_R D/2. Tolerance 1e-12 relative (round-off only).
    D, dm = 0.0437, 0.612
    a = math.radians(alpha_deg)
    w_c = cage_speed_rad_s(D, dm, a, w_i, w_o)
    w_r = element_speed_rad_s(D, dm, a, w_i, w_o)
    cos_a = 0.0 if alpha_deg == 90.0 else math.cos(a)
    r_i, r_o = (dm - D * cos_a) / 2, (dm + D * cos_a) / 2
    scale = max(abs(w_i), abs(w_o)) * dm
    assert (w_i - w_c) * r_i + w_r * D / 2 == pytest.approx(0.0, abs=1e-12 * scale)
    assert (w_o - w_c) * r_o - w_r * D / 2 == pytest.approx(0.0, abs=1e-12 * scale)


def test_outer_fixed_identities():
    # Analytic: with ω_o = 0, ω_c = ω_i(1 − γ)/2 and BPFO + BPFI = Z·f_shaft (the cage speed
    # lies between the ring speeds, so |ω_c| + |ω_i − ω_c| = |ω_i|). Tolerance 1e-12.
    D, dm, a, Z = 0.025, 0.180, math.radians(30.0), 14
    w_i = rpm_to_rad_s(1500.0)
    k = rolling_kinematics(D, dm, a, Z, inner_speed_rad_s=w_i)
    gamma = D * math.cos(a) / dm
    assert k.pitch_ratio == pytest.approx(gamma, rel=1e-14)
    assert k.cage_speed_rad_s == pytest.approx(w_i * (1 - gamma) / 2, rel=1e-12)
    assert k.bpfo_Hz + k.bpfi_Hz == pytest.approx(Z * 1500.0 / 60.0, rel=1e-12)
    # textbook forms (Randall & Antoni, MSSP 25 (2011) 485-520) with f_r the shaft frequency
    f_r = 25.0
    assert k.bpfo_Hz == pytest.approx(Z * f_r / 2 * (1 - gamma), rel=1e-12)
    assert k.bpfi_Hz == pytest.approx(Z * f_r / 2 * (1 + gamma), rel=1e-12)
    assert k.ftf_Hz == pytest.approx(f_r / 2 * (1 - gamma), rel=1e-12)
    assert k.bsf_Hz == pytest.approx(dm / (2 * D) * f_r * (1 - gamma**2), rel=1e-12)
    # sign convention: positive inner ring -> element spins negatively
    assert k.element_speed_rad_s < 0.0
    assert k.element_speed_magnitude_rad_s == pytest.approx(-k.element_speed_rad_s, rel=0.0)


def test_inner_fixed_outer_rotating():
    # Analytic: with ω_i = 0, ω_c = ω_o(1 + γ)/2 and BPFO + BPFI = Z·f_outer. Tolerance 1e-12.
    D, dm, Z = 0.040, 0.300, 12
    w_o = 2 * math.pi * 7.0
    k = rolling_kinematics(D, dm, 0.0, Z, outer_speed_rad_s=w_o)
    gamma = D / dm
    assert k.cage_speed_rad_s == pytest.approx(w_o * (1 + gamma) / 2, rel=1e-12)
    assert k.bpfo_Hz + k.bpfi_Hz == pytest.approx(Z * 7.0, rel=1e-12)
    assert k.element_speed_rad_s > 0.0


def test_rigid_rotation_of_whole_bearing():
    # Analytic: ω_i = ω_o = Ω moves the bearing as a rigid body: ω_c = Ω, no element rotation
    # relative to the cage, no element passes any raceway point. Tolerance 1e-12.
    W = 13.7
    k = rolling_kinematics(0.0953, 6.69, math.radians(60.0), 116, W, W)
    assert k.cage_speed_rad_s == pytest.approx(W, rel=1e-12)
    assert k.element_speed_rad_s == pytest.approx(0.0, abs=1e-12 * W)
    assert k.bpfo_Hz == pytest.approx(0.0, abs=1e-12 * W)
    assert k.bpfi_Hz == pytest.approx(0.0, abs=1e-12 * W)
    assert k.ftf_Hz == pytest.approx(W / (2 * math.pi), rel=1e-12)


def test_adding_rigid_rotation_shifts_cage_only():
    # Analytic (change of frame): adding Ω to both rings adds Ω to the cage speed and leaves
    # the element speed relative to the cage and the ball-pass frequencies unchanged. 1e-12.
    D, dm, a, Z, w_i, w_o, W = 0.03, 0.25, math.radians(15.0), 11, 40.0, -5.0, 17.0
    k0 = rolling_kinematics(D, dm, a, Z, w_i, w_o)
    k1 = rolling_kinematics(D, dm, a, Z, w_i + W, w_o + W)
    assert k1.cage_speed_rad_s == pytest.approx(k0.cage_speed_rad_s + W, rel=1e-12)
    assert k1.element_speed_rad_s == pytest.approx(k0.element_speed_rad_s, rel=1e-12)
    assert k1.bpfo_Hz == pytest.approx(k0.bpfo_Hz, rel=1e-12)
    assert k1.bpfi_Hz == pytest.approx(k0.bpfi_Hz, rel=1e-12)


def test_cage_tends_to_mean_ring_speed_for_small_gamma():
    # Analytic: γ -> 0 (α = 90° exactly, or D << d_m) gives ω_c = (ω_i + ω_o)/2 and
    # ω_R = d_m/(2D)·(ω_o − ω_i). Tolerance 1e-12 (γ = 0 exactly at 90°).
    D, dm, w_i, w_o = 0.06, 2.182, 3.0, -1.0
    assert pitch_ratio(D, dm, math.pi / 2) == 0.0
    assert cage_speed_rad_s(D, dm, math.pi / 2, w_i, w_o) == pytest.approx(1.0, rel=1e-12)
    assert element_speed_rad_s(D, dm, math.pi / 2, w_i, w_o) == pytest.approx(dm / (2 * D) * -4.0, rel=1e-12)


def test_rpm_conversion():
    # Analytic: 60 r/min = 2π rad/s; round trip exact to 1e-15; arrays keep their shape.
    assert rpm_to_rad_s(60.0) == pytest.approx(2 * math.pi, rel=1e-15)
    assert rad_s_to_rpm(math.pi) == pytest.approx(30.0, rel=1e-15)
    n = np.array([1.0, 30.0, 1500.0])
    np.testing.assert_allclose(rad_s_to_rpm(rpm_to_rad_s(n)), n, rtol=1e-15)
    np.testing.assert_allclose(rpm_to_rad_s(n), n * math.pi / 30.0, rtol=1e-15)


def test_result_is_frozen():
    # Analytic: the result dataclass is immutable; its value matches 2·BSF exactly.
    k = rolling_kinematics(0.01, 0.05, 0.0, 8, 100.0)
    assert isinstance(k, RollingKinematics)
    assert k.bsf_2x_Hz == 2.0 * k.bsf_Hz
    with pytest.raises(AttributeError):
        k.ftf_Hz = 0.0


# --------------------------------------------------------------------------- validation
@pytest.mark.parametrize(
    "kwargs, field",
    [
        (dict(element_diameter_m=-0.01), "element_diameter_m"),
        (dict(element_diameter_m=0.0), "element_diameter_m"),
        (dict(pitch_diameter_m=float("nan")), "pitch_diameter_m"),
        (dict(element_diameter_m=0.2, pitch_diameter_m=0.1), "element_diameter_m"),
        (dict(contact_angle_rad=-0.1), "contact_angle_rad"),
        (dict(contact_angle_rad=math.radians(91.0)), "contact_angle_rad"),
        (dict(n_elements=0), "n_elements"),
        (dict(n_elements=3.0), "n_elements"),
        (dict(n_elements=True), "n_elements"),
        (dict(inner_speed_rad_s=float("inf")), "inner_speed_rad_s"),
        (dict(outer_speed_rad_s=float("nan")), "outer_speed_rad_s"),
    ],
)
def test_validation_names_field(kwargs, field):
    args = dict(
        element_diameter_m=0.02,
        pitch_diameter_m=0.1,
        contact_angle_rad=0.2,
        n_elements=10,
        inner_speed_rad_s=1.0,
        outer_speed_rad_s=0.0,
    )
    args.update(kwargs)
    with pytest.raises(ValueError, match=field):
        rolling_kinematics(**args)
