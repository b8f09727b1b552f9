"""The background compilation of the dynamics kernels (mbd_core.multibody.warmup).

The warm-up is useful only if it compiles the very specialisations a run asks for: numba keys its
cache by the argument types of each call from Python. The reference is therefore a real run of the
cases: with the JIT off (``NUMBA_DISABLE_JIT=1``, a subprocess) every kernel called from Python is
wrapped to record the numba types of its arguments, once for the warm-up's small model and once for
short dynamic runs of a slewing and a wind case; every (kernel, types) of the runs must be among the
warm-up's. The cache check is compared with numba's own behaviour on a small kernel, and the
waiting side with processes whose outcome is known.
"""

from __future__ import annotations

import json
import logging
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: modules that call kernels from Python (the only ones: mbd_core/kernels is imported nowhere else)
CALLERS = ("mbd_core.multibody.explicit", "mbd_core.multibody.statics", "mbd_core.multibody.implicit",
           "mbd_core.multibody.bearings")


def _env(**extra) -> dict:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])),
               MPLBACKEND="Agg", **extra)
    return env


def _record_calls() -> set:
    """(kernel name, argument types) of every kernel call from Python, recorded from now on."""
    import importlib

    import numba

    calls = set()
    for name in CALLERS:
        mod = importlib.import_module(name)
        for key, fn in list(vars(mod).items()):
            if callable(fn) and getattr(fn, "__module__", "").startswith("mbd_core.kernels"):
                def recorded(*args, _fn=fn, _key=key):
                    calls.add((_key, tuple(str(numba.typeof(a)) for a in args)))
                    return _fn(*args)
                setattr(mod, key, recorded)
    return calls


def _child() -> None:
    """Print the recorded calls of the warm-up and of two short case runs as JSON."""
    from cases.results import RunOutput
    from cases.run import resolve_case
    from cases.slewing.dynamic import run_dynamic
    from cases.wind import scene as wind_scene
    from mbd_core.multibody import simulate, stable_timestep

    calls = _record_calls()
    from mbd_core.multibody.warmup import compile_kernels

    compile_kernels()
    warm = sorted(calls)
    calls.clear()
    slewing = resolve_case("slewing-rotation", True, ["analysis.duration_s=2e-3", "analysis.record_every=1"])
    run_dynamic(slewing, RunOutput(tempfile.mkdtemp()))
    # the wind scene (roller slices, ribs, slot pockets, implicit friction) for a few steps of its own
    # run's integrator (the case's run repeats these calls in 40 pieces)
    sc = wind_scene.build_scene(resolve_case("wind-speeds", True))
    h = stable_timestep(sc.model, sc.state).timestep_s
    simulate(sc.model, sc.state, sc.state.t + 3 * h, timestep_s=h, record_every=1)
    print(json.dumps({"warmup": warm, "runs": sorted(calls)}))


@pytest.fixture(scope="module")
def recorded():
    run = subprocess.run([sys.executable, __file__], env=_env(NUMBA_DISABLE_JIT="1"), capture_output=True,
                         text=True, timeout=1200, cwd=ROOT)
    assert run.returncode == 0, run.stderr[-3000:]
    data = json.loads(run.stdout.strip().splitlines()[-1])
    return {k: {(name, tuple(types)) for name, types in v} for k, v in data.items()}


def test_warmup_compiles_every_specialisation_that_case_runs_call(recorded):
    runs, warm = recorded["runs"], recorded["warmup"]
    # the runs reach the integrator, the stable step and the builder helpers at all
    assert {"run_explicit", "compute_forces", "friction_coefficient", "groove_point"} <= {k for k, _ in runs}
    missing = sorted(runs - warm)
    assert not missing, f"the warm-up misses {missing}"


def test_warmup_reaches_the_modal_entry_points(recorded):
    # the wind-rigid-flexible runs have modal rings: their stable step calls modal_mass_matrix
    assert "modal_mass_matrix" in {k for k, _ in recorded["warmup"]}


def test_cache_check_follows_numba_cache(tmp_path):
    """has_cached_overloads is False before and True after numba compiled a kernel into an empty cache."""
    code = ("from mbd_core.kernels.disk_cache import has_cached_overloads\n"
            "from mbd_core.kernels.laws import step\n"
            "before = has_cached_overloads(step)\n"
            "step(0.5, 0.0, 1.0, 0.0, 1.0)\n"
            "print(before, has_cached_overloads(step))\n")
    run = subprocess.run([sys.executable, "-c", code], env=_env(NUMBA_CACHE_DIR=str(tmp_path)),
                         capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.split() == ["False", "True"]


def test_finalize_waits_for_the_warmup(monkeypatch):
    from mbd_core.multibody import ModelBuilder, warmup

    waited = []
    monkeypatch.setattr(warmup, "wait", lambda: waited.append(True))
    mb = ModelBuilder()
    mb.add_body("b", 1.0, (1.0, 1.0, 1.0))
    mb.finalize()
    assert waited == [True]


def test_failed_warmup_only_warns(monkeypatch, caplog):
    from mbd_core.multibody import warmup

    proc = subprocess.Popen([sys.executable, "-c", "import sys; sys.stderr.write('broken\\n'); sys.exit(3)"],
                            stderr=subprocess.PIPE)
    monkeypatch.setattr(warmup, "_process", proc)
    with caplog.at_level(logging.WARNING, logger=warmup.__name__):
        warmup.wait()
    assert warmup._process is None
    assert "exit status 3: broken" in caplog.text


def test_waiting_for_the_warmup_is_a_phase_on_screen(monkeypatch):
    """While the main process waits for a warm-up still compiling, a phase says so (the kernels
    compile in another process, where the main process's compile listener sees nothing); it
    lasts as long as the wait, here a child that sleeps 0.5 s (±0.4 s for process start-up)."""
    import time

    from foundation.progress import Reporter, reporting
    from mbd_core.kernels.compile_progress import COMPILING_LABEL
    from mbd_core.multibody import warmup

    class Recorder(Reporter):
        def __init__(self):
            self.finished = []

        def finish(self, phase):
            self.finished.append((phase.label, phase.elapsed_s()))

    proc = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(0.5)"], stderr=subprocess.PIPE)
    monkeypatch.setattr(warmup, "_process", proc)
    monkeypatch.setattr(warmup, "_started_s", time.perf_counter())
    rec = Recorder()
    with reporting(rec):
        warmup.wait()
    assert len(rec.finished) == 1 and rec.finished[0][0].startswith(COMPILING_LABEL)
    assert 0.1 < rec.finished[0][1] < 0.9


@pytest.mark.parametrize("env, cached", [({}, True), ({"FLEXBEARING_KERNEL_WARMUP": "0"}, False),
                                         ({"NUMBA_DISABLE_JIT": "1"}, False)])
def test_no_warmup_when_cached_or_switched_off(monkeypatch, env, cached):
    from mbd_core.multibody import warmup

    for k, v in env.items():
        monkeypatch.setenv(k, v)
    monkeypatch.setattr(warmup, "kernels_cached", lambda: cached)
    monkeypatch.setattr(warmup.subprocess, "Popen", lambda *a, **k: pytest.fail("no process may start"))
    assert warmup.start() is False


if __name__ == "__main__":
    _child()


@pytest.mark.parametrize("name, quick, dynamic", [
    ("slewing-undulation", False, True),     # its spacer run (study.spacer_run_s > 0)
    ("slewing-rotation", True, True),
    ("slewing-static", False, False),
    ("slewing-thermal", False, False),
    ("wind-static", False, False),
    ("wind-rigid-flexible", True, True),
])
def test_warmup_starts_for_the_cases_that_run_dynamics(name, quick, dynamic):
    """Reference: the studies' code, where a dynamic run is reached (cases/*/studies.py run_study)."""
    from cases.run import _FAMILIES, resolve_case

    case = resolve_case(name, quick)
    assert _FAMILIES[type(case)][1].uses_dynamics(case) is dynamic


def test_undulation_without_spacer_run_needs_no_kernels():
    from cases.run import resolve_case
    from cases.slewing.studies import uses_dynamics

    assert uses_dynamics(resolve_case("slewing-undulation", False, ["study.spacer_run_s=0"])) is False
