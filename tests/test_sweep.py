"""``flexbearing sweep`` on Dask: points, a real LocalCluster against serial runs, a scheduler and
workers started from the ``dask`` command line, an interrupted sweep resumed, a refused point."""

from __future__ import annotations

import csv
import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

from cases.cli import main
from cases.config import CaseError
from cases.run import resolve_case, run_case
from cases.sweep.spec import SweepSpec, parse_vary, read_sweep_file

# the points: the quick quasi-static study of the 12 MW main bearing at four spectrum scales
SCALES = ("0.8", "1.0", "1.2", "1.4")


def test_vary_values_and_points(tmp_path):
    # numpy.linspace's ends and spacing; integers stay integers (an int key needs them)
    assert parse_vary("analysis.speed_rpm=20:30:3").values == ("20", "25", "30")
    assert parse_vary("loads.scale=0.5:1:3").values == ("0.5", "0.75", "1")
    assert parse_vary("x=1:2:3").values == ("1", "1.5", "2")
    # commas inside brackets and quotes belong to one value
    assert parse_vary('study.offsets_m=[0.3e-3,0.4e-3],[0.5e-3], "a,b"').values == \
        ("[0.3e-3,0.4e-3]", "[0.5e-3]", '"a,b"')
    a, b = parse_vary("contact.mu_dynamic=0.025,0.1"), parse_vary("contact.mu_static=0.05,0.2")
    grid = SweepSpec("wind-speeds", (a, b)).points()
    assert [p.values for p in grid] == [(("contact.mu_dynamic", x), ("contact.mu_static", y))
                                        for x in ("0.025", "0.1") for y in ("0.05", "0.2")]
    zipped = SweepSpec("wind-speeds", (a, b), mode="zip").points()
    assert [p.name for p in zipped] == ["mu_dynamic=0.025_mu_static=0.05", "mu_dynamic=0.1_mu_static=0.2"]
    assert zipped[1].assignments == ("contact.mu_dynamic=0.1", "contact.mu_static=0.2")
    with pytest.raises(CaseError, match="as many values"):
        SweepSpec("wind-speeds", (a, parse_vary("contact.mu_static=0.05,0.1,0.2")), mode="zip")
    with pytest.raises(CaseError, match="also given with --set"):
        SweepSpec("wind-speeds", (a,), sets=("contact.mu_dynamic=0.2",))
    with pytest.raises(CaseError, match="n ≥ 2"):
        parse_vary("loads.scale=0:1:1")
    # a sweep file: a range table, a list, nested keys, the case file relative to the file
    f = tmp_path / "s.toml"
    f.write_text('case = "my.toml"\nmode = "zip"\nset = ["loads.scale=1.2"]\n[vary]\n'
                 '"analysis.speed_rpm" = { start = 20, stop = 30, n = 2 }\ncontact.mu_dynamic = [0.05, 0.1]\n')
    s = read_sweep_file(str(f))
    assert s.case == str(tmp_path / "my.toml") and s.mode == "zip" and s.sets == ("loads.scale=1.2",)
    assert [(x.key, x.values) for x in s.axes] == [("analysis.speed_rpm", ("20", "30")),
                                                   ("contact.mu_dynamic", ("0.05", "0.1"))]
    f.write_text('case = "wind-static"\nrepeat = 2\n[vary]\n"loads.scale" = [1.0]\n')
    with pytest.raises(CaseError, match="repeat: unknown key"):
        read_sweep_file(str(f))


def _figures(folder: Path) -> dict:
    d = json.loads((folder / "summary.json").read_text())
    # (the times and places of the runs differ; "variants" records them for a study's own runs)
    return {k: v for k, v in d.items() if k not in ("wall_time_s", "peak_rss_mb", "sweep_point", "description",
                                                    "variants")}


def test_local_cluster_matches_serial_runs(tmp_path, capsys):
    """4 points on a real 2-worker LocalCluster give bit-for-bit the figures and CSV files of 4
    serial runs of the same cases in this process; a fifth point with an invalid value fails
    alone, named on the terminal and in sweep.json; the table reads back from Parquet."""
    out = tmp_path / "sweep"
    # -1: refused by the case's validation before any work; 10000: valid, but no equilibrium exists
    # (the rollers would need approaches beyond their diameter), so it fails on its worker
    code = main(["sweep", "wind-static", "--quick", "--vary", f"loads.scale={','.join(SCALES)},-1,10000",
                 "--workers", "2", "--out", str(out)])
    err = capsys.readouterr()
    assert code == 2  # points failed: the input's fault
    assert "2 of 6 points failed (scale=-1: loads.scale must be ≥ 0" in err.err
    assert "scale=-1: INVALID" in err.out and "scale=10000: FAILED: no converged equilibrium" in err.out
    meta = json.loads((out / "sweep.json").read_text())
    status = {p["name"]: p["status"] for p in meta["points"]}
    assert status == {**{f"scale={s}": "computed" for s in SCALES}, "scale=-1": "invalid", "scale=10000": "failed"}
    assert "no converged equilibrium" in meta["points"][-1]["error"] and not (out / "scale=10000").exists()
    assert meta["cluster"]["workers"] == 2 and meta["computed"] == 4
    for s in SCALES:
        serial = tmp_path / f"serial-{s}"
        run_case(resolve_case("wind-static", True, [f"loads.scale={s}"]), serial)
        assert _figures(out / f"scale={s}") == _figures(serial)
        for name in ("max_roller_loads.csv", "load_history.csv", "case.toml"):
            assert (out / f"scale={s}" / name).read_bytes() == (serial / name).read_bytes()
    rows = list(csv.DictReader(open(out / "sweep.csv")))
    table = pq.read_table(out / "sweep.parquet").to_pydict()
    assert table["point"] == [r["point"] for r in rows] == [f"scale={s}" for s in (*SCALES, "-1", "10000")]
    assert table["status"] == ["ok"] * 4 + ["invalid", "failed"]
    radial = [json.loads((out / f"scale={s}" / "summary.json").read_text())["max_roller_load_N"]["radial"]
              for s in SCALES]
    assert table["max_roller_load_N.radial"][:4] == radial
    assert [float(r["max_roller_load_N.radial"]) for r in rows[:4]] == radial
    assert table["loads.scale"] == [0.8, 1.0, 1.2, 1.4, -1.0, 10000.0]
    assert (out / "sweep_max_roller_load_N.radial.png").stat().st_size > 1000
    # the largest roller load grows with the load, more slowly than in proportion (Hertz: Q ∝ δ^1.5
    # stiffens, and more rollers share it)
    assert np.all(np.diff(radial) > 0) and radial[-1] / radial[0] < 1.4 / 0.8


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_sweep_on_a_scheduler_started_from_the_dask_command_line(tmp_path):
    """``dask scheduler`` and two ``dask worker`` processes on the loopback address; the sweep
    goes to them through ``--scheduler tcp://127.0.0.1:PORT`` and its figures equal a serial run's."""
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    dask = [sys.executable, "-m", "dask"]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    procs = [subprocess.Popen([*dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        for _ in range(2):
            procs.append(subprocess.Popen([*dask, "worker", address, "--nthreads", "1", "--nworkers", "1",
                                           "--no-dashboard"], env=env, stdout=subprocess.DEVNULL,
                                          stderr=subprocess.DEVNULL))
        from distributed import Client

        with Client(address, timeout="60s") as client:
            client.wait_for_workers(2, timeout=120)
        out = tmp_path / "sweep"
        assert main(["sweep", "wind-static", "--quick", "--vary", "loads.scale=0.9,1.1", "--scheduler", address,
                     "--out", str(out)]) == 0
        meta = json.loads((out / "sweep.json").read_text())
        assert meta["cluster"]["scheduler"] == address and meta["cluster"]["workers"] == 2
        workers = {p["worker"] for p in meta["points"]}
        assert all(w.split(":")[1] != str(os.getpid()) for w in workers)  # run by the workers, not here
        serial = tmp_path / "serial"
        run_case(resolve_case("wind-static", True, ["loads.scale=1.1"]), serial)
        assert _figures(out / "scale=1.1") == _figures(serial)
    finally:
        for p in procs[::-1]:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()


def test_interrupted_sweep_resumes_with_only_the_missing_points(tmp_path):
    """A sweep of 4 points on one worker stopped (SIGTERM) once 2 are done: rerun with --resume
    it computes only the points missing and reuses the others."""
    out = tmp_path / "sweep"
    # the thermal study of the 2 m slewing ring, quick, with a finer travel: about 2 s a point
    cmd = [sys.executable, "-m", "cases.cli", "sweep", "slewing-thermal", "--quick", "--set",
           "analysis.travel_steps=1440", "--vary", "study.offsets_m=[0.2e-3],[0.3e-3],[0.4e-3],[0.5e-3]",
           "--workers", "1", "--out", str(out)]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    done = 0
    deadline = time.monotonic() + 600
    while time.monotonic() < deadline and proc.poll() is None:
        try:
            done = json.loads((out / "sweep.json").read_text()).get("computed", 0)
        except (OSError, ValueError):
            done = 0
        if done >= 2:
            proc.send_signal(signal.SIGTERM)
            break
        time.sleep(0.05)
    proc.communicate(timeout=120)
    assert done >= 2, "the sweep ended before two points were done"
    assert proc.returncode != 0  # stopped, not completed
    first = json.loads((out / "sweep.json").read_text())
    finished = {p["name"] for p in first["points"] if p["status"] == "computed"}
    assert 2 <= len(finished) < 4, first["points"]
    resumed = subprocess.run([*cmd, "--resume"], env=env, capture_output=True, text=True, timeout=600)
    assert resumed.returncode == 0, resumed.stderr
    second = json.loads((out / "sweep.json").read_text())
    status = {p["name"]: p["status"] for p in second["points"]}
    # the points recorded as done are reused; so is a point whose worker completed it while the
    # cluster shut down (its folder is complete: it is swapped in whole or not at all)
    reused = {n for n, s in status.items() if s == "reused"}
    assert finished <= reused
    assert sum(s == "computed" for s in status.values()) == 4 - len(reused)
    # every point is complete and the table holds all four
    rows = list(csv.DictReader(open(out / "sweep.csv")))
    assert [r["status"] for r in rows] == ["ok"] * 4
    assert not [p for p in out.iterdir() if p.name.startswith(".") and "fb-tmp" in p.name]


def test_readme_sweep_file_runs(tmp_path):
    """The sweep file of the README runs as written: three thermal offsets of the 2 m slewing
    ring, whose worst ball load grows with the offset (the offset squeezes the balls in its
    sector: thesis study (d))."""
    text = (Path(__file__).parents[1] / "README.md").read_text(encoding="utf-8")
    block = "# my-sweep.toml" + text.split("```toml\n# my-sweep.toml")[1].split("```")[0]
    f = tmp_path / "my-sweep.toml"
    f.write_text(block)
    out = tmp_path / "sweep"
    assert main(["sweep", str(f), "--workers", "1", "--out", str(out)]) == 0
    rows = list(csv.DictReader(open(out / "sweep.csv")))
    assert [r["point"] for r in rows] == ["offsets_m=0.0003", "offsets_m=0.0004", "offsets_m=0.0005"]
    worst = [float(r["cases[0].max_ball_load_N"]) for r in rows]
    assert worst[0] < worst[1] < worst[2]
    serial = tmp_path / "serial"
    run_case(resolve_case("slewing-thermal", True, ["analysis.travel_steps=720", "study.offsets_m=[0.4e-3]"]), serial)
    assert _figures(out / "offsets_m=0.0004") == _figures(serial)
