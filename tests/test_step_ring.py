"""Rings of bearing description files meshed from STEP solids (``[rings.X] step_file``).

The STEP files are written with :func:`fem_rings.step_solid.write_step` (gmsh's OpenCASCADE kernel,
in millimetres) from the box section that the description builds for the ring, optionally with
axial bolt holes. References:
the same section revolved and meshed directly (an independent path through gmsh: a revolve, not a
STEP import), OpenCASCADE's exact volume of the solid, and the area of the holes' walls (2π·r·h).
"""

import math

import numpy as np
import pytest
import skfem

from cases.bearing_file import loads_bearing
from cases.bearing_solver import bearing_solver
from cases.config import CaseError
from fem_rings.mesh import MeshSpec, gmsh_session, mesh_ring, tangled_elements
from fem_rings.step_solid import check_step_solid, step_solid, write_step
from tests.test_bearing_rings import SMALL

TET = SMALL.replace("element_size_m = 0.03\nclamped_face", 'element_size_m = 0.03\nelement = "tet10"\nclamped_face')
#: eight axial bolt holes Ø12 mm on a Ø550 mm circle through the outer ring, at (k + ½)·45°
HOLES = (0.275, 0.006, 8)


def write_ring_step(profile, path, holes=None, cylinder_only=False):
    """The solid of revolution of ``profile`` (or of its bounding box) in mm, less axial holes."""
    r0, r1, z0, z1 = (1e3 * v for v in profile.bounds_m)

    def modify(occ, vol):
        if cylinder_only:
            occ.remove(vol, recursive=True)
            out = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, r1)
            vol, _ = occ.cut([(3, out)], [(3, occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, r0))])
        if holes:
            r_h, radius, n = holes
            tools = [(3, occ.addCylinder(1e3 * r_h * math.cos(a), 1e3 * r_h * math.sin(a), z0 - 1, 0, 0, z1 - z0 + 2,
                                         1e3 * radius)) for a in (2 * math.pi * (k + 0.5) / n for k in range(n))]
            vol, _ = occ.cut(vol, tools)
        return vol

    return write_step(path, profile, modify)


def _with_outer(text, line):
    return text.replace('element = "tet10"\nclamped_face', f"{line}\nclamped_face", 1)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("step")
    outer = loads_bearing(TET).rings["outer"].profile
    return folder, {"plain": write_ring_step(outer, folder / "outer.step"),
                    "holes": write_ring_step(outer, folder / "outer_holes.step", HOLES),
                    "no_groove": write_ring_step(outer, folder / "no_groove.step", cylinder_only=True)}


def _max_load(desc):
    dist = bearing_solver(desc).solve(desc.default_load)
    return max(float(np.max(r.load_N)) for r in dist.rows), dist.displacement


def test_step_ring_gives_the_load_distribution_of_its_revolved_section(files):
    folder, f = files
    revolved = loads_bearing(TET)
    step = loads_bearing(_with_outer(TET, 'step_file = "outer.step"'), base_dir=folder)
    assert step.rings["outer"].solid is not None and step.rings["outer"].solid.unit == "mm"
    q_rev, u_rev = _max_load(revolved)
    q_step, u_step = _max_load(step)
    # reference: the section revolved by gmsh and meshed directly; the STEP import meshes the same
    # geometry with other nodes (tet10, 30 mm), so the two differ by the mesh's noise (measured
    # 0.1 % on the displacement, 0.05 % on the largest load): 0.5 %
    assert q_step == pytest.approx(q_rev, rel=5e-3)
    assert np.linalg.norm(u_step[:3] - u_rev[:3]) <= 5e-3 * np.linalg.norm(u_rev[:3])


def _volume(ring) -> float:
    return skfem.Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(skfem.CellBasis(ring.mesh, skfem.ElementTetP2()))


def test_step_ring_keeps_its_holes(files):
    folder, f = files
    desc = loads_bearing(_with_outer(TET, 'step_file = "outer_holes.step"'), base_dir=folder)
    m = desc.rings["outer"]
    ring = mesh_ring(m.profile, MeshSpec(0.015, "tet10", solid=m.solid))
    assert len(tangled_elements(ring.mesh, "tet10")) == 0
    volume = check_step_solid(f["holes"]).volume_m3
    r_h, radius, n = HOLES
    z0, z1 = m.profile.bounds_m[2:]
    # the file: the revolved section less n holes π·r²·h (OpenCASCADE's exact faces, 1e-9)
    assert volume == pytest.approx(m.profile.revolved_properties(1.0)["mass_kg"] - n * math.pi * radius**2 * (z1 - z0),
                                   rel=1e-9)
    # reference: OpenCASCADE's volume of the solid; quadratic tetrahedra of 15 mm on its curved
    # faces hold it to 6e-5 (measured; 9e-4 at 30 mm): 2e-4
    assert _volume(ring) == pytest.approx(volume, rel=2e-4)
    # the holes' walls are the faces the section does not name: area n·2π·r·h (P2 facets with about
    # 12 per hole's circumference: measured 1.0e-3 low): 3e-3
    basis = skfem.FacetBasis(ring.mesh, skfem.ElementTetP2(), facets=ring.facet_sets["other"])
    area = skfem.Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(basis)
    assert area == pytest.approx(n * 2 * math.pi * radius * (z1 - z0), rel=3e-3)
    # the named faces are the section's: the raceway and both flat faces keep their facets
    assert {"raceway balls", "top", "bottom", "outer", "inner"} <= set(ring.facet_sets)


def test_tet10_rings_of_curved_sections_are_untangled():
    """gmsh's high-order optimisation: before it, 84 of 2102 (outer) and 136 of 2368 (inner)
    elements of these sections had a Jacobian changing sign inside them."""
    desc = loads_bearing(TET)
    for name in ("inner", "outer"):
        prof = desc.rings[name].profile
        ring = mesh_ring(prof, MeshSpec(0.03, "tet10"))
        assert len(tangled_elements(ring.mesh, "tet10")) == 0
        # reference: the section's revolved volume (exact arcs); 30 mm tet10 on the 13 mm groove
        # hold it to 6e-4 (measured inner 5.8e-4, outer 4.7e-4; 1.5e-5 at 15 mm): 1e-3
        assert _volume(ring) == pytest.approx(prof.revolved_properties(1.0)["mass_kg"], rel=1e-3)


def test_bad_step_rings_name_the_key(files, tmp_path):
    folder, f = files
    with pytest.raises(CaseError, match=r"^rings\.outer\.step_file: the solid has no face at the raceway of row "
                                        r"'balls' of the section \(box\)"):
        loads_bearing(_with_outer(TET, 'step_file = "no_groove.step"'), base_dir=folder)
    with pytest.raises(CaseError, match=r"^rings\.outer\.element: a STEP solid is meshed with \"tet10\""):
        loads_bearing(TET.replace('element = "tet10"\nclamped_face', 'element = "hex27"\nstep_file = "outer.step"\n'
                                  'clamped_face'), base_dir=folder)
    with gmsh_session("writer") as gmsh:
        gmsh.model.occ.addDisk(0, 0, 0, 300, 300)
        gmsh.model.occ.synchronize()
        gmsh.write(str(tmp_path / "disk.step"))
    with gmsh_session("writer") as gmsh:  # two rings about z in one file
        occ = gmsh.model.occ
        for r_in, r_out in ((254.0, 290.0), (300.0, 310.0)):
            occ.cut([(3, occ.addCylinder(0, 0, -30, 0, 0, 60, r_out))], [(3, occ.addCylinder(0, 0, -30, 0, 0, 60, r_in))])
        occ.synchronize()
        gmsh.write(str(tmp_path / "two.step"))
    with pytest.raises(CaseError, match=r"^rings\.outer\.step_file: two\.step holds 2 solids; a ring is one"):
        loads_bearing(_with_outer(TET, 'step_file = "two.step"'), base_dir=tmp_path)
    with pytest.raises(CaseError, match=r"^rings\.outer\.step_file: .*disk\.step is not a solid: 1 surfaces, 0 volumes"):
        loads_bearing(_with_outer(TET, 'step_file = "disk.step"'), base_dir=tmp_path)
    with pytest.raises(CaseError, match=r"^rings\.outer\.step_file: .*missing\.step: no such file"):
        loads_bearing(_with_outer(TET, 'step_file = "missing.step"'), base_dir=tmp_path)
    with pytest.raises(CaseError, match=r"^rings\.outer\.step_unit: must be one of"):
        loads_bearing(_with_outer(TET, 'step_file = "outer.step"\nstep_unit = "inch"'), base_dir=folder)
    # a file in metres read as millimetres is refused by its declared unit
    with pytest.raises(CaseError, match=r"^rings\.outer\.step_file: .*step_unit = 'm' disagrees with the file, which declares mm; step_unit = \"file\" uses"):
        loads_bearing(_with_outer(TET, 'step_file = "outer.step"\nstep_unit = "m"'), base_dir=folder)


def test_a_step_solid_is_hashed_by_its_content(files, tmp_path):
    folder, f = files
    a = step_solid(f["plain"], "mm")
    copy = tmp_path / "elsewhere.step"
    copy.write_bytes(f["plain"].read_bytes())
    from fem_rings.cache import _canonical, input_hash
    # reference: the cache key holds the digest, not the path (a moved file is not meshed again)
    assert input_hash("x", MeshSpec(0.03, "tet10", solid=a)) == input_hash("x", MeshSpec(0.03, "tet10",
                                                                                        solid=step_solid(copy, "mm")))
    assert input_hash("x", MeshSpec(0.03, "tet10", solid=a)) != input_hash("x", MeshSpec(0.03, "tet10",
                                                                                        solid=step_solid(f["holes"], "mm")))
    # a spec without a solid keeps the key it had before the field existed: no "solid" in it
    assert "solid" not in _canonical(MeshSpec(0.03, "tet10")) and "solid" in _canonical(MeshSpec(0.03, "tet10", solid=a))
