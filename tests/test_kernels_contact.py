"""Contact-law and ball–groove kernels against their numpy twins (tests/reference/contact_laws.py)
on seeded random and corner inputs, plus the physical properties the laws must have."""

import math

import numpy as np
import pytest

from mbd_core import kernels as K
from tests.reference import contact_laws as ref

RNG = np.random.default_rng(20261123)


def test_step_matches_twin_and_has_flat_ends():
    x = np.concatenate([RNG.uniform(-1, 3, 200), [0.0, 2.0, -0.0]])
    for xi in x:
        assert K.step(xi, 0.0, 1.5, 2.0, -0.5) == pytest.approx(float(ref.step(xi, 0.0, 1.5, 2.0, -0.5)), rel=1e-12, abs=1e-15)
    # zero slope at both ends (Adams STEP is C¹): one-sided differences vanish like h
    h = 1e-6
    assert abs(K.step(h, 0.0, 0.0, 1.0, 1.0) - K.step(0.0, 0.0, 0.0, 1.0, 1.0)) < 1e-11
    assert abs(K.step(1.0, 0.0, 0.0, 1.0, 1.0) - K.step(1.0 - h, 0.0, 0.0, 1.0, 1.0)) < 1e-11


@pytest.mark.parametrize("law", [K.NORMAL_IMPACT, K.NORMAL_HUNT_CROSSLEY])
def test_normal_force_matches_twin_and_is_never_tensile(law):
    k, n, c, d_max = 1e11, 1.5, 2e5 if law == K.NORMAL_IMPACT else 0.3, 1e-5
    deltas = np.concatenate([RNG.uniform(-2e-5, 5e-5, 300), [0.0, -0.0, 1e-5, 1e-300]])
    rates = np.concatenate([RNG.uniform(-5.0, 5.0, 300), [1.0, -1.0, -1e9, 0.0]])
    for d, r in zip(deltas, rates):
        f = K.normal_force(law, d, r, k, n, c, d_max)
        assert f == pytest.approx(float(ref.normal_force(law, d, r, k, n, c, d_max)), rel=1e-12, abs=1e-300)
        assert f >= 0.0
    # touching (zero gap) carries no force, whatever the approach speed: no jump at touch-down
    assert K.normal_force(law, 0.0, 10.0, k, n, c, d_max) == 0.0


@pytest.mark.parametrize("law,params", [
    (K.FRICTION_COULOMB, (0.24, 0.14, 1e-3, 2e-3)),        # thesis values
    (K.FRICTION_DREB_LINEAR, (0.5, 0.0, 0.0, 0.0)),
    (K.FRICTION_DREB_CONSTANT, (0.06, 1e-4, 0.0, 0.0)),
    (K.FRICTION_DREB_FALLING, (0.08, 0.01, 0.0, 0.0)),
    (K.FRICTION_KRAGELSKII, (0.02, 0.5, 12.0, 0.01)),
])
def test_friction_matches_twin_on_random_and_reversed_slip(law, params):
    for _ in range(100):
        v = RNG.normal(size=3) * RNG.choice([1e-5, 1e-3, 0.1, 3.0])
        fn = RNG.uniform(0, 5e4)
        out = np.empty(3)
        K.friction_force(law, np.array(params), fn, v, out)
        assert out == pytest.approx(ref.friction_force(law, params, fn, v), rel=1e-12, abs=1e-300)
        back = np.empty(3)
        K.friction_force(law, np.array(params), fn, -v, back)      # reversed slip: reversed force
        assert back == pytest.approx(-out, rel=1e-12, abs=1e-300)
        assert out @ v <= 0.0                                         # friction dissipates
    zero = np.empty(3)
    K.friction_force(law, np.array(params), 1e3, np.zeros(3), zero)
    assert np.all(zero == 0.0)


def test_coulomb_regularisation_levels():
    # Adams convention: μ(0) = 0, μ(v_s) = μ_s, μ(≥ v_d) = μ_d, continuous in between
    p = (0.24, 0.14, 1e-3, 2e-3)
    mu = lambda u: K.friction_coefficient(K.FRICTION_COULOMB, u, *p)
    assert mu(0.0) == 0.0 and mu(1e-3) == pytest.approx(0.24) and mu(2e-3) == pytest.approx(0.14)
    assert mu(1.0) == 0.14
    u = np.linspace(0, 3e-3, 3001)
    assert np.max(np.abs(np.diff([mu(x) for x in u]))) < 1e-3


def _kernel_ball_groove(x, r_c, z_c, rho, h, dr):
    n = len(x)
    th, d, nn = np.empty(n), np.empty(n), np.empty((n, 3))
    K.ball_groove_contacts(x, r_c, z_c, rho, h, dr, th, d, nn)
    return th, d, nn


def test_ball_groove_matches_twin_with_undulation_and_offset():
    r_c, z_c, rho = 0.5, 0.002, 0.525 * 95.25e-3 - 95.25e-3 / 2
    h = RNG.uniform(-5e-4, 5e-4, 37)
    dr = RNG.uniform(-3e-4, 3e-4, 11)
    th = RNG.uniform(0, 2 * np.pi, 500)
    rr = r_c + RNG.uniform(-0.01, 0.01, 500)
    x = np.column_stack((rr * np.cos(th), rr * np.sin(th), RNG.uniform(-0.01, 0.01, 500)))
    # corners: on the x axis (θ = 0 from both sides), y = −0.0, just below 2π, exactly at the centre
    x = np.vstack([x, [[0.5, 0.0, 0.0], [0.5, -0.0, 0.0], [0.5, -1e-18, 0.0], [0.5, -1e-9, 0.001],
                       [r_c + dr[0], 0.0, z_c + h[0]]]])
    got = _kernel_ball_groove(x, r_c, z_c, rho, h, dr)
    want = ref.ball_groove(x, r_c, z_c, rho, h, dr)
    for a, b in zip(got, want):
        assert a == pytest.approx(b, rel=1e-12, abs=1e-15)
    assert np.all((got[0] >= 0) & (got[0] < 2 * np.pi))
    assert np.all(got[2][-1] == 0.0) and got[1][-1] == pytest.approx(-rho)   # ball at the curvature centre


def test_ball_pressed_along_the_contact_line_gives_that_penetration_and_angle():
    # Geometry check (the slewing ring's groove): a ball whose centre sits at f·D − D/2 + ε from the
    # curvature centre along the 60° contact direction penetrates by ε at a 60° contact angle.
    D, f, alpha = 95.25e-3, 0.525, math.radians(60.0)
    r_c, z_c, rho = 0.5, 0.0, f * D - D / 2
    eps = 3e-5
    for theta in (0.0, 1.0, math.pi, 2 * math.pi - 1e-12):
        dirn = np.array([math.cos(alpha) * math.cos(theta), math.cos(alpha) * math.sin(theta), math.sin(alpha)])
        c = np.array([r_c * math.cos(theta), r_c * math.sin(theta), z_c])
        th, d, n = _kernel_ball_groove((c + (rho + eps) * dirn)[None], r_c, z_c, rho, np.zeros(1), np.zeros(1))
        assert d[0] == pytest.approx(eps, rel=1e-9)
        n_r = n[0, 0] * math.cos(th[0]) + n[0, 1] * math.sin(th[0])
        assert math.atan2(n[0, 2], n_r) == pytest.approx(alpha, rel=1e-12)


def test_friction_parameter_objects_validate_and_feed_the_kernel():
    from mbd_core.contact.friction import THESIS_FRICTION, Coulomb, DrebFalling, Kragelskii

    with pytest.raises(ValueError, match="mu_static"):
        Coulomb(0.1, 0.2)                      # static below dynamic (the paper's table swap)
    with pytest.raises(ValueError, match="v_static_m_s"):
        Coulomb(0.2, 0.1, 2e-3, 1e-3)
    with pytest.raises(ValueError, match="B_s_m"):
        DrebFalling(0.1, -1.0)
    with pytest.raises(ValueError, match="C_s_m"):
        Kragelskii(0.1, 0.1, -1.0, 0.0)
    law = THESIS_FRICTION
    assert K.friction_coefficient(law.code, 5e-3, *law.params) == pytest.approx(0.14)
