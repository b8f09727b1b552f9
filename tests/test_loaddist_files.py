"""``flexbearing loaddist NAME_OR_FILE.toml``: description files, their spectra, the outputs and the errors."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from cases.cli import main

FOUR_POINT = """[bearing]
name = "four-point test ring"
description = "60 balls Ø40 mm on Ø1.2 m"
[[rows]]
type = "four_point"
name = "balls"
count = 60
ball_diameter_m = 0.04
pitch_diameter_m = 1.2
conformity_inner = 0.53
conformity_outer = 0.53
diametral_clearance_m = 0.02e-3
[load]
spectrum_csv = "spectrum.csv"
"""
SPECTRUM = "Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,time_share\n0,0,-2e5,0,0,0.3\n5e4,0,-1e5,8e4,0,0.7\n"


@pytest.fixture
def four_point_file(tmp_path):
    (tmp_path / "spectrum.csv").write_text(SPECTRUM)
    path = tmp_path / "ring.toml"
    path.write_text(FOUR_POINT)
    return path


def _csv(path):
    with open(path) as fh:
        return list(csv.DictReader(fh))


def test_spectrum_runs_every_case_and_each_balances(four_point_file, tmp_path, capsys):
    """Each load case of the spectrum is solved; its element loads written to element_loads.csv (case
    and element numbered from 1) balance its applied load. A loaded +α diagonal (loaded by pushing
    the moving ring towards +z) pushes it back with −Q·sin α along z, a −α diagonal with +Q·sin α,
    both through the ball centre (z = 0): Fz = Σ (Q₊ sin α₊ − Q₋ sin α₋) and Mx = Σ y·(Q₊ sin α₊ −
    Q₋ sin α₋), y the ball's nominal position (forces 1e-6 relative, the solver's equilibrium tolerance
    is 1e-10; the moment 2e-4, as the lines of action pass through the displaced balls: about 0.1 mm
    of ring displacement on the 0.6 m pitch radius)."""
    out = tmp_path / "res"
    assert main(["loaddist", str(four_point_file), "--out", str(out)]) == 0
    assert "four-point test ring" in capsys.readouterr().out
    summary = json.loads((out / "summary.json").read_text())
    assert summary["n_load_cases"] == 2 and summary["load_cases"][1]["time_share"] == 0.7
    rows = _csv(out / "element_loads.csv")
    assert [int(r["case"]) for r in rows] == [1] * 60 + [2] * 60
    assert [int(r["element"]) for r in rows[:60]] == list(range(1, 61))
    for k, (Fz, Mx) in enumerate(((-2e5, 0.0), (-1e5, 8e4)), start=1):
        case = [r for r in rows if int(r["case"]) == k]
        psi = np.radians([float(r["azimuth_deg"]) for r in case])
        Qp, Qm = (np.array([float(r[c]) for r in case]) for c in ("load_plus_N", "load_minus_N"))
        ap, am = (np.radians([float(r[c]) for r in case]) for c in ("contact_angle_plus_deg", "contact_angle_minus_deg"))
        axial = Qp * np.sin(ap) - Qm * np.sin(am)
        y = 0.6 * np.sin(psi)
        assert axial.sum() == pytest.approx(Fz, rel=1e-6)
        assert (axial * y).sum() == pytest.approx(Mx, rel=2e-4, abs=2e-4 * abs(Fz) * 0.6)
        n_points = [int(r["n_contact_points"]) for r in case]
        assert n_points == [2 * int(a > 0) + 2 * int(b > 0) for a, b in zip(Qp, Qm)]
    assert (out / "element_loads.png").stat().st_size > 10_000
    assert (out / "contact_angles.png").stat().st_size > 10_000


def test_options_replace_the_files_load(four_point_file, capsys):
    """--Fz-N replaces the spectrum by one case: the pure axial load on a symmetric four-point row
    loads one diagonal of every ball alike, Z·Q·sin α = |Fz| (1e-9: equilibrium)."""
    assert main(["loaddist", str(four_point_file), "--Fz-N", "-1.5e5", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    row = d["rows"][0]
    Q, alpha = np.array(row["load_N"]), np.radians(row["contact_angle_deg"])
    assert np.ptp(Q) < 1e-9 * Q.max()
    assert np.sum(Q * np.sin(alpha)) == pytest.approx(1.5e5, rel=1e-9)


@pytest.mark.parametrize("arg, expected", [
    ("nonexist.toml", "nonexist.toml: cannot read"),
    (".", "is a folder"),
    ("notes.toml", "invalid TOML"),
    ("bogus-name", "bearing: unknown built-in bearing 'bogus-name'"),
])
def test_bad_bearing_argument_is_one_line(tmp_path, monkeypatch, capsys, arg, expected):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "notes.toml").write_text("just some words\n")
    assert main(["loaddist", arg]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and expected in err and "Traceback" not in err, err


def test_bad_key_in_file_is_one_line_naming_it(tmp_path, capsys):
    path = tmp_path / "b.toml"
    path.write_text(FOUR_POINT.replace("conformity_inner = 0.53", "conformity_inner = 0.49"))
    assert main(["loaddist", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "rows[0].conformity_inner: must be > 0.5" in err, err
