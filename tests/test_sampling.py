"""Raceway sampling of mode shapes and its work-consistent transpose."""

import numpy as np
import pytest

from cms_reduction import ReducedBody, reduce_model
from cms_reduction.sampling import interp_index, raceway_displacement, raceway_modal_force, sample_raceway
from fem_rings import MeshSpec, build_model
from fem_rings.nodesets import raceway_curve
from fem_rings.profile import rectangle
from fem_rings.solve import point_load, rigid_body_fields
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)


@pytest.fixture(scope="module")
def setup():
    model = build_model(rectangle("ring", 0.95, 1.05, -0.05, 0.05), MeshSpec(0.05, "tet10"), STEEL, use_cache=False)
    body = reduce_model(model, 10)
    curve = raceway_curve(model.ring, "top", 72)
    return model, body, sample_raceway(body, curve, True)


def test_modal_force_equals_full_model_virtual_work_at_samples(setup):
    # A unit force at each sample point: the full model's consistent nodal load F (isoparametric
    # interpolation transpose) does virtual work Fᵀφ_j on mode j; the sampled projection must give
    # the same number for every mode (acceptance: 1e-10 relative).
    model, body, s = setup
    rng = np.random.default_rng(1)
    worst = 0.0
    for k in range(0, len(s.theta_rad), 7):
        f = rng.normal(size=3)
        f /= np.linalg.norm(f)
        W_full = point_load(model, s.points_m[k][None], f[None]) @ body.shapes
        W_modal = raceway_modal_force(s.displacement, k, (k + 1) % len(s.theta_rad), 1.0, 0.0, f)
        worst = max(worst, np.max(np.abs(W_modal - W_full)) / np.max(np.abs(W_full)))
    assert worst < 1e-10


def test_interpolation_and_its_transpose_are_adjoint(setup):
    # f · u(θ; η) = Q(θ; f) · η for any θ, f, η (work consistency of the moving contact)
    _, body, s = setup
    rng = np.random.default_rng(2)
    for theta in rng.uniform(-1.0, 8.0, 10):
        i0, i1, w0, w1 = interp_index(s.theta_rad, theta, True)
        assert w0 + w1 == pytest.approx(1.0) and 0.0 <= w1 < 1.0
        f, eta = rng.normal(size=3), rng.normal(size=body.n_modes)
        lhs = f @ raceway_displacement(s.displacement, i0, i1, w0, w1, eta)
        rhs = raceway_modal_force(s.displacement, i0, i1, w0, w1, f) @ eta
        assert lhs == pytest.approx(rhs, rel=1e-12)


def test_sampled_rotation_of_a_rigid_rotation_field(setup):
    # Reference: a rigid rotation about each axis has displacement e_a × x and rotation e_a
    # everywhere; the isoparametric elements reproduce it exactly.
    model, _, s = setup
    R = rigid_body_fields(model.nodes_m)[:, 3:]
    synthetic = ReducedBody("rigid", model.nodes_m, R, np.ones(3), np.zeros(3), True, "tet10",
                            model.mesh.doflocs, model.mesh.t)
    curve = raceway_curve(model.ring, "top", 12)
    r = sample_raceway(synthetic, curve, True)
    assert np.abs(r.rotation - np.eye(3)[None]).max() < 1e-10
    expected = np.stack([np.cross(e, r.points_m) for e in np.eye(3)], axis=2)
    assert np.abs(r.displacement - expected).max() < 1e-12


def test_linear_interpolation_error_between_samples(setup):
    # Between samples the raceway field is interpolated linearly; for the n = 2 ring modes with
    # 72 samples the error at mid-interval is (nΔθ)²/8 ≈ 1.5e-3 of the amplitude. Reference: the
    # same field probed exactly at the mid-angles.
    model, body, s = setup
    mid = raceway_curve(model.ring, "top", 144)
    exact = sample_raceway(body, mid, True).displacement[1::2, :, 0]
    interp = np.array([raceway_displacement(s.displacement, *interp_index(s.theta_rad, t, True),
                                            np.eye(body.n_modes)[0]) for t in mid.theta_rad[1::2]])
    err = np.abs(interp - exact).max() / np.abs(exact).max()
    assert err == pytest.approx((2 * 2 * np.pi / 72) ** 2 / 8, rel=0.3)


def _rigid_body_of(model):
    R = rigid_body_fields(model.nodes_m)
    return ReducedBody("rigid", model.nodes_m, R, np.ones(6), np.zeros(6), True, model.ring.spec.element,
                       model.mesh.doflocs, model.mesh.t)


def test_theta_s_grid_on_a_flat_raceway(setup):
    # Three circles of samples across the 0.1 m wide top face at the Gauss–Legendre points
    # r = 1 ∓ 0.05·√(3/5) and r = 1; a rigid motion is reproduced exactly on every circle.
    from cms_reduction.sampling import sample_across

    model, _, _ = setup
    grid = sample_across(_rigid_body_of(model), model.ring, "top", 24, 3)
    radii = sorted(float(np.hypot(*g.points_m[0, :2])) for g in grid)
    assert radii == pytest.approx([1 - 0.05 * np.sqrt(0.6), 1.0, 1 + 0.05 * np.sqrt(0.6)], abs=1e-12)
    for g in grid:
        expected = np.stack([np.cross(e, g.points_m) for e in np.eye(3)], axis=2)
        assert np.abs(g.displacement[:, :, 3:] - expected).max() < 1e-12
        assert np.abs(g.displacement[:, :, :3] - np.eye(3)[None]).max() < 1e-12


def test_cage_pocket_wall_points_are_sampled():
    # Points on the circumferential walls of 12 box pockets of a cage: located on the cut mesh,
    # rigid motion reproduced exactly.
    from cms_reduction.sampling import pocket_contact_points, sample_points
    from fem_rings.cages import CagePockets

    pockets = CagePockets(12, "box", "radial", 0.5, 0.0, width_m=0.05, height_m=0.03)
    model = build_model(rectangle("cage", 0.48, 0.52, -0.03, 0.03), MeshSpec(0.015, "tet10"), STEEL, pockets,
                        use_cache=False)
    pts, th = pocket_contact_points(pockets)
    assert pts.shape == (24, 3)
    s = sample_points(_rigid_body_of(model), "pockets", pts, th)
    expected = np.stack([np.cross(e, pts) for e in np.eye(3)], axis=2)
    assert np.abs(s.displacement[:, :, 3:] - expected).max() < 1e-12
