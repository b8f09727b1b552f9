"""FFRF inertia invariants against the FE fields they integrate and the analytic revolved solid."""

import math

import numpy as np
import pytest

from cms_reduction.body import ReducedBody
from cms_reduction.invariants import (
    Invariants, center_of_mass_m, compute_invariants, inertia_tensor_kg_m2,
)
from fem_rings import MeshSpec, build_model, modal_analysis
from fem_rings.profile import rectangle
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
PROFILE = rectangle("ring", 0.95, 1.05, -0.05, 0.05)
N_THETA = 64


@pytest.fixture(scope="module")
def ring():
    """Free hex27 ring R = 1 m, 100 × 100 mm section: model, all 16 modes, elastic body."""
    model = build_model(PROFILE, MeshSpec(0.05, "hex27", n_theta=N_THETA), STEEL, use_cache=False)
    modes = modal_analysis(model, 16)
    assert modes.n_rigid == 6
    elastic = ~modes.rigid
    body = ReducedBody("ring", model.nodes_m, modes.shapes[:, elastic], modes.frequencies_Hz[elastic],
                       np.zeros(elastic.sum()), True, "hex27", model.mesh.doflocs, model.mesh.t)
    return model, modes, body


def _field(nodes_m, component_values):
    """Interleaved (3N,) field whose component c holds component_values[c] (None = 0)."""
    out = np.zeros((len(nodes_m), 3))
    for c, v in enumerate(component_values):
        if v is not None:
            out[:, c] = v
    return out.ravel()


def _direct_inertia(Ms, U):
    """∫ρ (|u|² 1 − u uᵀ) dV of the nodal position field U (N, 3) through the scalar mass."""
    C = U.T @ (Ms @ U)
    return np.trace(C) * np.eye(3) - C


def test_rigid_properties_equal_fe_field_integrals(ring):
    # Reference: ∫ρ f·g dV = Fᵀ M G for interleaved FE fields (fem_rings.assembly.mass_matrix).
    model, _, body = ring
    M, x = model.M, model.nodes_m
    inv = compute_invariants(M, body.nodes_m, body.shapes)
    ex = _field(x, [1.0])
    mass = ex @ M @ ex
    assert inv.mass_kg == pytest.approx(mass, rel=1e-10)
    for c in range(3):
        assert inv.first_moment_kg_m[c] == pytest.approx(ex @ M @ _field(x, [x[:, c]]), abs=1e-10 * mass)
    xx, yy, zz = (_field(x, [x[:, c]]) for c in range(3))
    J = np.empty((3, 3))
    J[2, 2] = xx @ M @ xx + yy @ M @ yy
    J[0, 0] = yy @ M @ yy + zz @ M @ zz
    J[1, 1] = xx @ M @ xx + zz @ M @ zz
    J[0, 1] = J[1, 0] = -(xx @ M @ yy)
    J[0, 2] = J[2, 0] = -(xx @ M @ zz)
    J[1, 2] = J[2, 1] = -(yy @ M @ zz)
    np.testing.assert_allclose(inv.inertia_kg_m2, J, rtol=0, atol=1e-10 * J[2, 2])


def test_rigid_properties_match_revolved_profile(ring):
    # Reference: Profile.revolved_properties (Pappus–Guldinus, exact for the rectangle).
    # A hex27 layer maps the arc of half-angle α = π/n_θ by a quadratic through three points on
    # the circle, whose sector area is sin α (1 + (1 − cos α)/3) instead of α (integrate
    # ½(x y' − y x') over the parabola): the FE volume is short by the exact factor
    # f = sin α (1 + (1 − cos α)/3)/α = 1 − α⁴/30 + …, 1.9e-7 at n_θ = 64.
    model, _, body = ring
    inv = compute_invariants(model.M, body.nodes_m, body.shapes)
    ref = PROFILE.revolved_properties(STEEL.density_kg_m3)
    a = math.pi / N_THETA
    f = math.sin(a) * (1 + (1 - math.cos(a)) / 3) / a
    assert inv.mass_kg == pytest.approx(ref["mass_kg"] * f, rel=1e-12)
    assert inv.mass_kg == pytest.approx(ref["mass_kg"], rel=1e-6)
    np.testing.assert_allclose(inv.first_moment_kg_m, 0.0, atol=1e-12 * inv.mass_kg)
    J = inv.inertia_kg_m2
    assert J[0, 0] == pytest.approx(ref["J_xx_kg_m2"], rel=1e-6)
    assert J[1, 1] == pytest.approx(ref["J_yy_kg_m2"], rel=1e-6)
    assert J[2, 2] == pytest.approx(ref["J_zz_kg_m2"], rel=1e-6)
    np.testing.assert_allclose(J[~np.eye(3, dtype=bool)], 0.0, atol=1e-12 * J[2, 2])


def test_modal_mass_is_identity_and_elastic_modes_decouple(ring):
    model, _, body = ring
    inv = compute_invariants(model.M, body.nodes_m, body.shapes)
    np.testing.assert_allclose(inv.I6_modal_mass, np.eye(body.n_modes), rtol=0, atol=1e-10)
    # Elastic free–free modes are M-orthogonal to the rigid fields e_a and e_a × x̄, so
    # I3 = ∫ρ Φ and I4 = ∫ρ x̄ × Φ vanish. Scale: Cauchy–Schwarz, |e_aᵀ M φ| ≤ √m and
    # |R_aᵀ M φ| ≤ √J_aa for φᵀ M φ = 1.
    assert np.abs(inv.I3).max() <= 1e-10 * math.sqrt(inv.mass_kg)
    assert np.abs(inv.I4).max() <= 1e-10 * math.sqrt(np.diag(inv.I7).max())
    np.testing.assert_allclose(inv.I5, -inv.I5.transpose(0, 2, 1), rtol=0, atol=1e-14)


def test_rigid_modes_recover_mass_and_inertia_by_parseval(ring):
    # The 6 rigid modes are an M-orthonormal basis of span{e_a, e_a × x̄}: by Parseval,
    # Σ_k (e_aᵀ M φ_k)² = e_aᵀ M e_a = m and Σ_k (R_aᵀ M φ_k)² = R_aᵀ M R_a = J_aa.
    model, modes, body = ring
    inv = compute_invariants(model.M, body.nodes_m, modes.shapes[:, modes.rigid])
    np.testing.assert_allclose((inv.I3**2).sum(axis=1), inv.mass_kg, rtol=1e-9)
    np.testing.assert_allclose((inv.I4**2).sum(axis=1), np.diag(inv.I7), rtol=1e-9)


@pytest.fixture(scope="module")
def deformed(ring):
    """All 16 modes (rigid included, so every invariant is non-zero), scalar mass, η of 1 mm."""
    model, modes, body = ring
    inv = compute_invariants(model.M, body.nodes_m, modes.shapes)
    Ms = model.M[0::3, 0::3]
    eta = np.random.default_rng(7).standard_normal(modes.shapes.shape[1])
    eta *= 1e-3 / np.abs(modes.shapes @ eta).max()       # peak nodal displacement 1 mm
    return inv, Ms, modes.shapes, body.nodes_m, eta


def test_inertia_tensor_of_deformed_body(deformed):
    # Reference: the inertia of the displaced node positions x̄ + Φη integrated with M_s; the
    # invariant form is exact because J(η) is quadratic in η.
    inv, Ms, phi, x, eta = deformed
    n = len(x)
    direct = _direct_inertia(Ms, x + (phi @ eta).reshape(n, 3))
    np.testing.assert_allclose(inertia_tensor_kg_m2(inv, eta), direct, rtol=0, atol=1e-10 * direct[2, 2])
    # First- and second-order parts separately, at a large amplitude (peak 0.1 m): the even and odd
    # parts of J(sη) are I7 + s² quadratic and s · linear.
    s = 100.0
    jp, jm = (_direct_inertia(Ms, x + (phi @ (sign * s * eta)).reshape(n, 3)) for sign in (1, -1))
    first = np.tensordot(inv.I8, s * eta, axes=(2, 0))
    second = np.einsum("ijkl,k,l->ij", inv.I9, s * eta, s * eta)
    np.testing.assert_allclose(0.5 * (jp - jm), first + first.T, rtol=0, atol=1e-10 * np.abs(first).max())
    np.testing.assert_allclose(0.5 * (jp + jm) - inv.I7, second, rtol=0, atol=1e-10 * np.abs(second).max())


def test_center_of_mass_of_deformed_body(deformed):
    inv, Ms, phi, x, eta = deformed
    u = x + (phi @ eta).reshape(-1, 3)
    direct = (Ms @ u).sum(axis=0) / Ms.sum()
    np.testing.assert_allclose(center_of_mass_m(inv, eta), direct, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match="eta must have shape"):
        center_of_mass_m(inv, eta[:-1])


def _skew(a):
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def test_equations_of_motion_of_module_docstring(deformed):
    # Reference: virtual work of the inertia forces on the FE fields. Body-frame acceleration of a
    # point u = x̄ + Φη: a = v̇ + ω×v + ω̇×u + ω×(ω×u) + 2ω×Φη̇ + Φη̈ (pointwise linear in u, so
    # the FE interpolation is exact); generalised forces ∫ρ a, ∫ρ u × a, ∫ρ Φᵀ a through M_s.
    inv, Ms, phi, x, eta = deformed
    rng = np.random.default_rng(11)
    m = len(eta)
    v, w, vd, wd = (rng.standard_normal(3) for _ in range(4))
    etad, etadd = rng.standard_normal(m) * 1e-2, rng.standard_normal(m) * 1e-2
    u = x + (phi @ eta).reshape(-1, 3)
    ud, udd = (phi @ etad).reshape(-1, 3), (phi @ etadd).reshape(-1, 3)
    acc = (vd + np.cross(w, v)) + np.cross(wd, u) + np.cross(w, np.cross(w, u)) + 2 * np.cross(w, ud) + udd
    Ma = Ms @ acc
    fe = np.concatenate([Ma.sum(axis=0), np.cross(u, Ma).sum(axis=0), phi.T @ Ma.ravel()])

    mass, S, J = inv.I1, inv.I2 + inv.I3 @ eta, inertia_tensor_kg_m2(inv, eta)
    I4e = inv.I4 + np.tensordot(eta, inv.I5, axes=(0, 1))
    G = inv.I8 + np.einsum("ijlk,l->ijk", inv.I9, eta)          # G_k = I8_k + Σ_l I9_lk η_l
    Sx, Wx = _skew(S), _skew(w)
    mass_matrix = np.block([[mass * np.eye(3), Sx.T, inv.I3], [Sx, J, I4e], [inv.I3.T, I4e.T, inv.I6]])
    h_v = mass * Wx @ v + Wx @ Wx @ S + 2 * Wx @ inv.I3 @ etad
    h_w = Sx @ Wx @ v + Wx @ J @ w + 2 * np.einsum("ijk,k,j->i", G, etad, w)
    h_e = (inv.I3.T @ (Wx @ v) - np.einsum("i,ijk,j->k", w, G, w)
           + 2 * np.einsum("a,alk,l->k", w, inv.I5, etad))
    ffrf = mass_matrix @ np.concatenate([vd, wd, etadd]) + np.concatenate([h_v, h_w, h_e])
    np.testing.assert_allclose(ffrf, fe, rtol=0, atol=1e-10 * np.abs(fe).max())


def test_arrays_round_trip_and_missing_key(ring):
    model, _, body = ring
    inv = compute_invariants(model.M, body.nodes_m, body.shapes)
    arrays = inv.to_arrays()
    assert all(k.startswith("inv:") for k in arrays) and len(arrays) == 9
    back = Invariants.from_arrays({**arrays, "other": np.zeros(2)})
    for k, a in back.to_arrays().items():
        np.testing.assert_array_equal(a, arrays[k])
    del arrays["inv:I5_modal_cross_m2"]
    with pytest.raises(KeyError, match="inv:I5_modal_cross_m2"):
        Invariants.from_arrays(arrays)


def test_rejects_mass_matrix_that_is_not_block_identity(ring):
    model, _, body = ring
    bad = model.M.tolil()
    bad[0, 1] = bad[1, 0] = 1.0
    with pytest.raises(ValueError, match="M_s ⊗ I₃"):
        compute_invariants(bad.tocsr(), body.nodes_m, body.shapes)
