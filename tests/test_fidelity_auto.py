"""``top.kind = "auto"`` (:mod:`cases.slewing.auto`): where it keeps the top structure rigid, and
where it refuses to decide. (Its modal choice on the undulated ring is checked against the quick
ladder's reference in ``tests/test_tradeoff.py``.)"""

import dataclasses
import json

import numpy as np
import pytest

from cases.cli import main
from cases.config import dumps_case, from_mapping
from cases.slewing import fidelity
from cases.slewing.presets import PRESETS
from cases.slewing import scene
from cases.slewing.case import SlewingCase
from cases.slewing.quasistatic import analytic_ball_load_N, equilibrium


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


def test_auto_sees_the_bolts_of_the_bottom_race_and_splits_the_tolerance(tmp_path):
    """2 m ring, flat races, dead load: the rigid loads are equal. The floating top structure stays
    rigid (a ring of revolution under equal loads). The bottom race is held at 12 bolts, which spread
    the loads (the FE reference: +13 % on the largest); its static response under the rigid ball
    forces shows it, and it goes modal. Each race is judged against half the tolerance."""
    base = from_mapping(SlewingCase, {"name": "flat", "geometry": {"variant": "2m"}, "study": {"kind": "single"}})
    case = base.with_(top={"kind": "auto"}, bottom={"kind": "auto"})
    path = tmp_path / "flat.toml"
    path.write_text(dumps_case(case))
    out = tmp_path / "run"
    assert main(["run", str(path), "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    got = {d["body"]: d for d in summary["fidelity_decisions"]}
    assert got["top"]["choice"] == "top.kind = rigid" and got["top"]["tolerance"] == pytest.approx(0.005)
    assert got["bottom"]["choice"].startswith("bottom.kind = modal") and got["bottom"]["tolerance"] == pytest.approx(0.005)
    # reference: the bottom race with its ball load shapes and 40 modes, harmonic-16 load shapes (the
    # ladder's reference model) on the same mesh; the rigid loads are the analytic W / (Z sin α)
    ref_case = base.with_(bottom={
        "kind": "modal", "n_modes": 40, "groove_harmonics": 16, "ball_load_shapes": True,
        "raceway_spread_m": scene.groove_patch_m(case)})
    ref = equilibrium(ref_case, scene.Bodies(None, scene.bottom_body(ref_case))).rows[0]
    assert summary["max_ball_load_N"] == pytest.approx(float(np.max(ref.load_N)), rel=0.01)
    Q, _ = analytic_ball_load_N(case)
    assert abs(float(np.max(ref.load_N)) - Q) / Q <= got["bottom"]["load_change_bound"]


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
