"""Strip traction in the multibody contact of a ball on a groove (``ContactLaw(strips=...)``).

References:
- Spin of a ball on its contact (pivoting): with a constant traction coefficient μ over the Hertz
  ellipse, the moment about the normal is M = (3/8)·μ·Q·a against the spin (the load per unit
  length across the major axis q(y) = (3Q/4a)(1 − y²/a²) times the lever |y|, integrated:
  2·∫0^a y·(3Q/4a)(1 − y²/a²) dy = 3Qa/8). The strips give it exactly for an even strip count
  (no strip straddles y = 0, each strip's load acts at its load centroid).
- A free ball spun about the contact normal then slows at the constant rate M/I, I = (2/5)m r²
  (solid sphere), until it stops.
- The kernel's force stage against its numpy twin with strips: tests/test_kernels_multibody.py.
- Implicit friction with strips: each slipping strip is a damper c_i = μQ_i/|v_i| at its own point, so
  with the linear law μ = B·u (whose secant is its slope) the assembled damping matrix is the exact
  Jacobian −∂(F, M)/∂(v, ω) of the strip traction: checked against central differences of the force
  stage.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mbd_core.contact.friction import DrebConstant, DrebLinear
from mbd_core.kernels import forces as FK
from mbd_core.multibody import ContactLaw, Driven, Fixed, Free, ModelBuilder, evaluate_forces, simulate, stable_timestep
from mbd_core.multibody.builder import quat_z_to
from mbd_core.multibody.model import make_work
from mbd_core.multibody.parts import StripTraction
from tests.reference.force_jacobian import force_velocity_jacobian

R_BALL, CONF, R_PITCH = 5e-3, 0.52, 0.05
K_HERTZ = 1e10                      # N/m^1.5
A_COEF = 2.5e-5                     # semi-major axis at 1 N, m/N^(1/3)
MU = 0.06
LOAD_N = 200.0
MASS = 7850 * 4 / 3 * math.pi * R_BALL**3


def _scene(motion, strips=10, omega=300.0, implicit=False, friction=DrebConstant(MU, 1e-3), velocity=(0.0, 0.0, 0.0),
           omega_body=None):
    """A ball pressed by LOAD_N radially outwards into a fixed outer groove at contact angle 0, spun
    about the contact normal (+x) at ``omega`` (or with the body-frame angular velocity ``omega_body``);
    it starts at the static approach of the load."""
    b = ModelBuilder(implicit_friction=implicit)
    ring = b.add_body("ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    delta0 = (LOAD_N / K_HERTZ) ** (2 / 3)
    groove = b.add_groove(ring, R_PITCH - (CONF * 2 * R_BALL - R_BALL), 0.0, CONF * 2 * R_BALL)
    inertia = 0.4 * MASS * R_BALL**2
    ball = b.add_body("ball", MASS, (inertia,) * 3, position_m=(R_PITCH + delta0, 0.0, 0.0),
                      orientation=quat_z_to((1.0, 0.0, 0.0)), velocity_m_s=velocity,
                      omega_rad_s=omega_body or (0.0, 0.0, omega), motion=motion)
    law = ContactLaw(K_HERTZ, 1.5, 0.0, 1e-6, "impact", friction, strips=StripTraction(strips, A_COEF) if strips else None)
    b.add_ball_groove(ball, ring, groove, R_BALL, law)
    b.add_force(ball, (LOAD_N, 0.0, 0.0))
    return b.finalize(), inertia


@pytest.mark.parametrize("strips", [2, 10, 40])
def test_spin_moment_is_three_eighths_mu_q_a(strips):
    (model, state), _ = _scene(Driven(300.0), strips=strips)
    w = make_work(model)
    assert FK.compute_forces(model.arrays, 0.0, state.q, state.v, state.eta, state.eta_dot, w)[0] == FK.STATUS_OK
    fn = w.contact_fn[0]
    assert fn == pytest.approx(LOAD_N, rel=1e-9)
    a = A_COEF * fn ** (1 / 3)
    # moment on the ball about the contact normal (+x), against its spin (+x): −(3/8)μQa
    assert w.body_t[1, 0] == pytest.approx(-3 / 8 * MU * fn * a, rel=1e-12)
    assert np.abs(w.body_t[1, 1:]).max() < 1e-12 * MU * fn * a
    assert w.contact_ft[0] < 1e-12 * MU * fn        # the strips' forces cancel in pure spin


def test_centre_point_law_has_no_spin_moment():
    (model, state), _ = _scene(Driven(300.0), strips=0)
    w = make_work(model)
    FK.compute_forces(model.arrays, 0.0, state.q, state.v, state.eta, state.eta_dot, w)
    assert np.abs(w.body_t[1]).max() < 1e-12


def test_free_ball_spin_decays_at_the_pivoting_rate():
    """The spin falls linearly at (3/8)μQa/I (measured within 1 % at 5 ms, before it stops)."""
    (model, state), inertia = _scene(Free(), strips=10)
    rate = 3 / 8 * MU * LOAD_N * A_COEF * LOAD_N ** (1 / 3) / inertia
    run = simulate(model, state, 5e-3, record_every=200)
    spin = run["v"][:, 1, 5]                              # body z = the contact normal
    t = run["t"]
    expected = 300.0 - rate * t
    assert expected[-1] > 50.0                            # still spinning
    assert spin[-1] == pytest.approx(expected[-1], rel=1e-2)
    assert np.max(np.abs(spin - expected)) < 1e-2 * 300.0


def test_implicit_friction_damping_is_the_jacobian_of_linear_strip_traction():
    """A free ball sliding, rolling and spinning in the groove (every strip slips, the curved surface
    adds M_x, M_y), linear law μ = 2·u: the damping matrix of its implicit friction (world (v, ω)) against
    −∂(F, M)/∂(v, ω_world) by central differences of the force stage (no normal damping, so the normal
    force does not depend on the velocity). Linear in the velocities: agreement to 1e-9 of the largest
    entry (the differences' round-off; measured 1.7e-12)."""
    (model, state), _ = _scene(Free(), strips=10, implicit=True, friction=DrebLinear(2.0),
                               velocity=(0.0, 0.02, -0.01), omega_body=(3.0, -5.0, 40.0))
    i = 1
    w = evaluate_forces(model, state)
    C = w.fric_c[i].copy()
    assert w.contact_fn[0] == pytest.approx(LOAD_N, rel=1e-9) and w.fric_n[0] == 0   # (noted, then gathered)
    jac = force_velocity_jacobian(model, state, i, 1e-5)
    assert np.abs(jac).max() > 1.0                            # the friction does act
    print(f"|C − J| / max|J| = {np.abs(C - jac).max() / np.abs(jac).max():.2g}")
    np.testing.assert_allclose(C, jac, rtol=0, atol=1e-9 * np.abs(jac).max())


def test_free_ball_spin_decays_at_the_pivoting_rate_with_implicit_friction():
    """The pivoting ball of test_free_ball_spin_decays_at_the_pivoting_rate with its friction implicit:
    the automatic step is the contact's, more than 20× the explicit friction's, and the spin still falls
    at (3/8)μQa/I within 1 % (measured: 1.34e-5 s against 3.48e-8 s; 220.772 against 220.723 rad/s at 5 ms,
    2.2e-4)."""
    (model, state), inertia = _scene(Free(), strips=10, implicit=True)
    (explicit, _), _ = _scene(Free(), strips=10)
    h_implicit = stable_timestep(model, state).timestep_s
    h_explicit = stable_timestep(explicit, state).timestep_s
    assert h_implicit > 20 * h_explicit
    rate = 3 / 8 * MU * LOAD_N * A_COEF * LOAD_N ** (1 / 3) / inertia
    run = simulate(model, state, 5e-3, record_every=10)
    spin, t = run["v"][:, 1, 5], run["t"]
    expected = 300.0 - rate * t
    assert expected[-1] > 50.0
    print(f"steps {h_implicit:.3g} s implicit, {h_explicit:.3g} s explicit; spin {spin[-1]:.3f} against {expected[-1]:.3f} rad/s")
    assert spin[-1] == pytest.approx(expected[-1], rel=1e-2)
    assert np.max(np.abs(spin - expected)) < 1e-2 * 300.0
