"""Resuming explicit runs: only the same model and settings, only forward, clear errors on damaged
checkpoints; a case run interrupted and resumed (API and ``flexbearing run --resume``) gives the
record of an uninterrupted run bit for bit (the reference: the uninterrupted run itself)."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import cases.slewing.dynamic as slewing_dynamic
from cases import integrate as integrate_mod
from cases.run import resolve_case, resume_folder, run_case
from mbd_core.multibody import simulate, stable_timestep
from mbd_core.multibody.recorder import read_run
from mbd_core.quasistatic import RingLoad
from test_multibody import SLEWING_ROW, slewing_model

ROOT = Path(__file__).resolve().parents[1]
G = 9.81


def _interrupted_record(tmp_path, load_N=2000.0 * G):
    model, state, _ = slewing_model(SLEWING_ROW, RingLoad(Fz_N=-load_N))
    h = stable_timestep(model, state).timestep_s
    simulate(model, state.copy(), 400 * h, timestep_s=h, folder=tmp_path / "rec", record_every=20, chunk_samples=5)
    return model, state, h


def test_resume_with_another_load_is_refused_naming_the_array(tmp_path):
    _, _, h = _interrupted_record(tmp_path, 2000.0 * G)
    other, state, _ = slewing_model(SLEWING_ROW, RingLoad(Fz_N=-3000.0 * G))
    with pytest.raises(ValueError, match=r"different model: body_force differ"):
        simulate(other, state.copy(), 800 * h, folder=tmp_path / "rec", record_every=20, resume=True)
    assert read_run(tmp_path / "rec")["status"] == "complete"  # the refused resume left the record as it was


def test_resume_to_a_time_before_the_checkpoint_is_refused(tmp_path):
    model, state, h = _interrupted_record(tmp_path)
    with pytest.raises(ValueError, match=r"before the checkpoint's time"):
        simulate(model, state.copy(), 200 * h, folder=tmp_path / "rec", record_every=20, resume=True)
    rec = read_run(tmp_path / "rec")
    assert rec["status"] == "complete" and rec["t"][-1] == pytest.approx(400 * h, rel=1e-12)


@pytest.mark.parametrize("damage", ["truncate", "empty", "bad-crc"])
def test_a_damaged_checkpoint_is_named_in_the_error(tmp_path, damage):
    model, state, h = _interrupted_record(tmp_path)
    ck = tmp_path / "rec" / "checkpoint.npz"
    data = ck.read_bytes()
    if damage == "truncate":
        ck.write_bytes(data[: len(data) // 2])
    elif damage == "empty":
        ck.write_bytes(b"")
    else:
        b = bytearray(data)
        b[len(b) // 2] ^= 0xFF
        ck.write_bytes(bytes(b))
    with pytest.raises(ValueError, match=r"checkpoint\.npz: checkpoint unreadable"):
        simulate(model, state.copy(), 800 * h, folder=tmp_path / "rec", record_every=20, resume=True)


def _stop_at(n):
    def progress(items, label):
        for k, x in enumerate(items):
            if k == n:
                raise KeyboardInterrupt
            yield x
    return progress


def test_integrate_resumes_bit_for_bit_and_refuses_another_model(tmp_path):
    model, state, _ = slewing_model(SLEWING_ROW, RingLoad(Fz_N=-2000.0 * G))
    whole = integrate_mod.integrate(model, state.copy(), 0.004, 20, chunks=8)

    with pytest.raises(KeyboardInterrupt), integrate_mod.checkpoints(tmp_path / "ck"):
        integrate_mod.integrate(model, state.copy(), 0.004, 20, progress=_stop_at(3), chunks=8)
    assert len(list((tmp_path / "ck" / "run_00").glob("piece_*.npz"))) == 3
    with integrate_mod.checkpoints(tmp_path / "ck", resume=True):
        resumed = integrate_mod.integrate(model, state.copy(), 0.004, 20, chunks=8)
    assert resumed.keys() == whole.keys()
    for k, v in whole.items():
        if isinstance(v, np.ndarray):
            np.testing.assert_array_equal(resumed[k], v, err_msg=k)
        else:
            assert resumed[k] == v, k
    other, _, _ = slewing_model(SLEWING_ROW, RingLoad(Fz_N=-3000.0 * G))
    with pytest.raises(integrate_mod.ResumeError, match=r"model differs .*body_force"), \
            integrate_mod.checkpoints(tmp_path / "ck", resume=True):
        integrate_mod.integrate(other, state.copy(), 0.004, 20, chunks=8)
    with pytest.raises(integrate_mod.ResumeError, match=r"duration_s differs"), \
            integrate_mod.checkpoints(tmp_path / "ck", resume=True):
        integrate_mod.integrate(model, state.copy(), 0.005, 20, chunks=8)


TINY = ["analysis.duration_s=0.01"]


def _recording(monkeypatch):
    runs = []
    real = slewing_dynamic.integrate

    def spy(*args, **kwargs):
        runs.append(real(*args, **kwargs))
        return runs[-1]

    monkeypatch.setattr(slewing_dynamic, "integrate", spy)
    return runs


def test_a_case_run_interrupted_and_resumed_equals_an_uninterrupted_one(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path / "cache"))
    runs = _recording(monkeypatch)
    case = resolve_case("slewing-rotation", True, TINY)
    run_case(case, tmp_path / "whole")
    with pytest.raises(KeyboardInterrupt):
        run_case(case, tmp_path / "cut", progress=_stop_at(17))
    assert not (tmp_path / "cut").exists()
    assert len(list(resume_folder(tmp_path / "cut").glob("run_00/piece_*.npz"))) == 17
    run_case(case, tmp_path / "cut", resume=True)
    whole, resumed = runs[0], runs[-1]
    for k, v in whole.items():
        if isinstance(v, np.ndarray):
            np.testing.assert_array_equal(resumed[k], v, err_msg=k)
    for name in ("ball_loads_time.csv", "spacer_forces_time.csv", "balls_end.vtu"):
        assert (tmp_path / "cut" / name).read_bytes() == (tmp_path / "whole" / name).read_bytes(), name
    assert not resume_folder(tmp_path / "cut").exists()  # removed once the results are in place
    # interrupted before any piece: nothing is kept
    with pytest.raises(KeyboardInterrupt):
        run_case(case, tmp_path / "early", progress=_stop_at(0))
    assert not resume_folder(tmp_path / "early").exists() and not (tmp_path / "early").exists()
    # a resume of another case is refused, naming the entry
    with pytest.raises(KeyboardInterrupt):
        run_case(case, tmp_path / "cut", progress=_stop_at(2))
    other = resolve_case("slewing-rotation", True, TINY + ["analysis.speed_rpm=7"])
    with pytest.raises(integrate_mod.ResumeError, match=r"analysis\.speed_rpm"):
        run_case(other, tmp_path / "cut", resume=True)


def _cli(out: Path, cache: Path, *extra) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(ROOT), FLEXBEARING_CACHE=str(cache), MPLBACKEND="Agg")
    return subprocess.Popen([sys.executable, "-m", "cases.cli", "run", "slewing-rotation", "--quick", "--set", TINY[0],
                             "--out", str(out), *extra], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


@pytest.fixture(scope="module")
def whole_cli(tmp_path_factory):
    """The uninterrupted run: the reference of the resumed ones."""
    folder = tmp_path_factory.mktemp("whole")
    assert _cli(folder / "whole", folder / "cache").wait(120) == 0
    return folder / "whole"


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM], ids=["SIGKILL", "SIGTERM"])
def test_cli_resume_after_a_kill_gives_the_uninterrupted_result(tmp_path, sig, whole_cli):
    cache = tmp_path / "cache"
    proc = _cli(tmp_path / "cut", cache)
    keep = resume_folder(tmp_path / "cut")
    t_end = time.monotonic() + 120
    while proc.poll() is None and time.monotonic() < t_end and len(list(keep.glob("run_00/piece_*.npz"))) < 10:
        time.sleep(0.001)
    proc.send_signal(sig)
    proc.wait(60)
    assert not (tmp_path / "cut").exists()
    n_kept = len(list(keep.glob("run_00/piece_*.npz")))
    assert 10 <= n_kept < 40
    resumed = _cli(tmp_path / "cut", cache, "--resume")
    assert resumed.wait(120) == 0, resumed.stderr.read().decode()
    for name in ("ball_loads_time.csv", "spacer_forces_time.csv", "balls_end.vtu"):
        assert (tmp_path / "cut" / name).read_bytes() == (whole_cli / name).read_bytes(), name
    a, b = (json.loads((d / "summary.json").read_text()) for d in (whole_cli, tmp_path / "cut"))
    for d in (a, b):
        del d["wall_time_s"], d["peak_rss_mb"]
    assert a == b
    assert sorted(p.name for p in tmp_path.iterdir() if p.name != "cache") == ["cut"]
