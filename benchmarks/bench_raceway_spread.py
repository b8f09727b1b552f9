"""Largest ball load of the undulated 2 m slewing ring against mesh, harmonics and raceway spread.

The top structure is modal (``n_modes`` normal modes + groove load shapes up to each harmonic),
reduced on each element size, with its groove sampled on the contact line (spread 0) or averaged
over a patch of the section (``top.raceway_spread_m``, :func:`fem_rings.nodesets.raceway_patch`).
Each line gives the largest ball load and the time of reduction + solve; the reductions run one
after the other (a 0.049 m mesh takes ~11 GB). Run::

    python benchmarks/bench_raceway_spread.py [--spreads 0 0.03] [--sizes 0.098 0.07 0.049]
                                              [--harmonics 16 32] [--modes 20]

Ends with one line of ``name=value`` figures (the relative change of the largest ball load from
the coarsest to the finest mesh, per spread and harmonic).
"""

from __future__ import annotations

import argparse
import time

from cases.slewing import fidelity
from cases.slewing.presets import PRESETS


def largest_ball_load_N(spread_m: float, size_m: float, harmonics: int, n_modes: int) -> float:
    """Largest ball load of the undulation scene, N."""
    case = fidelity.rung_case(PRESETS["slewing-undulation"], {
        "top.kind": "modal", "top.n_modes": n_modes, "top.groove_harmonics": harmonics, "top.element_size_m": size_m})
    return float(fidelity.measure(case.with_(top={"raceway_spread_m": spread_m})).load_N.max())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--spreads", type=float, nargs="+", default=[0.0, 0.03], help="raceway spread, m")
    ap.add_argument("--sizes", type=float, nargs="+", default=[0.098, 0.07, 0.049], help="element sizes, m")
    ap.add_argument("--harmonics", type=int, nargs="+", default=[16], help="highest groove harmonics")
    ap.add_argument("--modes", type=int, default=20, help="normal modes")
    args = ap.parse_args()
    figures = []
    for s in args.spreads:
        for H in args.harmonics:
            loads = []
            for h in args.sizes:
                t0 = time.perf_counter()
                loads.append(largest_ball_load_N(s, h, H, args.modes))
                print(f"spread {s:.3f} m  H {H:3d}  element {h:.3f} m  largest ball load {loads[-1]:9.0f} N  "
                      f"({time.perf_counter() - t0:.1f} s)", flush=True)
            figures.append(f"dQ_s{s:g}_H{H}={100.0 * (loads[-1] / loads[0] - 1.0):+.2f}%")
    print(" ".join(figures))


if __name__ == "__main__":
    main()
