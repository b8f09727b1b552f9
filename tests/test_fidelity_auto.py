"""``top.kind = "auto"`` (:mod:`cases.slewing.auto`): where it keeps the top structure rigid, and
where it refuses to decide. (Its modal choice on the undulated ring is checked against the quick
ladder's reference in ``tests/test_tradeoff.py``.)"""

import dataclasses
import json

import pytest

from cases.cli import main
from cases.config import dumps_case
from cases.slewing import fidelity
from cases.slewing.presets import PRESETS
from cases.slewing.quasistatic import analytic_ball_load_N


@pytest.fixture(scope="module")
def static_scene(tmp_path_factory):
    case = dataclasses.replace(fidelity.scene(PRESETS["slewing-static"]), name="static", description="")
    path = tmp_path_factory.mktemp("auto") / "static.toml"
    path.write_text(dumps_case(case))
    return case, path


def test_auto_keeps_the_top_rigid_under_a_uniform_load_and_says_why(static_scene):
    # Reference: Harris & Kotzalas (2007) §7.2, the thrust-loaded ball ring: every ball carries
    # Q = W / (Z sin α) at the loaded angle α (analytic_ball_load_N), which a ring of revolution
    # under that uniform load keeps; the rigid equilibrium solves it to 1e-9 (its Newton tolerance).
    case, path = static_scene
    out = path.parent / "run"
    assert main(["run", str(path), "--set", "top.kind=auto", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    decision = summary["fidelity_decisions"][0]
    assert decision["choice"] == "top.kind = rigid"
    assert decision["rigid_load_spread"] < 1e-9 and "alike under every ball" in decision["reason"]
    Q, _ = analytic_ball_load_N(case)
    assert summary["max_ball_load_N"] == pytest.approx(Q, rel=1e-9)
    assert summary["error_estimates"]["modal_truncation"] is None
    assert "rigid" in summary["error_estimates"]["why_none"]


def test_auto_decides_both_races_and_splits_the_tolerance(static_scene):
    # Reference: as above, the analytic thrust load of a ring of revolution: both races stay rigid
    # at the first step, each judged against half the tolerance (their deflections add).
    case, path = static_scene
    out = path.parent / "run-both"
    assert main(["run", str(path), "--set", "top.kind=auto", "--set", "bottom.kind=auto", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    got = {d["body"]: d for d in summary["fidelity_decisions"]}
    assert set(got) == {"top", "bottom"}
    for race, d in got.items():
        assert d["choice"] == f"{race}.kind = rigid" and d["tolerance"] == pytest.approx(0.005)
    Q, _ = analytic_ball_load_N(case)
    assert summary["max_ball_load_N"] == pytest.approx(Q, rel=1e-9)


@pytest.mark.parametrize("sets, named", [
    (["top.kind=auto", "analysis.travel_steps=4"], "top.kind"),
    (["top.kind=auto", "analysis.type=dynamic_explicit"], "top.kind"),
    (["bottom.kind=auto", "analysis.travel_steps=4"], "bottom.kind"),
    (["bottom.kind=auto", "bottom.groove_harmonics=4"], "bottom.groove_harmonics"),
    (["top.kind=auto", "top.n_modes=30"], "top.n_modes"),
    (["top.kind=auto", "top.ball_load_shapes=true", "top.raceway_spread_m=0.02"], "top."),
])
def test_auto_where_it_cannot_decide_is_refused_naming_the_key(static_scene, sets, named, capsys):
    _, path = static_scene
    out = path.parent / f"bad-{len(sets)}-{named}"
    args = ["run", str(path)]
    for s in sets:
        args += ["--set", s]
    assert main(args + ["--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert named in err and err.count("\n") <= 2
    assert not out.exists()
