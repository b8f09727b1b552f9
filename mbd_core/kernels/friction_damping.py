"""Damping matrices of the friction of bodies that integrate it implicitly (``m.body_fric_implicit``),
gathered after the contact stages of :func:`.forces.compute_forces`: per contact point
Jᵀ C_p J with C_p = c (I − m mᵀ) + (c_t − c) s sᵀ, the secant c = μ(u) F_n / u across the slip and,
where the law is steeper than its secant (c_t = F_n dμ/du > c), its slope along the slip direction s.
That is the Jacobian −∂F_t/∂v_t of F_t = −μ(|v_t|) F_n v_t/|v_t| there; elsewhere (a flat or falling
μ) the secant stays along the slip too, which keeps C positive semidefinite and a sliding contact
from reversing (:mod:`.explicit`). Pairs with a modal body take the secant only (the slip of a
deforming surface is not that of its frame, from which the direction is taken here)."""

from __future__ import annotations

import math

from numba import njit

from .body_frames import point_velocity
from .laws import friction_slope


@njit(cache=True, inline="always")
def _friction_damping(q, fc, g, i, c, mx, my, mz, px, py, pz):
    """Add c Jᵀ(I − m mᵀ)J to body i's friction damping fc[i] (world (v, ω), 6 × 6): the friction
    c v_t of a contact at world point p with unit normal m, J = [I, −[r]×] the velocity of the body's
    material point at p (r = p − centre) per (v, ω), so that JᵀPJ = JᵀJ − (Jᵀm)(Jᵀm)ᵀ with
    Jᵀm = (m, r × m); g is scratch (6,)."""
    rx, ry, rz = px - q[i, 0], py - q[i, 1], pz - q[i, 2]
    g[0], g[1], g[2] = mx, my, mz
    g[3], g[4], g[5] = ry * mz - rz * my, rz * mx - rx * mz, rx * my - ry * mx
    for j in range(6):
        cg = c * g[j]
        for k in range(6):
            fc[i, j, k] -= cg * g[k]
    r2 = rx * rx + ry * ry + rz * rz
    for j in range(3):
        fc[i, j, j] += c
    fc[i, 3, 3] += c * (r2 - rx * rx)
    fc[i, 4, 4] += c * (r2 - ry * ry)
    fc[i, 5, 5] += c * (r2 - rz * rz)
    fc[i, 3, 4] -= c * rx * ry
    fc[i, 4, 3] -= c * rx * ry
    fc[i, 3, 5] -= c * rx * rz
    fc[i, 5, 3] -= c * rx * rz
    fc[i, 4, 5] -= c * ry * rz
    fc[i, 5, 4] -= c * ry * rz
    # upper right −[r]×, lower left [r]×
    fc[i, 0, 4] += c * rz
    fc[i, 4, 0] += c * rz
    fc[i, 0, 5] -= c * ry
    fc[i, 5, 0] -= c * ry
    fc[i, 1, 3] -= c * rz
    fc[i, 3, 1] -= c * rz
    fc[i, 1, 5] += c * rx
    fc[i, 5, 1] += c * rx
    fc[i, 2, 3] += c * ry
    fc[i, 3, 2] += c * ry
    fc[i, 2, 4] -= c * rx
    fc[i, 4, 2] -= c * rx


@njit(cache=True, inline="always")
def _note_friction(imp, pts, cnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz):
    """Note one contact point of pair c (normal force fn, slip speed u, friction force ft, normal m,
    world point p) for the damping matrices (:func:`_friction_damping_matrices`) when body a or b
    integrates its friction implicitly: row cnt[0] of pts = (a, b, secant c = ft / u, m, p, c, fn, u)."""
    if (imp[a] == 0 and imp[b] == 0) or not (u > 0.0 and ft > 0.0):
        return
    k = cnt[0]
    if k >= pts.shape[0]:  # (sized for every slice and two points per other pair)
        return
    pts[k, 0], pts[k, 1], pts[k, 2] = a, b, ft / u
    pts[k, 3], pts[k, 4], pts[k, 5] = mx, my, mz
    pts[k, 6], pts[k, 7], pts[k, 8] = px, py, pz
    pts[k, 9], pts[k, 10], pts[k, 11] = c, fn, u
    cnt[0] = k + 1


@njit(cache=True, inline="always")
def _along_slip(q, g, i, extra, sx, sy, sz, px, py, pz, fc):
    """Add extra · (Jᵀs)(Jᵀs)ᵀ to body i's friction damping fc[i]: a damper of coefficient
    ``extra`` along the slip direction s at world point p (J as in :func:`_friction_damping`)."""
    rx, ry, rz = px - q[i, 0], py - q[i, 1], pz - q[i, 2]
    g[0], g[1], g[2] = sx, sy, sz
    g[3], g[4], g[5] = ry * sz - rz * sy, rz * sx - rx * sz, rx * sy - ry * sx
    for j in range(6):
        eg = extra * g[j]
        for k in range(6):
            fc[i, j, k] += eg * g[k]


@njit(cache=True)
def _friction_damping_matrices(m, q, v, w):
    """w.fric_c of every body with implicit friction from the noted points, w.fric_v = v. (A stage of
    its own: accumulating in the contact loops slows them down even where no friction acts.)"""
    imp, pts, fc, g = m.body_fric_implicit, w.fric_pts, w.fric_c, w.fric_g
    for i in range(imp.shape[0]):
        if imp[i] != 0:
            for j in range(6):
                w.fric_v[i, j] = v[i, j]
                for k in range(6):
                    fc[i, j, k] = 0.0
    for k in range(w.fric_n[0]):
        a, b, c = int(pts[k, 0]), int(pts[k, 1]), pts[k, 2]
        mx, my, mz, px, py, pz = pts[k, 3], pts[k, 4], pts[k, 5], pts[k, 6], pts[k, 7], pts[k, 8]
        if imp[a] != 0:
            _friction_damping(q, fc, g, a, c, mx, my, mz, px, py, pz)
        if imp[b] != 0:
            _friction_damping(q, fc, g, b, c, mx, my, mz, px, py, pz)
        if m.body_modal[a] >= 0 or m.body_modal[b] >= 0:
            continue  # (the slip of a deforming surface is not that of its frame: the secant alone)
        pair, fn, u = int(pts[k, 9]), pts[k, 10], pts[k, 11]
        fp = m.pair_fric_p[pair]
        extra = friction_slope(m.pair_fric[pair], u, fp[0], fp[1], fp[2], fp[3]) * fn - c
        if not extra > 0.0:
            continue
        # the tangent where the law is steeper than its secant (the start of a regularised step):
        # along the slip the damper is then dF_t/du, which keeps a settling slip from overshooting
        vax, vay, vaz = point_velocity(q, v, a, px, py, pz)
        vbx, vby, vbz = point_velocity(q, v, b, px, py, pz)
        rx, ry, rz = vax - vbx, vay - vby, vaz - vbz
        vn = rx * mx + ry * my + rz * mz
        tx, ty, tz = rx - vn * mx, ry - vn * my, rz - vn * mz
        ut = math.sqrt(tx * tx + ty * ty + tz * tz)
        if not ut > 0.0:
            continue
        tx, ty, tz = tx / ut, ty / ut, tz / ut
        if imp[a] != 0:
            _along_slip(q, g, a, extra, tx, ty, tz, px, py, pz, fc)
        if imp[b] != 0:
            _along_slip(q, g, b, extra, tx, ty, tz, px, py, pz, fc)
    w.fric_n[0] = 0
