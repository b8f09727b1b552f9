"""The examples run as scripts and are checked here (each example computes at module level).

The two heavy ones run at their ``--quick`` size (FLEXBEARING_EXAMPLE_QUICK=1: a mesh twice as
coarse, the same loads, supports, modes and run); the checks below hold at any mesh (load sums,
equilibrium, load carried after the ramp), and benchmarks/bench_examples.py makes them at the
full size.
"""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _run(name, monkeypatch, tmp_path):
    monkeypatch.setenv("FLEXBEARING_EXAMPLE_OUT", str(tmp_path / name))
    # the heavy examples at their quick size (coarser race mesh, same loads, supports and history);
    # their full size is run and checked by benchmarks/bench_examples.py
    monkeypatch.setenv("FLEXBEARING_EXAMPLE_QUICK", "1")
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("FLEXBEARING_EXAMPLE_QUICK", "1")
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_slewing_race_static(monkeypatch, tmp_path):
    ex = _run("slewing_race_static", monkeypatch, tmp_path)
    # each ball's Hertz patch carries Q = W/(Z sin α) along the local groove normals (unit vectors,
    # weights summing to one), W = 68.9 t × 9.81 m/s²
    Q = 68.9e3 * 9.81 / (16 * math.sin(math.radians(60.0)))
    assert np.linalg.norm(ex.forces_N, axis=1).sum() == pytest.approx(16 * Q, rel=1e-12)
    # static equilibrium: the bolt reactions balance the ball loads
    assert ex.reaction_N == pytest.approx(-ex.applied_N, abs=1e-9 * np.abs(ex.applied_N).max())
    assert (tmp_path / "slewing_race_static" / "race.vtu").stat().st_size > 0
    assert (tmp_path / "slewing_race_static" / "von_mises.png").stat().st_size > 0


def test_ball_bearing_dynamics(monkeypatch, tmp_path):
    ex = _run("ball_bearing_dynamics", monkeypatch, tmp_path)
    # friction drives the cage up to the no-slip speed ω_i (1 − γ)/2 (Harris & Kotzalas, Essential
    # Concepts, eq. 8.24) within 1 % once spun up; the cage then swings about it (±1.8 %, period
    # about 30 ms, lightly damped), so the mean is taken from 10 ms on (over two swings)
    after = ex.run["t"] > 0.01
    assert np.mean(ex.cage_speed_rad_s[after]) == pytest.approx(ex.theory.cage_speed_rad_s, rel=0.01)
    assert ex.run["status"] == "complete"
    assert (tmp_path / "ball_bearing_dynamics" / "cage_speed.png").stat().st_size > 0


def test_flexible_race_dynamics(monkeypatch, tmp_path):
    ex = _run("flexible_race_dynamics", monkeypatch, tmp_path)
    # after the moment has ramped up (0.12 s) the balls carry the dead load and the moment: axial
    # components Q sin α (recorded contact angles) sum to W, their moment about x to M (2 %: the top
    # race still swings a little on its contacts)
    end = ex.t > 0.15
    axial = ex.ball_load_N[end] * np.sin(ex.run["angle"][end][:, ex.fixed])
    y = ex.run["q"][end][:, list(ex.balls.elements), 1]
    assert axial.sum(axis=1) == pytest.approx(np.full(end.sum(), ex.WEIGHT_N), rel=0.01)
    assert np.abs((axial * y).sum(axis=1)) == pytest.approx(np.full(end.sum(), ex.MOMENT_NM), rel=0.02)
    # the race's stress peaks once the moment is on
    assert ex.worst.time_s > 0.1
    assert (tmp_path / "flexible_race_dynamics" / "stress" / "stress.pvd").stat().st_size > 0
    assert (tmp_path / "flexible_race_dynamics" / "race_worst_0000.png").stat().st_size > 0
