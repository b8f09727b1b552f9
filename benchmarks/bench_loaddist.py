"""Wall time of the quasi-static load distribution for the two built-in bearings and a four-point
wind-turbine pitch bearing (200 balls of 45 mm on a 3.0 m pitch circle, combined load; target
< 5 ms a solve).

Run: ``python benchmarks/bench_loaddist.py [--quick]``. Prints a table and one final line of
``name=value`` figures (seconds per solve, median of the repeats; peak resident memory).
"""

from __future__ import annotations

import argparse
import math
import resource
import statistics
import time

from cases.catalog import builtin_bearing
from mbd_core.quasistatic import Bearing, FourPointRow, RingLoad, solve_load_distribution

#: Target wall time of one four-point pitch-bearing solve, s.
FOUR_POINT_TARGET_S = 5e-3


def pitch_bearing() -> tuple[Bearing, RingLoad]:
    """A four-point pitch bearing of wind-turbine size (d_m = 3.0 m, 200 balls of 45 mm, α0 = 45°,
    conformity 0.53, 20 µm radial clearance) under axial load, radial load and tilting moment."""
    row = FourPointRow("balls", 200, 45e-3, 3.0, math.radians(45.0), 0.53, 0.53, radial_clearance_m=20e-6)
    return Bearing("four-point pitch", (row,)), RingLoad(Fx_N=2e5, Fy_N=1e5, Fz_N=4e5, Mx_Nm=1.5e6, My_Nm=-3e6)


def time_solve(name: str, repeats: int) -> tuple[float, int]:
    if name == "four-point-pitch":
        bearing, load = pitch_bearing()
    else:
        case = builtin_bearing(name)
        bearing, load = case.bearing, case.default_load
    solve_load_distribution(bearing, load)  # warm-up (imports, caches)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = solve_load_distribution(bearing, load)
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
    for name, key in (("slewing-ring", "slewing_116_balls_s"), ("three-row-roller", "three_row_286_rollers_s"),
                      ("four-point-pitch", "four_point_200_balls_s")):
        t, n_el = time_solve(name, repeats)
        figures[key] = t
        print(f"{name:>18}  {n_el:>8}  {t:>9.4f}")
    verdict = "within" if figures["four_point_200_balls_s"] < FOUR_POINT_TARGET_S else "ABOVE"
    print(f"four-point pitch bearing: {figures['four_point_200_balls_s'] * 1e3:.2f} ms a solve, {verdict} the "
          f"{FOUR_POINT_TARGET_S * 1e3:g} ms target")
    figures["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(" ".join(f"{k}={v:.4g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
