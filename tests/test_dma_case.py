"""The DMA bearing case (``family = "dma"``): friction torque of the DREB report's cageless bearing.

References:
- The DREB torque report (README Sources): race torques per ball at 267 N, 60 rev/min with the
  EHD-like traction κ = 1.0·u, 4.7e-4 (outer) and 3.6e-4 N·m (inner), "mostly from the drag"; its
  ball drag 0.0133 N at 60 rev/min (Table II); torque "almost linear" in speed and "load-independent"
  (Fig. 12).
- Angular momentum of the balls about the bearing axis (steady state): the torques of both races
  on the balls balance the drag moment, so T_inner + T_outer = M_drag (statics, independent of the
  traction model).
- Elastic contact frequency: a ball between its two linearised Hertz contacts, sqrt((k_i + k_o)/m)/2π.
"""

from __future__ import annotations

import csv
import json

import pytest

from cases.cli import main
from cases.dma.presets import PRESETS
from cases.dma.torque import run_torque


@pytest.fixture(scope="module")
def ehd():
    return run_torque(PRESETS["dma-torque"].with_(study={"kind": "torque"}, analysis={"duration_s": 0.02}))


def test_ehd_traction_torque_is_the_reports_drag_dominated_torque(ehd):
    """Within 25 % of the report per race (measured −4 % inner, −8 % outer); the drag within 10 % of
    its Table II (measured 0.0124 N, −6.5 %)."""
    assert ehd.mean_per_ball("inner") == pytest.approx(-3.6e-4, rel=0.25)
    assert ehd.mean_per_ball("outer") == pytest.approx(-4.7e-4, rel=0.25)
    assert ehd.drag_per_ball_N == pytest.approx(0.0133, rel=0.10)


def test_race_torques_balance_the_drag_moment(ehd):
    """Steady state: T_inner + T_outer = M_drag within 1 % (measured to 1e-4)."""
    total = ehd.mean_per_ball("inner") + ehd.mean_per_ball("outer")
    assert total * ehd.n_balls == pytest.approx(ehd.drag_moment_Nm, rel=0.01)


def test_constant_traction_shows_the_contact_frequency():
    """κ = 0.015 over 20 strips: the ball's axial motion peaks within 3 % of the linearised Hertz
    contact frequency (measured 12.17 kHz against 12.09 kHz); steady torques balance the drag too."""
    run = run_torque(PRESETS["dma-torque"].with_(study={"kind": "torque"}, traction={"model": "constant"},
                                                 analysis={"duration_s": 0.012}))
    peaks = run.summary()["ball_motion_peaks_Hz"]
    assert min(abs(f / run.contact_frequency_Hz - 1.0) for f in peaks) < 0.03
    total = (run.mean_per_ball("inner") + run.mean_per_ball("outer")) * run.n_balls
    assert total == pytest.approx(run.drag_moment_Nm, rel=0.02)


def test_speed_study_torque_grows_with_speed_and_not_with_load(tmp_path):
    """The report's Fig. 12 trends with κ = 1·u: the inner race torque ∝ speed within 15 % (10 → 60
    rev/min) and the same at 89 and 267 N within 10 %; files and summary agree."""
    out = tmp_path / "speed"
    assert main(["run", "dma-torque-speed", "--out", str(out), "--set", "study.speeds_rpm=[10.0, 60.0]",
                 "--set", "analysis.duration_s=0.02"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    with open(out / "torque_speed.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(summary["points"]) == 4
    t = {(float(r["thrust_N"]), float(r["outer_speed_rpm"])): float(r["inner_race_torque_Nm"]) for r in rows}
    for load in (89.0, 267.0):
        assert t[(load, 60.0)] / t[(load, 10.0)] == pytest.approx(6.0, rel=0.15)
    for speed in (10.0, 60.0):
        assert t[(89.0, speed)] == pytest.approx(t[(267.0, speed)], rel=0.10)
    assert (out / "torque_speed.png").stat().st_size > 10_000


def test_unused_and_bad_keys_are_refused(capsys):
    assert main(["run", "dma-torque", "--set", "traction.A=0.02"]) == 2
    assert "traction.A" in capsys.readouterr().err
    assert main(["run", "dma-torque", "--set", "analysis.duration_s=-1"]) == 2
    assert "analysis.duration_s" in capsys.readouterr().err
