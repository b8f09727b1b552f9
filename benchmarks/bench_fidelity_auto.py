"""``top.kind = "auto"`` against the hand-picked fidelity on the slewing ring's undulation scene.

The scene of the fidelity ladder (the 2 m ring on its undulated bottom race, top structure of the
reduced modulus 1.5975 GPa, one quasi-static equilibrium; :func:`cases.slewing.fidelity.scene`).
Three models, each run cold in a fresh process with an empty model cache (meshing and reduction
included, :func:`cases.tradeoff.measure_cold`):

- ``auto``: the cheap pass (rigid equilibrium, coarse compliance probe) and the model it picks;
- ``hand-picked``: the cheapest rung of the full ladder whose largest-load error is ≤ 1 %
  (ball load shapes on the 0.3·D groove patch, 20 modes, load shapes to harmonic 16);
- ``reference``: the ladder's reference (ball load shapes, 80 modes, harmonic 32, 0.7× the
  default element size; 16 GB, several minutes).

Printed: wall and CPU time, peak memory, largest ball load and its error against the reference,
and the ratio of auto's wall time to the hand-picked one's. ``--quick`` (CI): every model on the
quick ladder's mesh (twice the default element size), the reference that of the quick ladder
(ball load shapes, 40 modes, harmonic 16).

    python benchmarks/bench_fidelity_auto.py            # about 8 minutes, 16 GB
    python benchmarks/bench_fidelity_auto.py --quick    # about 1.5 minutes
"""

from __future__ import annotations

import argparse
import dataclasses

from cases.slewing import fidelity
from cases.slewing.presets import PRESETS
from cases.slewing.scene import DEFAULT_ELEMENT_SIZE_M, groove_patch_m
from cases.tradeoff import measure_cold


def models(case, quick: bool) -> dict[str, dict]:
    h0 = DEFAULT_ELEMENT_SIZE_M[case.geometry.variant]
    h = round((fidelity.QUICK_MESH_FACTOR if quick else 1.0) * h0, 4)
    patch = {"top.raceway_spread_m": groove_patch_m(case), "top.ball_load_shapes": True}
    ref = ({"top.n_modes": 40, "top.groove_harmonics": 16, "top.element_size_m": h} if quick else
           {"top.n_modes": 80, "top.groove_harmonics": 32, "top.element_size_m": round(0.7 * h0, 4)})
    return {"auto": {"top.kind": "auto", "top.element_size_m": h},
            "hand-picked": {"top.kind": "modal", "top.n_modes": 20, "top.groove_harmonics": 16, "top.element_size_m": h,
                            **patch},
            "reference": {"top.kind": "modal", **patch, **ref}}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the quick ladder's mesh and reference (CI)")
    args = ap.parse_args()
    case = dataclasses.replace(fidelity.scene(PRESETS["slewing-undulation"]), name="undulated-2m", description="")
    base = {"top.n_modes": 20, "top.groove_harmonics": 16, "top.raceway_spread_m": 0.0, "top.ball_load_shapes": False}
    runs = {}
    for name, settings in models(case, args.quick).items():
        # auto chooses the modal keys itself: the scene's are put back to the schema's defaults
        runs[name] = measure_cold("cases.slewing.fidelity", case.with_(top=_top(base)), settings)
    q_ref = float(runs["reference"]["outcome"].load_N.max())
    print(f"scene: {fidelity.describe_scene(case)}{' (quick: coarse mesh)' if args.quick else ''}")
    print(f"{'model':12s} {'wall s':>8s} {'CPU s':>8s} {'peak MB':>8s} {'Q_max N':>10s} {'error':>8s}")
    for name, m in runs.items():
        q = float(m["outcome"].load_N.max())
        print(f"{name:12s} {m['wall_s']:8.1f} {m['cpu_s']:8.1f} {m['peak_rss_mb']:8.0f} {q:10.0f} "
              f"{100 * abs(q - q_ref) / q_ref:7.3f}%")
    ratio = runs["auto"]["wall_s"] / runs["hand-picked"]["wall_s"]
    print(f"auto / hand-picked wall time: {ratio:.2f} (acceptance ≤ 1.5)")


def _top(settings: dict) -> dict:
    return {k.split(".")[1]: v for k, v in settings.items()}


if __name__ == "__main__":
    main()
