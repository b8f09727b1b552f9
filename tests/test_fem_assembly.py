"""Assembly of K and M, meshing and sets of fem_rings, checked against independent references."""

import math

import numpy as np
import pytest
import skfem
from skfem.models.elasticity import linear_elasticity

from fem_rings.assembly import lame_Pa, mass_matrix, scalar_basis, stiffness_matrix
from fem_rings.mesh import MeshSpec, mesh_ring
from fem_rings.model import build_model
from fem_rings.probe import probe_matrix
from fem_rings.profile import Arc, Line, Profile, rectangle
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)


@pytest.mark.parametrize("mesh", [
    skfem.MeshTet2.init_ball(1),
    skfem.MeshHex2.from_mesh(skfem.MeshHex1().refined(1)),
], ids=["tet10-curved", "hex27"])
def test_vectorised_assembly_equals_scikit_fem_forms(mesh):
    # Reference: scikit-fem's generic assembly of its own linear_elasticity form and a vector
    # mass form on the same basis; the batched matmul assembly must agree to round-off.
    basis = scalar_basis(mesh, 4)
    vb = skfem.Basis(mesh, skfem.ElementVector(mesh.elem()), intorder=4)
    K_ref = linear_elasticity(*lame_Pa(STEEL)).assemble(vb)
    M_ref = skfem.BilinearForm(lambda u, v, w: STEEL.density_kg_m3 * skfem.helpers.dot(u, v)).assemble(vb)
    K = stiffness_matrix(basis, STEEL)
    M = mass_matrix(basis, STEEL.density_kg_m3)
    assert abs(K - K_ref).max() <= 1e-13 * abs(K_ref).max()
    assert abs(M - M_ref).max() <= 1e-13 * abs(M_ref).max()


def _groove_profile():
    # 0.2 × 0.15 m section with a semicircular-ish groove (arc radius 0.05 m) in the top face
    c = (1.0, 0.075 + 0.03)
    r = 0.05
    dz = 0.075 - c[1]
    dr = math.sqrt(r * r - dz * dz)
    return Profile("grooved", (
        Line((0.9, 0.0), (1.1, 0.0), "bottom"),
        Line((1.1, 0.0), (1.1, 0.075), "outer"),
        Line((1.1, 0.075), (c[0] + dr, 0.075), "top"),
        Arc((c[0] + dr, 0.075), (c[0] - dr, 0.075), c, False, "groove"),
        Line((c[0] - dr, 0.075), (0.9, 0.075), "top"),
        Line((0.9, 0.075), (0.9, 0.0), "inner"),
    ))


@pytest.mark.parametrize("element,size", [("hex27", 0.05), ("tet10", 0.05)])
def test_mass_and_inertia_equal_revolved_profile(element, size):
    # Reference: Profile.revolved_properties, exact moments of the section (Green's theorem,
    # Pappus–Guldinus) — independent of the mesh. Acceptance: within 0.1 %.
    prof = rectangle("ring", 0.95, 1.05, -0.1, 0.1) if element == "hex27" else _groove_profile()
    model = build_model(prof, MeshSpec(size, element), STEEL, use_cache=False)
    ref = prof.revolved_properties(STEEL.density_kg_m3)
    x = model.nodes_m
    M = model.M
    ex = np.zeros(model.n_dofs)
    ex[0::3] = 1.0
    mass = ex @ M @ ex
    # ∫ρ (x² + y²) dV = uᵀ M u summed over the fields u = x e_x and u = y e_x
    fx = np.zeros(model.n_dofs)
    fx[0::3] = x[:, 0]
    fy = np.zeros(model.n_dofs)
    fy[0::3] = x[:, 1]
    fz = np.zeros(model.n_dofs)
    fz[0::3] = x[:, 2]
    Jzz = fx @ M @ fx + fy @ M @ fy
    Jxx = fy @ M @ fy + fz @ M @ fz
    assert mass == pytest.approx(ref["mass_kg"], rel=1e-3)
    assert Jzz == pytest.approx(ref["J_zz_kg_m2"], rel=1e-3)
    assert Jxx == pytest.approx(ref["J_xx_kg_m2"], rel=1e-3)
    # the curved quadratic geometry does much better than the 0.1 % asked for (seen: 8e-9 for the
    # swept rectangle, 1.7e-5 for the tetrahedral groove, whose arc is met only at the nodes)
    assert mass == pytest.approx(ref["mass_kg"], rel=1e-4)


def test_boundary_sets_are_named_after_profile_segments():
    # The groove facets lie on the arc of radius 0.05 m about (1.0, 0.105): every groove node does.
    prof = _groove_profile()
    ring = mesh_ring(prof, MeshSpec(0.04, "tet10", sector_deg=90.0))
    assert set(ring.facet_sets) == {"bottom", "outer", "top", "groove", "inner", "sector_start", "sector_end"}
    x = ring.nodes_m[ring.node_sets["groove"]]
    rho = np.hypot(np.hypot(x[:, 0], x[:, 1]) - 1.0, x[:, 2] - 0.105)
    assert np.max(np.abs(rho - 0.05)) < 1e-9
    end = ring.nodes_m[ring.node_sets["sector_end"]]
    assert np.max(np.abs(end[:, 0])) < 1e-9          # the 90° end face is the plane x = 0


def test_probe_interpolates_fields_on_curved_surface():
    # An isoparametric element reproduces any linear field exactly (the map itself is in the
    # space), also at points on the curved outer surface that lie just outside the straight-sided
    # chords; a quadratic field is quartic in reference coordinates, so only approximated.
    ring = mesh_ring(rectangle("ring", 0.95, 1.05, -0.1, 0.1), MeshSpec(0.05, "tet10"))
    basis = scalar_basis(ring.mesh, 2)
    th = np.linspace(0.0, 2 * np.pi, 97, endpoint=False)
    pts = np.column_stack((1.05 * np.cos(th), 1.05 * np.sin(th), np.full_like(th, 0.1)))
    P = probe_matrix(basis, pts)
    x = ring.nodes_m
    linear = 2 * x[:, 0] - x[:, 1] + 5 * x[:, 2]
    assert np.max(np.abs(P @ linear - (2 * pts[:, 0] - pts[:, 1] + 5 * pts[:, 2]))) < 1e-12
    quad = x[:, 0] ** 2 + 3 * x[:, 1] * x[:, 2]
    assert np.max(np.abs(P @ quad - (pts[:, 0] ** 2 + 3 * pts[:, 1] * pts[:, 2]))) < 1e-5


def test_cache_round_trip_gives_identical_model(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path))
    prof = rectangle("ring", 0.95, 1.05, -0.1, 0.1)
    spec = MeshSpec(0.06, "hex27", sector_deg=120.0)
    a = build_model(prof, spec, STEEL)
    b = build_model(prof, spec, STEEL)
    assert "cache_load" in b.timings_s and "assemble" in a.timings_s
    assert abs(a.K - b.K).max() == 0.0 and abs(a.M - b.M).max() == 0.0
    assert np.array_equal(a.nodes_m, b.nodes_m)
    assert {k: len(v) for k, v in a.ring.node_sets.items()} == {k: len(v) for k, v in b.ring.node_sets.items()}
    # a different material is a different entry
    c = build_model(prof, spec, ElasticMaterial("soft", 1.6e9, 0.3, 7850.0))
    assert "assemble" in c.timings_s


def test_hex_mesh_refuses_pockets_and_unknown_refine_names():
    prof = rectangle("ring", 0.95, 1.05, -0.1, 0.1)
    with pytest.raises(ValueError, match="refine"):
        mesh_ring(prof, MeshSpec(0.05, "tet10", refine={"groove": 0.5}))
    with pytest.raises(ValueError, match="size_m"):
        MeshSpec(-1.0)
    with pytest.raises(ValueError, match="sector_deg"):
        MeshSpec(0.1, sector_deg=400)
