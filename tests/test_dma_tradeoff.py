"""``flexbearing tradeoff dma-torque --quick`` and ``run --tolerance`` on the DMA bearing (the dma
family's ladder, :mod:`cases.dma.fidelity`), and the crb family's refusal.

The quick ladder measures the traction-models study's scene (κ = 0.030, 267 N, 60 rev/min) over
0.02 s. Checks against references:
- the reference and base rungs' race torques are those of direct runs of the same cases in this
  process (an independent path past the ladder's fresh interpreters), and each error column is its
  definition applied to them and to the written ball loads;
- the balls' mean loads are the quasi-static solution of the same row under the thrust (at 60 rev/min
  the centrifugal and gyroscopic terms are below 1e-4 of the load);
- the centre-point law misses the spin traction of the conforming grooves (error above 5 %) which
  10 strips resolve (below 0.5 %);
- ``--tolerance`` picks the fastest rung meeting it and runs the case's own study at it.
"""

import json
import math

import numpy as np
import pytest

from cases.cli import main
from cases.dma import fidelity
from cases.dma.presets import PRESETS
from cases.dma.torque import ball_row, run_torque
from cases.fidelity import rungs
from mbd_core.quasistatic import Bearing, RingLoad, solve_load_distribution
from tests.reference.tables import csv_rows




@pytest.fixture(scope="module")
def ladder_folder(tmp_path_factory):
    out = tmp_path_factory.mktemp("dma-tradeoff") / "ladder"
    assert main(["tradeoff", "dma-torque", "--quick", "--out", str(out)]) == 0
    return out


def _torques(settings):
    run = run_torque(fidelity.rung_case(PRESETS["dma-torque"], settings))
    return np.array([run.mean_per_ball("inner"), run.mean_per_ball("outer")]), run


def test_quick_ladder_errors_against_direct_runs(ladder_folder):
    case = PRESETS["dma-torque"]
    ladder = fidelity.ladder(case, quick=True)
    rows = {r["rung"]: r for r in csv_rows(ladder_folder / "tradeoff.csv")}
    assert set(rows) == {"base", "traction.strips=0", "traction.blend_m_s=0.001", "analysis.step_factor=0.5",
                         "reference"}
    ref_t, ref_run = _torques({**ladder.base, **ladder.reference})
    base_t, _ = _torques(dict(ladder.base))
    assert float(rows["base"]["race_torque"]) == pytest.approx(np.max(np.abs(base_t - ref_t) / np.abs(ref_t)),
                                                               rel=1e-6, abs=1e-9)
    loads = {r: np.array([float(x[f"{r}_N"]) for x in csv_rows(ladder_folder / "ball_loads.csv")]) for r in rows}
    np.testing.assert_allclose(loads["reference"], ref_run.ball_load_N, rtol=1e-7)
    for name, q in loads.items():
        d = q - loads["reference"]
        qmax = loads["reference"].max()
        assert float(rows[name]["load_rms"]) == pytest.approx(np.sqrt(np.mean(d * d)) / qmax, rel=1e-6, abs=1e-8)
    err = {k: float(r["race_torque"]) for k, r in rows.items()}
    # the conforming grooves' spin: the centre-point law cannot carry it, the strips do; a 1 mm/s
    # blend softens the constant law over slips the contacts have (above 5 %); at the stable step
    # the step's own error is far below the blend's (halving it moves the error by < 0.05 %)
    assert err["traction.strips=0"] > 0.05 and err["traction.blend_m_s=0.001"] > 0.05
    assert err["base"] < 0.01
    assert abs(err["analysis.step_factor=0.5"] - err["base"]) < 5e-4
    summary = json.loads((ladder_folder / "summary.json").read_text())
    assert summary["primary"] == "race_torque" and "κ = 0.03" in summary["scene"]
    assert (ladder_folder / "tradeoff_pareto.png").stat().st_size > 10_000


def test_ball_loads_are_the_quasi_static_solution(ladder_folder):
    row = ball_row(PRESETS["dma-torque"])
    static = solve_load_distribution(Bearing("dma", (row,)), RingLoad(Fz_N=267.0)).rows[0].load_N
    # 24 balls alike under pure thrust: the dynamic means equal the static load within 1 % (the
    # balls orbit and roll; their centrifugal force m·Ω²·r_m is 4e-4 N against 25 N)
    loads = np.array([float(x["reference_N"]) for x in csv_rows(ladder_folder / "ball_loads.csv")])
    assert loads == pytest.approx(np.asarray(static), rel=0.01)
    assert math.isclose(float(np.mean(static)), 25.1, rel_tol=0.01)


def test_run_with_a_tolerance_runs_the_rung_it_names(ladder_folder, tmp_path):
    rows = [r for r in csv_rows(ladder_folder / "tradeoff.csv") if r["rung"] != "reference"]
    meeting = [r for r in rows if float(r["race_torque"]) <= 0.01]
    fastest = min(meeting, key=lambda r: float(r["wall_s"]))
    out = tmp_path / "run"
    assert main(["run", "dma-torque", "--set", "study.kind=torque", "--set", "traction.model=constant",
                 "--set", "traction.A=0.03", "--tolerance", "1%", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["fidelity_choice"]["rung"] == fastest["rung"]
    settings = next(r.settings for r in rungs(fidelity.ladder(PRESETS["dma-torque"], True)) if r.name == fastest["rung"])
    assert summary["inner_race_torque_per_ball_Nm"] == pytest.approx(_torques(dict(settings))[0][0], rel=1e-9)


def test_a_family_without_a_ladder_says_why(tmp_path, capsys):
    assert main(["tradeoff", "nj216-friction", "--quick", "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "closed form contact by contact" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "t").exists()
