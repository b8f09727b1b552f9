"""``flexbearing tradeoff --quick`` on the slewing ring's undulation scene, and ``run --tolerance``.

The scene: the 2 m ring on its undulated bottom race (×1) under its dead load, top structure of the
thesis' reduced modulus 1.5975 GPa (study (c)), where the ring's bending decides the ball loads.
Checks against references:
- the reference rung's errors are zero and every error column is its definition applied to the
  written ball loads (ball_loads.csv, an output written separately from tradeoff.csv);
- convergence: the error falls from 5 to 20 modes and from no load shapes to harmonic 16; with the
  ball load shapes the equilibrium is the FE solution of the ring under the ball forces, which
  normal modes do not change: 20 and 40 modes agree within 0.5 % (Ritz: the exact static response
  lies in both bases);
- physics: the flexible top structure follows the undulation, so its largest ball load lies below
  the rigid one's (thesis ch. 4, study (c): 12 t flexible against 16.7 t rigid);
- ``--tolerance`` runs the case at the rung it names, so the run's largest ball load is that rung's
  (1e-6), and that rung is the fastest of those whose error meets the tolerance.
"""

import dataclasses
import json

import numpy as np
import pytest

from cases.cli import main
from cases.config import dumps_case
from cases.slewing import fidelity
from cases.slewing.presets import PRESETS
from tests.reference.tables import csv_rows


@pytest.fixture(scope="module")
def scene_file(tmp_path_factory):
    case = dataclasses.replace(fidelity.scene(PRESETS["slewing-undulation"]), name="undulated-2m", description="")
    path = tmp_path_factory.mktemp("tradeoff") / "undulated-2m.toml"
    path.write_text(dumps_case(case))
    return path


@pytest.fixture(scope="module")
def ladder_folder(scene_file):
    out = scene_file.parent / "ladder"
    assert main(["tradeoff", str(scene_file), "--quick", "--out", str(out)]) == 0
    return out




def test_quick_ladder_outputs_and_errors(ladder_folder):
    rows = {r["rung"]: r for r in csv_rows(ladder_folder / "tradeoff.csv")}
    assert set(rows) == {"base", "top.kind=rigid", "top.n_modes=5", "top.groove_harmonics=-1",
                         "top.ball_load_shapes=True", "reference"}
    for name in ("max_load", "load_max", "load_rms", "tau_max", "contact_angle_deg", "unloaded"):
        assert float(rows["reference"][name]) == 0.0
    loads = {r: np.array([float(x[f"{r}_N"]) for x in csv_rows(ladder_folder / "ball_loads.csv")]) for r in rows}
    ref = loads["reference"]
    for name, q in loads.items():
        d = q - ref
        assert float(rows[name]["max_load"]) == pytest.approx(abs(q.max() - ref.max()) / ref.max(), rel=1e-6, abs=1e-8)  # CSV: 9 digits (±0.5e-4 N on each load)
        assert float(rows[name]["load_rms"]) == pytest.approx(np.sqrt(np.mean(d * d)) / ref.max(), rel=1e-6, abs=1e-8)  # CSV: 9 digits (±0.5e-4 N on each load)
    err = {k: float(r["max_load"]) for k, r in rows.items()}
    assert err["top.n_modes=5"] > err["base"]
    assert err["top.groove_harmonics=-1"] > err["base"]
    assert err["top.ball_load_shapes=True"] < 0.005
    # the runs' own truncation estimates (error_estimates): with the ball load shapes the basis holds
    # the static response of the probe's ball force (Ritz: its residual compliance is round-off, so
    # the estimate is ≤ 1e-6); without them the missing flexibility is there (> 1 %); rigid: none
    est = {k: r["estimated_error"] for k, r in rows.items()}
    assert abs(float(est["top.ball_load_shapes=True"])) < 1e-6 and abs(float(est["reference"])) < 1e-6
    assert float(est["base"]) > 0.01 and est["top.kind=rigid"] == ""
    assert loads["reference"].max() < loads["top.kind=rigid"].max()
    summary = json.loads((ladder_folder / "summary.json").read_text())
    assert summary["primary"] == "max_load" and summary["reference"]["model"].startswith("modal top structure: ball load shapes + 40 modes")
    assert set(summary["pareto_front"]) <= set(rows) - {"reference"}
    for png in ("tradeoff_pareto.png", "convergence_top_n_modes.png", "convergence_top_groove_harmonics.png"):
        assert (ladder_folder / png).stat().st_size > 10_000


def test_run_with_a_tolerance_takes_the_fastest_rung_meeting_it(ladder_folder, scene_file):
    rows = [r for r in csv_rows(ladder_folder / "tradeoff.csv") if r["rung"] != "reference"]
    meeting = [r for r in rows if float(r["max_load"]) <= 0.15]
    fastest = min(meeting, key=lambda r: float(r["wall_s"]))
    out = scene_file.parent / "run15"
    assert main(["run", str(scene_file), "--tolerance", "15%", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    choice = summary["fidelity_choice"]
    assert choice["rung"] == fastest["rung"] and choice["ladder"] == "quick"
    assert choice["expected_error"] == pytest.approx(float(fastest["max_load"]), rel=1e-6)  # CSV: 9 digits
    assert summary["max_ball_load_N"] == pytest.approx(float(fastest["max_load_N"]), rel=1e-6)


@pytest.mark.parametrize("tolerance", ["0", "100%", "nan", "-2%"])
def test_impossible_tolerance_stops_before_any_work(scene_file, tolerance, capsys):
    out = scene_file.parent / f"bad-{tolerance}"
    assert main(["run", str(scene_file), f"--tolerance={tolerance}", "--out", str(out)]) == 2
    assert "--tolerance" in capsys.readouterr().err
    assert not out.exists()


def test_tolerance_no_rung_meets_names_the_best(ladder_folder, scene_file, capsys):
    rows = [r for r in csv_rows(ladder_folder / "tradeoff.csv") if r["rung"] != "reference"]
    best = min(rows, key=lambda r: float(r["max_load"]))
    out = scene_file.parent / "run-tight"
    assert main(["run", str(scene_file), "--tolerance", "1e-6", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"the best is {best['rung']}" in err and "no rung" in err
    assert not out.exists()


def test_auto_on_the_undulated_ring_is_modal_and_meets_the_reference(ladder_folder, scene_file):
    # Reference: the quick ladder's reference on the same mesh (ball load shapes with 40 modes and
    # harmonic-16 load shapes). auto keeps the ball load shapes with 5 modes and none: the static
    # response to the ball forces lies in both bases, so the largest loads agree to what the
    # groove-centre sampling adds beyond the patch average (measured 0.06 %; tolerance 0.5 %, the
    # 1 % auto aims at halved). The rigid pass's load spread (100 %: balls lift off) makes it modal.
    out = scene_file.parent / "auto"
    assert main(["run", str(scene_file), "--set", "top.kind=auto", "--set",
                 f"top.element_size_m={_quick_element_m()}", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    decision = summary["fidelity_decisions"][0]
    assert decision["choice"].startswith("top.kind = modal") and "ball_load_shapes = True" in decision["choice"]
    assert decision["rigid_load_spread"] > 0.5 and decision["load_change_bound"] > 0.01
    ref = max(float(r["reference_N"]) for r in csv_rows(ladder_folder / "ball_loads.csv"))
    assert summary["max_ball_load_N"] == pytest.approx(ref, rel=0.005)
    assert summary["error_estimates"]["modal_truncation"]["max_load"] < 1e-6  # the basis holds the response


def _quick_element_m():
    from cases.slewing.scene import DEFAULT_ELEMENT_SIZE_M

    return round(fidelity.QUICK_MESH_FACTOR * DEFAULT_ELEMENT_SIZE_M["2m"], 4)
