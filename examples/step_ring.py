"""A ring from a STEP solid: a four-point slewing bearing whose outer ring carries an external gear
and bolt holes, as a CAD model would give it.

The outer ring's solid is written here as a STEP file (:func:`fem_rings.step_solid.write_step`):
its box section revolved, 90 gear teeth (trapezoids 10 mm high, the full ring height) fused on the
outside and 24 bolt holes Ø14 mm drilled through. The bearing file points at it with
``step_file``; its box section still names the faces (the raceway, the bottom face it is bolted
on), and everything else of the solid (teeth, hole walls) is ``other``. The same bearing is solved
with the plain box ring beside it (the same element size; the teeth and holes refine the solid's
mesh around them, so part of the difference is the mesh's).

Run: ``python examples/step_ring.py`` (about two minutes: the teeth and holes make a 127k-DOF ring;
``FLEXBEARING_EXAMPLE_QUICK=1``: 45 coarser teeth and 45 mm elements, as the tests run it); from
the command line, with the files it writes::

    flexbearing loaddist results/examples/step-ring/geared.toml --out results/geared
    flexbearing modes results/examples/step-ring/geared.toml --ring outer
"""

import math
import os
from pathlib import Path

import numpy as np

from cases.bearing_file import read_bearing_file
from cases.bearing_rings import ring_mesh_spec
from cases.bearing_solver import bearing_solver
from fem_rings.model import build_model
from fem_rings.step_solid import check_step_solid, write_step

OUT = Path(os.environ.get("FLEXBEARING_EXAMPLE_OUT", "results/examples/step-ring"))
OUT.mkdir(parents=True, exist_ok=True)
QUICK = os.environ.get("FLEXBEARING_EXAMPLE_QUICK") == "1"

#: gear: teeth, their height and root / tip widths along the circumference, mm
TEETH, TOOTH_HEIGHT_MM, TOOTH_ROOT_MM, TOOTH_TIP_MM = (45, 10.0, 28.0, 14.0) if QUICK else (90, 10.0, 14.0, 7.0)
#: element size of both rings, m
ELEMENT_M = 0.045 if QUICK else 0.03
#: bolt holes through the outer ring: count, pitch diameter and hole diameter, m
BOLTS, BOLT_PITCH_M, HOLE_M = 24, 0.86, 0.014

BEARING = """
[bearing]
name = "geared four-point slewing bearing"
description = "Ø0.8 m, 60 balls Ø20 mm, outer ring with an external gear and bolt holes (STEP)"
moving_ring = "inner"

[[rows]]
type = "four_point"
name = "balls"
count = 60
ball_diameter_m = 0.02
pitch_diameter_m = 0.8
contact_angle_deg = 45.0
shoulder_angle_deg = 70.0
conformity_inner = 0.53
conformity_outer = 0.53

[rings.inner]
inner_diameter_m = 0.70
z_min_m = -0.035
z_max_m = 0.035
n_modes = 12
raceway_harmonics = 6
element_size_m = {element_m}
element = "tet10"
[rings.inner.bolts]
count = 24
pitch_diameter_m = 0.74
face = "top"

[rings.outer]
outer_diameter_m = 0.90
z_min_m = -0.035
z_max_m = 0.035
n_modes = 12
raceway_harmonics = 6
element_size_m = {element_m}
element = "tet10"
{outer_extra}
[rings.outer.bolts]
count = 24
pitch_diameter_m = 0.86
face = "bottom"

[load]
Fx_N = 2.0e4
Fz_N = -8.0e4
My_Nm = 1.2e4
"""


def gear_and_holes(occ, volumes):
    """Fuse the teeth onto the outer cylinder (r = 450 mm) and drill the bolt holes, in mm."""
    r, z0, h = 450.0, -35.0, 70.0
    teeth = []
    for k in range(TEETH):
        a = 2 * math.pi * k / TEETH
        c, s = math.cos(a), math.sin(a)
        # a trapezoid in the plane, root on the cylinder (reaching 1 mm into it), tip outside
        corners = [(r - 1.0, -TOOTH_ROOT_MM / 2), (r + TOOTH_HEIGHT_MM, -TOOTH_TIP_MM / 2),
                   (r + TOOTH_HEIGHT_MM, TOOTH_TIP_MM / 2), (r - 1.0, TOOTH_ROOT_MM / 2)]
        pts = [occ.addPoint(x * c - y * s, x * s + y * c, z0) for x, y in corners]
        lines = [occ.addLine(pts[i], pts[(i + 1) % 4]) for i in range(4)]
        face = occ.addPlaneSurface([occ.addCurveLoop(lines)])
        teeth += [d for d in occ.extrude([(2, face)], 0, 0, h) if d[0] == 3]
    volumes, _ = occ.fuse(volumes, teeth)
    holes = [(3, occ.addCylinder(500 * BOLT_PITCH_M * math.cos(a), 500 * BOLT_PITCH_M * math.sin(a), z0 - 1, 0, 0,
                                 h + 2, 500 * HOLE_M))
             for a in (2 * math.pi * (k + 0.5) / BOLTS for k in range(BOLTS))]
    volumes, _ = occ.cut(volumes, holes)
    return volumes


plain_text = BEARING.format(outer_extra="", element_m=ELEMENT_M)
(OUT / "plain.toml").write_text(plain_text)
plain = read_bearing_file(OUT / "plain.toml")
step_path = write_step(OUT / "outer-ring-geared.step", plain.rings["outer"].profile, gear_and_holes)
(OUT / "geared.toml").write_text(BEARING.format(outer_extra=f'step_file = "{step_path.name}"', element_m=ELEMENT_M))
geared = read_bearing_file(OUT / "geared.toml")

results = {}
for name, desc in (("plain", plain), ("geared", geared)):
    results[name] = bearing_solver(desc).solve(desc.default_load)
    q = results[name].rows[0].load_N
    print(f"{name:6s} outer ring: largest ball load {q.max():8.0f} N, loaded balls {int(np.sum(q > 0))}, "
          f"equilibrium residual {results[name].equilibrium_error:.1e}")

m = geared.rings["outer"]
ring = build_model(m.profile, ring_mesh_spec(m), m.material)  # the mesh the solver used (cached)
ones = np.zeros(ring.n_dofs)
ones[0::3] = 1.0
mass_kg = float(ones @ ring.M @ ones)
solid = check_step_solid(step_path)
print(f"geared outer ring: {ring.ring.summary()}; mass {mass_kg:.2f} kg (FE) against "
      f"{solid.volume_m3 * m.material.density_kg_m3:.2f} kg (the solid's volume × density)")
print(f"faces: {', '.join(f'{k} ({len(v)} facets)' for k, v in ring.ring.facet_sets.items())}")
