"""Residual flexibility of a reduced ring (``RacewaySpec.probe_spread_m``) and the truncation estimate
built on it (:mod:`mbd_core.quasistatic.estimates`)."""

import math

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from cms_reduction import reduce_model
from cms_reduction.augmentation import ElementAugmentation
from cms_reduction.body import with_stiffness_scaled
from fem_rings import MeshSpec, build_model
from fem_rings.nodesets import raceway_curve, raceway_patch
from fem_rings.profile import rectangle
from foundation.materials import ElasticMaterial
from mbd_core.quasistatic.estimates import truncation_estimate

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
SPREAD_M = 0.02


@pytest.fixture(scope="module")
def ring():
    # 0.04 m × 0.04 m section at r = 0.28…0.32 m, hex27 of 0.02 m: a small free ring
    model = build_model(rectangle("ring", 0.28, 0.32, -0.02, 0.02), MeshSpec(0.02, "hex27"), STEEL, use_cache=False)
    curve = raceway_curve(model.ring, "top", 180)
    probe = ElementAugmentation(curve, (0.0,), tuple(raceway_patch(curve, model.ring.profile, SPREAD_M)), SPREAD_M)
    return model, probe


def _exact_compliance(model, F):
    """Fᵀu with K u = F − M R (RᵀMR)⁻¹ RᵀF, RᵀM u = 0 (inertia relief), solved as the saddle-point
    system with SuperLU: an independent route to the compliance of the free ring's elastic motion
    (the reduction uses a Cholesky factor of K − σM)."""
    x = model.nodes_m - model.nodes_m.mean(axis=0)
    n = len(x)
    R = np.zeros((n, 3, 6))
    R[:, :, :3] = np.eye(3)
    for k, w in enumerate(np.eye(3)):          # rotation about axis k: w × x
        R[:, :, 3 + k] = np.cross(w, x)
    R = R.reshape(-1, 6)
    MR = model.M @ R
    F_rel = F - MR @ np.linalg.solve(R.T @ MR, R.T @ F)
    A = sp.bmat([[model.K, sp.csr_matrix(MR)], [sp.csr_matrix(MR.T), None]]).tocsc()
    rhs = np.vstack((F_rel, np.zeros((6, F.shape[1]))))
    u = spla.splu(A).solve(rhs)[: F.shape[0]]
    return F.T @ u


def test_residual_compliance_is_the_exact_one_less_the_modal_one(ring):
    # Reference: the exact compliance of the probe loads (saddle-point solve, _exact_compliance) less
    # the Ritz compliance of the kept modes Σ (φᵀF)²/ω² computed here from the body's shapes. The
    # reduction's shift σ = −(2π)² rad²/s² against ω₁² ≈ (2π·300 Hz)² changes both by ~1e-5: rtol 1e-3.
    model, probe = ring
    body = reduce_model(model, 12, probes=[probe])
    R = np.array(body.metadata["residual_compliance_m_per_N"])
    F = probe.load_vectors(model, True)
    w2 = (2.0 * math.pi * np.asarray(body.frequencies_Hz)) ** 2
    P = body.shapes.T @ F
    exact = _exact_compliance(model, F)
    expected = exact - P.T @ (P / w2[:, None])
    assert body.frequencies_Hz[0] > 100.0
    np.testing.assert_allclose(body.metadata["probe_compliance_m_per_N"], exact, rtol=1e-3)
    np.testing.assert_allclose(R, expected, rtol=1e-3, atol=1e-3 * np.abs(expected).max())
    assert np.all(np.linalg.eigvalsh(R) > 0.0)  # 12 modes miss part of a local load's response


def test_more_modes_leave_less_residual_and_the_load_shape_leaves_none(ring):
    # Reference: Rayleigh–Ritz. A larger basis holding the smaller one has a larger Ritz compliance
    # (the static response is the minimiser of the potential energy over the basis), so the residual
    # falls, as a matrix (R_6 − R_24 positive semi-definite); a basis holding the probe loads' own
    # static shapes represents their response exactly: residual ≤ 1e-8 of the full compliance.
    model, probe = ring
    R6, R24 = (np.array(reduce_model(model, n, probes=[probe]).metadata["residual_compliance_m_per_N"]) for n in (6, 24))
    assert np.linalg.eigvalsh(R6 - R24).min() > -1e-9 * np.abs(R6).max()
    assert np.trace(R24) < np.trace(R6)
    full = np.array(reduce_model(model, 6, augmentation=[probe], probes=[probe]).metadata["residual_compliance_m_per_N"])
    exact = _exact_compliance(model, probe.load_vectors(model, True))
    assert np.abs(full).max() < 1e-8 * np.abs(exact).max()


def test_a_softer_ring_scales_the_compliances_by_1_over_E(ring):
    # Reference: K ∝ E at fixed M, so every compliance scales with 1/E.
    model, probe = ring
    body = reduce_model(model, 6, probes=[probe])
    soft = with_stiffness_scaled(body, 0.25)
    for key in ("residual_compliance_m_per_N", "probe_compliance_m_per_N"):
        np.testing.assert_allclose(soft.metadata[key], 4.0 * np.array(body.metadata[key]), rtol=1e-14)


def test_probes_need_a_free_floating_body(ring):
    model, probe = ring
    with pytest.raises(ValueError, match="free floating"):
        reduce_model(model, 6, probes=[probe], floating=False)


def test_truncation_estimate_by_hand():
    # Reference: hand values. R = [[4, 1], [1, 2]]·1e-9 m/N, C = 5·R, contact direction at 60°:
    # nᵀRn = (4·0.25 + 2·0.866·0.5·1 + 2·0.75)·1e-9 = 3.3660254e-9 m/N; at Q = 30 kN, r = 1.0098e-4 m;
    # δ = 0.1 mm: η = 1.5·r/δ = 1.5147, κ = 5η = 7.5735, error η/(1+κ) = 0.17667.
    R = np.array([[4e-9, 1e-9], [1e-9, 2e-9]])
    n = np.array([[math.cos(math.radians(60)), math.sin(math.radians(60))]] * 3)
    est = truncation_estimate(5.0 * R, R, n, [10e3, 30e3, 20e3], [0.05e-3, 0.1e-3, 0.08e-3])
    g = 1e-9 * (4 * 0.25 + 2 * math.cos(math.radians(60)) * math.sin(math.radians(60)) + 2 * 0.75)
    eta = 1.5 * g * 30e3 / 0.1e-3
    assert est["element"] == 1
    assert est["residual_deflection_m"] == pytest.approx(g * 30e3, rel=1e-12)
    assert est["stiffness_ratio"] == pytest.approx(eta, rel=1e-12)
    assert est["ring_stiffness_ratio"] == pytest.approx(5 * eta, rel=1e-12)
    assert est["max_load"] == pytest.approx(eta / (1 + 5 * eta), rel=1e-12)
    assert est["max_load"] == pytest.approx(0.17667, rel=1e-4)


def test_a_ring_held_at_its_bolts_measures_its_probe_compliance(ring):
    # Reference: the full stiffness matrix with every DOF of the bolt patches' nodes removed (a
    # grounded rigid patch holds its nodes), solved with SuperLU: Fᵀ K_ff⁻¹ F_f. The reduction
    # solves the interior block with its own factor: rtol 1e-8. Residual: that less the Ritz
    # compliance of the kept fixed-interface modes, Σ (φᵀF)²/ω², with no shift.
    from cms_reduction.craig_bampton import Interface
    from fem_rings.nodesets import patch_nodes

    model, probe = ring
    bolts = [Interface(f"bolt {k}", patch_nodes(model.ring, "bottom", a, 0.02)) for k, a in enumerate((45, 165, 285))]
    body = reduce_model(model, 10, bolts, probes=[probe])
    F = probe.load_vectors(model, True)
    held = np.unique(np.concatenate([3 * b.nodes[:, None] + np.arange(3) for b in bolts]).ravel())
    free = np.setdiff1d(np.arange(model.K.shape[0]), held)
    u = spla.splu(model.K.tocsc()[free][:, free]).solve(F[free])
    exact = F[free].T @ u
    np.testing.assert_allclose(body.metadata["probe_compliance_m_per_N"], exact, rtol=1e-8)
    w2 = (2.0 * math.pi * np.asarray(body.frequencies_Hz)) ** 2
    P = body.shapes.T @ F
    expected = exact - P.T @ (P / w2[:, None])
    np.testing.assert_allclose(body.metadata["residual_compliance_m_per_N"], expected, rtol=1e-6,
                               atol=1e-6 * np.abs(exact).max())
    assert np.all(np.linalg.eigvalsh(np.array(body.metadata["residual_compliance_m_per_N"])) > 0.0)


def test_probes_refuse_a_body_with_free_interfaces(ring):
    from cms_reduction.craig_bampton import Interface
    from fem_rings.nodesets import patch_nodes

    model, probe = ring
    held = Interface("held", patch_nodes(model.ring, "bottom", 45, 0.02))
    loose = Interface("loose", patch_nodes(model.ring, "bottom", 225, 0.02), grounded=False)
    with pytest.raises(ValueError, match="held at all their interfaces"):
        reduce_model(model, 6, [held, loose], probes=[probe])
