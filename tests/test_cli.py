"""The flexbearing command line: numbers it prints, files it writes, and its user errors."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from cases.cli import main


def run_json(capsys, *argv: str) -> dict:
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_hertz_ball_json_reproduces_thesis_table8(capsys):
    """Thesis Table 8, 5 t on a load ball (inner groove, f = 0.525, pitch 6690 mm, α = 60°):
    p0 = 1689.7 MPa (0.5 %), a = 9.97 mm, b = 1.40 mm (1 %), τ_max = 538.7 MPa at 1.05 mm (1.5 %)."""
    d = run_json(capsys, "hertz", "ball", "--ball-diameter-mm", "95.25", "--conformity", "0.525",
                 "--pitch-diameter-mm", "6690", "--contact-angle-deg", "60", "--load-N", str(5000 * 9.81))
    assert d["max_pressure_p0_Pa"] == pytest.approx(1689.7e6, rel=5e-3)
    assert d["semi_major_axis_a_m"] == pytest.approx(9.97e-3, rel=1e-2)
    assert d["semi_minor_axis_b_m"] == pytest.approx(1.40e-3, rel=1e-2)
    assert d["tau_max_Pa"] == pytest.approx(538.7e6, rel=1.5e-2)
    assert d["depth_tau_max_m"] == pytest.approx(1.05e-3, rel=1.5e-2)


def test_hertz_line_plane_strain_shear(capsys):
    """Roller on a flat raceway: τ_max = 0.300·p0 at 0.786·b (Johnson, Contact Mechanics §4.3), 0.5 %;
    b from Johnson eq. 4.45 with E* = E/(2(1−ν²))."""
    d = run_json(capsys, "hertz", "line", "--roller-diameter-mm", "60", "--length-mm", "60", "--load-N", "1e5",
                 "--E-GPa", "210", "--nu", "0.3")
    e_star = 210e9 / (2 * (1 - 0.3**2))
    b = math.sqrt(4 * (1e5 / 0.06) * 0.03 / (math.pi * e_star))
    assert d["half_width_b_m"] == pytest.approx(b, rel=1e-12)
    assert d["tau_max_Pa"] / d["max_pressure_p0_Pa"] == pytest.approx(0.300, rel=5e-3)
    assert d["depth_tau_max_m"] / d["half_width_b_m"] == pytest.approx(0.786, rel=5e-3)


def test_loaddist_default_writes_consistent_results(tmp_path, capsys):
    """Default job: the full-scale slewing ring under 503.25 t. The written ball loads balance the
    applied axial load: Σ Q·sin α = W·g within 1e-9 (equilibrium); no temporary folder is left."""
    out = tmp_path / "slewing"
    assert main(["loaddist", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "load balls" in printed and "116" in printed
    summary = json.loads((out / "summary.json").read_text())
    row = summary["rows"][0]
    Q = np.array(row["load_N"])
    alpha = np.radians(row["contact_angle_deg"])
    assert np.sum(Q * np.sin(alpha)) == pytest.approx(503.25e3 * 9.81, rel=1e-9)
    with open(out / "element_loads.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 116
    assert float(rows[0]["load_N"]) == pytest.approx(Q[0], rel=1e-6)
    assert (out / "element_loads.png").stat().st_size > 10_000
    assert sorted(p.name for p in tmp_path.iterdir()) == ["slewing"]


def test_loaddist_given_load_three_row(capsys):
    """Given loads replace the default; the reaction balances them (1e-6 relative, issue acceptance)."""
    d = run_json(capsys, "loaddist", "three-row-roller", "--Fz-N", "1e6", "--Fy-N", "-5e5", "--Mx-Nm", "1e6")
    load = np.array(list(d["load"].values()))
    reaction = np.array(list(d["reaction"].values()))
    np.testing.assert_allclose(load[:3] + reaction[:3], 0.0, atol=1e-6 * np.linalg.norm(load[:3]))
    np.testing.assert_allclose(load[3:] + reaction[3:], 0.0, atol=1e-6 * np.linalg.norm(load[3:]))


@pytest.mark.parametrize(
    "argv, field",
    [
        (["hertz", "ball", "--ball-diameter-mm", "95.25", "--conformity", "0.5", "--pitch-diameter-mm", "6690",
          "--load-N", "1"], "--conformity"),
        (["hertz", "ball", "--ball-diameter-mm", "-1", "--conformity", "0.52", "--pitch-diameter-mm", "6690",
          "--load-N", "1"], "--ball-diameter-mm"),
        (["hertz", "ball", "--ball-diameter-mm", "95.25", "--conformity", "0.52", "--pitch-diameter-mm", "90",
          "--load-N", "1"], "--pitch-diameter-mm"),
        (["hertz", "spheres", "--diameter-1-mm", "10", "--diameter-2-mm", "10", "--load-N", "0"], "--load-N"),
        (["hertz", "line", "--roller-diameter-mm", "60", "--raceway-diameter-mm", "50", "--concave",
          "--length-mm", "60", "--load-N", "10"], "roller"),
        (["loaddist", "--Fz-N", "1e5"], "no converged equilibrium"),
        (["hertz", "ball", "--ball-diameter-mm", "95.25", "--conformity", "0.52", "--pitch-diameter-mm", "6690",
          "--load-N", "1", "--nu", "0.7"], "--nu"),
    ],
)
def test_user_errors_name_the_field_without_traceback(argv, field, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert field in err
    assert "Traceback" not in err
    assert err.startswith("flexbearing: error:")


def test_modes_of_a_slewing_race_folder_and_figures(tmp_path, capsys):
    # Mass: the FE mass matrix against the exact mass of the revolved section (0.1 %, acceptance
    # of the free–free model); six rigid-body modes; elastic modes in degenerate pairs of a
    # complete ring (n = 2 out-of-plane first for this flat section).
    out = tmp_path / "modes"
    d = run_json(capsys, "modes", "slewing-bottom-race-1m", "--size-mm", "60", "--modes", "10", "--no-cache",
                 "--out", str(out))
    assert d["mass_kg"] == pytest.approx(d["mass_of_section_kg"], rel=1e-3)
    assert d["n_rigid_modes"] == 6
    f = [m["frequency_Hz"] for m in d["modes"]]
    assert max(f[:6]) < 1e-3 * f[6]
    assert f[7] == pytest.approx(f[6], rel=1e-3)
    assert (d["modes"][6]["family"], d["modes"][6]["waves"]) == ("out", 2)
    assert sorted(p.name for p in out.iterdir()) == [".flexbearing-results.json", "mode_07.png", "mode_08.png", "modes.vtu",
                                                    "summary.json"]
    assert json.loads((out / "summary.json").read_text())["dofs"] == d["dofs"]


def test_modes_rejects_unknown_part_and_too_few_modes(capsys):
    assert main(["modes", "slewing-bottom-race-1m", "--modes", "3"]) == 2
    assert "--modes" in capsys.readouterr().err
    capsys.readouterr()
    assert main(["modes", "no-such-ring"]) == 2
    assert "unknown part 'no-such-ring'" in capsys.readouterr().err
