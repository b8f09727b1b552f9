"""Reduction of the 2 m slewing-ring top race: 20 normal modes + raceway augmentation.

FE model (mesh + assembly), Craig–Bampton reduction with groove load shapes (contact-normal
direction, n = 0…8), invariants and groove sampling (360 points); then the size of the saved
body. Run::

    python benchmarks/bench_cms.py [--quick]

Ends with one line of ``name=value`` figures.
"""

from __future__ import annotations

import argparse
import resource
import tempfile
import time
from pathlib import Path

from cms_reduction.persist import body_paths, load_body, save_body
from cms_reduction.pipeline import RacewaySpec, ReductionSpec, reduced_body
from fem_rings import MeshSpec
from fem_rings.sections import SlewingSection, slewing_top_race
from foundation.materials import ElasticMaterial


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="coarse mesh, 6 modes")
    args = ap.parse_args()
    size, n_modes = (0.08, 6) if args.quick else (0.03, 20)
    steel = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
    contact = tuple(SlewingSection().groove("top", 2.0).contact_point_m)
    spec = ReductionSpec(n_modes=n_modes, raceways=(RacewaySpec("groove", 360, contact, ("normal",), 8),))
    t0 = time.perf_counter()
    body = reduced_body(slewing_top_race(2.0), MeshSpec(size, "hex27"), steel, spec, use_cache=False)
    t1 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        npz, js = body_paths(save_body(body, Path(tmp) / "top_race"))
        mb = (npz.stat().st_size + js.stat().st_size) / 2**20
        t2 = time.perf_counter()
        load_body(npz)
        t3 = time.perf_counter()
    figures = {
        "dofs": body.shapes.shape[0], "modes": body.n_modes, "reduce_s": round(t1 - t0, 2),
        "file_mb": round(mb, 1), "load_s": round(t3 - t2, 3),
        "f_first_Hz": round(float(body.frequencies_Hz[0]), 2), "f_last_Hz": round(float(body.frequencies_Hz[-1]), 1),
        "peak_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0),
    }
    print(f"2 m top race: {figures['dofs']} DOF → {figures['modes']} modes "
          f"({n_modes} normal + groove load shapes), {figures['f_first_Hz']}–{figures['f_last_Hz']} Hz")
    print(f"reduce {figures['reduce_s']} s (mesh, assemble, reduce, invariants, sampling); "
          f"file {figures['file_mb']} MB, load {figures['load_s']} s")
    print(" ".join(f"{k}={v}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
