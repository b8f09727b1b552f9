"""Free–free modes of a built-in ring part on two meshes: six rigid modes and a consistent first pair.

The check of tests/test_rigid_modes.py (``test_built_in_part_has_six_rigid_modes_and_a_mesh_
consistent_first_pair``) at the default element layers round the ring, which the test reduces for
the three-row outer ring: on each mesh six rigid modes (fem_rings.modal_basis) and a (nearly)
degenerate first elastic pair (modes 7–8 within 0.2 %); between the meshes the pair's mean from
above within 0.1 % (Rayleigh–Ritz: refining does not raise a frequency, up to the change of the
discretised geometry, the meshes not being nested) and within 2 %.

Default: the three-row outer ring at 0.18 m and 0.15 m (61k and 78k DOF). ``--quick`` (CI): the
three-row front cage at 0.08 m and 0.05 m. Run::

    python benchmarks/bench_part_modes.py [--quick] [--part NAME --sizes COARSE FINE]

Ends with one line of ``name=value`` figures.
"""

from __future__ import annotations

import argparse
import resource
import time

import numpy as np

from cases.parts import RING_PARTS
from fem_rings import MeshSpec, build_model, modal_analysis


def first_pair(name: str, size_m: float) -> dict:
    """Mesh ``name`` at ``size_m`` (default element and layers), solve 8 elastic modes; check them."""
    part = RING_PARTS[name]
    profile, pockets = part.make()
    t0 = time.perf_counter()
    model = build_model(profile, MeshSpec(size_m, part.default_element), part.material, pockets, use_cache=False)
    modes = modal_analysis(model, 8)
    f = modes.elastic_frequencies_Hz
    assert modes.n_rigid == 6, (name, size_m, modes.n_rigid)
    assert f[1] / f[0] - 1 < 2e-3, (name, size_m, f)
    return {"dof": model.n_dofs, "pair_Hz": float(np.mean(f)), "wall_s": time.perf_counter() - t0}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="the three-row front cage (a few seconds)")
    ap.add_argument("--part", choices=sorted(RING_PARTS), help="a built-in part (default: see above)")
    ap.add_argument("--sizes", type=float, nargs=2, metavar=("COARSE_M", "FINE_M"), help="the two mesh sizes, m")
    args = ap.parse_args()
    name, sizes = ("three-row-front-cage", (0.08, 0.05)) if args.quick else ("three-row-outer-ring", (0.18, 0.15))
    name, sizes = args.part or name, tuple(args.sizes or sizes)
    coarse, fine = (first_pair(name, s) for s in sizes)
    change = fine["pair_Hz"] / coarse["pair_Hz"] - 1
    assert -0.02 < change <= 1e-3, (name, coarse, fine)
    for size_m, r in zip(sizes, (coarse, fine)):
        print(f"{name} at {size_m} m: {r['dof']} DOF, first pair {r['pair_Hz']:.3f} Hz, {r['wall_s']:.1f} s")
    figures = {"coarse_dof": coarse["dof"], "fine_dof": fine["dof"], "coarse_pair_Hz": coarse["pair_Hz"],
               "fine_pair_Hz": fine["pair_Hz"], "pair_change_pct": 100 * change,
               "coarse_wall_s": coarse["wall_s"], "fine_wall_s": fine["wall_s"],
               "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}
    print(" ".join(f"{k}={v:.5g}" if isinstance(v, float) else f"{k}={v}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
