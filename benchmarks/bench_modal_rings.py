"""Load distribution with modal rings from a bearing description file: time per load case once the
rings are reduced, the reduction itself (cold and from the cache), and how far the limiting load
curve moves with ring flexibility.

Full size: ``examples/bearings/modal/pitch-bearing-modal-rings.toml`` (Ø2.5 m four-point pitch
bearing, 140 balls, two box-section rings bolted with 54 bolts each, hex27 of 47 mm, 20 modes and
load shapes up to n = 8 per ring) through ``examples/modal_rings.py``: figures of the three load
cases, the limiting load curve with modal and rigid rings on 36 rays. Target (issue): a load case
in < 0.5 s after the reduction is cached.

``--quick``: a Ø0.5 m four-point bearing (40 balls, 30 mm elements, 12 modes, n ≤ 4), the size of
tests/test_bearing_rings.py: reduction, then 20 solves.

Run::

    python benchmarks/bench_modal_rings.py [--quick]

Ends with one line of ``name=value`` figures.
"""

from __future__ import annotations

import argparse
import os
import resource
import runpy
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _solve_times(solver, loads, repeat: int) -> float:
    t0 = time.process_time()
    for _ in range(repeat):
        for load in loads:
            solver.solve(load)
    return (time.process_time() - t0) / (repeat * len(loads))


def quick() -> str:
    from test_bearing_rings import SMALL

    from cases.bearing_file import loads_bearing
    from cases.bearing_solver import bearing_solver

    desc = loads_bearing(SMALL)
    t0 = time.process_time()
    modal = bearing_solver(desc)
    cold = time.process_time() - t0
    t0 = time.process_time()
    bearing_solver(desc)
    warm = time.process_time() - t0
    per_case = _solve_times(modal, desc.load_cases, 20)
    rigid = _solve_times(bearing_solver(desc, rigid=True), desc.load_cases, 20)
    print(f"Ø0.5 m four-point, {modal.label}: reduction {cold:.1f} s CPU cold, {warm:.2f} s from the cache; "
          f"{per_case * 1e3:.1f} ms CPU per load case (rigid rings {rigid * 1e3:.2f} ms)")
    return (f"reduction_cold_s={cold:.2f} reduction_cached_s={warm:.3f} modal_case_ms={per_case * 1e3:.2f} "
            f"rigid_case_ms={rigid * 1e3:.3f} peak_mb={_peak_mb():.0f}")


def full() -> str:
    import numpy as np

    os.environ.pop("FLEXBEARING_EXAMPLE_QUICK", None)
    t0 = time.process_time()
    ex = runpy.run_path(str(ROOT / "examples" / "modal_rings.py"), run_name="modal_rings")
    total = time.process_time() - t0
    per_case = _solve_times(ex["modal"], ex["desc"].load_cases, 5)
    ratio = ex["ratio"]
    return (f"modal_case_ms={per_case * 1e3:.1f} reduction_s={ex['reduction_s']:.1f} "
            f"curve_ratio_min={np.nanmin(ratio):.4f} curve_ratio_mean={np.nanmean(ratio):.4f} "
            f"curve_ratio_max={np.nanmax(ratio):.4f} eq_limited_rays_modal={int(ex['curve_modal'].equilibrium_limited.sum())} "
            f"eq_limited_rays_rigid={int(ex['curve_rigid'].equilibrium_limited.sum())} total_cpu_s={total:.0f} "
            f"peak_mb={_peak_mb():.0f}")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true")
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        os.environ.setdefault("FLEXBEARING_CACHE", os.path.join(tmp, "cache"))
        os.environ.setdefault("FLEXBEARING_EXAMPLE_OUT", os.path.join(tmp, "out"))
        print(quick() if args.quick else full())


if __name__ == "__main__":
    main()
