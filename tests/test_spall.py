"""Raceway spalls: the ball centre's path over a pit, and the spectrum of a bearing with a spalled
outer race.

References: the path is plane geometry (a circle of radius R_b resting on the pit's edges or bottom,
written out in the test); the defect frequency BPFO = (Z/2)·f_i·(1 − (D/d_m) cos α) of a ball bearing
with a fixed outer ring (Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., §8.3; the project's
:func:`mbd_core.bearing.kinematics.rolling_kinematics` gives the same), read as bearing diagnostics do
from the envelope spectrum (Randall & Antoni, Mech. Syst. Signal Process. 25 (2011) 485–520: each
pass over the spall rings the bearing's resonance, here near 2.1 kHz, and the envelope of that ringing
repeats at BPFO).
"""

import math

import numpy as np
import pytest
from scipy.signal import hilbert

from mbd_core.bearing.kinematics import rolling_kinematics
from mbd_core.bearing.spall import spall_drop_m, spall_radial_offset_m
from mbd_core.contact.friction import Coulomb
from mbd_core.multibody import Driven, Fixed, ModelBuilder, simulate
from mbd_core.multibody.bearings import add_ball_row, set_rolling_velocities
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.quasistatic import BallRow


def test_drop_over_a_short_and_a_long_pit():
    R = 6e-3
    # short, deep pit (2 mm, 0.2 mm): the ball bridges it; over the pit's centre it drops to where it
    # rests on both edges, R − √(R² − (1 mm)²) = 83.9 µm, short of the bottom
    assert spall_drop_m([0.0], 2e-3, 2e-4, R)[0] == pytest.approx(R - math.sqrt(R**2 - 1e-6), rel=1e-12)
    # shallow pit (20 µm): the ball reaches the bottom where both edges are farther than √(R² − (R − d)²)
    reach = math.sqrt(R**2 - (R - 2e-5) ** 2)
    s = np.array([0.0, 1e-3 - reach - 1e-6, 1e-3 - 0.5 * reach, 1e-3 + 1e-9])
    drop = spall_drop_m(s, 2e-3, 2e-5, R)
    assert drop[0] == drop[1] == pytest.approx(2e-5, rel=1e-12)
    assert drop[2] == pytest.approx(R - math.sqrt(R**2 - (0.5 * reach) ** 2), rel=1e-12)   # on the edge
    assert drop[3] == 0.0
    np.testing.assert_allclose(spall_drop_m([-0.3e-3, 0.3e-3], 2e-3, 2e-5, R), 2e-5, rtol=1e-9)   # symmetric


def test_offset_table_signs_place_and_sampling():
    table = spall_radial_offset_m(4096, 0.05, math.pi / 2, 2e-3, 2e-5, 6e-3, "outer")
    inner = spall_radial_offset_m(4096, 0.05, math.pi / 2, 2e-3, 2e-5, 6e-3, "inner")
    assert table.max() == pytest.approx(2e-5) and np.array_equal(inner, -table)
    theta = np.arange(4096) * 2 * math.pi / 4096
    assert np.all(np.abs(theta[table > 0] - math.pi / 2) * 0.05 < 1e-3)          # within the pit
    with pytest.raises(ValueError, match="n_samples to at least"):
        spall_radial_offset_m(256, 0.05, 0.0, 2e-3, 2e-5, 6e-3, "outer")
    with pytest.raises(ValueError, match="race"):
        spall_radial_offset_m(4096, 0.05, 0.0, 2e-3, 2e-5, 6e-3, "cage")


def test_spalled_outer_race_rings_at_bpfo():
    # 12 balls of 12 mm on d_m = 100 mm at 30°, inner ring at 6000 rev/min under 2 kN axial and 0.5 kN
    # radial; a 2 mm × 20 µm spall on the fixed outer race at the bottom of the load zone
    row = BallRow("balls", 12, 12e-3, 0.1, math.radians(30), 0.52, 0.52, "inner", axial_sign=1)
    omega = 6000.0 * 2 * math.pi / 60
    r_outer = 0.05 + 6e-3 * math.cos(row.contact_angle_rad)
    spall = spall_radial_offset_m(8192, r_outer, 1.5 * math.pi, 2e-3, 2e-5, 6e-3, "outer", row.contact_angle_rad)
    b = ModelBuilder()
    inner = b.add_body("inner ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Driven(omega, translation_free=True))
    outer = b.add_body("outer ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    balls = add_ball_row(b, row, inner, outer, friction=Coulomb(0.1, 0.08, 0.05, 0.1), damping_N_s_m=200.0,
                         cage_mass_kg=0.05, fixed_groove_m=(None, spall))
    b.add_force(inner, (0.0, -500.0, 2000.0))
    model, state = b.finalize()
    state = static_equilibrium(model, state).state
    set_rolling_velocities(model, state, balls.elements, inner, other_ring=outer)
    run = simulate(model, state, 0.1, record_every=20)
    t, z = run["t"], run["q"][:, model.body("inner ring"), 2]
    keep = t > 0.02                                   # after the start's transient
    x = z[keep] - z[keep].mean()
    envelope = np.abs(hilbert(x))
    spectrum = np.abs(np.fft.rfft((envelope - envelope.mean()) * np.hanning(x.size)))
    freq = np.fft.rfftfreq(x.size, float(np.mean(np.diff(t))))
    df = freq[1]                                      # 12.5 Hz
    bpfo = rolling_kinematics(row.ball_diameter_m, row.pitch_diameter_m, row.contact_angle_rad, 12,
                              inner_speed_rad_s=omega).bpfo_Hz
    band = (freq > 100.0) & (freq < 2.5 * bpfo)
    peak = freq[band][np.argmax(spectrum[band])]
    # within the FFT's resolution (measured 537.5 Hz against 537.6 Hz; the cage turns 0.36 % faster than
    # the kinematic one, which moves the passes by 1.9 Hz)
    assert abs(peak - bpfo) <= df, (peak, bpfo, df)
    second = (freq > 1.5 * bpfo) & (freq < 2.5 * bpfo)
    assert abs(freq[second][np.argmax(spectrum[second])] - 2 * bpfo) <= df
