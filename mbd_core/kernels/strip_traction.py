"""Traction of an elliptical contact from the slip distribution across it (strip model).

The Hertz ellipse (semi-axes a along y, the major axis across the rolling direction, and b along
x, the rolling direction) is cut into ``n`` strips along its major axis, as in the DREB program
(README, Sources) and its successors. Along a strip the slip is taken as that of its centre line.
The contact surface of a ball in a groove is curved across the major axis: its points lie at
(0, y, z(y)), z = κ·y² towards body 1 (κ = 1/(2R_d), R_d the radius of the deformed surface,
2·r_groove·r_ball/(r_groove + r_ball) for equal elastic constants: Harris & Kotzalas, *Rolling
Bearing Analysis*, the "Heathcote" slip of conforming contacts). Body 1 slips relative to body 2
there with the rigid-body field v + ω × (0, y, z):

    v(y) = (v_x − ω_z·y + ω_y·z(y),  v_y − ω_x·z(y)),

v_x, v_y the sliding velocity at the contact centre, ω the relative angular velocity (ω_z the spin
about the contact normal z = x × y, ω_y the rolling about the major axis). Spin alone gives one
point of pure rolling; the rolling term over the curved surface gives the two of a conforming
groove. The Hertz pressure p0·√(1 − x²/a'² − y²/a²) integrated over x gives the load
per unit length q(y) = (3Q / 4a)·(1 − y²/a²); each strip carries its exact share

    Q_i = Q·(S(y_i+1) − S(y_i)),   S(y) = ¾·(y/a − y³/(3a³)) + ½,

at its load centroid ȳ_i, where the traction is −μ(|v(ȳ_i)|)·Q_i·v/|v| with μ any law of
:mod:`mbd_core.kernels.laws`. The sums give the tangential force on body 1 and its moment about
the contact centre, the levers (0, ȳ_i, z(ȳ_i)): the spin torque M_z = −Σ ȳ_i·F_x,i and the small
M_x, M_y of the curved surface. The centre-point law −μ(|v(0)|)·Q·v̂(0) is the limit of a narrow
ellipse (a → 0) or of no spin and a flat contact.

Closed forms of the strip model on a flat contact (tests): constant μ and pure spin,
M = −sign(ω)·(3/8)·μ·Q·a; linear law μ = B·u, F_x = −B·Q·v_x and M = −B·ω·Q·a²/5; on a curved
one with the linear law and rolling only, F_x = −B·Q·(v_x + ω_y·κ·a²/5).
"""

from __future__ import annotations

import math

from numba import njit

from .laws import friction_coefficient

__all__ = ["strip_traction", "strip_traction_forces", "strip_load_share"]


@njit(cache=True, _nrt=False)
def strip_load_share(s):
    """Share of the contact load on the part y < s·a of the ellipse (−1 ≤ s ≤ 1)."""
    return 0.75 * (s - s * s * s / 3.0) + 0.5


@njit(cache=True, inline="always", _nrt=False)
def strip_traction_forces(load_N, a_m, slip_x, slip_y, omega_x, omega_y, omega_z, curvature_per_m, law, p0, p1, p2,
                          p3, n_strips, each=None):
    """(F_x, F_y N, M_x, M_y, M_z N·m) on body 1 from ``n_strips`` strips over a curved contact surface
    (module docstring); ω the relative angular velocity of body 1 in the contact frame, rad/s. ``each``
    (≥ n_strips, 5), when given: per strip (ȳ, z(ȳ) m, Q_i N, |v| m/s, secant μQ_i/|v| N·s/m; 0 where it
    does not slip), for the damping matrices of implicit friction (:mod:`.friction_damping`)."""
    fx, fy, mx, my, mz = 0.0, 0.0, 0.0, 0.0, 0.0
    if load_N <= 0.0:
        return fx, fy, mx, my, mz
    s0 = -1.0
    w0 = strip_load_share(-1.0)
    for i in range(n_strips):
        s1 = -1.0 + 2.0 * (i + 1) / n_strips
        w1 = strip_load_share(s1)
        q = load_N * (w1 - w0)
        # load centroid: ∫ s(1 − s²) ds / ∫ (1 − s²) ds over the strip, times a
        m1 = 0.5 * (s1 * s1 - s0 * s0) - 0.25 * (s1 ** 4 - s0 ** 4)
        m0 = (s1 - s0) - (s1 ** 3 - s0 ** 3) / 3.0
        y = a_m * m1 / m0
        z = curvature_per_m * y * y
        vx = slip_x - omega_z * y + omega_y * z
        vy = slip_y - omega_x * z
        u = math.sqrt(vx * vx + vy * vy)
        f = 0.0
        if u > 0.0:
            f = friction_coefficient(law, u, p0, p1, p2, p3) * q / u
            fx -= f * vx
            fy -= f * vy
            # lever (0, y, z) × (−f vx, −f vy, 0)
            mx += z * f * vy
            my -= z * f * vx
            mz += y * f * vx
        if each is not None:
            each[i, 0], each[i, 1], each[i, 2], each[i, 3], each[i, 4] = y, z, q, u, f
        s0, w0 = s1, w1
    return fx, fy, mx, my, mz


@njit(cache=True, _nrt=False)
def strip_traction(load_N, a_m, slip_x, slip_y, spin_rad_s, law, p0, p1, p2, p3, n_strips, out):
    """F_x, F_y (N) and M_z (N·m) on body 1 into ``out`` (3,) over a flat contact with spin only."""
    fx, fy, _, _, mz = strip_traction_forces(load_N, a_m, slip_x, slip_y, 0.0, 0.0, spin_rad_s, 0.0, law, p0, p1,
                                             p2, p3, n_strips)
    out[0], out[1], out[2] = fx, fy, mz
