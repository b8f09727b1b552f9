"""The variants of ``wind-friction`` in one process against two Dask workers on this machine.

``flexbearing run wind-friction`` runs one dynamic run of the 12 MW main bearing per friction set
(:func:`cases.sweep.variants.run_variants`). This runs the case twice as a user would, each in
its own process: the variants one after the other, then with ``--workers 2`` (a LocalCluster of
two worker processes, one thread each). Printed: wall time of each, their ratio (the speed-up), the
CPU time of all the processes, the peak memory of each worker, the time to the first finished
variant, and whether the two runs' cage forces are identical bit for bit.

The numba kernels are compiled (and cached) before the timing. Run::

    python benchmarks/bench_sweep.py [--quick]     # --quick: the 2-set quick case, 0.3 s simulated
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def _cpu_children_s() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _run(args: list[str]) -> dict:
    t0, c0 = time.perf_counter(), _cpu_children_s()
    subprocess.run([sys.executable, "-m", "cases.cli", *args], check=True, stdout=subprocess.DEVNULL)
    return {"wall_s": time.perf_counter() - t0, "cpu_s": _cpu_children_s() - c0}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="the quick case (2 friction sets, 0.3 s simulated)")
    args = ap.parse_args()
    from mbd_core.multibody import warmup

    if not warmup.kernels_cached():
        warmup.compile_kernels()
    quick = ["--quick"] if args.quick else []
    with tempfile.TemporaryDirectory() as tmp:
        serial = _run(["run", "wind-friction", *quick, "--out", f"{tmp}/serial"])
        parallel = _run(["run", "wind-friction", *quick, "--workers", "2", "--out", f"{tmp}/parallel"])
        s = json.loads(Path(f"{tmp}/serial/summary.json").read_text())
        p = json.loads(Path(f"{tmp}/parallel/summary.json").read_text())
    same = s["by_friction"] == p["by_friction"]
    print(f"wind-friction{' --quick' if args.quick else ''}: {len(s['variants'])} friction sets")
    print(f"  one process: {serial['wall_s']:.1f} s wall, {serial['cpu_s']:.1f} s CPU, peak "
          f"{max(v['peak_rss_mb'] for v in s['variants'].values()):.0f} MB; first variant after "
          f"{min(v['finished_after_s'] for v in s['variants'].values()):.1f} s")
    per_worker = {}
    for v in p["variants"].values():
        per_worker[v["worker"]] = max(per_worker.get(v["worker"], 0.0), v["peak_rss_mb"])
    print(f"  2 workers:   {parallel['wall_s']:.1f} s wall, {parallel['cpu_s']:.1f} s CPU, peak per worker "
          f"{', '.join(f'{m:.0f}' for m in per_worker.values())} MB; first variant after "
          f"{min(v['finished_after_s'] for v in p['variants'].values()):.1f} s")
    print(f"  cage forces identical bit for bit: {same}")
    print(f"speed-up with 2 workers: {serial['wall_s'] / parallel['wall_s']:.2f}x wall (target >= 1.7 at full size)")


if __name__ == "__main__":
    main()
