"""Ball–groove contact geometry on a ring with race deviations (batched kernel).

The groove is the circle of its curvature centres in the ring frame (z the ring axis): radius r_c,
height z_c, groove radius f·D. A ball of diameter D centred at x (ring frame) at angle
θ = atan2(y, x) ∈ [0, 2π) touches the groove when its centre lies farther than f·D − D/2 from the
curvature centre c(θ):

    c(θ) = ((r_c + Δr(θ)) cos θ, (r_c + Δr(θ)) sin θ, z_c + h(θ)),
    δ = |x − c(θ)| − (f·D − D/2),      n = (x − c)/|x − c|,

with h(θ) the raceway's axial undulation and Δr(θ) its radial offset (thermal misalignment),
tabulated on a uniform periodic grid of θ ∈ [0, 2π) and interpolated linearly (a table of length
1 is a constant). n is the unit normal from the groove centre towards the ball centre: the
contact force on the ball is −F n, on the ring +F n at the contact point x − (D/2) n.
The contact angle is atan2(n_z, n_r) with n_r the radial component of n.
"""

from __future__ import annotations

import math

from numba import njit

TWO_PI = 2.0 * math.pi


@njit(cache=True, _nrt=False)
def periodic_lookup(table, theta):
    """Linear interpolation of a uniform periodic table over [0, 2π) at θ ∈ [0, 2π)."""
    n = table.shape[0]
    if n == 1:
        return table[0]
    s = theta / TWO_PI * n
    i0 = int(math.floor(s))
    w = s - i0
    i0 = i0 % n
    i1 = (i0 + 1) % n
    return (1.0 - w) * table[i0] + w * table[i1]


@njit(cache=True, _nrt=False)
def periodic_lookup_range(table, start, stop, theta):
    """:func:`periodic_lookup` on the table ``table[start:stop]`` (no view is made)."""
    n = stop - start
    if n == 1:
        return table[start]
    s = theta / TWO_PI * n
    i0 = int(math.floor(s))
    w = s - i0
    i0 = i0 % n
    i1 = (i0 + 1) % n
    return (1.0 - w) * table[start + i0] + w * table[start + i1]


@njit(cache=True, _nrt=False)
def groove_point(x0, x1, x2, r_c, z_c, clearance_radius, h_table, dr_table):
    """(θ, δ, n_x, n_y, n_z) of one ball centred at (x0, x1, x2) in the ring frame (see module doc)."""
    return groove_point_in(x0, x1, x2, r_c, z_c, clearance_radius, h_table, 0, h_table.shape[0],
                           dr_table, 0, dr_table.shape[0])


@njit(cache=True, _nrt=False)
def groove_point_in(x0, x1, x2, r_c, z_c, clearance_radius, h_all, h0, h1, dr_all, dr0, dr1):
    """:func:`groove_point` with the tables given as ranges [h0, h1), [dr0, dr1) of larger arrays."""
    th = math.atan2(x1, x0)
    if th < 0.0:
        th += TWO_PI
    if th >= TWO_PI:
        th -= TWO_PI
    rho = math.sqrt(x0 * x0 + x1 * x1)  # cos θ = x0/ρ, sin θ = x1/ρ
    cs, sn = (x0 / rho, x1 / rho) if rho > 0.0 else (1.0, 0.0)
    r = r_c + periodic_lookup_range(dr_all, dr0, dr1, th)
    dx = x0 - r * cs
    dy = x1 - r * sn
    dz = x2 - (z_c + periodic_lookup_range(h_all, h0, h1, th))
    d = math.sqrt(dx * dx + dy * dy + dz * dz)
    if d > 0.0:
        return th, d - clearance_radius, dx / d, dy / d, dz / d
    return th, d - clearance_radius, 0.0, 0.0, 0.0


@njit(cache=True, _nrt=False)
def ball_groove_contacts(x, r_c, z_c, clearance_radius, h_table, dr_table, out_theta, out_delta, out_normal):
    """Penetration and normal of balls in a groove.

    Parameters
    ----------
    x : (n, 3) float64, m
        Ball centres in the ring frame.
    r_c, z_c : float, m
        Radius and height of the groove's curvature-centre circle.
    clearance_radius : float, m
        f·D − D/2: distance from the curvature centre at which a ball touches.
    h_table, dr_table : (k,) float64, m
        Axial undulation h(θ) and radial offset Δr(θ) on a uniform grid over [0, 2π).
    out_theta : (n,) float64, rad — ball angle in [0, 2π)
    out_delta : (n,) float64, m — penetration (negative: gap)
    out_normal : (n, 3) float64 — unit normal, groove centre → ball centre (0 if undefined)
    """
    for i in range(x.shape[0]):
        th, delta, nx, ny, nz = groove_point(
            x[i, 0], x[i, 1], x[i, 2], r_c, z_c, clearance_radius, h_table, dr_table
        )
        out_theta[i] = th
        out_delta[i] = delta
        out_normal[i, 0] = nx
        out_normal[i, 1] = ny
        out_normal[i, 2] = nz
