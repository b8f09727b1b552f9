"""Cost of the roller slices coupled through the half-space against the uncoupled ISO/TS 16281 slices.

One roller of the 12 MW wind bearing's radial row (Ø55 × 55 mm on its inner raceway, 74 kN, a
raceway tilt of 0.15 mrad) at 10, 20 and 40 slices: the coupled slices under the roller load
(:func:`mbd_core.contact.line_halfspace.coupled_slices_under_load`: dense influence matrix interpolated
from its table over ln(b/w), built by the first call and not timed; fixed point on the half-widths
with the approach as an unknown) and the ISO slices under the same load (a scalar
root of Σ k_s·(δ + θx_k − g_k)^(10/9) = Q, scipy brentq). ``--quick``: fewer repeats.

Run::

    python benchmarks/bench_line_halfspace.py [--quick]

Ends with one line of ``name=value`` figures (ms per roller and the ratios).
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from scipy.optimize import brentq

from mbd_core.contact.line import iso16281_stiffness, line_contact
from mbd_core.contact.line_halfspace import coupled_slices_under_load

D, L, DM, Q, TILT = 0.055, 0.055, 1.8, 73_676.0, 1.46e-4


def _iso(n: int) -> np.ndarray:
    x = (np.arange(n) + 0.5) / n * L - L / 2
    k = iso16281_stiffness(L) / n
    gap = -0.5 * TILT * x

    def excess(delta):
        return np.sum(k * np.maximum(delta - gap, 0.0) ** (10 / 9)) - Q

    delta = brentq(excess, 0.0, 1e-3, xtol=1e-15)
    return k * np.maximum(delta - gap, 0.0) ** (10 / 9)


def _ms(fn, repeats: int) -> float:
    fn()
    t0 = time.process_time()
    for _ in range(repeats):
        fn()
    return 1e3 * (time.process_time() - t0) / repeats


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="fewer repeats")
    repeats = 2 if ap.parse_args().quick else 10
    contact = line_contact(D, DM - D, L)
    figures = {}
    for n in (10, 20, 40):
        x = (np.arange(n) + 0.5) / n * L - L / 2
        coupled = _ms(lambda: coupled_slices_under_load(Q, -0.5 * TILT * x, L, contact.effective_radius_m,
                                                         contact.E_eff_Pa), repeats)
        iso = _ms(lambda: _iso(n), repeats)
        figures[f"ms_coupled_{n}"] = coupled
        figures[f"ms_iso_{n}"] = iso
        figures[f"ratio_{n}"] = coupled / iso
        print(f"{n:3d} slices: coupled {coupled:8.2f} ms, ISO {iso:6.2f} ms per roller (CPU), ratio {coupled / iso:6.1f}")
    print(" ".join(f"{k}={v:.3g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
