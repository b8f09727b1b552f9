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

from .body_frames import relative_velocity_across
from .laws import friction_slope


# The matrices are symmetric: the contact points fill their upper triangles (j ≤ k) only, and
# :func:`_friction_damping_matrices` copies them to the lower ones once per evaluation.


@njit(cache=True, inline="always", _nrt=False)
def _lever_outer(q, g, i, coef, dx, dy, dz, px, py, pz, fc):
    """Add coef · (Jᵀd)(Jᵀd)ᵀ to the upper triangle of body i's friction damping fc[i] (world (v, ω),
    6 × 6), with Jᵀd = (d, r × d) for the direction d at world point p (r = p − centre, J = [I, −[r]×]
    the velocity of the body's material point at p per (v, ω)); g is scratch (6,)."""
    rx, ry, rz = px - q[i, 0], py - q[i, 1], pz - q[i, 2]
    g[0], g[1], g[2] = dx, dy, dz
    g[3], g[4], g[5] = ry * dz - rz * dy, rz * dx - rx * dz, rx * dy - ry * dx
    for j in range(6):
        cg = coef * g[j]
        for k in range(j, 6):
            fc[i, j, k] += cg * g[k]


@njit(cache=True, inline="always", _nrt=False)
def _friction_damping(q, fc, g, i, c, mx, my, mz, px, py, pz):
    """Add c Jᵀ(I − m mᵀ)J to the upper triangle of body i's friction damping fc[i] (world (v, ω),
    6 × 6): the friction c v_t of a contact at world point p with unit normal m (J as in
    :func:`_lever_outer`), as JᵀJ − (Jᵀm)(Jᵀm)ᵀ; g is scratch (6,)."""
    _lever_outer(q, g, i, -c, mx, my, mz, px, py, pz, fc)
    rx, ry, rz = px - q[i, 0], py - q[i, 1], pz - q[i, 2]
    r2 = rx * rx + ry * ry + rz * rz
    for j in range(3):
        fc[i, j, j] += c
    fc[i, 3, 3] += c * (r2 - rx * rx)
    fc[i, 4, 4] += c * (r2 - ry * ry)
    fc[i, 5, 5] += c * (r2 - rz * rz)
    fc[i, 3, 4] -= c * rx * ry
    fc[i, 3, 5] -= c * rx * rz
    fc[i, 4, 5] -= c * ry * rz
    # upper right −[r]×
    fc[i, 0, 4] += c * rz
    fc[i, 0, 5] -= c * ry
    fc[i, 1, 3] -= c * rz
    fc[i, 1, 5] += c * rx
    fc[i, 2, 3] += c * ry
    fc[i, 2, 4] -= c * rx


@njit(cache=True, inline="always", _nrt=False)
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


@njit(cache=True, _nrt=False)
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
        tx, ty, tz, _ = relative_velocity_across(q, v, a, b, px, py, pz, mx, my, mz)
        ut = math.sqrt(tx * tx + ty * ty + tz * tz)
        if not ut > 0.0:
            continue
        tx, ty, tz = tx / ut, ty / ut, tz / ut
        if imp[a] != 0:
            _lever_outer(q, g, a, extra, tx, ty, tz, px, py, pz, fc)
        if imp[b] != 0:
            _lever_outer(q, g, b, extra, tx, ty, tz, px, py, pz, fc)
    w.fric_n[0] = 0
    for i in range(imp.shape[0]):  # the lower triangles from the upper ones
        if imp[i] != 0:
            for j in range(1, 6):
                for k in range(j):
                    fc[i, j, k] = fc[i, k, j]
