"""Geometry of the contacts between rolling elements and their neighbours (scalar kernels).

Every function works in one frame (the caller picks it) and returns the penetration δ (m,
negative: gap), the unit normal m of the force on the *element* and the contact point p (m).
Penalty contacts carry force only for δ > 0.

Ball–ball (spacer balls), spheres of radii r_a, r_b centred at x_a, x_b:
    δ = r_a + r_b − |x_a − x_b|,   m = (x_a − x_b)/|x_a − x_b|,   p = x_a − r_a m.

Roller end–rib. The roller (centre c, unit axis a, radius r, length L) has a flat end at
s = σ L/2 (σ = ±1) whose rim is rounded with edge radius r_e: a torus with centre circle of
radius ρ = r − r_e about e = c + σ (L/2 − r_e) a. The rib is a surface of the raceway kinds of
:mod:`.roller_slices` (plane z = Z facing ±z, or cylinder of radius R). With d the direction into
the rib surface and u the unit projection of d normal to the axis (0 when the end face is parallel
to the rib), the deepest point of the torus is q = e + ρ u + r_e d, and δ is the depth of q behind
the rib surface, m = −d, p = q. Stiffness: a sphere of radius r_e on a plane (Hertz), by default.

Element–cage pocket. Pocket k of a cage sits at angle φ on radius r_p, height z_p (cage frame):
centre P = (r_p cos φ, r_p sin φ, z_p), radial e_r = (cos φ, sin φ, 0), circumferential
e_t = (−sin φ, cos φ, 0); c_p is the clearance (pocket half-width minus element radius).
    ``POCKET_CYLINDER`` (ball in a radial cylindrical hole): w = x − P with its e_r part removed,
        δ = |w| − c_p, m = −w/|w|, p = x − r m.
    ``POCKET_SLOT`` (roller between two flat faces normal to e_t), evaluated at the roller end
        points x_s = c + s a: u = (x_s − P)·e_t, δ = |u| − c_p, m = −sign(u) e_t, p = x_s − r m.
"""

from __future__ import annotations

import math

from numba import njit

from .roller_slices import RACEWAY_INNER_CYLINDER, RACEWAY_OUTER_CYLINDER, RACEWAY_PLANE_UP

POCKET_CYLINDER = 0
POCKET_SLOT = 1


@njit(cache=True, _nrt=False)
def ball_ball(xa, xb, ra, rb):
    """(δ, m_x, m_y, m_z, p_x, p_y, p_z) of two spheres; m on sphere a, from b towards a."""
    dx, dy, dz = xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]
    d = math.sqrt(dx * dx + dy * dy + dz * dz)
    if d == 0.0:
        return -math.inf, 0.0, 0.0, 0.0, xa[0], xa[1], xa[2]
    mx, my, mz = dx / d, dy / d, dz / d
    return ra + rb - d, mx, my, mz, xa[0] - ra * mx, xa[1] - ra * my, xa[2] - ra * mz


@njit(cache=True, _nrt=False)
def _into_surface(kind, x, y):
    """Unit direction into a rib/raceway surface of the given kind at (x, y, ·)."""
    if kind == RACEWAY_INNER_CYLINDER or kind == RACEWAY_OUTER_CYLINDER:
        r = math.sqrt(x * x + y * y)
        sign = -1.0 if kind == RACEWAY_INNER_CYLINDER else 1.0
        if r == 0.0:
            return sign, 0.0, 0.0
        return sign * x / r, sign * y / r, 0.0
    return 0.0, 0.0, (-1.0 if kind == RACEWAY_PLANE_UP else 1.0)


@njit(cache=True, _nrt=False)
def _depth(kind, value, q):
    """Depth (m) of point q behind a surface of the given kind and radius/height ``value``."""
    if kind == RACEWAY_INNER_CYLINDER:
        return value - math.sqrt(q[0] * q[0] + q[1] * q[1])
    if kind == RACEWAY_OUTER_CYLINDER:
        return math.sqrt(q[0] * q[0] + q[1] * q[1]) - value
    if kind == RACEWAY_PLANE_UP:
        return value - q[2]
    return q[2] - value


@njit(cache=True, _nrt=False)
def roller_end(center, axis, radius, length, end_sign, edge_radius, kind, value, out_point):
    """(δ, m_x, m_y, m_z) of a roller end against a rib; the contact point goes to ``out_point`` (3,)."""
    h = end_sign * (0.5 * length - edge_radius)
    ex, ey, ez = center[0] + h * axis[0], center[1] + h * axis[1], center[2] + h * axis[2]
    dx, dy, dz = _into_surface(kind, ex, ey)
    dot = dx * axis[0] + dy * axis[1] + dz * axis[2]
    ux, uy, uz = dx - dot * axis[0], dy - dot * axis[1], dz - dot * axis[2]
    nu = math.sqrt(ux * ux + uy * uy + uz * uz)
    rho = radius - edge_radius
    if nu > 1e-12:
        ex += rho * ux / nu
        ey += rho * uy / nu
        ez += rho * uz / nu
    dx, dy, dz = _into_surface(kind, ex, ey)
    out_point[0] = ex + edge_radius * dx
    out_point[1] = ey + edge_radius * dy
    out_point[2] = ez + edge_radius * dz
    return _depth(kind, value, out_point), -dx, -dy, -dz


@njit(cache=True, _nrt=False)
def pocket_cylinder(x, radius, angle, r_p, z_p, clearance):
    """(δ, m_x, m_y, m_z, p_x, p_y, p_z) of a ball centred at x (cage frame) in a cylindrical pocket."""
    c, s = math.cos(angle), math.sin(angle)
    wx, wy, wz = x[0] - r_p * c, x[1] - r_p * s, x[2] - z_p
    radial = wx * c + wy * s
    wx -= radial * c
    wy -= radial * s
    d = math.sqrt(wx * wx + wy * wy + wz * wz)
    if d == 0.0:
        return -clearance, 0.0, 0.0, 0.0, x[0], x[1], x[2]
    mx, my, mz = -wx / d, -wy / d, -wz / d
    return d - clearance, mx, my, mz, x[0] - radius * mx, x[1] - radius * my, x[2] - radius * mz


@njit(cache=True, _nrt=False)
def pocket_slot(xs, radius, angle, r_p, z_p, clearance):
    """(δ, m_x, m_y, m_z, p_x, p_y, p_z) of a roller end point xs (cage frame) in a slot pocket."""
    c, s = math.cos(angle), math.sin(angle)
    u = -(xs[0] - r_p * c) * s + (xs[1] - r_p * s) * c
    sign = 1.0 if u >= 0.0 else -1.0
    mx, my = sign * s, -sign * c
    return abs(u) - clearance, mx, my, 0.0, xs[0] - radius * mx, xs[1] - radius * my, xs[2]
