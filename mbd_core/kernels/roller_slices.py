"""Roller–raceway slice geometry: penetration of each slice of a tilted or skewed roller.

A roller of radius D/2 and effective length L, centre c and unit axis a (ring frame, z the ring
axis), is cut into n_s slices of width L/n_s centred at s_k = −L/2 + (k + ½) L/n_s (ISO/TS 16281
slicing). Slice k is a circle of radius ρ_k = D/2 − drop_k (drop_k: the profile's crown or
logarithmic drop at s_k) about p_k = c + s_k a, in the plane normal to a. Its deepest point
towards the raceway is q_k = p_k + ρ_k d/|d|, with d the raceway's inward direction projected
normal to the axis, and the penetration is the depth of q_k behind the raceway surface:

``RACEWAY_INNER_CYLINDER`` (radius R, roller outside it, e.g. the inner ring's radial raceway)
    d = −e_r, δ = R − r(q), normal on the roller +e_r(q);
``RACEWAY_OUTER_CYLINDER`` (roller inside it)
    d = +e_r, δ = r(q) − R, normal −e_r(q);
``RACEWAY_PLANE_UP`` (plane z = Z below the roller, facing +z)
    d = −ẑ, δ = Z − q_z, normal +ẑ;
``RACEWAY_PLANE_DOWN`` (plane z = Z above the roller, facing −z)
    d = +ẑ, δ = q_z − Z, normal −ẑ.

The normal is the direction of the force the raceway puts on the roller. Slice forces follow
from :func:`mbd_core.kernels.laws.normal_force` with the slice stiffness c_L/n_s and n = 10/9.
"""

from __future__ import annotations

import math

from numba import njit

RACEWAY_INNER_CYLINDER = 0
RACEWAY_OUTER_CYLINDER = 1
RACEWAY_PLANE_UP = 2
RACEWAY_PLANE_DOWN = 3


@njit(cache=True, _nrt=False)
def roller_slices(center, axis, length, radius, drop, raceway, value, out_delta, out_point, out_normal):
    """Penetration (n_s,) m, deepest points (n_s, 3) m and normals (n_s, 3) of the slices of one roller.

    ``drop`` (n_s,) m is the profile drop of each slice; ``value`` the raceway radius R or height Z, m.
    """
    n_s = drop.shape[0]
    for k in range(n_s):
        s = -0.5 * length + (k + 0.5) * length / n_s
        px = center[0] + s * axis[0]
        py = center[1] + s * axis[1]
        pz = center[2] + s * axis[2]
        if raceway <= RACEWAY_OUTER_CYLINDER:
            r = math.sqrt(px * px + py * py)
            sign = -1.0 if raceway == RACEWAY_INNER_CYLINDER else 1.0
            dx, dy, dz = sign * px / r, sign * py / r, 0.0
        else:
            dx, dy, dz = 0.0, 0.0, (-1.0 if raceway == RACEWAY_PLANE_UP else 1.0)
        dot = dx * axis[0] + dy * axis[1] + dz * axis[2]
        dx -= dot * axis[0]
        dy -= dot * axis[1]
        dz -= dot * axis[2]
        nd = math.sqrt(dx * dx + dy * dy + dz * dz)
        rho = radius - drop[k]
        qx, qy, qz = px + rho * dx / nd, py + rho * dy / nd, pz + rho * dz / nd
        out_point[k, 0], out_point[k, 1], out_point[k, 2] = qx, qy, qz
        if raceway <= RACEWAY_OUTER_CYLINDER:
            rq = math.sqrt(qx * qx + qy * qy)
            ex, ey = qx / rq, qy / rq
            if raceway == RACEWAY_INNER_CYLINDER:
                out_delta[k] = value - rq
                out_normal[k, 0], out_normal[k, 1], out_normal[k, 2] = ex, ey, 0.0
            else:
                out_delta[k] = rq - value
                out_normal[k, 0], out_normal[k, 1], out_normal[k, 2] = -ex, -ey, 0.0
        elif raceway == RACEWAY_PLANE_UP:
            out_delta[k] = value - qz
            out_normal[k, 0], out_normal[k, 1], out_normal[k, 2] = 0.0, 0.0, 1.0
        else:
            out_delta[k] = qz - value
            out_normal[k, 0], out_normal[k, 1], out_normal[k, 2] = 0.0, 0.0, -1.0


# -- raceways of a modal ring sampled on a (θ, s) grid ---------------------------------------------------
# A straight raceway of a modal ring is sampled on n_c circles (cms_reduction.sampling.sample_across): circle
# j at the coordinate s_j across the raceway (s = z on a cylinder, s = r on a plane; ascending), each with
# the same n_θ angles. A point at (θ, s) takes the sample fields bilinearly: linear in θ within each circle
# (mbd_core.kernels.raceway.interp_index), linear in s between the two circles around it, and those of the
# end circle beyond the first or last circle (the lever p − p_s to the held sample point then carries the
# section's small rotation on, so a rigid tilt of the section is still followed there).


@njit(cache=True, inline="always", _nrt=False)
def surface_coordinate(raceway, x, y, z):
    """s of a ring-frame point on a surface of the given kind: z on a cylinder, r on a plane (m)."""
    if raceway <= RACEWAY_OUTER_CYLINDER:
        return z
    return math.sqrt(x * x + y * y)


@njit(cache=True, _nrt=False)
def circle_index(circle_s, s):
    """Neighbouring circles (j0, j1) and linear weights (v0, v1) of coordinate s on the ascending circle
    coordinates ``circle_s`` (n_c,) m; the end circle alone (j0 = j1, v1 = 0) beyond the ends."""
    n = circle_s.shape[0]
    if s <= circle_s[0]:
        return 0, 0, 1.0, 0.0
    if s >= circle_s[n - 1]:
        return n - 1, n - 1, 1.0, 0.0
    j = 0
    while circle_s[j + 1] < s:
        j += 1
    v1 = (s - circle_s[j]) / (circle_s[j + 1] - circle_s[j])
    return j, j + 1, 1.0 - v1, v1
