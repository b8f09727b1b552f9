"""Implicit against explicit friction on the 12 MW wind main bearing: speed and what it costs.

The rigid scene of ``flexbearing run wind-speeds`` held at load case 18 (30 r/min), run twice from
the same start: friction explicit (the step limited by the slope of the friction law) and implicit
(:mod:`mbd_core.kernels.explicit`; the step limited by the contacts). Printed per variant: the
automatic step, ms per step, the wall time of the run (after a 0.1 ms run that loads or compiles the
kernels); then the differences between the two runs
over the last half of the run — mean roller spin of the loaded rollers (the figure of the case,
against the no-slip value) and mean cage speed per row, and the mean roller–cage force per row.

Full run: 10 slices, 0.4 s; ``--quick``: 5 slices, 0.04 s (the figures then describe the start-up).

Run::

    python benchmarks/bench_friction.py [--quick]
"""

from __future__ import annotations

import argparse
import time

from cases.wind.case import WindCase
from cases.wind.dynamic import cage_forces, cage_speeds, roller_speeds
from cases.wind.scene import build_scene
from mbd_core.multibody.explicit import simulate


def run(case: WindCase):
    sc = build_scene(case)
    # a short run first loads or compiles the kernels, so that the timed run is stepping only
    simulate(sc.model, sc.state.copy(), sc.state.t + 1e-4, record_every=case.analysis.record_every)
    t0 = time.perf_counter()
    rec = simulate(sc.model, sc.state, case.analysis.duration_s, record_every=case.analysis.record_every)
    wall = time.perf_counter() - t0
    n_steps = round(case.analysis.duration_s / rec["timestep_s"])
    return sc, rec, wall, n_steps


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="5 slices, 0.04 s")
    args = ap.parse_args()
    duration = 0.04 if args.quick else 0.4
    base = WindCase().with_(loads={"source": "constant"}, rollers={"n_slices": 5 if args.quick else 10},
                            analysis={"duration_s": duration, "settle_s": duration / 2, "record_every": 20})
    out = {}
    for name, implicit in (("explicit", False), ("implicit", True)):
        case = base.with_(contact={"implicit_friction": implicit})
        sc, rec, wall, n = run(case)
        out[name] = (roller_speeds(case, sc, rec), cage_speeds(case, sc, rec), cage_forces(case, sc, rec))
        print(f"{name:8s} friction: step {rec['timestep_s']:.3g} s, {1e3 * wall / n:6.3f} ms/step, {wall:6.1f} s wall "
              f"for {duration:g} s")
        out[name] += (wall,)
    rs_e, cs_e, cf_e, w_e = out["explicit"]
    rs_i, cs_i, cf_i, w_i = out["implicit"]
    for row in rs_e:
        f_e, f_i = _mean_force(cf_e[row]), _mean_force(cf_i[row])
        print(f"  {row:12s} loaded roller speed error {rs_e[row]['loaded_error']:+.3%} / "
              f"{rs_i[row]['loaded_error']:+.3%}, "
              f"cage speed error {cs_e[row]['error']:+.3%} / {cs_i[row]['error']:+.3%}, "
              f"mean cage force {f_e:6.1f} / {f_i:6.1f} N (explicit / implicit)")
    print(f"implicit over explicit friction: ×{w_e / w_i:.1f} faster")


def _mean_force(d: dict) -> float:
    return d["mean_in_contact_N"]


if __name__ == "__main__":
    main()
