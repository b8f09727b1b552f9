"""Rings that bend: a wind-turbine pitch bearing solved with modal rings and with rigid rings.

``examples/bearings/modal/pitch-bearing-modal-rings.toml`` is the Ø2.5 m four-point pitch bearing
of ``pitch-bearing-four-point.toml`` with a box section for each ring, bolted with 54 bolts to a
rigid hub and blade root (format: ``cases/bearings/README.md``, ``[rings.X]``). Each ring is meshed,
reduced (cached on disk) and every load case of the spectrum is solved with the modal rings and
with rigid rings; then the limiting load curve (p0 at the ISO 76 limit, s0 = 1) with both, on the
same rays. Written to ``results/examples/modal-rings/`` (or ``$FLEXBEARING_EXAMPLE_OUT``).

The same from the command line::

    flexbearing loaddist examples/bearings/modal/pitch-bearing-modal-rings.toml --limiting-curve --out results/pitch-modal
    flexbearing modes examples/bearings/modal/pitch-bearing-modal-rings.toml --ring outer

``--quick`` (or ``FLEXBEARING_EXAMPLE_QUICK=1``, what tests/test_examples.py sets): elements of
70 mm instead of 47 mm (and washers of 100 mm, so that each holds nodes of that mesh), 12 modes and
load shapes up to n = 4 per ring, 8 rays instead of 36.
Full size: ``benchmarks/bench_modal_rings.py``.

Run: ``python examples/modal_rings.py [--quick]``.
"""

import os
import sys
import time
from pathlib import Path

import numpy as np

from cases.bearing_file import bearing_from_mapping
from cases.bearing_plots import plot_limiting_load_curve
from cases.bearing_solver import bearing_solver
from cases.config import read_toml
from cases.report import write_load_distribution
from mbd_core.bearing.limiting_load import limiting_load_curve, ray_ratios

FILE = Path(__file__).resolve().parent / "bearings" / "modal" / "pitch-bearing-modal-rings.toml"
OUT = Path(os.environ.get("FLEXBEARING_EXAMPLE_OUT", "results/examples/modal-rings"))
QUICK = os.environ.get("FLEXBEARING_EXAMPLE_QUICK") == "1" or (__name__ == "__main__" and "--quick" in sys.argv[1:])
N_RAYS = 8 if QUICK else 36

data = read_toml(FILE)
if QUICK:
    for ring in data["rings"].values():
        ring.update(element_size_m=0.07, n_modes=12, raceway_harmonics=4)
        ring["bolts"]["washer_diameter_m"] = 0.1  # a washer holding ≥ 3 nodes of the coarse mesh
desc = bearing_from_mapping(data, FILE.parent, str(FILE))

t0 = time.perf_counter()
modal = bearing_solver(desc)
reduction_s = time.perf_counter() - t0
rigid = bearing_solver(desc, rigid=True)
print(f"{desc.name}: {modal.label} (reduced or loaded in {reduction_s:.1f} s)")

t0 = time.perf_counter()
modal_results = [modal.solve(load) for load in desc.load_cases]
solve_s = (time.perf_counter() - t0) / len(desc.load_cases)
rigid_results = [rigid.solve(load) for load in desc.load_cases]
for k, (m, r) in enumerate(zip(modal_results, rigid_results)):
    qm, qr = m.rows[0].load_N.max(), r.rows[0].load_N.max()
    print(f"  case {k + 1}: largest ball load {qm:.0f} N modal, {qr:.0f} N rigid ({100 * (qm / qr - 1):+.2f} %)")
print(f"  {solve_s * 1e3:.1f} ms per load case with the modal rings")
write_load_distribution(modal_results, OUT / "modal", {"case": "modal rings", **modal.summary()}, desc.time_share)
write_load_distribution(rigid_results, OUT / "rigid", {"case": "rigid rings"}, desc.time_share)

curve_rigid = limiting_load_curve(desc.bearing, n_rays=N_RAYS)
curve_modal = limiting_load_curve(desc.bearing, n_rays=N_RAYS, axial_ref_N=curve_rigid.axial_ref_N,
                                  moment_ref_Nm=curve_rigid.moment_ref_Nm, solve=modal.solve)
ratio = ray_ratios(curve_modal, curve_rigid)
worst = int(np.nanargmin(ratio))
print(f"  limiting load curve, modal over rigid along {np.isfinite(ratio).sum()} rays: min {ratio[worst]:.3f} "
      f"(at F_a {curve_rigid.axial_N[worst] / 1e3:.0f} kN, M {curve_rigid.moment_Nm[worst] / 1e3:.0f} kN·m), "
      f"mean {np.nanmean(ratio):.3f}, max {np.nanmax(ratio):.3f}; rays limited by the end of equilibrium "
      f"(balls over the groove shoulder) {int(curve_modal.equilibrium_limited.sum())} modal, "
      f"{int(curve_rigid.equilibrium_limited.sum())} rigid")
OUT.mkdir(parents=True, exist_ok=True)
plot_limiting_load_curve(curve_modal, OUT / "limiting_load_curve.png", desc.name, reference=curve_rigid,
                         labels=("modal rings", "rigid rings"))
