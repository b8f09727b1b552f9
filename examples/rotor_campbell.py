"""Campbell diagram and unbalance response of a turbocharger-sized rotor on rigid bearings.

A steel shaft of Ø12 mm and 110 mm with an overhung turbine wheel (Ø44 mm, 12 mm thick) at one end
and a compressor wheel (Ø40 mm, 15 mm) at the other, both as solid discs of the shaft's steel (a
real compressor wheel is aluminium and bladed; this keeps one material); ball bearings at two 3 mm
seats 30 mm apart, held laterally (pinned: the seats may tilt), the axial motion held at the
compressor nose. The model is solid FE (tet10), reduced to its 16 lowest modes on the supports, spun
in its own frame with Coriolis, spin softening and centrifugal stress stiffening
(:mod:`mbd_core.rotordynamics`).

Prints the whirl modes at rest and the critical speeds where forward and backward whirl cross the
running speed (1×), and writes campbell.png and unbalance.png (10 g·mm at the turbine wheel,
stationary damping of 2 % of the first forward critical) to $FLEXBEARING_EXAMPLE_OUT (default
results/rotor_campbell).

Then the same rotor on its ball bearings instead of rigid seats: Craig–Bampton at the two seats,
each seat on the hybrid angular-contact row of ``high_speed_ball_bearing.py`` (back to back, 300 N
preload) as an isotropic spring with the row's tangent stiffness at each speed (centrifugal force
and gyroscopic moment of the balls: the rows soften with speed): campbell_on_bearings.png.

Run: python examples/rotor_campbell.py
"""

import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from fem_rings.mesh import MeshSpec  # noqa: E402
from fem_rings.model import build_model  # noqa: E402
from fem_rings.profile import polygon  # noqa: E402
from foundation.materials import BEARING_STEEL  # noqa: E402
from foundation.materials import SILICON_NITRIDE  # noqa: E402
from mbd_core.quasistatic import BallRow, RingLoad  # noqa: E402
from mbd_core.rotordynamics import (ball_row_spring, campbell, held_dofs, on_bearings, seat_basis,  # noqa: E402
                                    spinning_body_of_model, statically_determinate_holds, supported_modes,
                                    unbalance_response)

out_dir = Path(os.environ.get("FLEXBEARING_EXAMPLE_OUT", "results/rotor_campbell"))
out_dir.mkdir(parents=True, exist_ok=True)

SHAFT_R, TURBINE_R, COMPRESSOR_R = 6e-3, 22e-3, 20e-3
points = [(0, 0), (TURBINE_R, 0), (TURBINE_R, 0.012), (SHAFT_R, 0.012), (SHAFT_R, 0.035), (SHAFT_R, 0.038),
          (SHAFT_R, 0.067), (SHAFT_R, 0.070), (SHAFT_R, 0.095), (COMPRESSOR_R, 0.095), (COMPRESSOR_R, 0.110),
          (0, 0.110)]
names = ["turbine_face", "turbine_rim", "turbine_back", "shaft", "seat_turbine", "shaft_mid", "seat_compressor",
         "shaft_compressor", "compressor_back", "compressor_rim", "compressor_nose", "axis"]
rotor = polygon("turbocharger rotor", points, names)
model = build_model(rotor, MeshSpec(size_m=4e-3, refine={n: 0.6 for n in names[3:8]}), BEARING_STEEL)
x = model.nodes_m
nose = model.node_set("compressor_nose")
holds = [(model.node_set("seat_turbine"), "xy"), (model.node_set("seat_compressor"), "xy"),
         ([nose[np.argmin(np.hypot(x[nose, 0], x[nose, 1]))]], "z")]
frequencies_Hz, shapes = supported_modes(model, holds, 16)
body = spinning_body_of_model(model, shapes, frequencies_Hz, held_dofs(len(x), holds))

speeds_rpm = np.linspace(0.0, 200_000.0, 81)
diagram = campbell(body, speeds_rpm * math.pi / 30.0, 8)
lateral = np.abs(np.round(diagram.order[1])) == 1   # at rest a lateral pair is planar: told apart once spinning
print("at rest (Hz):", ", ".join(f"{f:.0f}{' (lateral)' if lat else ''}"
                                 for f, lat in zip(diagram.fixed_Hz[0], lateral)))
forward_critical_rpm = diagram.critical_speeds_rad_s(whirl=1) * 30.0 / math.pi
backward_critical_rpm = diagram.critical_speeds_rad_s(whirl=-1) * 30.0 / math.pi
print("forward critical speeds (rev/min):", ", ".join(f"{v:.0f}" for v in forward_critical_rpm))
print("backward critical speeds (rev/min):", ", ".join(f"{v:.0f}" for v in backward_critical_rpm))

fig, ax = plt.subplots(figsize=(7, 5))
for j in range(diagram.fixed_Hz.shape[1]):
    for whirl, style, label in ((1, "-", "forward"), (-1, "--", "backward"), (0, ":", "no whirl (n = 0)")):
        y = np.where(diagram.whirl[:, j] == whirl, diagram.fixed_Hz[:, j], np.nan)
        ax.plot(speeds_rpm, y, style, color="C0" if whirl == 1 else "C3" if whirl == -1 else "0.5",
                label=label if j == 0 or not ax.get_legend_handles_labels()[1].count(label) else None)
ax.plot(speeds_rpm, speeds_rpm / 60.0, "k-", lw=0.8, label="1× running speed")
for v in forward_critical_rpm:
    ax.axvline(v, color="C0", lw=0.5)
ax.set_xlabel("speed (rev/min)")
ax.set_ylabel("frequency in the fixed frame (Hz)")
ax.set_title("Campbell diagram, rotor on pinned bearing seats")
ax.legend()
fig.tight_layout()
fig.savefig(out_dir / "campbell.png", dpi=120)
plt.close(fig)

# unbalance response: 10 g·mm spread over the turbine wheel's rim, measured there
turbine = model.node_set("turbine_rim")
first = forward_critical_rpm[0] * math.pi / 30.0
run_up_rad_s = np.linspace(0.3, 2.0, 171) * first
zeta = 0.02
response = unbalance_response(body, shapes, 1e-5, turbine, turbine, run_up_rad_s,
                              stationary_damping_per_s=2.0 * zeta * first)
peak_rpm = run_up_rad_s[np.argmax(response.radius_m)] * 30.0 / math.pi
print(f"unbalance response peaks at {peak_rpm:.0f} rev/min, orbit radius {response.radius_m.max() * 1e6:.1f} µm")
fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
a1.semilogy(run_up_rad_s * 30 / math.pi, response.radius_m * 1e6)
a1.set_ylabel("orbit radius at the turbine rim (µm)")
a2.plot(run_up_rad_s * 30 / math.pi, np.degrees(response.phase_lag_rad))
a2.set_ylabel("phase lag (deg)")
a2.set_xlabel("speed (rev/min)")
a1.set_title("10 g·mm at the turbine wheel, stationary damping 2 %")
fig.tight_layout()
fig.savefig(out_dir / "unbalance.png", dpi=120)
plt.close(fig)

# on the ball bearings: the rows' stiffness at each speed
seats = [model.node_set("seat_turbine"), model.node_set("seat_compressor")]
free_Hz, free_shapes = seat_basis(model, seats, 16)
free_rotor = spinning_body_of_model(model, free_shapes, free_Hz, statically_determinate_holds(model))
row = BallRow("hybrid", 8, 5.556e-3, 26e-3, math.radians(15), 0.52, 0.53, "inner", axial_sign=1,
              ball_material=SILICON_NITRIDE)
PRELOAD_N = 300.0
anisotropy = []


def rotor_on_bearings(speed_rad_s):
    spring, left_out = ball_row_spring(row, RingLoad(Fz_N=PRELOAD_N), speed_rad_s)
    anisotropy.append(left_out)
    return on_bearings(free_rotor, free_shapes, model.nodes_m, [(seats[0], spring), (seats[1], spring.mirrored())])


bearing_speeds_rpm = np.linspace(0.0, 200_000.0, 21)
on_balls = campbell(rotor_on_bearings, bearing_speeds_rpm * math.pi / 30.0, 14)
forward_critical_on_balls_rpm = on_balls.critical_speeds_rad_s(whirl=1) * 30.0 / math.pi
print("on the ball bearings, forward critical speeds (rev/min):",
      ", ".join(f"{v:.0f}" for v in forward_critical_on_balls_rpm), f"(anisotropy left out ≤ {max(anisotropy):.1e})")
fig, ax = plt.subplots(figsize=(7, 5))
for j in range(on_balls.fixed_Hz.shape[1]):
    for whirl, marker, colour, label in ((1, "o", "C0", "forward"), (-1, "x", "C3", "backward")):
        y = np.where((on_balls.whirl[:, j] == whirl) & (on_balls.fixed_Hz[:, j] > 1.0), on_balls.fixed_Hz[:, j], np.nan)
        ax.plot(bearing_speeds_rpm, y, marker, color=colour, ms=4, label=label if j == 0 else None)
ax.plot(bearing_speeds_rpm, bearing_speeds_rpm / 60.0, "k-", lw=0.8, label="1× running speed")
ax.legend()
ax.set_ylim(0, 8000)
ax.set_xlabel("speed (rev/min)")
ax.set_ylabel("frequency in the fixed frame (Hz)")
ax.set_title("Campbell diagram on the preloaded hybrid rows")
fig.tight_layout()
fig.savefig(out_dir / "campbell_on_bearings.png", dpi=120)
plt.close(fig)
