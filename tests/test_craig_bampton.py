"""Craig–Bampton reduction against the full FE model it comes from."""

import numpy as np
import pytest

from scipy.sparse.linalg import eigsh

from cms_reduction import Augmentation, Interface, reduce_model
from cms_reduction.craig_bampton import rbe2_transform
from fem_rings import MeshSpec, Support, build_model, modal_analysis, static_solve
from fem_rings.nodesets import patch_nodes, raceway_curve
from fem_rings.profile import rectangle
from fem_rings.solve import line_load, point_load, rigid_body_fields
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)


@pytest.fixture(scope="module")
def ring():
    # slender ring R = 1 m, 0.1 × 0.1 m section
    return build_model(rectangle("ring", 0.95, 1.05, -0.05, 0.05), MeshSpec(0.05, "hex27", n_theta=48),
                       STEEL, use_cache=False)


@pytest.fixture(scope="module")
def pads(ring):
    # four support pads on the bottom face, 90° apart, each three node layers (±3.75°) long
    return [patch_nodes(ring.ring, "bottom", 90.0 * k, 0.07) for k in range(4)]


def test_free_body_reproduces_free_free_modes(ring):
    # Reference: the full model's free–free modes. The reduced basis contains them exactly, so the
    # frequencies agree to round-off (acceptance: 0.5 % below the cut-off); the six rigid modes
    # are removed for the floating frame and the kept modes carry no rigid content.
    body = reduce_model(ring, 12)
    full = modal_analysis(ring, 18)
    assert body.floating and body.n_modes == 12
    assert np.max(np.abs(body.frequencies_Hz / full.elastic_frequencies_Hz[:12] - 1)) < 1e-8
    R = rigid_body_fields(ring.nodes_m)
    assert np.abs(R.T @ (ring.M @ body.shapes)).max() < 1e-9
    assert np.allclose(body.shapes.T @ (ring.M @ body.shapes), np.eye(12), atol=1e-10)


def test_grounded_ring_matches_constrained_full_model(ring, pads):
    # Reference: the full model with every pad node held (a rigid pad fixed to the ground is the
    # same constraint). Acceptance: 0.5 % below the cut-off; seen ~1e-11.
    body = reduce_model(ring, 12, [Interface(f"pad {k}", p) for k, p in enumerate(pads)])
    full = modal_analysis(ring, 12, supports=[Support(p) for p in pads])
    assert not body.floating
    assert np.max(np.abs(body.frequencies_Hz[:10] / full.frequencies_Hz[:10] - 1)) < 1e-8


def test_collinear_interface_is_rejected(ring):
    line = patch_nodes(ring.ring, "bottom", 0.0, 0.01)      # one radial line of nodes
    with pytest.raises(ValueError, match="lie on one line"):
        reduce_model(ring, 4, [Interface("line pad", line, grounded=False)])


def test_free_interface_constraint_modes_approximate_free_free_modes(ring, pads):
    # Craig–Bampton with one free (not grounded) pad: constraint modes + 20 fixed-interface modes
    # is a Rayleigh–Ritz basis of the ring *with that pad made rigid* (the RBE2 constraint itself
    # stiffens the ring: its free–free n = 2, 3 pairs split and one of each rises by ~1.3 %).
    # Reference: the full model with the same rigid pad, u = T q, solved directly.
    # The modes well below the cut-off must come out within 0.5 % and from above.
    itf = Interface("pad", pads[0], grounded=False)
    body = reduce_model(ring, 20, [itf], floating=True)
    T, _, _ = rbe2_transform(ring, [itf])
    Kq, Mq = (T.T @ ring.K @ T).tocsc(), (T.T @ ring.M @ T).tocsc()
    lam = np.sort(eigsh(Kq, k=14, M=Mq, sigma=-40.0, which="LM")[0])
    ref = np.sqrt(np.clip(lam[6:], 0, None)) / (2 * np.pi)
    ratio = body.frequencies_Hz[:8] / ref
    assert np.all(ratio > 1 - 1e-9)
    assert np.all(ratio < 1.005)


def _static_errors(ring, pads, load, augmentation):
    supports = [Support(p) for p in pads]
    u = static_solve(ring, load, supports).displacement_m
    body = reduce_model(ring, 12, [Interface(f"pad {k}", p) for k, p in enumerate(pads)], augmentation)
    eta = (body.shapes.T @ load) / body.omega_rad_s**2
    ur = body.displacement_m(eta)
    return abs(np.abs(ur[:, 2]).max() / np.abs(u[:, 2]).max() - 1)


def test_augmentation_recovers_static_deflection_on_four_supports(ring, pads):
    # Reference: full FE static solution with the same four pads held. Acceptance: reduced within
    # 2 % with augmentation (axial and radial raceway loads, n = 0…8), 12 normal modes. Seen:
    # uniform line load 1.65 % without / 2e-13 with augmentation (the load lies in the augmented
    # span); 16 equal point loads 1.30 % without / 0.49 % with.
    curve = raceway_curve(ring.ring, "top", 96)
    aug = (Augmentation(curve, ("axial", "radial"), 8),)
    q = np.tile([0.0, 0.0, -1e4], (96, 1))
    line = line_load(ring, curve.points_m, q, closed=True)
    th = np.arange(16) * 2 * np.pi / 16
    pts = np.column_stack((np.cos(th), np.sin(th), np.full(16, 0.05)))
    points16 = point_load(ring, pts, np.tile([0.0, 0.0, -1e4], (16, 1)))
    e_line = (_static_errors(ring, pads, line, ()), _static_errors(ring, pads, line, aug))
    e_16 = (_static_errors(ring, pads, points16, ()), _static_errors(ring, pads, points16, aug))
    assert e_line[1] < 1e-8 and e_16[1] < 0.02
    assert e_line[0] == pytest.approx(0.0165, abs=0.002)
    assert e_16[0] == pytest.approx(0.013, abs=0.002)
    assert e_16[1] < e_16[0] / 2


def test_averaging_interface_adds_no_stiffness(ring, pads):
    # An averaging (RBE3-like) master only measures the patch's mean rigid motion: with the master
    # left free, the reduced free body must reproduce the free–free ring (unlike the rigid pad
    # above, which raises one mode of each pair by ~1.3 %). Reference: the full free–free model;
    # within 0.5 % and from above (Rayleigh–Ritz) for the modes well below the cut-off.
    body = reduce_model(ring, 20, [Interface("pad", pads[0], grounded=False, kind="averaging")], floating=True)
    full = modal_analysis(ring, 18).elastic_frequencies_Hz
    ratio = body.frequencies_Hz[:8] / full[:8]
    assert np.all(ratio > 1 - 1e-9) and np.all(ratio < 1.005)


def test_grounded_averaging_pads_static_deflection_against_lagrange_solution(ring, pads):
    # Reference: an independent saddle-point solve of the full model, [[K, Cᵀ], [C, 0]] [u; λ] =
    # [f; 0], where each pad's least-squares rigid fit (GᵀG)⁻¹Gᵀ u_s is held at zero (the
    # averaging constraint, built here from the node positions). Acceptance: reduced with
    # augmentation within 2 %; the line load lies in the augmented span, so it is exact.
    import scipy.sparse as sp
    from scipy.sparse.linalg import spsolve

    x = ring.nodes_m
    rows = []
    for p in pads:
        d = x[p] - x[p].mean(axis=0)
        G = np.zeros((len(p), 3, 6))
        G[:, :, :3] = np.eye(3)
        for a, e in enumerate(np.eye(3)):
            G[:, :, 3 + a] = np.cross(e, d)
        G = G.reshape(-1, 6)
        A = np.linalg.solve(G.T @ G, G.T)
        Cp = np.zeros((6, ring.n_dofs))
        Cp[:, (3 * p[:, None] + np.arange(3)).ravel()] = A
        rows.append(Cp)
    C = sp.csr_matrix(np.vstack(rows))
    curve = raceway_curve(ring.ring, "top", 96)
    f = line_load(ring, curve.points_m, np.tile([0.0, 0.0, -1e4], (96, 1)), closed=True)
    kkt = sp.bmat([[ring.K, C.T], [C, None]]).tocsc()
    u = spsolve(kkt, np.concatenate([f, np.zeros(C.shape[0])]))[: ring.n_dofs].reshape(-1, 3)
    body = reduce_model(ring, 12, [Interface(f"pad {k}", p, kind="averaging") for k, p in enumerate(pads)],
                        (Augmentation(curve, ("axial", "radial"), 4),))
    ur = body.displacement_m((body.shapes.T @ f) / body.omega_rad_s**2)
    # peak deflection: seen 5.9e-6 with NumPy 2.4 / SciPy 1.17 (earlier below 1e-6), the level of the
    # whole-field difference below; 1e-5 holds it with the same margin
    assert np.abs(ur[:, 2]).max() == pytest.approx(np.abs(u[:, 2]).max(), rel=1e-5)
    assert np.linalg.norm(ur - u) < 1e-4 * np.linalg.norm(u)     # seen 8e-6 (saddle-point LU round-off)


def test_free_body_with_nearly_dependent_load_shapes_is_mass_orthonormal(ring):
    # Free–free reduction with raceway load shapes in three directions on the flat top face
    # ("normal" there is "axial": exactly dependent; radial and axial harmonics nearly so, Gram
    # eigenvalue ratios down to 1e-9). Reference: the identity, ΦᵀMΦ = I, which the module
    # promises to 1e-10; the one-pass orthonormalisation reached only 2.7e-7. The modes must also
    # stay K-orthogonal with ΦᵀKΦ = diag(ω²) (relative to the largest ω², same tolerance).
    curve = raceway_curve(ring.ring, "top", 180)
    body = reduce_model(ring, 12, augmentation=[Augmentation(curve, ("normal", "radial", "axial"), 8)])
    m = body.n_modes
    assert np.abs(body.shapes.T @ (ring.M @ body.shapes) - np.eye(m)).max() < 1e-10
    Kr = body.shapes.T @ (ring.K @ body.shapes)
    assert np.abs(Kr - np.diag(body.omega_rad_s**2)).max() < 1e-10 * body.omega_rad_s[-1] ** 2
    # the twelve normal modes are still the free–free ones (the load shapes only add to them)
    full = modal_analysis(ring, 18).elastic_frequencies_Hz
    assert np.abs(body.frequencies_Hz[:4] / full[:4] - 1).max() < 1e-8
