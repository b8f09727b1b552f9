"""Studies that compare runs of one case (wind-driving-speed) run them as variants: each an
ordinary run in a sub-folder, in this process or on a Dask LocalCluster with identical results,
and reused after an interruption by ``--resume``."""

from __future__ import annotations

import json

import pytest

from cases import run as run_module
from cases.cli import main
from cases.run import resolve_case, run_case, resume_folder

# the quick driving-speed study (20 and 30 r/min) cut to 60 ms simulated, 20 ms settling
SHORT = ["analysis.duration_s=0.06", "analysis.settle_s=0.02"]


def _summary(folder) -> dict:
    return json.loads((folder / "summary.json").read_text())


def test_variants_on_two_workers_equal_the_serial_ones(tmp_path, capsys):
    args = ["run", "wind-driving-speed", "--quick", *[x for s in SHORT for x in ("--set", s)]]
    assert main([*args, "--out", str(tmp_path / "serial")]) == 0
    assert main([*args, "--workers", "2", "--out", str(tmp_path / "dask")]) == 0
    serial, dask = _summary(tmp_path / "serial"), _summary(tmp_path / "dask")
    # bit for bit: each variant is the same explicit run, in another process
    assert serial["by_speed_rpm"] == dask["by_speed_rpm"]
    assert serial["front_rear_cage_force_ratio"] == dask["front_rear_cage_force_ratio"]
    assert dask["cluster"]["workers"] == 2
    assert {v["worker"] for v in serial["variants"].values()} == {"this process"}
    assert "this process" not in {v["worker"] for v in dask["variants"].values()}
    for name in ("speed=20rpm", "speed=30rpm"):
        for folder in (tmp_path / "serial", tmp_path / "dask"):
            assert (folder / name / "timeseries.nc").stat().st_size > 0
        # the variant is the speeds study of the case at that speed; its figures are in the comparison
        v = _summary(tmp_path / "dask" / name)
        assert v["study"] == "speeds"
        assert v["cage_forces"] == dask["by_speed_rpm"][name.split("=")[1].replace("rpm", ".0")]


def test_workers_refused_for_a_study_of_one_run(capsys):
    assert main(["run", "wind-static", "--quick", "--workers", "2"]) == 2
    assert "--workers: the static study of wind-static-quick makes one run" in capsys.readouterr().err


def test_resume_reuses_the_finished_variants(tmp_path, monkeypatch):
    """A run stopped after its variants finished keeps them in its checkpoint folder; with
    ``resume`` they are reused (not run again) and the results equal an uninterrupted run's."""
    case = resolve_case("wind-driving-speed", True, SHORT)
    out = tmp_path / "run"
    from cases.wind import plots

    def stop(*a, **k):
        raise KeyboardInterrupt

    with monkeypatch.context() as m:
        m.setattr(plots, "sweep_figure", stop)
        with pytest.raises(KeyboardInterrupt):
            run_case(case, out)
    kept = resume_folder(out) / "points"
    assert sorted(p.name for p in kept.iterdir() if not p.name.startswith(".")) == ["speed=20rpm", "speed=30rpm"]
    resumed = run_case(case, out, resume=True).summary
    assert {v["worker"] for v in resumed["variants"].values()} == {"reused"}
    fresh = run_case(case, tmp_path / "fresh").summary
    assert resumed["by_speed_rpm"] == fresh["by_speed_rpm"]
    assert not resume_folder(out).exists()
    assert run_module.runs_variants(case)
