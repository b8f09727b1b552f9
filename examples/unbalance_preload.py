"""Why turbocharger ball bearings are preloaded: a rotating unbalance at 50 000 rev/min with and
without axial preload.

The hybrid angular-contact row of ``high_speed_ball_bearing.py`` (8 Si3N4 balls of 5.556 mm on
d_m = 26 mm, α0 = 15°) carries an inner ring driven at 50 000 rev/min, free to move and tilt, with
10 g·mm of unbalance: a radial force U Ω² = 274 N turning with the ring (a world-frame load history
sampled 64 times per revolution). Once with a 10 N axial load that only locates the ring ("not
preloaded") and once with a 300 N preload. Without preload the balls opposite the unbalance lose
contact once per turn of the load relative to the cage; with preload every ball stays loaded. The
dynamic loads are set beside the quasi-static high-speed solution under the same load frozen in
place (:func:`mbd_core.quasistatic.solve_high_speed_row`).

Writes ball_loads.png and prints the unloaded share and the load range to $FLEXBEARING_EXAMPLE_OUT
(default results/unbalance_preload).

Run: python examples/unbalance_preload.py
"""

import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from foundation.materials import SILICON_NITRIDE  # noqa: E402
from mbd_core.contact.friction import Coulomb  # noqa: E402
from mbd_core.multibody import Driven, Fixed, ModelBuilder, simulate  # noqa: E402
from mbd_core.multibody.bearings import add_ball_row, start_at_equilibrium  # noqa: E402
from mbd_core.quasistatic import BallRow, RingLoad, solve_high_speed_row  # noqa: E402

out_dir = Path(os.environ.get("FLEXBEARING_EXAMPLE_OUT", "results/unbalance_preload"))
SPEED_RPM = 50_000.0
UNBALANCE_KG_M = 1e-5                      # 10 g·mm
WINDOW_S = 6e-3                            # five turns of the ring
row = BallRow("hybrid", 8, 5.556e-3, 26e-3, math.radians(15), 0.52, 0.53, "inner", axial_sign=1,
              ball_material=SILICON_NITRIDE)
omega = SPEED_RPM * math.pi / 30
unbalance_N = UNBALANCE_KG_M * omega ** 2


def run(axial_N: float) -> dict:
    b = ModelBuilder()
    inner = b.add_body("inner ring", 0.05, (5e-6, 5e-6, 8e-6), motion=Driven(omega, translation_free=True, tilt_free=True))
    outer = b.add_body("outer ring", 0.08, (8e-6, 8e-6, 1.4e-5), motion=Fixed())
    balls = add_ball_row(b, row, inner, outer, friction=Coulomb(0.1, 0.08, 0.05, 0.1), damping_N_s_m=20.0,
                         cage_mass_kg=2e-3, pocket_clearance_m=0.1e-3, cage_stiffness_N_per_m=1e6)
    b.add_bushing(outer, balls.cage, (0.0, 0.0, 0.0), (2e5, 2e5, 0, 0, 0, 0), (5.0, 5.0, 0, 0, 0, 0))
    t = np.linspace(0.0, WINDOW_S, int(64 * WINDOW_S * omega / (2 * math.pi)) + 1)
    loads = np.zeros((t.size, 6))
    loads[:, 0], loads[:, 1], loads[:, 2] = unbalance_N * np.cos(omega * t), unbalance_N * np.sin(omega * t), axial_N
    b.add_load_history(inner, t, loads)
    model, state = b.finalize()
    # start at the quasi-static equilibrium under the load at t = 0
    quasi = solve_high_speed_row(row, RingLoad(Fz_N=axial_N, Fx_N=unbalance_N), omega)
    start_at_equilibrium(model, state, balls, inner, outer, quasi)
    rec = simulate(model, state, WINDOW_S, record_every=10)
    late = rec["t"] > WINDOW_S / 3               # after the start has settled
    fi = rec["fn"][late][:, list(balls.moving_pairs)]
    return {"axial_N": axial_N, "t": rec["t"][late], "inner_N": fi, "unloaded_share": float(np.mean(fi <= 0.0)),
            "min_N": float(fi.min()), "max_N": float(fi.max()),
            "quasi_min_N": float(quasi.inner_load_N.min()), "quasi_max_N": float(quasi.inner_load_N.max())}


cases = [run(10.0), run(300.0)]
out_dir.mkdir(parents=True, exist_ok=True)
fig, axes = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
for ax, c in zip(axes, cases):
    ax.plot(c["t"] * 1e3, c["inner_N"][:, 0], label="ball 1")
    ax.axhline(c["quasi_max_N"], color="0.5", ls="--", lw=0.8, label="quasi-static max / min")
    ax.axhline(c["quasi_min_N"], color="0.5", ls="--", lw=0.8)
    ax.set_ylabel("inner contact load (N)")
    ax.set_title(f"axial {c['axial_N']:.0f} N, {UNBALANCE_KG_M * 1e6:.0f} g·mm at {SPEED_RPM:.0f} rev/min: "
                 f"unloaded {100 * c['unloaded_share']:.0f} % of the time", fontsize=10)
    ax.legend(loc="upper right", fontsize=8)
axes[-1].set_xlabel("time (ms)")
fig.tight_layout()
fig.savefig(out_dir / "ball_loads.png", dpi=120)
plt.close(fig)
for c in cases:
    print(f"axial {c['axial_N']:5.0f} N: inner loads {c['min_N']:.1f}…{c['max_N']:.1f} N (quasi-static "
          f"{c['quasi_min_N']:.1f}…{c['quasi_max_N']:.1f} N), unloaded {100 * c['unloaded_share']:.1f} % of the time")
