"""Traction of an elliptical contact from the slip distribution across it (strip model).

The Hertz ellipse (semi-axes a along y, the major axis across the rolling direction, and b along
x, the rolling direction) is cut into ``n`` strips along its major axis, as in the DREB program
(README, Sources) and its successors. Along a strip the slip is taken as that of its centre line:
body 1 slips relative to body 2 at (0, y) with

    v(y) = (v_x − ω·y, v_y),

v_x, v_y the sliding velocity at the contact centre and ω the relative spin about the contact
normal (z = x × y). The Hertz pressure p0·√(1 − x²/a'² − y²/a²) integrated over x gives the load
per unit length q(y) = (3Q / 4a)·(1 − y²/a²); each strip carries its exact share

    Q_i = Q·(S(y_i+1) − S(y_i)),   S(y) = ¾·(y/a − y³/(3a³)) + ½,

at its load centroid ȳ_i, where the traction is −μ(|v(ȳ_i)|)·Q_i·v/|v| with μ any law of
:mod:`mbd_core.kernels.laws`. The sums give the tangential force on body 1 and its moment about
the normal (spin torque) M = −Σ ȳ_i·F_x,i. Points of pure rolling (v = 0) lie where v_x = ω·y
(with v_y = 0); the centre-point law −μ(|v(0)|)·Q·v̂(0) is the limit of a narrow ellipse (a → 0)
or of no spin.

Closed forms of the strip model (tests): constant μ and pure spin, M = −sign(ω)·(3/8)·μ·Q·a;
linear law μ = B·u, F_x = −B·Q·v_x and M = −B·ω·Q·a²/5.
"""

from __future__ import annotations

import math

from numba import njit

from .laws import friction_coefficient

__all__ = ["strip_traction", "strip_traction_forces", "strip_load_share"]


@njit(cache=True)
def strip_load_share(s):
    """Share of the contact load on the part y < s·a of the ellipse (−1 ≤ s ≤ 1)."""
    return 0.75 * (s - s * s * s / 3.0) + 0.5


@njit(cache=True, inline="always")
def strip_traction_forces(load_N, a_m, slip_x, slip_y, spin_rad_s, law, p0, p1, p2, p3, n_strips):
    """(F_x N, F_y N, M_z N·m) on body 1 from ``n_strips`` strips (module docstring)."""
    fx, fy, mz = 0.0, 0.0, 0.0
    if load_N <= 0.0:
        return fx, fy, mz
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
        vx = slip_x - spin_rad_s * y
        u = math.sqrt(vx * vx + slip_y * slip_y)
        if u > 0.0:
            f = friction_coefficient(law, u, p0, p1, p2, p3) * q / u
            fx -= f * vx
            fy -= f * slip_y
            mz += y * f * vx
        s0, w0 = s1, w1
    return fx, fy, mz


@njit(cache=True)
def strip_traction(load_N, a_m, slip_x, slip_y, spin_rad_s, law, p0, p1, p2, p3, n_strips, out):
    """:func:`strip_traction_forces` into ``out`` (3,): F_x, F_y (N) and M_z (N·m) on body 1."""
    out[0], out[1], out[2] = strip_traction_forces(load_N, a_m, slip_x, slip_y, spin_rad_s, law, p0, p1, p2, p3,
                                                   n_strips)
