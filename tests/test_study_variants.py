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
    assert main(["run", "wind-load-case", "--quick", "--workers", "2"]) == 2
    assert "--workers: the load-case study of wind-load-case-quick makes one run" in capsys.readouterr().err


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


def _csv(path) -> list[dict]:
    import csv

    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def test_slewing_thermal_offsets_on_two_workers_equal_the_serial_ones(tmp_path):
    """Study (d) runs each offset as a ``single`` travel in its own folder; on a 2-worker
    LocalCluster the key figures and the worst ball's history are bit for bit those of the
    in-process run (the same quasi-static travel in another process)."""
    args = ["run", "slewing-thermal", "--quick", "--set", "study.offsets_m=[0.3e-3, 0.5e-3]"]
    assert main([*args, "--out", str(tmp_path / "serial")]) == 0
    assert main([*args, "--workers", "2", "--out", str(tmp_path / "dask")]) == 0
    serial, dask = _summary(tmp_path / "serial"), _summary(tmp_path / "dask")
    assert serial["cases"] == dask["cases"]
    assert [c["folder"] for c in dask["cases"]] == ["offset=0.3mm", "offset=0.5mm"]
    assert dask["cluster"]["workers"] == 2
    for case in dask["cases"]:
        name = f"travel_ball_history_{case['offset_mm']:g}mm_E200GPa.csv"
        assert (tmp_path / "dask" / case["folder"] / name).read_bytes() == \
            (tmp_path / "serial" / case["folder"] / name).read_bytes()
        # the variant is the single travel of the case at that offset
        assert _summary(tmp_path / "dask" / case["folder"])["study"] == "single"
    # the offset squeezes the balls in its sector: the worst ball load grows with it (thesis study (d))
    assert dask["cases"][0]["max_ball_load_N"] < dask["cases"][1]["max_ball_load_N"]


def test_slewing_study_resumes_with_its_finished_points(tmp_path, monkeypatch):
    """A slewing study stopped after its points finished reuses them with ``resume``."""
    from cases.slewing import studies

    case = resolve_case("slewing-thermal", True, ["study.offsets_m=[0.3e-3, 0.5e-3]"])
    out = tmp_path / "run"

    def stop_after_the_points(*a, **k):
        points(*a, **k)
        raise KeyboardInterrupt

    points = studies._travel_runs
    with monkeypatch.context() as m:
        m.setattr(studies, "_travel_runs", stop_after_the_points)
        with pytest.raises(KeyboardInterrupt):
            run_case(case, out)
    resumed = run_case(case, out, resume=True).summary
    assert {v["worker"] for v in resumed["variants"].values()} == {"reused"}
    assert resumed["cases"] == run_case(case, tmp_path / "fresh").summary["cases"]


def test_wind_spectrum_load_cases_on_two_workers_equal_the_serial_ones(tmp_path):
    """The 32 load cases of wind-static are ``load-case`` runs: on 2 workers the table and every
    load case's roller loads are bit for bit the in-process ones."""
    args = ["run", "wind-static", "--quick"]
    assert main([*args, "--out", str(tmp_path / "serial")]) == 0
    assert main([*args, "--workers", "2", "--out", str(tmp_path / "dask")]) == 0
    for name in ("max_roller_loads.csv", *(f"load_case={k:02d}/roller_loads.csv" for k in range(1, 33))):
        assert (tmp_path / "dask" / name).read_bytes() == (tmp_path / "serial" / name).read_bytes(), name
    assert _summary(tmp_path / "dask")["max_roller_load_N"] == _summary(tmp_path / "serial")["max_roller_load_N"]


def test_a_load_case_balances_its_load(tmp_path):
    """The roller loads of one load case, read back from roller_loads.csv, balance the load put
    on the inner ring (statics, independent of the solver's own residual): the radial row's
    rollers (contact angle 0) carry Fx and Fy with the ring's weight, the difference of the two
    thrust rows (contact angle 90°) carries Fz."""
    import math

    import numpy as np

    from cases.wind.scene import inner_ring_load
    from cases.wind.spectrum import load_cases

    out = tmp_path / "lc"
    assert main(["run", "wind-load-case", "--set", "loads.case_index=5", "--out", str(out)]) == 0
    rows = _csv(out / "roller_loads.csv")
    load = inner_ring_load(load_cases()[0][5])

    def of(row):
        q = np.array([float(r["load_N"]) for r in rows if r["row"] == row])
        psi = np.radians([float(r["azimuth_deg"]) for r in rows if r["row"] == row])
        return q, psi

    q, psi = of("radial")
    fx, fy = np.sum(q * np.cos(psi)), np.sum(q * np.sin(psi))
    scale = math.hypot(load.Fx_N, load.Fy_N, load.Fz_N)
    # tolerance 1e-6 of the load: the quasi-static Newton solve converges to 1e-8 (test_wind_cases)
    assert abs(abs(fx) - abs(load.Fx_N)) < 1e-6 * scale and abs(abs(fy) - abs(load.Fy_N)) < 1e-6 * scale
    thrust = of("front thrust")[0].sum() - of("rear thrust")[0].sum()
    assert abs(abs(thrust) - abs(load.Fz_N)) < 1e-6 * scale
    s = _summary(out)
    # (the CSV holds the loads to its printed digits)
    assert s["load_case"] == 6 and s["max_roller_load_N"]["radial"] == pytest.approx(q.max(), rel=1e-6)
