"""Validity warnings of the load distributions reach the case outputs (summary.json and the report).

Reference: the same 32 load cases solved here directly with
:func:`mbd_core.quasistatic.solve_load_distribution` (an independent path to the warnings that the
study must pass on), among them the ISO 76 static limit of roller bearings (p0 = 4.0 GPa), which
15 × the synthetic spectrum exceeds in the radial row.
"""

import json

from cases.cli import main
from cases.run import resolve_case
from cases.wind.case import INNER_RING_MASS_KG
from cases.wind.scene import G_M_S2, rows
from cases.wind.spectrum import load_cases
from mbd_core.quasistatic import Bearing, RingLoad, solve_load_distribution


def _direct_warnings(scale: float) -> set[str]:
    case = resolve_case("wind-static", True, [f"loads.scale={scale}"])
    bearing = Bearing("three-row roller", rows(case))
    loads, _ = load_cases()
    found = set()
    for k, f in enumerate(loads * scale):
        res = solve_load_distribution(bearing, RingLoad(Fx_N=f[0], Fy_N=f[1] - INNER_RING_MASS_KG * G_M_S2,
                                                        Fz_N=f[2], Mx_Nm=f[3], My_Nm=f[4]))
        found |= {f"load case {k + 1}: {w}" for w in res.warnings}  # load cases numbered from 1 in the outputs
    return found


def test_overloaded_spectrum_warns_in_summary_and_report(tmp_path, capsys):
    out = tmp_path / "static"
    assert main(["run", "wind-static", "--quick", "--set", "loads.scale=15", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["warnings"]) == _direct_warnings(15.0)
    assert any("ISO 76" in w and "'radial'" in w for w in summary["warnings"])
    printed = capsys.readouterr().out
    assert printed.count("WARNING:") == 6        # five warnings, then a pointer to summary.json
    assert "more warnings in summary.json" in printed


def test_nominal_spectrum_has_no_warnings(tmp_path):
    out = tmp_path / "static"
    assert main(["run", "wind-static", "--quick", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary.get("warnings", []) == [] and _direct_warnings(1.0) == set()
