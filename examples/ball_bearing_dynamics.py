"""An angular-contact ball bearing spun up by friction: inner ring driven at 1000 rpm under 2 kN
axial load, outer ring fixed, a cage; record written to $FLEXBEARING_EXAMPLE_OUT (default
results/ball_bearing_dynamics) with a plot of the cage speed.

Run: python examples/ball_bearing_dynamics.py
"""

import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from mbd_core.bearing import rolling_kinematics  # noqa: E402
from mbd_core.contact.friction import Coulomb  # noqa: E402
from mbd_core.multibody import Driven, Fixed, ModelBuilder, simulate  # noqa: E402
from mbd_core.multibody.bearings import add_ball_row  # noqa: E402
from mbd_core.multibody.statics import static_equilibrium  # noqa: E402
from mbd_core.quasistatic import BallRow  # noqa: E402

out_dir = Path(os.environ.get("FLEXBEARING_EXAMPLE_OUT", "results/ball_bearing_dynamics"))
omega_i_rad_s = 1000 * 2 * math.pi / 60

row = BallRow("balls", 12, 12e-3, 0.1, math.radians(30), 0.52, 0.52, "inner", axial_sign=1)
b = ModelBuilder()
inner = b.add_body("inner ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Driven(omega_i_rad_s, translation_free=True))
outer = b.add_body("outer ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
balls = add_ball_row(b, row, inner, outer, friction=Coulomb(0.1, 0.08, 0.01, 0.02), damping_N_s_m=200.0,
                     cage_mass_kg=0.05, pocket_clearance_m=0.2e-3, cage_stiffness_N_per_m=2e6)
b.add_bushing(outer, balls.cage, (0.0, 0.0, 0.0), (1e6, 1e6, 0, 0, 0, 0), (50.0, 50.0, 0, 0, 0, 0))  # land guidance
b.add_force(inner, (0.0, 0.0, 2000.0))
model, state = b.finalize()
state = static_equilibrium(model, state).state          # balls at rest, loaded: friction spins them up
run = simulate(model, state, 0.08, record_every=50, folder=out_dir / "run")

cage_speed_rad_s = run["v"][:, balls.cage, 5]
alpha_rad = float(run["angle"][-1, list(balls.moving_pairs)].mean())
theory = rolling_kinematics(row.ball_diameter_m, row.pitch_diameter_m, alpha_rad, row.n_balls, omega_i_rad_s)

fig, ax = plt.subplots(figsize=(6, 3.5))
ax.plot(run["t"], cage_speed_rad_s * 60 / (2 * math.pi), label="cage (simulated)")
ax.axhline(theory.cage_speed_rad_s * 60 / (2 * math.pi), color="k", ls="--", label="no-slip kinematics")
ax.set_xlabel("time (s)")
ax.set_ylabel("cage speed (r/min)")
ax.set_title("Spin-up under 2000 N axial load, inner ring at 1000 r/min")
ax.legend()
fig.tight_layout()
fig.savefig(out_dir / "cage_speed.png", dpi=120)
print(f"cage speed {cage_speed_rad_s[-1] * 30 / math.pi:.2f} rpm, no-slip theory "
      f"{theory.cage_speed_rad_s * 30 / math.pi:.2f} rpm, loaded contact angle {math.degrees(alpha_rad):.2f}°")
