"""Explicit step of the 12 MW wind main bearing: rigid against modal rings and cages.

The scene of ``flexbearing run wind-speeds`` (:func:`cases.wind.scene.build_scene`): 98 radial and
2 × 94 thrust rollers, each cut into slices on both raceways, guide ribs at both roller ends, three
free cages with slot pockets, the inner ring driven at 30 r/min under load case 18 and its weight.
Three variants: rigid rings and cages; modal rings (20 free–free / fixed-interface modes, the
slices on sampled raceway grids); modal rings and cages (20 modes each, pocket walls sampled).
Full run: the case's meshes and 10 slices per roller, 286 rollers → 5720 slice contacts with the
raceways; ``--quick``: 5 slices, 8 modes on coarse meshes (the test's variant).

Each variant is stepped at its own automatic step (friction implicit, so the roller contacts or,
with modal cages, a cage's stiffest mode with its contacts set it) after a short run that loads or
compiles the kernels; printed: ms per step, the ratio to the rigid scene, and the wall time that 8
simulated seconds take at that rate (the paper's Adams runs are not timed in the source; the
target is 30 min for the flexible model).

Run::

    python benchmarks/bench_wind.py [--quick]
"""

from __future__ import annotations

import argparse
import time

from cases.wind.case import WindCase
from cases.wind.scene import build_scene
from mbd_core.multibody.explicit import simulate

VARIANTS = {"rigid": {}, "modal rings": {"rings": "modal"}, "modal rings and cages": {"rings": "modal", "cages": "modal"}}
QUICK_BODIES = {"n_modes": 8, "bolts": 24, "ring_element_size_m": 0.1, "cage_element_size_m": 0.03}


def ms_per_step(case: WindCase, steps: int) -> tuple[float, float]:
    sc = build_scene(case)
    warm = simulate(sc.model, sc.state, 20 * 2.5e-6, record_every=10)
    h = warm["timestep_s"]
    t0 = time.perf_counter()
    simulate(sc.model, sc.state, sc.state.t + steps * h, timestep_s=h, record_every=max(steps // 10, 1))
    return 1e3 * (time.perf_counter() - t0) / steps, h


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="5 slices, coarse 8-mode bodies, 100 steps")
    args = ap.parse_args()
    steps = 100 if args.quick else 1000
    base = WindCase().with_(loads={"source": "constant"}, rollers={"n_slices": 5 if args.quick else 10})
    rigid_ms = None
    for name, bodies in VARIANTS.items():
        case = base.with_(bodies={**bodies, **(QUICK_BODIES if args.quick and bodies else {})})
        ms, h = ms_per_step(case, steps)
        rigid_ms = rigid_ms or ms
        print(f"{name:22s}: {ms:6.3f} ms/step at h = {h:.3g} s, ×{ms / rigid_ms:4.1f} the rigid scene; "
              f"8 simulated s in {8.0 / h * ms / 6e4:5.1f} min")
    print(f"modal rings and cages over rigid: ×{ms / rigid_ms:.1f} per step")


if __name__ == "__main__":
    main()
