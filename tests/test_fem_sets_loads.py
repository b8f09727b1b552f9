"""Named sets, raceway curves, cage pockets and consistent loads of ring models."""

import math

import numpy as np
import pytest

from fem_rings.cages import CagePockets
from fem_rings.mesh import MeshSpec, mesh_ring
from fem_rings.model import build_model
from fem_rings.nodesets import nodes_where, patch_nodes, raceway_curve
from fem_rings.probe import probe_matrix
from fem_rings.assembly import scalar_basis
from fem_rings.profile import Arc, Profile, rectangle
from fem_rings.sections import SlewingSection, slewing_bottom_race
from fem_rings.solve import line_load, point_load, surface_load
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)


@pytest.fixture(scope="module")
def race_1m():
    # bottom race of the 1 m slewing ring, quarter sector, groove refined
    return mesh_ring(slewing_bottom_race(1.0), MeshSpec(0.03, "tet10", sector_deg=90.0, refine={"groove": 0.5}))


def test_groove_raceway_curve_sits_on_the_contact_circle(race_1m):
    # Reference: the slewing ring's groove geometry — contact point at 60° on an arc of radius
    # f·D = 0.525 × 95.25 mm about the curvature centre (BallGroove, an independent construction).
    groove = SlewingSection().groove("bottom", 1.0)
    curve = raceway_curve(race_1m, "groove", 37, at_rz_m=groove.contact_point_m)
    assert curve.center_rz_m == pytest.approx(groove.curvature_center_m, abs=1e-12)
    assert np.linalg.norm(curve.rz_m - curve.center_rz_m) == pytest.approx(0.525 * 95.25e-3, rel=1e-12)
    assert curve.rz_m == pytest.approx(groove.contact_point_m, abs=1e-12)
    # the surface normal out of the race points from the contact point to the curvature centre,
    # i.e. along the contact line towards the ball centre: 60° above the radial plane, inward
    assert curve.normal_rz == pytest.approx([-math.cos(math.radians(60)), math.sin(math.radians(60))], abs=1e-12)
    assert curve.theta_rad[[0, -1]] == pytest.approx([0.0, math.pi / 2])
    # the points lie on the meshed solid: the isoparametric probe finds them and gives them back
    P = probe_matrix(scalar_basis(race_1m.mesh, 2), curve.points_m)
    assert np.max(np.abs(P @ race_1m.nodes_m - curve.points_m)) < 1e-12


def test_named_sets_and_patches(race_1m):
    assert {"groove", "bolt_face", "bore", "outer", "sector_start", "sector_end"} <= set(race_1m.facet_sets)
    z = race_1m.nodes_m[race_1m.node_sets["bolt_face"], 2]
    assert np.ptp(z) < 1e-12                       # the bolt face is one plane
    pad = patch_nodes(race_1m, "bolt_face", 45.0, 0.02)
    th = np.degrees(np.arctan2(race_1m.nodes_m[pad, 1], race_1m.nodes_m[pad, 0]))
    r = np.hypot(race_1m.nodes_m[pad, 0], race_1m.nodes_m[pad, 1])
    assert np.all(np.abs(np.radians(th - 45.0)) * r <= 0.02 + 1e-9)
    with pytest.raises(ValueError, match="'nothing'.*empty"):
        nodes_where(race_1m, lambda r, t, z: r > 10.0, "nothing")


def _box_through_annulus_area(r1, r2, w):
    """Area of the strip |y| ≤ w/2 inside the annulus r1 ≤ r ≤ r2 on the side x > 0 (closed form of
    ∫ (√(r2² − y²) − √(r1² − y²)) dy)."""
    F = lambda r, y: 0.5 * (y * math.sqrt(r * r - y * y) + r * r * math.asin(y / r))
    return 2 * (F(r2, w / 2) - F(r1, w / 2))


def test_cage_pockets_cut_the_right_volume():
    # Reference: ring volume minus n × (pocket height × strip area through the annulus), closed form.
    r1, r2, h_ring = 0.48, 0.52, 0.06
    pockets = CagePockets(12, "box", "radial", 0.5, 0.0, width_m=0.05, height_m=0.03)
    prof = rectangle("cage", r1, r2, -h_ring / 2, h_ring / 2)
    model = build_model(prof, MeshSpec(0.012, "tet10"), STEEL, pockets, use_cache=False)
    assert len(model.ring.facet_sets["pocket"]) > 0
    ex = np.zeros(model.n_dofs)
    ex[0::3] = 1.0
    volume = (ex @ model.M @ ex) / STEEL.density_kg_m3
    ref = math.pi * (r2**2 - r1**2) * h_ring - 12 * 0.03 * _box_through_annulus_area(r1, r2, 0.05)
    assert volume == pytest.approx(ref, rel=1e-4)
    # pocket faces: the tangential walls sit at ±w/2 from each pocket's mid-plane
    x = model.nodes_m[model.node_set("pocket")]
    th = np.arctan2(x[:, 1], x[:, 0])
    k = np.round(th / (2 * math.pi / 12))
    local_t = -x[:, 0] * np.sin(k * math.pi / 6) + x[:, 1] * np.cos(k * math.pi / 6)
    z = x[:, 2]
    on_wall = np.isclose(np.abs(local_t), 0.025, atol=1e-9) | np.isclose(np.abs(z), 0.015, atol=1e-9)
    assert on_wall.all()


def test_point_and_line_loads_are_statically_equivalent():
    # Consistent nodal forces Pᵀf reproduce the resultant force and moment of the applied loads
    # (the interpolation reproduces constants and linear fields exactly).
    model = build_model(rectangle("ring", 0.95, 1.05, -0.05, 0.05), MeshSpec(0.05, "tet10", sector_deg=180.0),
                        STEEL, use_cache=False)
    x = model.nodes_m
    pts = np.array([[0.0, 1.0, 0.05], [0.99, 0.1, -0.02]])
    forces = np.array([[0.0, 0.0, -1000.0], [50.0, -20.0, 300.0]])
    F = point_load(model, pts, forces).reshape(-1, 3)
    assert F.sum(axis=0) == pytest.approx(forces.sum(axis=0), abs=1e-9)
    assert np.cross(x, F).sum(axis=0) == pytest.approx(np.cross(pts, forces).sum(axis=0), abs=1e-9)
    # q = 2 kN/m downward along a half circle on the top face, r = 1 m: resultant q × (chord length)
    th = np.linspace(0.0, math.pi, 181)
    curve = np.column_stack((np.cos(th), np.sin(th), np.full_like(th, 0.05)))
    F = line_load(model, curve, (0.0, 0.0, -2000.0), closed=False).reshape(-1, 3)
    chords = np.linalg.norm(np.diff(curve, axis=0), axis=1).sum()
    assert F.sum(axis=0) == pytest.approx([0.0, 0.0, -2000.0 * chords], abs=1e-6)
    assert chords == pytest.approx(math.pi, rel=1e-4)


def _round_section_sector(size_m, element="hex27", R=0.5, a=0.05):
    """A 30° sector of a ring with a round section (radius a about r = R): a torus piece whose
    curved quadratic facets made scikit-fem's facet point location fail."""
    profile = Profile("round", (Arc((R + a, 0.0), (R - a, 0.0), (R, 0.0), True, "top"),
                                Arc((R - a, 0.0), (R + a, 0.0), (R, 0.0), True, "bottom")))
    return build_model(profile, MeshSpec(size_m, element, sector_deg=30.0, n_theta=3), STEEL, use_cache=False)


@pytest.mark.parametrize("size_m,element", [(0.015, "hex27"), (0.0125, "hex27"), (0.015, "tet10")])
def test_surface_load_on_curved_facets_integrates_the_exact_area(size_m, element):
    # Reference: the torus surface, area (2πR/12)(πa) per half section (Pappus), the flat cut
    # faces πa², and the projected area of the upper half (2πR/12)(2a) for the axial resultant of
    # a unit pressure. A uniform traction t on a surface has the resultant t × area. Tolerance
    # 2e-4: the quadratic facets interpolate the circles at three points per edge, an O(φ⁴)
    # geometric error in the area for an edge angle φ; seen 3.4e-5 (curved), 1e-5 (cut faces).
    # The old FacetBasis raised "Newton iteration didn't converge" on the curved hex27 facets.
    R, a = 0.5, 0.05
    model = _round_section_sector(size_m, element, R, a)
    t = np.array([1.0, -2.0, 3.0])
    areas = {"top": 2 * math.pi * R / 12 * math.pi * a, "bottom": 2 * math.pi * R / 12 * math.pi * a,
             "sector_start": math.pi * a**2, "sector_end": math.pi * a**2}
    for name, area in areas.items():
        F = surface_load(model, model.ring.facet_sets[name], t).reshape(-1, 3).sum(axis=0)
        assert F == pytest.approx(t * area, rel=2e-4), name

    def pressure_1Pa(x):                      # traction −n of a unit pressure, n the torus normal
        r = np.hypot(x[0], x[1])
        n_r, n_z = (r - R) / a, x[2] / a
        return -np.array([n_r * x[0] / r, n_r * x[1] / r, n_z])

    Fz = surface_load(model, model.ring.facet_sets["top"], pressure_1Pa).reshape(-1, 3).sum(axis=0)[2]
    assert Fz == pytest.approx(-2 * math.pi * R / 12 * 2 * a, rel=2e-4)


def test_surface_load_agrees_with_scikit_fem_facet_basis_where_that_converges():
    # Reference: scikit-fem's FacetBasis (point location by Newton iteration), on the facet sets
    # where its iteration converges: the same quadrature, so the same vector to round-off.
    import skfem

    model = _round_section_sector(0.03)
    for name in ("top", "bottom", "sector_start"):
        facets = model.ring.facet_sets[name]
        fb = skfem.FacetBasis(model.mesh, skfem.ElementVector(model.mesh.elem()), facets=facets,
                              intorder=model.intorder[0])
        ref = skfem.LinearForm(lambda v, w: 1.0 * v[0] - 2.0 * v[1] + 3.0 * v[2]).assemble(fb)
        mine = surface_load(model, facets, np.array([1.0, -2.0, 3.0]))
        assert np.abs(mine - ref).max() < 1e-12 * np.abs(ref).max(), name
