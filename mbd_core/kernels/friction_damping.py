"""Damping matrices of the friction of bodies that integrate it implicitly (``m.body_fric_implicit``):
per contact point c Jᵀ(I − m mᵀ)J, gathered after the contact stages of :func:`.forces.compute_forces`."""

from __future__ import annotations

from numba import njit



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
def _note_friction(imp, pts, cnt, a, b, u, ft, mx, my, mz, px, py, pz):
    """Note one contact point's friction (slip speed u, force ft, normal m, world point p) for the
    damping matrices (:func:`_friction_damping_matrices`) when body a or b integrates its friction
    implicitly: row cnt[0] of pts = (a, b, c = ft / u, m, p)."""
    if (imp[a] == 0 and imp[b] == 0) or not (u > 0.0 and ft > 0.0):
        return
    k = cnt[0]
    if k >= pts.shape[0]:  # (sized for every slice and two points per other pair)
        return
    pts[k, 0], pts[k, 1], pts[k, 2] = a, b, ft / u
    pts[k, 3], pts[k, 4], pts[k, 5] = mx, my, mz
    pts[k, 6], pts[k, 7], pts[k, 8] = px, py, pz
    cnt[0] = k + 1


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
        if imp[a] != 0:
            _friction_damping(q, fc, g, a, c, pts[k, 3], pts[k, 4], pts[k, 5], pts[k, 6], pts[k, 7], pts[k, 8])
        if imp[b] != 0:
            _friction_damping(q, fc, g, b, c, pts[k, 3], pts[k, 4], pts[k, 5], pts[k, 6], pts[k, 7], pts[k, 8])
    w.fric_n[0] = 0
