"""Tests of ``cases.wind.spectrum``: the synthetic 32-case load spectrum of the 12 MW main bearing.

References:

* Weibull distribution F(v) = 1 − exp(−(v/λ)^k), evaluated independently with
  ``scipy.stats.weibull_min`` (IEC 61400-1:2019 §6.3.2.2 uses k = 2).
* Thrust curve, torque and weights: the formulas of the module docstring, evaluated by hand
  below with the defaults of ``SpectrumModel`` (g = 9.81 m/s²).
* Spline: a cubic spline interpolates its knots; "natural" ends have f'' = 0 at the end knots.
* CSV rows are 1-based line numbers in the file (header = row 1, units = row 2).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import weibull_min

from cases.wind.spectrum import (
    SpectrumError,
    SpectrumModel,
    load_cases,
    read_csv,
    sequence,
    spline,
    write_csv,
)

G = 9.81
HEADER = "time,Fx,Fy,Fz,Mx,My,Mz\n"
UNITS = "s,N,N,N,N*m,N*m,N*m\n"


@pytest.fixture(scope="module")
def cases():
    return load_cases(SpectrumModel())


def test_time_shares_are_weibull_bin_probabilities(cases):
    _, share = cases
    # bins: [0, 3), 30 equal bins 3…25 m/s, [25, ∞); Weibull λ = 10.5 m/s, k = 2
    edges = np.array([0.0] + [3.0 + 22.0 * i / 30.0 for i in range(31)])
    dist = weibull_min(c=2.0, scale=10.5)
    expected = np.append(np.diff(dist.cdf(edges)), dist.sf(25.0))
    assert share.shape == (32,)
    assert share.sum() == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(share, expected, rtol=0, atol=1e-12)


def test_thrust_curve_at_rated_and_maximum(cases):
    loads, _ = cases
    thrust = loads[:, 2]
    # case 11 is the bin [10.333, 11.067) m/s that holds rated (11 m/s), midpoint 10.7 m/s: T_r (v/v_r)²
    assert thrust[11] == pytest.approx(1.5e6 * (10.7 / 11.0) ** 2, rel=1e-12)
    # case 12, midpoint 3 + (22/30)·11.5 = 11.4333 m/s, above rated: T_r (v_r/v)^1
    v12 = 3.0 + 22.0 / 30.0 * 11.5
    assert thrust[12] == pytest.approx(1.5e6 * 11.0 / v12, rel=1e-12)
    assert thrust.max() <= 1.5e6
    assert thrust[0] == 0.0  # idle
    assert thrust[31] == pytest.approx(0.1 * 1.5e6, rel=1e-12)  # parked, feathered


def test_weights_give_radial_load_and_tilting_moment(cases):
    loads, _ = cases
    # Fy = −(m_rotor + m_shaft) g = −(1.1e5 + 2.0e4)·9.81 N
    np.testing.assert_allclose(loads[:, 1], -(1.1e5 + 2.0e4) * G, rtol=1e-12)
    # rotor weight at z = −2.0 m: r × F = (0, 0, −2)×(0, −1.1e5 g, 0) → Mx = −2.0·1.1e5 g;
    # shaft weight at z = +0.8 m → Mx = +0.8·2.0e4 g; sum −2 001 240 N·m
    np.testing.assert_allclose(loads[:, 3], -2.0 * 1.1e5 * G + 0.8 * 2.0e4 * G, rtol=1e-12)
    assert loads[0, 3] == pytest.approx(-2001240.0, rel=1e-12)


def test_torque_and_asymmetric_loads(cases):
    loads, _ = cases
    q_rated = 12e6 / (7.8 * 2.0 * math.pi / 60.0)  # P/ω, N·m
    np.testing.assert_allclose(loads[12:31, 5], q_rated, rtol=1e-12)  # at and above rated
    assert loads[11, 5] == pytest.approx(q_rated * (10.7 / 11.0) ** 2, rel=1e-12)
    assert loads[0, 5] == 0.0 and loads[31, 5] == 0.0  # idle and parked
    assert np.all(load_cases(SpectrumModel(include_torque=False))[0][:, 5] == 0.0)
    # case 5: φ = 2π·3·5/32; Fx = 0.05 T sin φ, My = 0.3 T cos φ − 2.0 Fx
    phi, t5 = 2.0 * math.pi * 15.0 / 32.0, loads[5, 2]
    assert loads[5, 0] == pytest.approx(0.05 * t5 * math.sin(phi), rel=1e-12)
    assert loads[5, 4] == pytest.approx(0.3 * t5 * math.cos(phi) - 2.0 * 0.05 * t5 * math.sin(phi), rel=1e-12)


def test_sequence_equal_spacing_and_order(cases):
    loads, share = cases
    t, f = sequence(loads, share, duration_s=8.0)
    np.testing.assert_allclose(t, 0.25 * np.arange(32) + 0.125, rtol=0, atol=1e-15)  # 8 s/32 = 0.25 s
    assert np.array_equal(f, loads)
    _, f2 = sequence(loads, share, order="by_share")
    assert np.array_equal(f2[0], loads[np.argmax(share)])
    with pytest.raises(ValueError, match="permutation"):
        sequence(loads, share, order=[0] * 32)


def test_spline_through_knots_and_held_outside(cases):
    loads, share = cases
    t, f = sequence(loads, share)
    fun = spline(t, f)
    np.testing.assert_allclose(fun(t), f, rtol=1e-9, atol=1e-9 * np.abs(f).max())
    assert np.array_equal(fun([-1.0, 0.0])[0], fun(t[0])[0])
    np.testing.assert_allclose(fun([-1.0, 100.0]), f[[0, -1]], rtol=1e-9, atol=1e-9 * np.abs(f).max())
    # natural ends: second derivative zero at the end knots (finite difference, h = 1e-4 s)
    h = 1e-4
    d2 = (fun(t[0] + 2 * h) - 2 * fun(t[0] + h) + fun(t[0])) / h**2
    assert np.all(np.abs(d2) <= 1e-3 * np.abs(f).max() / 0.25**2)


def test_csv_round_trip_exact(tmp_path, cases):
    loads, share = cases
    t, f = sequence(loads, share)
    path = write_csv(tmp_path / "spectrum.csv", t, f)
    lines = path.read_text().splitlines()
    assert lines[:2] == [HEADER.strip(), UNITS.strip()]
    t2, f2 = read_csv(path)
    assert np.array_equal(t2, t) and np.array_equal(f2, f)


def test_csv_units_converted(tmp_path):
    path = tmp_path / "kn.csv"
    path.write_text("time,Fx,Fy,Fz,Mx,My,Mz\ns,kN,kN,MN,kN*m,kNm,MN*m\n0,1.5,-2,0.25,3,4,1.2\n1,0,0,0,0,0,0\n")
    t, f = read_csv(path)
    assert np.array_equal(t, [0.0, 1.0])
    np.testing.assert_allclose(f[0], [1500.0, -2000.0, 250000.0, 3000.0, 4000.0, 1.2e6], rtol=1e-15)


GOOD = ["0,1,2,3,4,5,6", "1,1,2,3,4,5,6", "2,1,2,3,4,5,6", "3,1,2,3,4,5,6"]  # rows 3…6


@pytest.mark.parametrize("text, row, column", [
    (HEADER + UNITS + "\n".join(GOOD[:2] + ["2,1,2,,4,5,6"] + GOOD[3:]), 5, "Fz"),  # missing value
    (HEADER + UNITS + "\n".join(GOOD[:1] + ["0,1,2,3,4,5,6"] + GOOD[2:]), 4, "time"),  # time not increasing
    (HEADER + "s,N,kip,N,N*m,N*m,N*m\n" + "\n".join(GOOD), 2, "Fy"),  # bad unit
    (HEADER + UNITS + "\n".join(["0,1,2,3,4,abc,6"] + GOOD[1:]), 3, "My"),  # not a number
    (HEADER + UNITS + "\n".join(GOOD[:3] + ["3,1,2,3,inf,5,6"]), 6, "Mx"),  # not finite
    ("time,Fx,Fy,Fq,Mx,My,Mz\n" + UNITS + "\n".join(GOOD), 1, "Fz"),  # wrong header
])
def test_bad_csv_names_row_and_column(tmp_path, text, row, column):
    path = tmp_path / "bad.csv"
    path.write_text(text + "\n")
    with pytest.raises(SpectrumError) as err:
        read_csv(path)
    msg = str(err.value)
    assert str(path) in msg and f"row {row}," in msg and f"column {column}" in msg


@pytest.mark.parametrize("text, row", [
    (HEADER + UNITS + "\n".join(GOOD[:2] + ["2,1,2,3,4,5"]), 5),  # wrong number of fields
    (HEADER + UNITS + GOOD[0], 3),  # one data row only
    (HEADER, 2),  # no units row
])
def test_bad_csv_names_row(tmp_path, text, row):
    path = tmp_path / "bad.csv"
    path.write_text(text + "\n")
    with pytest.raises(SpectrumError, match=f"row {row}:"):
        read_csv(path)


@pytest.mark.parametrize("kwargs, name", [
    (dict(weibull_shape=-1.0), "weibull_shape"),
    (dict(cut_in_m_s=11.0), "cut_in_m_s"),
    (dict(rated_m_s=30.0), "cut_out_m_s"),
    (dict(rotor_mass_kg=float("nan")), "rotor_mass_kg"),
    (dict(n_cases=2), "n_cases"),
    (dict(parked_thrust_ratio=1.5), "parked_thrust_ratio"),
])
def test_model_validation_names_field(kwargs, name):
    with pytest.raises(ValueError, match=name):
        SpectrumModel(**kwargs)
