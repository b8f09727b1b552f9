"""The built-in bearings are description files read by the reader of any user's file: each must build
the same rows and give a bit-identical load distribution to their former construction in Python,
kept here as the reference (the values of the slewing-ring thesis and of Pang et al. 2024, see
cases/catalog.py)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from cases.catalog import BUILTIN_BEARINGS, builtin_bearing
from foundation.materials import BEARING_STEEL
from mbd_core.quasistatic import BallRow, Bearing, RingLoad, RollerRow, solve_load_distribution

G_M_S2 = 9.81


def _slewing(pitch_m: float, n_balls: int, load_t: float, label: str):
    row = BallRow(name="load balls", n_balls=n_balls, ball_diameter_m=95.25e-3, pitch_diameter_m=pitch_m,
                  contact_angle_rad=math.radians(60.0), conformity_moving=0.525, conformity_fixed=0.525,
                  moving_raceway="inner", axial_sign=-1, ball_material=BEARING_STEEL, race_material=BEARING_STEEL)
    return Bearing(f"fast-reactor slewing ring, {label}", (row,)), RingLoad(Fz_N=-load_t * 1000.0 * G_M_S2)


def _three_row():
    radial = RollerRow("radial", 98, 55e-3, 55e-3, 1.963, "radial", load_sign=1, gap_m=0.10e-3,
                       axial_position_m=0.0, n_slices=20)
    front = RollerRow("front thrust", 94, 60e-3, 60e-3, 2.182, "thrust", load_sign=1, gap_m=0.085e-3,
                      axial_position_m=-0.09, n_slices=20)
    rear = RollerRow("rear thrust", 94, 60e-3, 60e-3, 2.182, "thrust", load_sign=-1, gap_m=0.085e-3,
                     axial_position_m=0.09, n_slices=20)
    return (Bearing("12 MW wind main bearing, three-row roller", (radial, front, rear)),
            RingLoad(Fy_N=-1.3e6, Fz_N=1.5e6, Mx_Nm=3.0e6))


REFERENCE = {
    "slewing-ring": lambda: _slewing(6.69, 116, 500.0 + 3.25, "full-scale Ø6.69 m"),
    "slewing-ring-1m": lambda: _slewing(1.0, 16, 68.9, "1 m scaled"),
    "slewing-ring-2m": lambda: _slewing(2.0, 33, 140.0, "2 m scaled"),
    "three-row-roller": _three_row,
}


def test_every_builtin_has_a_reference():
    assert sorted(REFERENCE) == sorted(BUILTIN_BEARINGS)


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_file_builds_the_same_bearing(name):
    ref_bearing, ref_load = REFERENCE[name]()
    case = builtin_bearing(name)
    assert case.bearing.name == ref_bearing.name
    assert len(case.bearing.rows) == len(ref_bearing.rows)
    for got, ref in zip(case.bearing.rows, ref_bearing.rows):
        assert type(got) is type(ref)
        for f in dataclasses.fields(ref):  # exact equality, field by field
            assert getattr(got, f.name) == getattr(ref, f.name), (name, got.name, f.name)
    assert case.default_load == ref_load


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_file_gives_a_bit_identical_load_distribution(name):
    ref_bearing, ref_load = REFERENCE[name]()
    case = builtin_bearing(name)
    got = solve_load_distribution(case.bearing, case.default_load)
    ref = solve_load_distribution(ref_bearing, ref_load)
    assert np.array_equal(got.displacement, ref.displacement)
    for a, b in zip(got.rows, ref.rows):
        for key in ("load_N", "approach_m", "contact_angle_rad"):
            assert np.array_equal(getattr(a, key), getattr(b, key)), (name, a.name, key)
