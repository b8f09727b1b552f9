"""The flexible start of a dynamic slewing run: how long the multibody static equilibrium takes.

A dynamic run with a modal top structure starts at the flexible quasi-static equilibrium mapped
onto the multibody model (:func:`cases.slewing.dynamic.start_state`), polished by
:func:`mbd_core.multibody.statics.static_equilibrium` (Levenberg–Marquardt with finite-difference
Jacobians, balls held at their azimuths). Printed per scene: the unknowns, the force evaluations,
the CPU time of the polish and the forces it leaves, and the largest deviation of the polished ball
loads from the flexible quasi-static solution (:func:`cases.slewing.quasistatic.equilibrium`, an
independent Newton solver with the balls condensed) relative to the largest load.

Scenes: the 2 m ring on its undulated bottom race with the quick modal top (12 modes + load shapes
to harmonic 8, 0.12 m mesh), and (without ``--quick``) the full Ø6.69 m ring of
``slewing-full-scale-turning`` with its default top (53 modal coordinates). The top structures'
reductions are built on the first run and cached (``FLEXBEARING_CACHE``); only the start is timed.

Run::

    python benchmarks/bench_static_start.py [--quick]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from cases.slewing import dynamic, scene
from cases.slewing.dynamic import build_scene, start_state
from cases.slewing.presets import PRESETS
from cases.slewing.quasistatic import equilibrium
from mbd_core.multibody import evaluate_forces


def _cases(quick: bool) -> dict:
    out = {"2m-undulated-quick-top": PRESETS["slewing-rotation"].with_(
        geometry={"variant": "2m"}, undulation={"scale": 1.0},
        top={"kind": "modal", "n_modes": 12, "groove_harmonics": 8, "element_size_m": 0.12})}
    if not quick:
        out["full-scale"] = PRESETS["slewing-full-scale-turning"]
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="the 2 m ring only")
    args = ap.parse_args()
    results = []
    solve = dynamic.static_equilibrium
    for name, case in _cases(args.quick).items():
        bodies = scene.Bodies(scene.top_body(case), scene.bottom_body(case))
        reference = equilibrium(case, bodies).rows[0].load_N
        sc = build_scene(case, bodies)
        seen = {}

        def timed(model, state, **kw):
            t0 = time.process_time()
            res = solve(model, state, **kw)
            seen.update(cpu_s=time.process_time() - t0, evaluations=res.n_evaluations,
                        force_N=res.force_residual_N, scale_N=res.force_scale_N)
            return res

        dynamic.static_equilibrium = timed  # the polish inside start_state, timed alone
        try:
            state = start_state(sc, case, bodies)
        finally:
            dynamic.static_equilibrium = solve
        still = state.copy()
        still.v[:] = 0.0
        still.eta_dot[:] = 0.0
        loads = evaluate_forces(sc.model, still).contact_fn[list(sc.ball_pairs_top)]
        deviation = float(np.abs(loads - reference).max() / reference.max())
        print(f"[{name}] static equilibrium: {seen['evaluations']} force evaluations, {seen['cpu_s']:.2f} s CPU; "
              f"force left {seen['force_N']:.3g} N of {seen['scale_N']:.3g} N; polished ball loads within "
              f"{deviation:.2e} of the largest quasi-static load")
        results.append(f"{name}_cpu_s={seen['cpu_s']:.3g} {name}_evaluations={seen['evaluations']} "
                       f"{name}_deviation={deviation:.3g}")
    print(" ".join(results))


if __name__ == "__main__":
    main()
