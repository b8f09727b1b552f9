"""Fault injection: ``flexbearing loaddist … --out DIR`` killed (SIGKILL, SIGTERM) at random points.

Each of 20 runs writes a result with its own load (so old and new are told apart) and is killed
after a seeded random delay, as soon as its temporary folder holds summary.json (results written,
not yet swapped in), or as soon as the target changed (right after the swap). Every time the
target must hold either the complete previous result or the complete new one (summary.json
parseable with the expected load, every file present, the project's marker); after SIGTERM
nothing else may remain (the cleanup ran), after SIGKILL the next start's recovery
(:func:`cases.outdir.recover`) must leave nothing else.
"""

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

from cases.outdir import MARKER, recover

ROOT = Path(__file__).resolve().parents[1]
FILES = {"summary.json", "element_loads.csv", "contacts.csv", "element_loads.png", "contact_angles.png", MARKER}


def _start(out: Path, Fz_N: float, cache: Path) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(ROOT), FLEXBEARING_CACHE=str(cache), MPLBACKEND="Agg")
    return subprocess.Popen([sys.executable, "-m", "cases.cli", "loaddist", "slewing-ring", f"--Fz-N={Fz_N}",
                             "--out", str(out)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def _load_of(out: Path) -> float:
    assert {p.name for p in out.iterdir()} == FILES
    assert json.loads((out / MARKER).read_text())["format"] == "flexbearing-results/1"
    return json.loads((out / "summary.json").read_text())["load"]["Fz_N"]


def _entries(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name != "cache")


def _wait_for(proc: subprocess.Popen, ready, timeout_s: float = 30.0) -> None:
    t_end = time.monotonic() + timeout_s
    while proc.poll() is None and time.monotonic() < t_end and not ready():
        time.sleep(0.0005)


def test_killed_runs_leave_the_old_or_the_new_result_and_no_leftovers(tmp_path):
    rng = random.Random(18)
    out = tmp_path / "results"
    cache = tmp_path / "cache"
    t0 = time.monotonic()
    first = _start(out, -1.0e6, cache)
    assert first.wait(60) == 0, first.stderr.read().decode()
    duration_s = time.monotonic() - t0
    complete = -1.0e6
    outcomes = {"old": 0, "new": 0}
    for i in range(20):
        sig = signal.SIGKILL if i % 2 == 0 else signal.SIGTERM
        new_load = -1.0e6 - 1.0e4 * (i + 1)
        before = (out / MARKER).stat().st_ino
        proc = _start(out, new_load, cache)
        mode = i % 4
        if mode < 2:  # anywhere, up to a little past the end of an undisturbed run
            _wait_for(proc, lambda: False, rng.uniform(0.2, 1.1) * duration_s)
        elif mode == 2:  # results written in the temporary folder, not swapped in yet
            _wait_for(proc, lambda: any((p / "summary.json").exists() for p in tmp_path.glob(".results.fb-tmp-*")))
        else:  # right after the swap
            _wait_for(proc, lambda: (out / MARKER).exists() and (out / MARKER).stat().st_ino != before)
        if proc.poll() is None:
            proc.send_signal(sig)
        rc = proc.wait(60)
        err = proc.stderr.read().decode()
        assert "Traceback" not in err, err
        load = _load_of(out)
        assert load in (complete, new_load), (i, load)
        outcomes["new" if load == new_load else "old"] += 1
        if rc == 0:
            assert load == new_load
        complete = load
        left = [p for p in _entries(tmp_path) if p != "results"]
        if sig == signal.SIGTERM:
            assert left == [], (i, left)  # the handler's cleanup ran
        recover(tmp_path)  # what the next run does first
        assert _entries(tmp_path) == ["results"], (i, left)
    assert outcomes["old"] > 0 and outcomes["new"] > 0, outcomes
    last = _start(out, -2.0e6, cache)
    assert last.wait(60) == 0
    assert _load_of(out) == -2.0e6
    assert _entries(tmp_path) == ["results"]
