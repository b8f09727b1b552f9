"""The two heavy examples at their full size, with the checks tests/test_examples.py makes at the
reduced (``--quick``) size the test suite affords.

slewing_race_static
    The 1 m bottom race (hex27, 30 mm, 15 mm on the groove) under 16 Hertz-distributed ball loads
    Q = W/(Z sin α) (W = 68.9 t × 9.81 m/s², Z = 16, α = 60°), bolted at 16 patches. Checks: the
    magnitudes of the patch forces sum to Z·Q (the loads are unit normals times weights summing to
    one: round-off only), and the bolt reactions balance the applied force (static equilibrium of
    the FE solution: round-off of the sparse solve). Figures: largest axial deflection and von Mises
    stress, DOF, wall time.
flexible_race_dynamics
    The same race (40 mm, 20 mm on the groove) as a Craig–Bampton body in a 0.2 s run under the dead
    load and a tilting moment ramped up to 150 kN·m. Checks (from 0.15 s on, after the ramp): the axial
    ball-load components Q sin α sum to W within 1 % and their moment about x is M within 2 % (the top
    race still swings a little on its contacts), and the race's worst stress comes after 0.1 s.
    Figures: worst relative errors, worst von Mises, wall time.

``--quick`` runs slewing_race_static alone at its quick size (60 mm, the size of the test: ~3 s).
The dynamic example's quick size (60 mm, 30 mm on the groove: ~13 s measured) would bring the quick
benchmark close to CI's ~20 s budget; tests/test_examples.py runs it. Full size, measured: static
168k DOF in 56 s, dynamic 62 s, 2.6 GB peak (shared 2-core machine). Run::

    python benchmarks/bench_examples.py [--quick]

Ends with one line of ``name=value`` figures.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import os
import resource
import tempfile
import time
from pathlib import Path

import numpy as np

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def run_example(name: str, out: Path, quick: bool):
    """Execute ``examples/<name>.py`` (it computes at module level) writing into ``out``; returns the
    module and its wall time, s."""
    os.environ["FLEXBEARING_EXAMPLE_OUT"] = str(out / name)
    os.environ["FLEXBEARING_EXAMPLE_QUICK"] = "1" if quick else "0"
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    t0 = time.perf_counter()
    spec.loader.exec_module(module)
    return module, time.perf_counter() - t0


def check_static(ex) -> dict:
    """Relative errors of the static example against Σ|F| = Z·Q and Σ reactions = −Σ applied."""
    q_N = 68.9e3 * 9.81 / (16 * math.sin(math.radians(60.0)))
    load_err = abs(np.linalg.norm(ex.forces_N, axis=1).sum() / (16 * q_N) - 1.0)
    balance_err = np.abs(ex.reaction_N + ex.applied_N).max() / np.abs(ex.applied_N).max()
    assert load_err < 1e-12 and balance_err < 1e-9, (load_err, balance_err)
    return {"static_dof": ex.model.n_dofs,
            "static_load_rel_err": load_err, "static_balance_rel_err": balance_err,
            "static_max_deflection_mm": ex.max_deflection_m * 1e3,
            "static_max_von_mises_MPa": float(ex.von_mises.max()) / 1e6}


def check_dynamic(ex) -> dict:
    """Worst relative errors of the axial load and moment carried by the balls after the ramp."""
    end = ex.t > 0.15
    axial = ex.ball_load_N[end] * np.sin(ex.run["angle"][end][:, ex.fixed])
    y = ex.run["q"][end][:, list(ex.balls.elements), 1]
    weight_err = np.abs(axial.sum(axis=1) / ex.WEIGHT_N - 1.0).max()
    moment_err = np.abs(np.abs((axial * y).sum(axis=1)) / ex.MOMENT_NM - 1.0).max()
    assert weight_err < 0.01 and moment_err < 0.02 and ex.worst.time_s > 0.1, (weight_err, moment_err)
    return {"dynamic_weight_rel_err": weight_err, "dynamic_moment_rel_err": moment_err,
            "dynamic_worst_time_s": ex.worst.time_s, "dynamic_worst_von_mises_MPa": ex.worst.von_mises_Pa / 1e6}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="the static example at its quick size only")
    args = ap.parse_args()
    figures = {}
    with tempfile.TemporaryDirectory() as tmp:
        os.environ.setdefault("FLEXBEARING_CACHE", str(Path(tmp) / "cache"))
        ex, wall_s = run_example("slewing_race_static", Path(tmp), args.quick)
        figures.update(check_static(ex), static_wall_s=wall_s)
        print(f"slewing_race_static ({'quick' if args.quick else 'full'}): {wall_s:.1f} s")
        if not args.quick:
            ex, wall_s = run_example("flexible_race_dynamics", Path(tmp), False)
            figures.update(check_dynamic(ex), dynamic_wall_s=wall_s)
            print(f"flexible_race_dynamics (full): {wall_s:.1f} s")
    figures["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(" ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
