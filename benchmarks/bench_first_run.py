"""CPU time and peak memory of a case's first run on a cold machine, phase by phase.

A user's first command meets an empty result cache and an empty numba cache: every ring is
meshed, assembled and reduced, every kernel compiled. This benchmark runs a case that way (fresh
temporary ``FLEXBEARING_CACHE`` and ``NUMBA_CACHE_DIR``, removed afterwards) in a child process and
prints, per phase, the CPU seconds spent in it (exclusive: a compilation inside the dynamic run
counts as compilation) and the process's peak resident memory when the phase last ended.

    python benchmarks/bench_first_run.py                       # slewing-undulation, as the README
    python benchmarks/bench_first_run.py wind-rigid-flexible --quick
    python benchmarks/bench_first_run.py --quick               # CI: a small cold run (~20 s of CPU)
    python benchmarks/bench_first_run.py --warm-cache DIR ...  # keep the result cache in DIR

``--quick`` alone runs ``slewing-undulation --quick`` with a coarse top structure and without its
spacer-ball run (:data:`CI_CASE`): every FE phase and the quasi-static solves, no numba compilation.
CPU time, not wall time, is the figure to compare on a shared machine; the wall time and the CPU
of child processes (the numba warm-up) are printed too. The FE solves use ``FLEXBEARING_SPARSE_SOLVER``
as set in the environment (the default install: ``cholespy``).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: phase name → "module:function" timed in the child; the innermost active phase gets the CPU
PHASES = {
    "meshing": ("fem_rings.mesh:mesh_ring",),
    "assembly": ("fem_rings.assembly:stiffness_matrix", "fem_rings.assembly:mass_matrix"),
    "factorisation": ("fem_rings.linalg:factorize_spd",),
    "eigen solve": ("fem_rings.modal_basis:deflated_eigsh",),
    "CB reduction (rest)": ("cms_reduction.craig_bampton:reduce_model",),
    "invariants, sampling, stress modes": ("cms_reduction.invariants:compute_invariants",
                                           "cms_reduction.sampling:sample_raceway",
                                           "cms_reduction.stress_modes:add_stress_modes"),
    "quasi-static solves": ("cases.slewing.quasistatic:equilibrium", "cases.slewing.quasistatic:travel"),
    "dynamic run": ("cases.slewing.dynamic:run_dynamic", "cases.wind.dynamic:run"),
    "waiting for the kernel warm-up": ("mbd_core.multibody.warmup:wait",),
}
COMPILE = "numba compilation"
#: the CI run of ``--quick`` alone: (case, --set overrides)
CI_CASE = ("slewing-undulation", ("study.spacer_run_s=0", "top.element_size_m=0.25"))
OTHER = "imports, plots, output, rest"


def _peak_mb(who=resource.RUSAGE_SELF) -> float:
    return resource.getrusage(who).ru_maxrss / 1024.0


class _Clock:
    """Exclusive CPU time per phase with a stack of active phases."""

    def __init__(self) -> None:
        self.stack = [OTHER]
        self.cpu_s = {OTHER: 0.0}
        self.peak_mb = {OTHER: 0.0}
        self.last = time.process_time()

    def _switch(self) -> None:
        now = time.process_time()
        top = self.stack[-1]
        self.cpu_s[top] = self.cpu_s.get(top, 0.0) + now - self.last
        self.peak_mb[top] = max(self.peak_mb.get(top, 0.0), _peak_mb())
        self.last = now

    def enter(self, phase: str) -> None:
        self._switch()
        self.stack.append(phase)

    def leave(self) -> None:
        self._switch()
        self.stack.pop()


def _wrap(clock: _Clock, phase: str, fn):
    def timed(*args, **kwargs):
        clock.enter(phase)
        try:
            return fn(*args, **kwargs)
        finally:
            clock.leave()
    timed.__wrapped__ = fn
    return timed


def _instrument(clock: _Clock) -> None:
    """Wrap every phase function, in its module and wherever it was imported by name."""
    import importlib

    import cases.run  # noqa: F401  (loads the whole package, so that every importer is patched)
    for phase, targets in PHASES.items():
        for target in targets:
            mod_name, fn_name = target.split(":")
            try:
                mod = importlib.import_module(mod_name)
            except ImportError:
                continue
            fn = getattr(mod, fn_name, None)
            if fn is None:
                continue
            timed = _wrap(clock, phase, fn)
            for m in list(sys.modules.values()):
                d = getattr(m, "__dict__", None)
                if d is None:
                    continue
                for k, v in list(d.items()):
                    if v is fn:
                        setattr(m, k, timed)
    from numba.core import event

    class _Compiles(event.Listener):
        def on_start(self, ev):
            clock.enter(COMPILE)

        def on_end(self, ev):
            clock.leave()

    event.register("numba:compile", _Compiles())


def _child(args) -> None:
    clock = _Clock()
    _instrument(clock)
    from cases.run import resolve_case, run_case

    case = resolve_case(args.case, quick_run=args.quick_case, overrides=args.set)
    run_case(case, args.out)
    clock._switch()
    print(json.dumps({"cpu_s": clock.cpu_s, "peak_mb": clock.peak_mb, "total_cpu_s": time.process_time()}))


def _table(report: dict, wall_s: float, children_cpu_s: float, children_peak_mb: float) -> str:
    rows = [(p, report["cpu_s"][p], report["peak_mb"][p]) for p in [*PHASES, COMPILE, OTHER] if p in report["cpu_s"]]
    lines = [f"{'phase':38s} {'CPU s':>8s} {'peak MB':>8s}"]
    lines += [f"{p:38s} {c:8.1f} {m:8.0f}" for p, c, m in rows]
    lines.append(f"{'main process':38s} {report['total_cpu_s']:8.1f} {max(report['peak_mb'].values()):8.0f}")
    lines.append(f"{'all processes (the warm-up included)':38s} {children_cpu_s:8.1f} {children_peak_mb:8.0f}")
    # last line: what .ci/run shows of each benchmark
    lines.append(f"first run: CPU {report['total_cpu_s']:.1f} s (all processes {children_cpu_s:.1f} s), "
                 f"peak {max(report['peak_mb'].values()):.0f} MB, wall {wall_s:.1f} s")
    return "\n".join(lines)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("case", nargs="?", default=None, help="case name (default slewing-undulation)")
    p.add_argument("--quick", action="store_true", help="the case's --quick variant (alone: the CI run, CI_CASE)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="override a case entry")
    p.add_argument("--warm-cache", default=None, help="result cache folder to use and keep (default: a cold one)")
    p.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--quick-case", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--out", default=None, help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.child:
        _child(args)
        return 0
    case, sets = args.case, list(args.set)
    if case is None:
        case, sets = (CI_CASE[0], list(CI_CASE[1]) + sets) if args.quick else ("slewing-undulation", sets)
    with tempfile.TemporaryDirectory(prefix="fb-first-run-") as tmp:
        env = dict(os.environ, NUMBA_CACHE_DIR=str(Path(tmp, "numba")), MPLBACKEND="Agg",
                   FLEXBEARING_CACHE=args.warm_cache or str(Path(tmp, "cache")))
        env.setdefault("FLEXBEARING_SPARSE_SOLVER", "cholespy")
        root = str(Path(__file__).resolve().parents[1])
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [root, env.get("PYTHONPATH")]))
        cmd = [sys.executable, __file__, "--child", case, "--out", str(Path(tmp, "out"))]
        cmd += ["--quick-case"] if args.quick else []
        cmd += [f"--set={kv}" for kv in sets]
        t0 = time.perf_counter()
        run = subprocess.run(cmd, env=env, capture_output=True, text=True)
        wall_s = time.perf_counter() - t0
    if run.returncode:
        sys.stderr.write(run.stderr[-4000:])
        return run.returncode
    report = json.loads(run.stdout.strip().splitlines()[-1])
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    print(f"cold first run of {case}{' --quick' if args.quick else ''}{''.join(' --set ' + kv for kv in sets)} "
          f"(sparse solver {env['FLEXBEARING_SPARSE_SOLVER']})")
    print(_table(report, wall_s, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024.0))
    return 0


if __name__ == "__main__":
    sys.exit(main())
