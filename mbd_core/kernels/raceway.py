"""Deformation of a flexible raceway at a contact angle, and the modal force of a contact there.

A modal ring's raceway is sampled at angles θ_j (:mod:`cms_reduction.sampling`): D_j (3, m) the
mode displacements and Ω_j (3, m) the small mode rotations at the raceway points, per unit modal
coordinate. A contact at angle θ between θ_i0 and θ_i1 with linear weights (w0, w1) sees

    u(θ) = (w0 D_i0 + w1 D_i1) η,     u̇(θ) = (w0 D_i0 + w1 D_i1) η̇,

and its force f there does the virtual work f·δu, so its modal force is the transpose of the same
interpolation, Q += (w0 D_i0 + w1 D_i1)ᵀ f — energy is neither created nor lost by the projection.
The same two functions serve rotations (Ω) and moments. The numpy versions in
:mod:`cms_reduction.sampling` are the reference (``interp_index``, ``raceway_displacement``,
``raceway_modal_force``).
"""

from __future__ import annotations

import math

from numba import njit

TWO_PI = 2.0 * math.pi


@njit(cache=True, _nrt=False)
def interp_index(theta_grid, theta, periodic):
    """Neighbouring sample indices and weights (i0, i1, w0, w1) of angle θ (rad) on a sample grid.

    A periodic grid (uniform, θ_j = θ_0 + 2πj/n) wraps at 2π; otherwise θ is clamped to the
    sampled range of an ascending grid.
    """
    n = theta_grid.shape[0]
    if periodic:
        t = theta % TWO_PI
        s = (t - theta_grid[0]) / (TWO_PI / n)
        f = math.floor(s)
        i0 = int(f) % n
        w1 = s - f
        return i0, (i0 + 1) % n, 1.0 - w1, w1
    t = min(max(theta, theta_grid[0]), theta_grid[n - 1])
    lo, hi = 0, n - 1
    while hi - lo > 1:  # largest i0 with θ_i0 ≤ t, at most n − 2
        mid = (lo + hi) // 2
        if theta_grid[mid] <= t:
            lo = mid
        else:
            hi = mid
    w1 = (t - theta_grid[lo]) / (theta_grid[lo + 1] - theta_grid[lo])
    return lo, lo + 1, 1.0 - w1, w1


@njit(cache=True, _nrt=False)
def raceway_field(table, i0, i1, w0, w1, eta):
    """(u_x, u_y, u_z) = (w0 T_i0 + w1 T_i1) η for a table T (n, 3, m) and coordinates η (m,)."""
    ux = uy = uz = 0.0
    for k in range(eta.shape[0]):
        e = eta[k]
        ux += (w0 * table[i0, 0, k] + w1 * table[i1, 0, k]) * e
        uy += (w0 * table[i0, 1, k] + w1 * table[i1, 1, k]) * e
        uz += (w0 * table[i0, 2, k] + w1 * table[i1, 2, k]) * e
    return ux, uy, uz


@njit(cache=True, _nrt=False)
def add_modal_force(table, i0, i1, w0, w1, fx, fy, fz, out):
    """out (m,) += (w0 T_i0 + w1 T_i1)ᵀ f: the modal force of a force (or moment) f at the angle."""
    for k in range(out.shape[0]):
        out[k] += ((w0 * table[i0, 0, k] + w1 * table[i1, 0, k]) * fx
                   + (w0 * table[i0, 1, k] + w1 * table[i1, 1, k]) * fy
                   + (w0 * table[i0, 2, k] + w1 * table[i1, 2, k]) * fz)
