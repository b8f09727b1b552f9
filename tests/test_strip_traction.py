"""Strip traction of an elliptical contact (mbd_core.kernels.strip_traction) against closed forms
of the strip model, a fine numerical integral over the major axis (scipy quad, independent of the
strip sums), its numpy twin (tests/reference), and the centre-point law as the narrow-ellipse limit.

The strip model (DREB program, README Sources): slip of the centre line v(y) = (v_x − ω·y, v_y),
load per unit length q(y) = (3Q/4a)·(1 − y²/a²) (Hertz pressure integrated over x).
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from mbd_core.kernels.laws import (FRICTION_DREB_CONSTANT, FRICTION_DREB_LINEAR, FRICTION_KRAGELSKII,
                                   friction_coefficient)
from mbd_core.kernels.strip_traction import strip_traction
from tests.reference import strip_traction as twin

Q, A = 120.0, 1.2e-3  # N, m (a ball contact of the DMA bearing size)
CONSTANT = (FRICTION_DREB_CONSTANT, 0.03, 1e-12, 0.0, 0.0)  # κ = 0.03 above 1e-12 m/s
LINEAR = (FRICTION_DREB_LINEAR, 2.0, 0.0, 0.0, 0.0)  # κ = 2.0 s/m · u
KRAGELSKII = (FRICTION_KRAGELSKII, 0.02, 1.5, 8.0, 0.01)


def _kernel(vx, vy, w, law, n=400, load=Q, a=A):
    out = np.zeros(3)
    strip_traction(load, a, vx, vy, w, *law, n, out)
    return out


def _mu(law, u):
    return friction_coefficient(law[0], u, *law[1:])


def _integral(vx, vy, w, law, a=A):
    """(F_x, F_y, M) of the continuous strip model by adaptive quadrature over y."""
    def parts(y):
        ux = vx - w * y
        u = math.hypot(ux, vy)
        f = 0.0 if u == 0.0 else _mu(law, u) * 3 * Q / (4 * a) * (1 - (y / a) ** 2) / u
        return -f * ux, -f * vy, y * f * ux
    pts = [vx / w] if w and abs(vx / w) < a else None  # the pure-rolling line: a kink of the slip
    tiny = (1e-13 * Q, 1e-13 * Q, 1e-13 * Q * a)  # (absolute floors: a component may vanish)
    return np.array([quad(lambda y, k=k: parts(y)[k], -a, a, points=pts, limit=400, epsabs=tiny[k], epsrel=1e-9)[0]
                     for k in range(3)])


def test_closed_forms_of_the_strip_model():
    # constant μ, pure spin: no force, M = −sign(ω)·(3/8)·μ·Q·a
    f = _kernel(0.0, 0.0, 5.0, CONSTANT)
    assert abs(f[0]) < 1e-9 * Q and f[1] == 0.0
    assert f[2] == pytest.approx(-3 / 8 * 0.03 * Q * A, rel=1e-3)
    # linear law κ = B·u: F_x = −B·Q·v_x, F_y = −B·Q·v_y exactly (Σ q_i = Q, Σ q_i·ȳ_i = 0 by
    # symmetry), M = −B·ω·Q·a²/5 to O(1/n²) (Σ q_i·ȳ_i² against ∫ q·y² dy)
    vx, vy, w = 0.004, -0.001, 3.0
    f = _kernel(vx, vy, w, LINEAR)
    assert f[0] == pytest.approx(-2.0 * Q * vx, rel=1e-9) and f[1] == pytest.approx(-2.0 * Q * vy, rel=1e-9)
    assert f[2] == pytest.approx(-2.0 * w * Q * A**2 / 5, rel=1e-3)


@pytest.mark.parametrize("law", [CONSTANT, LINEAR, KRAGELSKII], ids=["constant", "linear", "kragelskii"])
def test_rolling_with_spin_matches_the_fine_integral(law):
    """Sliding, side slip and spin with two points of pure rolling inside the ellipse (v_x = ω·y at
    y = 0.4a when v_y = 0): 400 strips within 1e-3 of the quadrature, the numpy twin to 1e-12."""
    for vx, vy, w in ((0.4 * A * 6.0, 0.0, 6.0), (0.002, 0.0005, -4.0), (0.0, 0.0, 2.0)):
        ref = _integral(vx, vy, w, law)
        got = _kernel(vx, vy, w, law)
        scale = np.array([max(abs(ref[0]), abs(ref[1]), 1e-6 * Q)] * 2 + [max(abs(ref[2]), 1e-6 * Q * A)])
        assert np.all(np.abs(got - ref) <= 1e-3 * scale), (vx, vy, w, got, ref)
        numpy = twin.strip_traction(Q, A, vx, vy, w, lambda u: _mu(law, u), 40)
        assert np.allclose(_kernel(vx, vy, w, law, n=40), numpy, rtol=1e-12, atol=1e-14 * Q)


def test_strip_count_converges_at_second_order_away_from_pure_rolling():
    """Linear law, spin: the error of M falls as 1/n² (observed order printed in the assertion)."""
    ref = -2.0 * 3.0 * Q * A**2 / 5
    errors = [abs(_kernel(0.001, 0.0, 3.0, LINEAR, n=n)[2] - ref) for n in (10, 20, 40)]
    orders = [math.log2(errors[k] / errors[k + 1]) for k in range(2)]
    assert all(1.9 < p < 2.1 for p in orders), orders


def test_narrow_ellipse_is_the_centre_point_law():
    """As a → 0 (or without spin) the strips see the centre's slip: −μ(|v|)·Q·v̂."""
    vx, vy = 0.003, 0.001
    u = math.hypot(vx, vy)
    centre = -_mu(KRAGELSKII, u) * Q * np.array([vx, vy]) / u
    assert np.allclose(_kernel(vx, vy, 0.0, KRAGELSKII)[:2], centre, rtol=1e-12)
    narrow = _kernel(vx, vy, 4.0, KRAGELSKII, a=1e-7)
    assert np.allclose(narrow[:2], centre, rtol=1e-6)
    assert abs(narrow[2]) < 1e-6 * Q * 1e-7
    assert not np.any(_kernel(vx, vy, 4.0, KRAGELSKII, load=0.0))


def _curved(vx, vy, omega, curvature, law, n=400):
    from mbd_core.kernels.strip_traction import strip_traction_forces
    return np.array(strip_traction_forces(Q, A, vx, vy, *omega, curvature, *law, n))


def test_curved_contact_closed_forms_and_two_points_of_pure_rolling():
    """Rolling over the surface z = κy² of a conforming groove (Heathcote slip):

    - linear law κ = B·u, rolling only: F_x = −B·Q·(v_x + ω_y·κ·a²/5) (Σ q_i ȳ_i² → Q a²/5);
    - constant μ with v_x = −ω_y·κ·(s₀a)²: pure rolling at y = ±s₀a, the middle slipping one way and
      the sides the other, F_x = −μQ·(1 − 2·(3/2)(s₀ − s₀³/3)) (the load share inside |y| < s₀a);
    - the twin (independent cross products) to 1e-12 with a spin and a side slip added.
    """
    kappa, wy = 1.0 / (2 * 4e-3), 150.0
    vx = 0.002
    f = _curved(vx, 0.0, (0.0, wy, 0.0), kappa, LINEAR)
    assert f[0] == pytest.approx(-2.0 * Q * (vx + wy * kappa * A**2 / 5), rel=1e-4)
    s0 = 0.5
    f = _curved(-wy * kappa * (s0 * A) ** 2, 0.0, (0.0, wy, 0.0), kappa, CONSTANT, n=2000)
    inside = 1.5 * (s0 - s0**3 / 3)
    assert f[0] == pytest.approx(-0.03 * Q * (1.0 - 2.0 * inside), rel=2e-3)
    omega = (3.0, wy, -5.0)
    got = _curved(0.001, -0.0004, omega, kappa, KRAGELSKII, n=40)
    want = twin.strip_traction_curved(Q, A, 0.001, -0.0004, omega, kappa, lambda u: _mu(KRAGELSKII, u), 40)
    assert np.allclose(got, want, rtol=1e-12, atol=1e-14 * Q * A)
