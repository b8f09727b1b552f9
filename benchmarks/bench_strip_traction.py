"""Cost of the strip traction of an elliptical contact against the centre-point law.

Times, inside one compiled loop each (no Python call per evaluation), the traction of a ball
contact (120 N, a = 1.2 mm, rolling with sliding and spin, Kragelskii law):

- the centre-point law (:func:`mbd_core.kernels.laws.friction_force`): one friction coefficient;
- the strip model (:func:`mbd_core.kernels.strip_traction.strip_traction`) with 10, 20 and 40
  strips (20 strips bring the spin moment within 1e-3 of the converged strip model,
  tests/test_strip_traction.py).

Only the traction is timed, not the contact geometry and normal force around it: the ratio is an
upper bound of what strips add to a whole ball contact. ``--quick``: 10× fewer evaluations.

Run::

    python benchmarks/bench_strip_traction.py [--quick]

Ends with one line of ``name=value`` figures (ns per evaluation and the ratios to the centre point).
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from numba import njit

from mbd_core.kernels.laws import FRICTION_KRAGELSKII, friction_force
from mbd_core.kernels.strip_traction import strip_traction

LAW = (FRICTION_KRAGELSKII, 0.02, 1.5, 8.0, 0.01)


@njit(cache=True)
def _centre_loop(n, params, out):
    v = np.empty(3)
    acc = 0.0
    for i in range(n):
        v[0] = 0.003 + 1e-9 * i
        v[1] = 0.001
        v[2] = 0.0
        friction_force(LAW[0], params, 120.0, v, out)
        acc += out[0]
    return acc


@njit(cache=True)
def _strip_loop(n, n_strips, out):
    acc = 0.0
    for i in range(n):
        strip_traction(120.0, 1.2e-3, 0.003 + 1e-9 * i, 0.001, 4.0, LAW[0], LAW[1], LAW[2], LAW[3], LAW[4],
                       n_strips, out)
        acc += out[0]
    return acc


def _ns(fn, n: int) -> float:
    fn(10)  # compile or load, then time
    t0 = time.perf_counter()
    fn(n)
    return 1e9 * (time.perf_counter() - t0) / n


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="10x fewer evaluations")
    n = 200_000 if ap.parse_args().quick else 2_000_000
    params, out = np.array(LAW[1:], float), np.zeros(3)
    centre = _ns(lambda k: _centre_loop(k, params, out), n)
    figures = {"ns_centre_point": centre}
    print(f"centre-point law: {centre:.1f} ns per evaluation")
    for strips in (10, 20, 40):
        ns = _ns(lambda k, s=strips: _strip_loop(k, s, out), n // 4)
        figures[f"ns_{strips}_strips"] = ns
        figures[f"ratio_{strips}_strips"] = ns / centre
        print(f"{strips:3d} strips: {ns:7.1f} ns per evaluation, {ns / centre:5.1f} × the centre-point law")
    print(" ".join(f"{k}={v:.3g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
