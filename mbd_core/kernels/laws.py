"""Contact force laws: penalty normal force and slip-dependent friction (scalar kernels).

Normal force, never tensile, δ the penetration (m) and δ̇ its rate (m/s):

``NORMAL_IMPACT`` (the Adams IMPACT function)
    F = k δⁿ + STEP(δ, 0, 0, d_max, c) δ̇ — the damping coefficient ramps from 0 at touch-down to
    c at δ = d_max, so there is no force jump when contact starts.
``NORMAL_HUNT_CROSSLEY`` (Hunt & Crossley, J. Appl. Mech. 42, 1975)
    F = k δⁿ (1 + c δ̇), with c = 3(1 − e)/(2 v₀) for a restitution e at impact speed v₀.

STEP is Adams' cubic blend h0 + (h1 − h0) Δ² (3 − 2Δ), Δ = (x − x0)/(x1 − x0) clipped to [0, 1].

Friction coefficient μ(u) of the slip speed u = |v_slip| ≥ 0 (m/s), parameters p0…p3:

``FRICTION_COULOMB`` — regularised Coulomb (Adams): p0 = μ_static, p1 = μ_dynamic,
    p2 = v_static, p3 = v_dynamic; μ = STEP(u, 0, 0, v_s, μ_s) below v_s, STEP(u, v_s, μ_s, v_d, μ_d)
    between, μ_d above. μ(0) = 0, so a contact at rest carries no force jump.
``FRICTION_DREB_LINEAR`` — κ = B u (p0 = B, s/m) (a traction model of the DREB program, MTI
    1977: *Rolling Element Bearing and Lubricant Technology Program, Part I: Prediction of Torque
    in DMA Bearings*).
``FRICTION_DREB_CONSTANT`` — κ = A (p0 = A) for u > 0 (blended to 0 below p1 = u_0, m/s).
``FRICTION_DREB_FALLING`` — κ = A − B u (p0 = A, p1 = B), not below 0; blended from 0 below
    p2 = u_0 (m/s) when p2 > 0 (as the constant law; 0: none, κ(0⁺) = A).
``FRICTION_KRAGELSKII`` — κ = (A + B u) e^(−C u) + D (p0 = A, p1 = B, p2 = C, p3 = D).
``FRICTION_LIMITING_SHEAR`` — κ = κ_L (1 − e^(−u/u_c)) (p0 = κ_L, p1 = u_c m/s): the traction of a
    film that shears viscously at small slip and at its limiting shear stress τ_L = κ_L·p̄ beyond
    (Bair & Winer's τ/τ_L = 1 − exp(−η γ̇/τ_L) with γ̇ = u/h, so u_c = h τ_L/η); also the mixed
    lubrication law with κ_L the asperity-weighted blend (:mod:`mbd_core.contact.friction`).

The friction force on body 1 opposes the slip velocity v_t of body 1 relative to body 2:
F_t = −μ(|v_t|) F_n v_t/|v_t| (zero at |v_t| = 0).
"""

from __future__ import annotations

import math

from numba import njit

NORMAL_IMPACT = 0
NORMAL_HUNT_CROSSLEY = 1

FRICTION_COULOMB = 0
FRICTION_DREB_LINEAR = 1
FRICTION_DREB_CONSTANT = 2
FRICTION_DREB_FALLING = 3
FRICTION_KRAGELSKII = 4
FRICTION_LIMITING_SHEAR = 5


@njit(cache=True, _nrt=False)
def step(x, x0, h0, x1, h1):
    """Adams STEP: cubic blend from h0 at x ≤ x0 to h1 at x ≥ x1, zero slope at both ends."""
    if x <= x0:
        return h0
    if x >= x1:
        return h1
    d = (x - x0) / (x1 - x0)
    return h0 + (h1 - h0) * d * d * (3.0 - 2.0 * d)


@njit(cache=True, _nrt=False)
def normal_force(law, delta, delta_dot, k, n, c, d_max):
    """Penalty normal force ≥ 0 (N) for penetration delta (m) and its rate delta_dot (m/s)."""
    if delta <= 0.0:
        return 0.0
    return normal_force_elastic(law, k * delta**n, delta, delta_dot, c, d_max)


@njit(cache=True, _nrt=False)
def normal_force_elastic(law, elastic, delta, delta_dot, c, d_max):
    """:func:`normal_force` from its elastic part k δⁿ (N), computed once by the caller (δ > 0)."""
    if law == NORMAL_IMPACT:
        f = elastic + step(delta, 0.0, 0.0, d_max, c) * delta_dot
    else:
        f = elastic * (1.0 + c * delta_dot)
    return f if f > 0.0 else 0.0


@njit(cache=True, _nrt=False)
def friction_coefficient(law, u, p0, p1, p2, p3):
    """Friction (traction) coefficient μ ≥ 0 at slip speed u ≥ 0 (m/s)."""
    if law == FRICTION_COULOMB:
        if u < p2:
            return step(u, 0.0, 0.0, p2, p0)
        if u < p3:
            return step(u, p2, p0, p3, p1)
        return p1
    if law == FRICTION_DREB_LINEAR:
        return p0 * u
    if law == FRICTION_DREB_CONSTANT:
        return step(u, 0.0, 0.0, p1, p0)
    if law == FRICTION_DREB_FALLING:
        if u < p2:
            edge = p0 - p1 * p2
            return step(u, 0.0, 0.0, p2, edge if edge > 0.0 else 0.0)
        mu = p0 - p1 * u
        return mu if mu > 0.0 else 0.0
    if law == FRICTION_LIMITING_SHEAR:
        return p0 * -math.expm1(-u / p1)
    mu = (p0 + p1 * u) * math.exp(-p2 * u) + p3
    return mu if mu > 0.0 else 0.0


@njit(cache=True, _nrt=False)
def step_slope(x, x0, h0, x1, h1):
    """d/dx of :func:`step`."""
    if x <= x0 or x >= x1:
        return 0.0
    d = (x - x0) / (x1 - x0)
    return (h1 - h0) * 6.0 * d * (1.0 - d) / (x1 - x0)


@njit(cache=True, _nrt=False)
def friction_slope(law, u, p0, p1, p2, p3):
    """dμ/du of :func:`friction_coefficient` at slip speed u > 0, s/m (0 where μ is clipped at 0)."""
    if law == FRICTION_COULOMB:
        if u < p2:
            return step_slope(u, 0.0, 0.0, p2, p0)
        if u < p3:
            return step_slope(u, p2, p0, p3, p1)
        return 0.0
    if law == FRICTION_DREB_LINEAR:
        return p0
    if law == FRICTION_DREB_CONSTANT:
        return step_slope(u, 0.0, 0.0, p1, p0)
    if law == FRICTION_DREB_FALLING:
        if u < p2:
            edge = p0 - p1 * p2
            return step_slope(u, 0.0, 0.0, p2, edge if edge > 0.0 else 0.0)
        return -p1 if p0 - p1 * u > 0.0 else 0.0
    if law == FRICTION_LIMITING_SHEAR:
        return p0 / p1 * math.exp(-u / p1)
    mu = (p0 + p1 * u) * math.exp(-p2 * u) + p3
    if mu <= 0.0:
        return 0.0
    return (p1 - p2 * (p0 + p1 * u)) * math.exp(-p2 * u)


@njit(cache=True, _nrt=False)
def friction_force(law, params, fn, v_slip, out):
    """Friction force (3,) N on body 1 into ``out`` for normal force fn and slip velocity (3,)."""
    u = math.sqrt(v_slip[0] ** 2 + v_slip[1] ** 2 + v_slip[2] ** 2)
    if u == 0.0 or fn <= 0.0:
        out[0] = 0.0
        out[1] = 0.0
        out[2] = 0.0
        return
    mu = friction_coefficient(law, u, params[0], params[1], params[2], params[3])
    s = -mu * fn / u
    out[0] = s * v_slip[0]
    out[1] = s * v_slip[1]
    out[2] = s * v_slip[2]

