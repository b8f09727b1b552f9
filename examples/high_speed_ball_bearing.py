"""A hybrid angular-contact ball bearing of turbocharger size at 10 000 … 200 000 rev/min: what the
stable-step guard picks at each speed, whether the run stays bounded, and the dynamic ball loads
beside the quasi-static high-speed solution (centrifugal force and gyroscopic moment).

8 silicon-nitride balls of 5.556 mm (7/32 in) on d_m = 26 mm, α0 = 15°, f = 0.52 / 0.53, steel
rings; inner ring driven, free to move and tilt, under a 150 N axial spring preload; a land-guided
cage. Each speed runs ``window_s`` from the quasi-static high-speed equilibrium
(:func:`mbd_core.quasistatic.solve_high_speed_row`: ring displacement, ball centres, rolling speeds). Speeds from $FLEXBEARING_EXAMPLE_RPM
(comma-separated, default 10000,50000,100000,200000); outputs to $FLEXBEARING_EXAMPLE_OUT (default
results/high_speed_ball_bearing): table.csv and steps.png.

Run: python examples/high_speed_ball_bearing.py
"""

import csv
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
from mbd_core.multibody.explicit import DivergenceError, stable_timestep  # noqa: E402
from mbd_core.quasistatic import BallRow, RingLoad, solve_high_speed_row  # noqa: E402

out_dir = Path(os.environ.get("FLEXBEARING_EXAMPLE_OUT", "results/high_speed_ball_bearing"))
speeds_rpm = [float(v) for v in os.environ.get("FLEXBEARING_EXAMPLE_RPM", "10000,50000,100000,200000").split(",")]
window_s = 4e-3
preload_N = 150.0
row = BallRow("hybrid", 8, 5.556e-3, 26e-3, math.radians(15), 0.52, 0.53, "inner", axial_sign=1,
              ball_material=SILICON_NITRIDE)


def run_at(speed_rpm: float) -> dict:
    omega = speed_rpm * math.pi / 30
    b = ModelBuilder()
    inner = b.add_body("inner ring", 0.05, (5e-6, 5e-6, 8e-6), motion=Driven(omega, translation_free=True, tilt_free=True))
    outer = b.add_body("outer ring", 0.08, (8e-6, 8e-6, 1.4e-5), motion=Fixed())
    balls = add_ball_row(b, row, inner, outer, friction=Coulomb(0.1, 0.08, 0.05, 0.1), damping_N_s_m=20.0,
                         cage_mass_kg=2e-3, pocket_clearance_m=0.1e-3, cage_stiffness_N_per_m=1e6)
    b.add_bushing(outer, balls.cage, (0.0, 0.0, 0.0), (2e5, 2e5, 0, 0, 0, 0), (5.0, 5.0, 0, 0, 0, 0))  # land guidance
    b.add_force(inner, (0.0, 0.0, preload_N))
    model, state = b.finalize()
    # start at the quasi-static high-speed equilibrium: ring displacement, ball centres, rolling speeds,
    # the cage at the balls' orbit speed
    quasi = solve_high_speed_row(row, RingLoad(Fz_N=preload_N), omega)
    start_at_equilibrium(model, state, balls, inner, outer, quasi)
    limit = stable_timestep(model, state)
    out = {"speed_rpm": speed_rpm, "timestep_s": float(limit.timestep_s), "step_set_by": limit.reason,
           "quasi_static_outer_N": float(quasi.outer_load_N.mean()),
           "quasi_static_inner_N": float(quasi.inner_load_N.mean())}
    try:
        rec = simulate(model, state, window_s, record_every=20)
    except DivergenceError as e:
        return {**out, "status": "stopped", "cause": str(e)}
    late = rec["t"] > 0.5 * window_s
    fi, fo = (rec["fn"][late][:, list(p)] for p in (balls.moving_pairs, balls.fixed_pairs))
    finite = all(np.all(np.isfinite(rec[k])) for k in ("q", "v", "fn"))
    return {**out, "status": "complete" if finite else "non-finite", "cause": "",
            "outer_N": float(fo.mean()), "inner_N": float(fi.mean()),
            "inner_unloaded_share": float(np.mean(fi == 0.0)),
            "ball_speed_max_rad_s": float(np.abs(rec["v"][:, list(balls.elements), 3:]).max())}


rows = [run_at(s) for s in speeds_rpm]
out_dir.mkdir(parents=True, exist_ok=True)
keys = sorted({k for r in rows for k in r})
with open(out_dir / "table.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=keys)
    w.writeheader()
    w.writerows(rows)
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.loglog([r["speed_rpm"] for r in rows], [r["timestep_s"] for r in rows], "o-")
ax.set_xlabel("inner ring speed (r/min)")
ax.set_ylabel("stable time step (s)")
ax.set_title("Step picked by the stable-step guard")
fig.tight_layout()
fig.savefig(out_dir / "steps.png", dpi=120)
for r in rows:
    print(f"{r['speed_rpm']:8.0f} r/min  step {r['timestep_s']:.3g} s  {r['status']}  "
          f"Q_o {r.get('outer_N', float('nan')):.1f} N (quasi-static {r['quasi_static_outer_N']:.1f} N)  "
          f"Q_i {r.get('inner_N', float('nan')):.1f} N (quasi-static {r['quasi_static_inner_N']:.1f} N)")
