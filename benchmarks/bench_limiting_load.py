"""Wall time of a static limiting load curve (F_a against M at s0 = 1, ISO 76).

Two bearings: a single angular-contact ball row (100 balls of 20 mm on a 1.0 m pitch circle,
α0 = 60°; 36 rays over the half-plane of the axial direction it carries) and the four-point wind
pitch bearing of ``bench_loaddist.py`` (200 balls of 45 mm on 3.0 m, α0 = 45°; 36 rays all
round). Each ray is a bracket and Brent's method on the load scale, every evaluation a rigid-ring
load distribution. Target: a few seconds a curve.

Run: ``python benchmarks/bench_limiting_load.py [--quick]`` (``--quick``: 12 rays, one repeat).
Prints a table and one final line of ``name=value`` figures (seconds per curve).
"""

from __future__ import annotations

import argparse
import math
import time

from mbd_core.bearing.limiting_load import limiting_load_curve
from mbd_core.quasistatic import BallRow, Bearing, FourPointRow

#: Target wall time of one 36-ray curve of the 100-ball row, s.
TARGET_S = 5.0


def bearings() -> dict[str, Bearing]:
    ac = BallRow("balls", 100, 20e-3, 1.0, math.radians(60.0), 0.53, 0.53)
    fp = FourPointRow("balls", 200, 45e-3, 3.0, math.radians(45.0), 0.53, 0.53, radial_clearance_m=20e-6)
    return {"angular-100-balls": Bearing("angular contact", (ac,)), "four-point-200-balls": Bearing("pitch", (fp,))}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="12 rays and one repeat instead of 36 rays, best of 3")
    args = ap.parse_args()
    n_rays, repeats = (12, 1) if args.quick else (36, 3)
    figures = {}
    print(f"{'bearing':>22}  {'rays':>4}  {'carried':>7}  {'best s':>7}")
    for name, bearing in bearings().items():
        times = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            curve = limiting_load_curve(bearing, n_rays=n_rays)
            times.append(time.perf_counter() - t0)
        figures[f"{name.replace('-', '_')}_s"] = min(times)
        print(f"{name:>22}  {n_rays:>4}  {int(curve.carried.sum()):>7}  {min(times):>7.3f}")
    t = figures["angular_100_balls_s"]
    print(f"100-ball row, {n_rays} rays: {t:.2f} s, {'within' if t < TARGET_S else 'ABOVE'} the {TARGET_S:g} s target")
    print(" ".join(f"{k}={v:.4g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
