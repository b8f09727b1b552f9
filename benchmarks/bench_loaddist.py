"""Wall time of the quasi-static load distribution for the two built-in bearings.

Run: ``python benchmarks/bench_loaddist.py [--quick]``. Prints a table and one final line of
``name=value`` figures (seconds per solve, median of the repeats; peak resident memory).
"""

from __future__ import annotations

import argparse
import resource
import statistics
import time

from cases.catalog import builtin_bearing
from mbd_core.quasistatic import solve_load_distribution


def time_solve(name: str, repeats: int) -> tuple[float, int]:
    case = builtin_bearing(name)
    solve_load_distribution(case.bearing, case.default_load)  # warm-up (imports, caches)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = solve_load_distribution(case.bearing, case.default_load)
        times.append(time.perf_counter() - t0)
    n_el = sum(len(r.load_N) for r in res.rows)
    return statistics.median(times), n_el


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="3 repeats instead of 30")
    args = ap.parse_args()
    repeats = 3 if args.quick else 30
    figures = {}
    print(f"{'bearing':>18}  {'elements':>8}  {'median s':>9}")
    for name, key in (("slewing-ring", "slewing_116_balls_s"), ("three-row-roller", "three_row_286_rollers_s")):
        t, n_el = time_solve(name, repeats)
        figures[key] = t
        print(f"{name:>18}  {n_el:>8}  {t:>9.4f}")
    figures["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(" ".join(f"{k}={v:.4g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
