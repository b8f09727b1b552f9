"""Speed of the turbocharger case: 0.1 s of the preloaded rotor at 50 000 rev/min.

The ``turbocharger`` preset (a 10-mode flexible rotor with its stress stiffening at the running speed,
two hybrid angular-contact rows of 8 balls with their cages, the outer rings in squeeze-film dampers,
10 g·mm of unbalance), built (the rotor's reduction cached in ``FLEXBEARING_CACHE``) and run for
0.1 s of simulated time from its start on the unbalance orbit (:func:`cases.turbocharger.studies.simulate_case`).
Printed: the CPU time of building and of the run (which builds its scene again and analyses the
record), the step and the number of steps, the wall time, and the CPU time per step without the build; the target is 0.1 s simulated in under 2 minutes of wall time on a 2-core laptop-class
machine. ``--quick``: 5 ms of the quick variant (6 modes).

Run::

    python benchmarks/bench_turbocharger.py [--quick]
"""

from __future__ import annotations

import argparse
import time

from cases.turbocharger import presets
from cases.turbocharger.scene import build_scene, rotor_body
from cases.turbocharger.studies import simulate_case


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="5 ms of the quick variant")
    args = ap.parse_args()
    case = presets.PRESETS["turbocharger"]
    duration = 0.1
    if args.quick:
        case, duration = presets.quick(case), 0.005
    case = case.with_(run={"duration_s": duration, "settle_s": 0.5 * duration})
    rotor_body(case)                                 # the reduction, cached: not timed
    cpu0, wall0 = time.process_time(), time.perf_counter()
    scene = build_scene(case)
    build_cpu = time.process_time() - cpu0
    simulate_case(case.with_(run={"duration_s": 0.002, "settle_s": 0.001}))   # compiles the kernels: not timed
    cpu_b, wall_b = time.process_time(), time.perf_counter()
    build_scene(case)                                # the build as the run does it, warm
    warm_build_cpu = time.process_time() - cpu_b
    cpu1, wall1 = time.process_time(), time.perf_counter()
    _, run = simulate_case(case)
    run_cpu, run_wall = time.process_time() - cpu1, time.perf_counter() - wall1
    steps = duration / run.summary["timestep_s"]
    step_cpu = max(run_cpu - warm_build_cpu, 0.0)  # the run rebuilds its scene (cached reduction) first
    print(f"turbocharger{' (quick)' if args.quick else ''}: {scene.model.n_bodies} bodies, {scene.model.n_pairs} "
          f"contacts, {scene.body.n_modes} rotor modes; build {build_cpu:.2f} s CPU")
    print(f"{duration:g} s simulated at step {run.summary['timestep_s']:.3g} s ({steps:.0f} steps): "
          f"{run_cpu:.1f} s CPU and {run_wall:.1f} s wall with the build and the analysis, "
          f"{1e6 * step_cpu / steps:.1f} µs/step without the build (warm: {warm_build_cpu:.2f} s CPU; the analysis "
          "included); "
          f"target 120 s wall for 0.1 s: {'met' if args.quick or run_wall < 120.0 else 'NOT met'} "
          f"(building and a 2 ms warm-up run with any compiling: {wall_b - wall0:.1f} s wall)")


if __name__ == "__main__":
    main()
