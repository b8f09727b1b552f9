"""Cost of the strip traction of an elliptical contact against the centre-point law.

Times, inside one compiled loop each (no Python call per evaluation), the traction of a ball
contact (120 N, a = 1.2 mm, rolling with sliding and spin, Kragelskii law):

- the centre-point law (:func:`mbd_core.kernels.laws.friction_force`): one friction coefficient;
- the strip model (:func:`mbd_core.kernels.strip_traction.strip_traction`) with 10, 20 and 40
  strips (20 strips bring the spin moment within 1e-3 of the converged strip model,
  tests/test_strip_traction.py).

That traction alone computes each strip's load share and centroid per call; the force stage reads them
from a table built once per model (:func:`mbd_core.kernels.strip_traction.strip_table`), so the traction
alone is an upper bound of what strips add there. The whole force stage of a bearing is then
timed too (:func:`mbd_core.kernels.forces.compute_forces` in a compiled loop): a 24-ball angular-contact
row without cage (48 ball–groove contacts, 46 closed, rigid rings, balls rolling with spin, Kragelskii law) with the
centre-point law and with 5, 10 and 20 strips per contact (``add_ball_row(traction_strips=…)``); the
cost per ball contact is the force stage's time over the closed contacts. ``--quick``: 10× fewer evaluations.

Run::

    python benchmarks/bench_strip_traction.py [--quick]

Ends with one line of ``name=value`` figures (ns per evaluation and the ratios to the centre point).
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from numba import njit

import math

from mbd_core.contact.friction import Kragelskii
from mbd_core.kernels.forces import compute_forces
from mbd_core.kernels.laws import FRICTION_KRAGELSKII, friction_force
from mbd_core.kernels.strip_traction import strip_traction
from mbd_core.multibody import Driven, Fixed, ModelBuilder
from mbd_core.multibody.bearings import add_ball_row
from mbd_core.multibody.model import make_work
from mbd_core.quasistatic import BallRow

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


@njit(cache=True)
def _force_loop(n, a, q, v, eta, eta_dot, w):
    acc = 0.0
    for i in range(n):
        compute_forces(a, 1e-9 * i, q, v, eta, eta_dot, w)
        acc += w.body_f[0, 2]
    return acc


PUSH_M = 12e-6  # axial shift of the inner ring that presses the balls into both grooves


def _bearing(strips: int):
    """24 balls on rigid rings, the inner ring turning at 600 rpm and shifted axially so that the balls
    touch both grooves (46 of the 48 contacts closed); balls rolling (orbit at about 0.4 of the ring speed) with spin."""
    row = BallRow("dma", 24, 15.875e-3, 0.125, math.radians(26.0), 0.52, 0.52, "inner", axial_sign=1)
    b = ModelBuilder()
    inner = b.add_body("inner", 1.0, (1e-3, 1e-3, 2e-3), position_m=(0.0, 0.0, PUSH_M),
                       motion=Driven(2 * math.pi * 10.0))
    outer = b.add_body("outer", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    rows = add_ball_row(b, row, inner, outer, friction=Kragelskii(*LAW[1:]), traction_strips=strips)
    model, state = b.finalize()
    for i in rows.elements:   # rolling with spin
        r = state.q[i, :3]
        e_t = np.array([-r[1], r[0], 0.0]) / math.hypot(r[0], r[1])
        state.v[i, :3] = 0.4 * 2 * math.pi * 10.0 * 0.0625 * e_t
        state.v[i, 3:] = (-150.0, 0.0, 40.0)
    return model, state


def _force_stage_ns(strips: int, n: int) -> tuple[float, int]:
    """ns per force evaluation of the bearing and its number of loaded ball–groove contacts."""
    model, state = _bearing(strips)
    w = make_work(model)
    args = (model.arrays, state.q, state.v, state.eta, state.eta_dot, w)
    _force_loop(10, *args)
    loaded = int(np.count_nonzero(w.contact_fn > 0.0))
    t0 = time.perf_counter()
    _force_loop(n, *args)
    return 1e9 * (time.perf_counter() - t0) / n, loaded


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
    centre_stage, loaded = _force_stage_ns(0, n // 20)
    print(f"force stage of 24 balls, {loaded} loaded contacts, centre-point law: {centre_stage / 1e3:.2f} µs "
          f"({centre_stage / loaded:.0f} ns per contact)")
    figures["ns_per_contact_centre"] = centre_stage / loaded
    for strips in (5, 10, 20):
        ns, _ = _force_stage_ns(strips, n // 20)
        figures[f"contact_ratio_{strips}_strips"] = ns / centre_stage
        print(f"{strips:3d} strips: {ns / 1e3:.2f} µs ({ns / loaded:.0f} ns per contact), "
              f"{ns / centre_stage:.2f} × the centre-point law per ball contact")
    print(" ".join(f"{k}={v:.3g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
