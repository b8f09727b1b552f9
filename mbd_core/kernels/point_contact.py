"""One contact point's normal and friction force (the law of :mod:`.laws` at a point with a normal),
applied to both bodies, and the per-contact outputs of the work arrays."""

from __future__ import annotations

import math

from numba import njit

from .body_frames import point_velocity, _add_force
from .laws import friction_coefficient, normal_force_elastic


# Hot per-contact functions take plain arrays and scalars, never the model namedtuple: passing a
# tuple of ~50 arrays to a function that is not inlined costs about 0.5 µs per call, and so does
# reading a field of m or w inside an inlined per-contact function (hoist such reads out of the
# loops); every array argument of a call costs reference counting (~10 ns), so the small helpers
# that take arrays are inlined by numba (inline="always").
@njit(cache=True, inline="always", _nrt=False)
def point_force(law, k, n_exp, damping, d_max, fric, p0, p1, p2, p3, delta, mx, my, mz, rx, ry, rz):
    """Force on body a of one contact point with penetration δ > 0, unit normal m (on a) and
    relative velocity r = v_a(p) − v_b(p) of the two surfaces there.

    Returns (F_n N, |v_t| m/s, |F_t| N, elastic energy J, f_x, f_y, f_z N).
    """
    vn = rx * mx + ry * my + rz * mz
    elastic = k * delta**n_exp
    fn = normal_force_elastic(law, elastic, delta, -vn, damping, d_max)
    tx, ty, tz = rx - vn * mx, ry - vn * my, rz - vn * mz
    u = math.sqrt(tx * tx + ty * ty + tz * tz)
    ft = 0.0
    fx, fy, fz = fn * mx, fn * my, fn * mz
    if u > 0.0 and fn > 0.0:
        ft = friction_coefficient(fric, u, p0, p1, p2, p3) * fn
        s = ft / u
        fx -= s * tx
        fy -= s * ty
        fz -= s * tz
    return fn, u, ft, elastic * delta / (n_exp + 1.0), fx, fy, fz


@njit(cache=True, inline="always", _nrt=False)
def contact_force(q, v, bf, bt, fric_p, c, a, b, law, k, n_exp, damping, d_max, fric, delta,
                  mx, my, mz, px, py, pz):
    """Normal and friction force of contact point p of pair c between bodies a and b.

    m is the unit normal of the force on a; the force goes to both bodies (a: +, b: −).
    Returns (F_n N, |v_t| m/s, |F_t| N, elastic energy J).
    """
    if delta <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    vax, vay, vaz = point_velocity(q, v, a, px, py, pz)
    vbx, vby, vbz = point_velocity(q, v, b, px, py, pz)
    fn, u, ft, e, fx, fy, fz = point_force(law, k, n_exp, damping, d_max, fric, fric_p[c, 0], fric_p[c, 1],
                                           fric_p[c, 2], fric_p[c, 3], delta, mx, my, mz,
                                           vax - vbx, vay - vby, vaz - vbz)
    _add_force(q, bf, bt, a, fx, fy, fz, px, py, pz)
    _add_force(q, bf, bt, b, -fx, -fy, -fz, px, py, pz)
    return fn, u, ft, e


@njit(cache=True, inline="always", _nrt=False)
def _store(w, c, fn, delta, u, ft, px, py, pz, mx, my, mz):
    """The outputs of pair c: F_n N, penetration m, slip m/s, |F_t| N, contact point p (world, m) and
    unit normal m of the force on the element (world)."""
    w.contact_fn[c] = fn
    w.contact_delta[c] = delta
    w.contact_slip[c] = u
    w.contact_ft[c] = ft
    w.contact_point[c, 0] = px
    w.contact_point[c, 1] = py
    w.contact_point[c, 2] = pz
    w.contact_normal[c, 0] = mx
    w.contact_normal[c, 1] = my
    w.contact_normal[c, 2] = mz

