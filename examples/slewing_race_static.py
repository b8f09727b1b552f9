"""Bottom race of the 1 m slewing ring under its 16 ball loads, bolted down at 16 patches.

Each load ball presses on the groove along its 60° contact line with Q = W/(Z sin α)
(W = 68.9 t × g, Z = 16, the thesis' 1 m model), spread over its Hertz contact ellipse with the
semi-ellipsoidal pressure p = p0·√(1 − x²/a² − y²/b²) (a, b from the exact Hertz solution of
:mod:`mbd_core.contact.hertz`). The race's bolt face is held at 16 patches (bolt-head footprints,
15 mm radius) half-way between the balls. The mesh resolves the ring's bending, not the contact
stresses under each ball (those follow from the Hertz solution, ``flexbearing hertz``). Writes a VTU for ParaView and a PNG of the
von Mises stress to ``results/examples/slewing-race-static`` (or ``$FLEXBEARING_EXAMPLE_OUT``).

``--quick`` (or ``FLEXBEARING_EXAMPLE_QUICK=1``, what tests/test_examples.py sets): a mesh of 60 mm
instead of 30 mm (30 mm on the groove instead of 15 mm), the same loads and supports; the load and
equilibrium figures do not depend on the mesh, the deflection and stress are coarser.
``benchmarks/bench_examples.py`` runs the full size and checks it.

Run: ``python examples/slewing_race_static.py [--quick]``.
"""

import math
import os
import sys
from pathlib import Path

import numpy as np

from fem_rings import MeshSpec, Support, build_model, nodal_stress_Pa, static_solve, von_mises_Pa
from fem_rings.nodesets import patch_nodes, raceway_curve
from fem_rings.output import write_vtu
from fem_rings.render import render_png
from fem_rings.sections import SlewingSection, slewing_bottom_race
from fem_rings.solve import point_load
from mbd_core.contact import ball_on_groove
from foundation.materials import ElasticMaterial

OUT = Path(os.environ.get("FLEXBEARING_EXAMPLE_OUT", "results/examples/slewing-race-static"))
QUICK = os.environ.get("FLEXBEARING_EXAMPLE_QUICK") == "1" or (__name__ == "__main__" and "--quick" in sys.argv[1:])
MESH_SIZE_M = 0.06 if QUICK else 0.03
N_BALLS, LOAD_T, ALPHA_DEG = 16, 68.9, 60.0
STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)

model = build_model(slewing_bottom_race(1.0), MeshSpec(MESH_SIZE_M, "hex27", refine={"groove": 0.5}), STEEL)

# ball loads: Hertz pressure on the groove about each contact point, pointing into the race
groove = SlewingSection().groove("bottom", 1.0)
balls = raceway_curve(model.ring, "groove", N_BALLS, at_rz_m=groove.contact_point_m)
Q_N = LOAD_T * 1e3 * 9.81 / (N_BALLS * math.sin(math.radians(ALPHA_DEG)))
hertz = ball_on_groove(groove.ball_diameter_m, groove.conformity, 1.0, math.radians(ALPHA_DEG), "outer")
a_m, b_m = (float(v) for v in hertz.semi_axes_m(Q_N))  # a along the rolling direction


def hertz_patch(n: int = 9):
    """Points (ξ, η) in the unit disc and weights ∝ √(1 − ξ² − η²) summing to 1 (midpoint rule)."""
    g = (np.arange(n) + 0.5) / n * 2.0 - 1.0
    xi, eta = (v.ravel() for v in np.meshgrid(g, g))
    w = np.sqrt(np.clip(1.0 - xi**2 - eta**2, 0.0, None))
    keep = w > 0
    return xi[keep], eta[keep], w[keep] / w[keep].sum()


xi, eta, weight = hertz_patch()
centre = np.asarray(groove.curvature_center_m)
phi0 = math.atan2(*(np.asarray(groove.contact_point_m) - centre)[::-1])      # angle on the groove arc
phi = phi0 + eta * b_m / groove.radius_m                                     # across the groove
rz = centre + groove.radius_m * np.column_stack((np.cos(phi), np.sin(phi)))
into_race = np.column_stack((np.cos(phi), np.sin(phi)))                      # away from the centre
points, forces = [], []
for th_ball in balls.theta_rad:
    th = th_ball + xi * a_m / rz[:, 0]                                       # along the rolling direction
    points.append(np.column_stack((rz[:, 0] * np.cos(th), rz[:, 0] * np.sin(th), rz[:, 1])))
    forces.append(Q_N * weight[:, None] * np.column_stack(
        (into_race[:, 0] * np.cos(th), into_race[:, 0] * np.sin(th), into_race[:, 1])))
points_m, forces_N = np.vstack(points), np.vstack(forces)
f = point_load(model, points_m, forces_N)

bolts = [Support(patch_nodes(model.ring, "bolt_face", 360.0 * (k + 0.5) / N_BALLS, 0.015), name=f"bolt {k}")
         for k in range(N_BALLS)]
result = static_solve(model, f, bolts)
stress = nodal_stress_Pa(model, result.displacement_m)
von_mises = von_mises_Pa(stress)

applied_N = forces_N.sum(axis=0)
reaction_N = result.reaction_N.reshape(-1, 3).sum(axis=0)
max_deflection_m = float(np.abs(result.displacement_m[:, 2]).max())

write_vtu(OUT / "race.vtu", model.mesh, {"displacement_m": result.displacement_m, "stress_Pa": stress,
                                          "von_mises_Pa": von_mises})
render_png(OUT / "von_mises.png", model.mesh, von_mises, scale=1e-6, displacement_m=result.displacement_m,
           title=f"1 m bottom race, {N_BALLS} balls × {Q_N:.0f} N at {ALPHA_DEG:g}°")

if __name__ == "__main__":
    print(f"{model.ring.summary()}; ball load {Q_N:.0f} N on a {2 * a_m * 1e3:.1f} × "
          f"{2 * b_m * 1e3:.1f} mm Hertz ellipse")
    print(f"applied {applied_N} N, reactions {reaction_N} N")
    print(f"max axial deflection {max_deflection_m * 1e3:.4f} mm, max von Mises {von_mises.max() / 1e6:.1f} MPa")
    print(f"wrote {OUT}/race.vtu, {OUT}/von_mises.png")
