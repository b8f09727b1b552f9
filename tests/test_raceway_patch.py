"""Raceway sampling averaged over a patch of the section (``RacewaySpec.spread_m``) and its transpose."""

import math

import numpy as np
import pytest

from cms_reduction import ReducedBody, reduce_model
from cms_reduction.augmentation import Augmentation
from cms_reduction.sampling import raceway_modal_force, sample_points, sample_raceway
from fem_rings import MeshSpec, build_model
from fem_rings.nodesets import RacewayCurve, raceway_curve, raceway_patch
from fem_rings.profile import rectangle
from fem_rings.sections import SlewingSection, slewing_top_race
from fem_rings.solve import line_load_operator, point_load
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)


@pytest.fixture(scope="module")
def ring_model():
    # 0.1 m × 0.1 m section at r = 0.95…1.05 m; the "top" face z = 0.05 m is a straight raceway.
    # (On 0.05 m tet10 elements the probe misses some interior points: hex27 here.)
    return build_model(rectangle("ring", 0.95, 1.05, -0.05, 0.05), MeshSpec(0.05, "hex27"), STEEL, use_cache=False)


def _linear_body(model, A, b):
    """A body whose modes k are the linear fields u(x) = A[k] x + b[k]."""
    x = model.nodes_m
    shapes = np.stack([(x @ A[k].T + b[k]).ravel() for k in range(len(A))], axis=1)
    m = len(A)
    return ReducedBody("linear", x, shapes, np.ones(m), np.zeros(m), True, "hex27", model.mesh.doflocs, model.mesh.t)


def test_patch_average_of_a_linear_field_is_its_value_at_the_centroid(ring_model):
    # Reference: the patch of the straight top face is the rectangle r ∈ [1 − s, 1 + s],
    # z ∈ [0.05 − s, 0.05] of the section, whose centroid is (1, 0.05 − s/2); a linear field's area
    # average is its value there, and its rotation ½ curl u is the skew part of A everywhere.
    # The hex27 elements reproduce linear fields and the Gauss rule integrates them exactly, so
    # only rounding remains (tolerance 1e-12 of the field's size).
    model = ring_model
    rng = np.random.default_rng(7)
    A, b = rng.normal(size=(3, 3, 3)), rng.normal(size=(3, 3))
    body = _linear_body(model, A, b)
    s = 0.02
    curve = raceway_curve(model.ring, "top", 24)
    patch = raceway_patch(curve, model.ring.profile, s)
    assert len(patch) == 12 and sum(w for _, w in patch) == pytest.approx(1.0, abs=1e-15)
    smp = sample_raceway(body, curve, True, patch)
    th = curve.theta_rad
    centroid = np.column_stack((np.cos(th), np.sin(th), np.full(len(th), 0.05 - 0.5 * s)))
    expected = np.stack([centroid @ A[k].T + b[k] for k in range(3)], axis=2)
    assert np.abs(smp.displacement - expected).max() < 1e-12 * np.abs(expected).max()
    skew = np.stack([0.5 * np.array([A[k][2, 1] - A[k][1, 2], A[k][0, 2] - A[k][2, 0], A[k][1, 0] - A[k][0, 1]])
                     for k in range(3)], axis=1)
    assert np.abs(smp.rotation - skew[None]).max() < 1e-12 * np.abs(skew).max()
    np.testing.assert_array_equal(smp.points_m, curve.points_m)


def _groove_curve(spread_name="groove"):
    """The 2 m slewing top race and its groove circle at the 60° contact point, built by hand."""
    profile = slewing_top_race(2.0, SlewingSection())
    arc = next(seg for seg in profile.segments if seg.name == "groove")
    c = np.asarray(arc.center)
    e0 = np.array([-math.cos(math.radians(60.0)), math.sin(math.radians(60.0))])  # inner upper contact
    rz = c + arc.radius_m * e0
    th = np.linspace(0.0, 2.0 * math.pi, 8, endpoint=False)
    pts = np.column_stack((rz[0] * np.cos(th), rz[0] * np.sin(th), np.full(len(th), rz[1])))
    return profile, arc, RacewayCurve(spread_name, th, pts, rz, -e0, c)


def test_groove_patch_centroid_is_the_annular_sector_centroid():
    # Reference: the patch is the annular sector R ≤ ρ ≤ R + s, |φ| ≤ s/R about the groove centre,
    # whose centroid lies on the contact radius at ρ̄ = (2/3)(R₂³ − R₁³)/(R₂² − R₁²) · sin α / α
    # (α = s/R). The 4-point Gauss rule integrates cos φ over ±0.6 rad to ~3e-9 relative
    # (Gauss–Legendre error bound, Abramowitz & Stegun 25.4.30): tolerance 1e-8 of R.
    profile, arc, curve = _groove_curve()
    R, s = arc.radius_m, 0.03
    patch = raceway_patch(curve, profile, s)
    w = np.array([wk for _, wk in patch])
    mean = w @ np.array([pc.rz_m for pc, _ in patch])
    alpha = s / R
    rho = 2.0 / 3.0 * ((R + s) ** 3 - R ** 3) / ((R + s) ** 2 - R ** 2) * math.sin(alpha) / alpha
    e0 = (curve.rz_m - curve.center_rz_m) / R
    assert np.abs(mean - (curve.center_rz_m + rho * e0)).max() < 1e-8 * R


def test_a_patch_past_the_groove_edge_is_refused_naming_spread_m():
    # The groove of the 95.25 mm ball ends 36° (32 mm of arc) beyond the 60° contact point: the
    # outer Gauss points of a 50 mm patch (0.86 rad) leave the section.
    profile, _, curve = _groove_curve()
    raceway_patch(curve, profile, 0.03)
    with pytest.raises(ValueError) as err:
        raceway_patch(curve, profile, 0.05)
    assert "spread_m" in str(err.value) and "groove" in str(err.value)


def test_patch_sample_is_the_transpose_of_point_loads_on_the_patch(ring_model):
    # Work consistency: a force f at θ_j does the work Σ_k w_k f·u(p_k); the full model's
    # consistent nodal loads of forces w_k f at the patch points (fem_rings point_load, an
    # independent path) must give the same modal force (1e-10 relative, rounding only).
    model = ring_model
    body = reduce_model(model, 6)
    curve = raceway_curve(model.ring, "top", 24)
    patch = raceway_patch(curve, model.ring.profile, 0.02)
    smp = sample_raceway(body, curve, True, patch)
    f = np.array([0.3, -0.5, 0.8])
    for j in (0, 5, 17):
        pts = np.array([pc.points_m[j] for pc, _ in patch])
        F = point_load(model, pts, np.array([wk * f for _, wk in patch]))
        W_full = F @ body.shapes
        W_modal = raceway_modal_force(smp.displacement, j, (j + 1) % 24, 1.0, 0.0, f)
        assert np.abs(W_modal - W_full).max() < 1e-10 * np.abs(W_full).max()


def test_patch_load_keeps_the_line_load_resultant(ring_model):
    # Circle k carries w_k of the force per radian of the centre line (per length w_k q r₀/r_k), so
    # the patch load of a uniform axial line load has the resultant of the line load itself:
    # 2π r₀ q times the chord factor of the polygon, the same on every circle (rounding only).
    model = ring_model
    curve = raceway_curve(model.ring, "top", 36)
    patch = tuple(raceway_patch(curve, model.ring.profile, 0.02))
    spread = Augmentation(curve, ("axial",), 0, patch=patch).load_vectors(model, True)[:, 0].reshape(-1, 3)
    line = Augmentation(curve, ("axial",), 0).load_vectors(model, True)[:, 0].reshape(-1, 3)
    chord = 36 * 2.0 * math.sin(math.pi / 36)        # polygon perimeter / r
    assert line.sum(axis=0)[2] == pytest.approx(chord * 1.0, rel=1e-12)
    assert np.abs(spread.sum(axis=0) - line.sum(axis=0)).max() < 1e-12 * chord
    # it is spread: no longer concentrated on the loaded line
    assert not np.allclose(spread, line)


def test_zero_spread_is_the_sample_and_load_on_the_line(ring_model):
    # spread_m = 0 (no patch) keeps the sampling and the load shapes of the contact line itself,
    # bit for bit: the same points probed, the same line-load operator.
    model = ring_model
    rng = np.random.default_rng(3)
    body = _linear_body(model, rng.normal(size=(2, 3, 3)), rng.normal(size=(2, 3)))
    curve = raceway_curve(model.ring, "top", 24)
    a, b = sample_raceway(body, curve, True), sample_points(body, "top", curve.points_m, curve.theta_rad, True)
    np.testing.assert_array_equal(a.displacement, b.displacement)
    np.testing.assert_array_equal(a.rotation, b.rotation)
    vec = Augmentation(curve, ("normal",), 2).load_vectors(model, True)
    load = line_load_operator(model, curve.points_m, closed=True)
    d = -np.tile([0.0, 0.0, 1.0], (24, 1))
    np.testing.assert_array_equal(vec[:, 2], load(np.sin(curve.theta_rad)[:, None] * d))  # cos 0, cos 1, sin 1


def test_largest_groove_patch_is_set_by_the_outer_gauss_point():
    # Reference: the outer of 4 Gauss–Legendre points sits at u = 0.8611363 s, so the patch stays
    # on the groove while 0.8611363 s / R is below the angle from the contact point to the nearer
    # groove edge (measured here from the arc's end points). 1 % either side of that limit.
    profile, arc, curve = _groove_curve()
    c, R = curve.center_rz_m, arc.radius_m
    e0 = (curve.rz_m - c) / R
    to_edge = min(math.acos(np.clip(e0 @ (np.asarray(p) - c) / R, -1.0, 1.0)) for p in (arc.start, arc.end))
    s_max = R * to_edge / 0.8611363115940526
    raceway_patch(curve, profile, 0.99 * s_max)
    with pytest.raises(ValueError, match="past the edge of the raceway"):
        raceway_patch(curve, profile, 1.01 * s_max)


def test_slewing_case_checks_the_spread_naming_the_key():
    # Bad input is refused when the case is made, before meshing, naming the key.
    from cases.slewing.presets import PRESETS
    from cases.slewing.scene import _groove_spec

    base = PRESETS["slewing-undulation"]
    for bad in (-0.01, float("nan"), 0.05):
        with pytest.raises(ValueError, match="raceway_spread_m"):
            base.with_(top={"raceway_spread_m": bad})
    case = base.with_(top={"raceway_spread_m": 0.03})
    assert _groove_spec(case, "top", 16).spread_m == 0.03
    assert _groove_spec(base, "top", 16).spread_m == 0.0


def test_element_load_shapes_carry_unit_forces_at_the_elements(ring_model):
    # Reference: the consistent nodal forces Pᵀf of point forces sum to the sum of the forces
    # (the quadratic shape functions are a partition of unity). A unit radial force at ψ spread by
    # Gauss weights over ±s along the circumference at radius r0 sums to (cos ψ, sin ψ, 0) times
    # the Gauss average of cos(s x / r0), i.e. 1 − (s/r0)²/6 to O((s/r0)⁴); an axial one to (0, 0, 1).
    from cms_reduction.augmentation import ElementAugmentation

    curve = raceway_curve(ring_model.ring, "top", 360)
    s = 0.02
    patch = tuple(raceway_patch(curve, ring_model.ring.profile, s))
    psi = (0.3, 2.0)
    F = ElementAugmentation(curve, psi, patch, s).load_vectors(ring_model, True)
    assert F.shape[1] == 2 * len(psi)
    resultants = F.reshape(-1, 3, F.shape[1]).sum(axis=0).T      # (columns, 3)
    r0 = float(curve.rz_m[0])
    shrink = 1.0 - (s / r0) ** 2 / 6.0
    for i, p in enumerate(psi):
        np.testing.assert_allclose(resultants[2 * i], shrink * np.array([math.cos(p), math.sin(p), 0.0]), atol=1e-6)
        np.testing.assert_allclose(resultants[2 * i + 1], [0.0, 0.0, 1.0], atol=1e-12)


def test_element_load_shapes_need_a_patch(ring_model):
    from cms_reduction.augmentation import ElementAugmentation
    from cms_reduction.pipeline import RacewaySpec

    curve = raceway_curve(ring_model.ring, "top", 36)
    with pytest.raises(ValueError, match="patch"):
        ElementAugmentation(curve, (0.0,), (), 0.01)
    with pytest.raises(ValueError, match="element_angles_deg needs spread_m > 0"):
        RacewaySpec("groove", element_angles_deg=(0.0, 90.0))
