"""The named dynamic cases with a modal top structure: a quick run of study (d) dynamic
(`slewing-thermal-modal --quick`: 2 m ring, thermal offset Δ = 0.4 mm, the quick modal top of
12 modes + raceway load shapes to harmonic 8, 0.4 s, implicit friction).

Reference: the flexible quasi-static equilibrium (:func:`cases.slewing.quasistatic.equilibrium`, a
Newton solver of the same reduced top structure with the balls condensed, independent of the
multibody code) at the run's top rotation and ball phase of five samples. Measured on this machine:
0.68 % of the largest load over all balls; 2.54 % of their own load for the balls above a quarter of
the largest, at a ball on a thermal sector's 5° edge, where a ball 0.03° off the even spacing that
the quasi-static row keeps carries a visibly different load. Tolerances 1.5 % and 4 %.
"""

from __future__ import annotations

import json

import h5py
import numpy as np
import pytest

from cases.run import resolve_case, run_case


@pytest.fixture(scope="module")
def thermal_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("thermal") / "run"
    case = resolve_case("slewing-thermal-modal", quick_run=True)
    run_case(case, out)
    return out, json.loads((out / "summary.json").read_text())


def test_the_thermal_run_follows_the_flexible_quasistatic_loads(thermal_run):
    _, s = thermal_run
    cmp = s["quasistatic_comparison"]
    assert len(cmp["time_s"]) == 5
    assert cmp["max_deviation"] < 0.015, cmp
    assert cmp["max_deviation_loaded"] < 0.04, cmp
    # the thermal offset matters: the largest ball load is far above the flat races' W/(Z sin α)
    assert s["max_ball_load_N"] > 2.0 * s["analytic_ball_load_N"]


def test_the_comparison_table_and_the_raw_series_agree(thermal_run):
    out, s = thermal_run
    table = np.loadtxt(out / "quasistatic_comparison.csv", delimiter=",", skiprows=1)
    assert table.shape == (5 * 33, 5)
    dev = np.abs(table[:, 3] - table[:, 4]).max() / table[:, 4].max()
    assert dev == pytest.approx(s["quasistatic_comparison"]["max_deviation"], rel=1e-3)  # CSV rounding
    with h5py.File(out / "timeseries.nc", "r") as f:
        t = f["time"][:]
        c = list(f["contact"].asstr()[:]).index("load balls ball 0–moving")
        k = int(np.argmin(np.abs(t - table[0, 0])))
        assert f["normal_force"][k, c] == pytest.approx(table[0, 3], abs=1e-3)
        assert "modal_coordinate" in f and f["mode_body"].asstr()[0] == "top structure"


def test_a_run_that_would_record_too_few_samples_is_refused_naming_the_key(tmp_path, capsys):
    from cases.cli import main

    out = tmp_path / "r"
    # 0.01 s at the 1 m ring's 1.65e-5 s step: 606 steps in 40 pieces of 15, one sample each at most
    argv = ["run", "slewing-rotation", "--quick", "--set", "analysis.duration_s=0.01",
            "--set", "analysis.record_every=50", "--out", str(out)]
    assert main(argv) == 2
    err = capsys.readouterr().err.split("\r")[-1]
    assert err.startswith("flexbearing: error: analysis.record_every = 50: the run of 0.01 s at the step 1.65e-05 s "
                          "would record fewer than 20 samples; use at most 15"), err
    assert not out.exists()
