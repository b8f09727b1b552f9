"""The logarithmic roller profile of ISO/TS 16281:2008 in the slice model of roller rows."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from mbd_core.quasistatic import Bearing, RingLoad, RollerRow, solve_load_distribution
from mbd_core.quasistatic.rows import roller_drop_m

ROW = RollerRow("radial", 24, 0.04, 0.06, 0.5, "radial", n_slices=30)


def test_log_drop_matches_the_iso_formula():
    # p·ln(1/(1 − (2x/L)²)) with p = 0.00035·D_we (ISO/TS 16281:2008), evaluated point by point
    row = replace(ROW, profile="logarithmic")
    L, p = 0.06, 0.00035 * 0.04
    x = np.array([0.0, 0.01, -0.02, 0.029, -0.0299])
    expected = [p * math.log(1.0 / (1.0 - (2.0 * xi / L) ** 2)) for xi in x]
    assert row.drop_m(x) == pytest.approx(expected, rel=1e-13, abs=1e-20)
    assert replace(row, log_relief_m=2e-5).drop_m(x) == pytest.approx(np.array(expected) * 2e-5 / p, rel=1e-13)


def test_parabolic_drop_is_the_former_expression_bit_for_bit():
    x = np.linspace(-0.029, 0.029, 17)
    got = roller_drop_m(x, 0.06, "parabolic", 7e-6, 0.0)
    assert np.array_equal(got, 7e-6 * (2.0 * x / 0.06) ** 2)


def _slices(row: RollerRow, load: RingLoad) -> np.ndarray:
    res = solve_load_distribution(Bearing("b", (row,)), load)
    r = res.rows[0]
    return r.slice_load_N[int(np.argmax(r.load_N))]


def test_log_profile_unloads_the_roller_ends_under_a_central_load():
    # centred radial load (no tilt): a straight roller's slices all carry the same load, so its ends
    # carry as much as its middle (where a real contact has its edge peak); the logarithmic profile
    # relieves the ends: every slice's load falls from the middle outwards
    load = RingLoad(Fx_N=2.0e5)
    straight = _slices(ROW, load)
    log = _slices(replace(ROW, profile="logarithmic"), load)
    assert straight == pytest.approx(np.full(30, straight.mean()), rel=1e-9)
    mid = log[14:16].mean()
    assert log[0] < mid and log[-1] < mid
    assert np.all(np.diff(log[:15]) >= 0.0) and np.all(np.diff(log[15:]) <= 0.0)
    # the same roller load is carried on a shorter length: the middle slices carry more
    assert mid > straight.mean()


def test_log_profile_moves_the_tilted_rollers_peak_off_the_edge():
    # a tilting moment misaligns the rollers: a straight roller then carries its largest slice load
    # at one end (the edge load of ISO/TS 16281's slice model); the logarithmic profile relieves
    # both ends, so the peak lies inside the roller and the end carries less than the straight one's
    load = RingLoad(Fx_N=2.0e5, My_Nm=1.0e3)
    straight = _slices(ROW, load)
    log = _slices(replace(ROW, profile="logarithmic"), load)
    assert int(np.argmax(straight)) in (0, 29)
    end = int(np.argmax(straight))
    assert 0 < int(np.argmax(log)) < 29
    assert log[end] < 0.5 * straight[end]
