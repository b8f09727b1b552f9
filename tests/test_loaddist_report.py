"""What ``flexbearing loaddist`` reports besides the element loads: s0, contacts, stiffness, limiting curve.

References:
- s0 (ISO 76:2006): the load that brings p0 to 4.2 GPa over the load that acts; with Hertz theory
  (p0 ∝ Q^(1/3), Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., ch. 6) that is
  (4200 MPa / p0_max)³, p0_max here computed in the test from the Hertz constants of the inner
  (more curved) groove of the most loaded ball — the contact ISO 76 names for ball bearings.
- Hertz p0 = 3Q/(2π·a·b) with a, b of the Hertz ellipse (Johnson, *Contact Mechanics*, 1985, ch. 4).
- The limiting load curve written by the command equals :func:`limiting_load_curve` called directly
  (whose own reference tests are in tests/test_limiting_load.py).
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from cases.catalog import builtin_bearing
from cases.cli import main
from mbd_core.bearing.limiting_load import limiting_load_curve
from mbd_core.contact.hertz import ball_on_groove


def _csv(path):
    with open(path) as fh:
        return list(csv.DictReader(fh))


@pytest.fixture(scope="module")
def slewing_out(tmp_path_factory):
    out = tmp_path_factory.mktemp("ld") / "slewing"
    assert main(["loaddist", "slewing-ring-2m", "--out", str(out), "--limiting-curve"]) == 0
    return out


def test_static_safety_is_the_iso76_pressure_ratio_cubed(slewing_out):
    row = builtin_bearing("slewing-ring-2m").bearing.rows[0]
    loads = [float(r["load_N"]) for r in _csv(slewing_out / "element_loads.csv")]
    Q = max(loads)
    inner = ball_on_groove(row.ball_diameter_m, row.conformity_moving, row.pitch_diameter_m, row.contact_angle_rad,
                           "inner")
    a, b = (float(x) for x in inner.semi_axes_m(Q))
    p0 = 1.5 * Q / (math.pi * a * b)
    summary = json.loads((slewing_out / "summary.json").read_text())
    s0 = summary["static_safety"]["s0"]
    # 1e-9: the same Hertz constants, evaluated along a different path
    assert s0 == pytest.approx((4200e6 / p0) ** 3, rel=1e-9)
    (r,) = summary["static_safety"]["rows"]
    assert r["contact"] == "inner groove" and r["max_pressure_MPa"] == pytest.approx(p0 / 1e6, rel=1e-9)
    assert loads[r["element"] - 1] == Q  # elements numbered from 1 in both files


def test_contacts_csv_holds_the_hertz_pressure_and_ellipse_of_every_loaded_contact(slewing_out):
    row = builtin_bearing("slewing-ring-2m").bearing.rows[0]
    rows = _csv(slewing_out / "contacts.csv")
    assert {r["contact"] for r in rows} == {"inner groove", "outer groove"}
    assert len(rows) == 2 * row.n_balls
    for r in rows:
        Q = float(r["load_N"])
        c = ball_on_groove(row.ball_diameter_m, row.conformity_moving if r["contact"] == "inner groove"
                           else row.conformity_fixed, row.pitch_diameter_m, row.contact_angle_rad,
                           r["contact"].split()[0])
        a, b = (float(x) for x in c.semi_axes_m(Q))
        assert float(r["a_mm"]) == pytest.approx(a * 1e3, rel=1e-6)  # CSV holds 6 decimals
        assert float(r["p0_MPa"]) == pytest.approx(1.5 * Q / (math.pi * a * b) / 1e6 if Q > 0 else 0.0,
                                                   rel=1e-6, abs=1e-6)


def test_the_written_limiting_curve_is_the_library_curve(slewing_out):
    curve = limiting_load_curve(builtin_bearing("slewing-ring-2m").bearing, n_rays=36)
    rows = _csv(slewing_out / "limiting_load_curve.csv")
    got = np.array([[float(r["axial_force_N"]), float(r["tilting_moment_Nm"])] for r in rows])
    want = np.column_stack([curve.axial_N, curve.moment_Nm])
    np.testing.assert_allclose(got, want, rtol=1e-5, equal_nan=True)  # CSV holds 6 significant digits
    assert (slewing_out / "limiting_load_curve.png").stat().st_size > 0


def test_stiffness_matrix_in_summary_is_the_solvers(slewing_out):
    from mbd_core.quasistatic import solve_load_distribution

    case = builtin_bearing("slewing-ring-2m")
    K = solve_load_distribution(case.bearing, case.default_load).stiffness
    summary = json.loads((slewing_out / "summary.json").read_text())
    km = summary["stiffness_matrix"]
    assert km["columns"] == ["x", "y", "z", "rot_x", "rot_y"] and km["units"][2][2] == "N/m"
    np.testing.assert_array_equal(np.array(km["values"]), K)  # written in SI, not scaled to mm


@pytest.mark.parametrize("args, expected", [
    (["--s0", "-1", "--limiting-curve", "--out", "X"], "--s0 must be a positive number"),
    (["--p0-limit-MPa", "nan", "--limiting-curve", "--out", "X"], "--p0-limit-MPa must be a"),
    (["--limiting-curve"], "--limiting-curve writes limiting_load_curve.csv and .png: give --out"),
    (["--s0", "2"], "give --limiting-curve"),
])
def test_bad_limiting_curve_options_are_one_line(tmp_path, monkeypatch, capsys, args, expected):
    monkeypatch.chdir(tmp_path)
    assert main(["loaddist", "slewing-ring-1m", *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and expected in err and "Traceback" not in err, err
    assert not (tmp_path / "X").exists()
