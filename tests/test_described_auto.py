"""``bearing.rings = "auto"`` on a bearing file with modal rings (:mod:`cases.described.auto`).

The bearing is that of ``tests/test_bearing_tradeoff.py``: one angular-contact ball row in two small
box rings (the inner ring bolted, the outer clamped at a face), here under pure thrust. Checks
against references:
- the rigid loads are equal, but the bolts spread them (+4.5 % on the largest in the finite-element
  reference: element load shapes with 40 modes and harmonics to 16, the quick ladder's reference,
  solved directly here): auto goes modal for the bolted ring and meets 1 %, and the true change
  from rigid rings stays below the sum of the rings' bounds η/(1 + η), as the decision assumes;
- the keys auto chooses, and the studies it does not decide for, are refused naming the key.
"""

import dataclasses
import json

import numpy as np
import pytest

from cases.bearing_file import loads_bearing
from cases.bearing_rings import with_fidelity
from cases.bearing_solver import bearing_solver
from cases.cli import main
from mbd_core.quasistatic import RingLoad

from tests.test_bearing_tradeoff import BEARING


def _write(folder, bearing_text, extra=""):
    (folder / "ac.toml").write_text(bearing_text)
    case = folder / "case.toml"
    case.write_text(f'family = "bearing"\nname = "ac-auto"\n[bearing]\nfile = "{folder / "ac.toml"}"\nrings = "auto"\n'
                    + extra)
    return case


def _largest(desc, load, rings=None) -> float:
    d = desc if rings is None else dataclasses.replace(desc, rings=rings)
    return max(float(np.max(r.load_N)) for r in bearing_solver(d, rigid=rings == {}).solve(load).rows)


def test_auto_under_pure_thrust_sees_the_bolts(tmp_path):
    """Equal rigid loads, yet the bolted inner ring carries the balls over its 8 bolts more stiffly
    than those between them: the FE reference spreads the loads by ±5 %; auto sees it in the static
    response and goes modal."""
    thrust = BEARING.replace("Fx_N = 3.0e3\n", "").replace("My_Nm = 4.0e2\n", "")
    case = _write(tmp_path, thrust)
    out = tmp_path / "run"
    assert main(["run", str(case), "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    inner = next(d for d in summary["fidelity_decisions"] if d["body"] == "rings.inner")
    assert inner["choice"].startswith("modal")
    desc = loads_bearing(thrust)
    load = RingLoad(Fz_N=-1.2e4)
    reference = _largest(desc, load, with_fidelity(dict(desc.rings), {"n_modes": 40, "raceway_harmonics": 16,
                                                                      "element_load_shapes": True}))
    assert summary["largest_element_load_N"] == pytest.approx(reference, rel=0.01)
    rigid = _largest(desc, load, {})
    bound = sum(d["load_change_bound"] for d in summary["fidelity_decisions"])
    assert abs(reference - rigid) / rigid <= bound
    # the chosen basis holds the static response to the element forces: no residual flexibility at
    # the probe; the 4 mm element patch under 40 mm elements is said to carry the mesh's error
    assert summary["error_estimates"]["modal_truncation"]["max_load"] < 1e-6
    assert any("narrower than the ring's elements" in w for w in summary["warnings"])


def test_auto_refuses_what_it_chooses_and_the_studies_it_does_not_decide(tmp_path, capsys):
    case = _write(tmp_path, BEARING, "[rings]\nn_modes = 5\n")
    assert main(["run", str(case), "--out", str(tmp_path / "a")]) == 2
    assert "rings.n_modes" in capsys.readouterr().err and not (tmp_path / "a").exists()
    case = _write(tmp_path, BEARING, '[study]\nkind = "limiting-curve"\n')
    assert main(["run", str(case), "--out", str(tmp_path / "b")]) == 2
    err = capsys.readouterr().err
    assert "bearing.rings" in err and "limiting-curve" in err and not (tmp_path / "b").exists()
