"""Mesh + assemble + 30 modes of a ring finite-element model, wall time and peak memory.

The ring is the slewing-ring bottom race (groove included) at Ø2 m. Each size runs in its own
process so that its peak resident memory is its own. Run::

    python benchmarks/bench_fem.py [--quick] [--element hex27|tet10]

Prints a table and, per size, one line of ``name=value`` figures
(``dofs=… mesh_s=… assemble_s=… factor_backend=… modes_s=… total_s=… peak_rss_mb=…``).
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time

#: element size (m) giving a quick model and about 50k / 150k DOF on the Ø2 m race, per family
SIZES = {
    "hex27": {"quick": 0.12, "50k": 0.056, "150k": 0.037},
    "tet10": {"quick": 0.1, "50k": 0.06, "150k": 0.03},
}


def run_one(element: str, size_m: float) -> dict:
    from fem_rings.mesh import MeshSpec
    from fem_rings.model import build_model
    from fem_rings.sections import slewing_bottom_race
    from fem_rings.solve import modal_analysis
    from foundation.materials import ElasticMaterial

    steel = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
    t0 = time.perf_counter()
    model = build_model(slewing_bottom_race(2.0), MeshSpec(size_m, element), steel, use_cache=False)
    t1 = time.perf_counter()
    modes = modal_analysis(model, 30)
    t2 = time.perf_counter()
    return {
        "dofs": model.n_dofs,
        "mesh_s": round(model.timings_s["mesh"], 2),
        "assemble_s": round(model.timings_s["assemble"], 2),
        "factor_backend": modes.backend,
        "modes_s": round(t2 - t1, 2),
        "total_s": round(t2 - t0, 2),
        "first_elastic_Hz": round(float(modes.elastic_frequencies_Hz[0]), 3),
        "peak_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="only a small model (~25k DOF)")
    ap.add_argument("--element", choices=sorted(SIZES), default="hex27")
    ap.add_argument("--child", type=float, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child is not None:
        print(json.dumps(run_one(args.element, args.child)))
        return
    labels = ["quick"] if args.quick else ["50k", "150k"]
    print(f"{'target':>6} {'DOF':>8} {'mesh s':>7} {'asm s':>7} {'modes s':>8} {'total s':>8} {'peak MB':>8}")
    lines = []
    for label in labels:
        out = subprocess.run([sys.executable, __file__, "--element", args.element, "--child",
                              str(SIZES[args.element][label])], capture_output=True, text=True, check=True)
        r = json.loads(out.stdout.strip().splitlines()[-1])
        print(f"{label:>6} {r['dofs']:>8} {r['mesh_s']:>7} {r['assemble_s']:>7} {r['modes_s']:>8} "
              f"{r['total_s']:>8} {r['peak_rss_mb']:>8}")
        lines.append(" ".join(f"{k}={v}" for k, v in {"element": args.element, "target": label, **r}.items()))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
