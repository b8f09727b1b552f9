"""Forces on all bodies of a multibody model at one state (the force stage of a step).

The model ``m`` is a namedtuple of flat arrays (:class:`mbd_core.multibody.model.ModelArrays`), the
work ``w`` one of preallocated scratch arrays (:class:`mbd_core.multibody.model.WorkArrays`).
State: ``q`` (n_b, 7) = position r (world, m) and unit quaternion (w, x, y, z) body → world;
``v`` (n_b, 6) = velocity (world, m/s) and angular velocity ω (body frame, rad/s).

Stages: external loads (constant + cubic-spline histories) → bushings → contacts. Each
contact gives a penetration δ, the unit normal m of the force on its element (body a), and a
contact point p; then

    F_n = normal_force(δ, δ̇) ≥ 0,        δ̇ = −(v_a(p) − v_b(p))·m,
    v_t = (v_a(p) − v_b(p)) − ((v_a(p) − v_b(p))·m) m,     F_t = −μ(|v_t|) F_n v_t/|v_t|,

with v_i(p) = v_i + ω_i × (p − r_i) the velocity of body i's material point at p. Body a gets
F_n m + F_t at p, body b the opposite. Results: ``w.body_f`` (n_b, 3) N and ``w.body_t`` (n_b, 3) N·m
(world frame, about the body's reference point = centre of mass) and the per-contact outputs.

Returns (status, index): 0 ok; ``STATUS_NONFINITE`` (non-finite force at contact ``index``, or at
body ``index`` − n_contacts when ``index`` ≥ n_contacts; messages in :mod:`mbd_core.multibody.explicit`);
``STATUS_PENETRATION`` (penetration beyond the pair's bound at contact ``index``).
``STATUS_ENERGY`` is set by the step loop (:mod:`.explicit`) on a kinetic-energy runaway,
``STATUS_MODAL`` when the mass matrix of a modal body is no longer positive definite.

Contacts on a modal ring or cage deform with it. A groove follows its sampled raceway
(:func:`_nearest_deformed_centre`); a roller slice or roller end on a surface sampled on a (θ, s) grid
(:mod:`.roller_slices`) and an element in a pocket whose two walls are sampled (leading and trailing
wall, interpolated linearly along the segment between them) see the surface displaced, at the contact
point p (ring frame) of the rigid geometry with its normal n (of the force on the element), by

    d = Σ_c w_c (D_c η + (Ω_c η) × (p − p_s)),     p_s = Σ_c w_c p_c,

over the interpolation's sample rows c with weights w_c: the section moves rigidly with the sampled
point's displacement and small rotation. The penetration becomes δ + n·d, the surface's velocity
Σ_c w_c (D_c η̇ + (Ω_c η̇) × (p − p_s)) enters the relative velocity, and the force g on the ring returns
to the modes by the transpose, Q += Σ_c w_c (D_cᵀ g + Ω_cᵀ((p − p_s) × g)), so that Q = −∂E/∂η exactly
(the weights, n and p depend on the element's pose only). The sampled fields of each row are computed
once per pair and the loads gathered per row before they are projected (``w.flex_*``, a small cache of
rows that is flushed when full): the slices of a roller share a few rows.

Bodies that integrate their friction implicitly (``m.body_fric_implicit``) also get, per contact
point, the damping matrix c Jᵀ(I − m mᵀ)J of the friction in (v, ω) world, c = |F_t|/|v_t| the secant
coefficient (``w.fric_c``, from the points noted in ``w.fric_pts``), and the velocity of this
evaluation (``w.fric_v``), for the kick of :mod:`.explicit`.
"""

from __future__ import annotations

import math

from numba import njit

from .ball_groove import TWO_PI, groove_point_in
from .element_contacts import POCKET_CYLINDER, ball_ball, pocket_cylinder, pocket_slot, roller_end
from .laws import friction_coefficient, normal_force_elastic
from .raceway import interp_index
from .roller_slices import circle_index, roller_slices, surface_coordinate
from .splines import spline_value

BALL_GROOVE = 0
BALL_BALL = 1
ROLLER_RACEWAY = 2
ROLLER_RIB = 3
ELEMENT_POCKET = 4

STATUS_OK = 0
STATUS_NONFINITE = 1
STATUS_PENETRATION = 2
STATUS_ENERGY = 3
STATUS_MODAL = 4


@njit(cache=True, inline="always")
def rotate(q, i, x, y, z):
    """R(q_i) (x, y, z): body frame → world."""
    w, a, b, c = q[i, 3], q[i, 4], q[i, 5], q[i, 6]
    tx = 2.0 * (b * z - c * y)
    ty = 2.0 * (c * x - a * z)
    tz = 2.0 * (a * y - b * x)
    return x + w * tx + (b * tz - c * ty), y + w * ty + (c * tx - a * tz), z + w * tz + (a * ty - b * tx)


@njit(cache=True, inline="always")
def rotate_back(q, i, x, y, z):
    """R(q_i)ᵀ (x, y, z): world → body frame."""
    w, a, b, c = q[i, 3], -q[i, 4], -q[i, 5], -q[i, 6]
    tx = 2.0 * (b * z - c * y)
    ty = 2.0 * (c * x - a * z)
    tz = 2.0 * (a * y - b * x)
    return x + w * tx + (b * tz - c * ty), y + w * ty + (c * tx - a * tz), z + w * tz + (a * ty - b * tx)


@njit(cache=True, inline="always")
def point_velocity(q, v, i, px, py, pz):
    """World velocity of body i's material point at world position p."""
    ox, oy, oz = rotate(q, i, v[i, 3], v[i, 4], v[i, 5])
    rx, ry, rz = px - q[i, 0], py - q[i, 1], pz - q[i, 2]
    return v[i, 0] + oy * rz - oz * ry, v[i, 1] + oz * rx - ox * rz, v[i, 2] + ox * ry - oy * rx


@njit(cache=True, inline="always")
def _add_force(q, bf, bt, i, fx, fy, fz, px, py, pz):
    """Add force (fx, fy, fz) at world point p to body i's force and moment about its centre."""
    rx, ry, rz = px - q[i, 0], py - q[i, 1], pz - q[i, 2]
    bf[i, 0] += fx
    bf[i, 1] += fy
    bf[i, 2] += fz
    bt[i, 0] += ry * fz - rz * fy
    bt[i, 1] += rz * fx - rx * fz
    bt[i, 2] += rx * fy - ry * fx


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


# Hot per-contact functions take plain arrays and scalars, never the model namedtuple: passing a
# tuple of ~50 arrays to a function that is not inlined costs about 0.5 µs per call, and so does
# reading a field of m or w inside an inlined per-contact function (hoist such reads out of the
# loops); every array argument of a call costs reference counting (~10 ns), so the small helpers
# that take arrays are inlined by numba (inline="always").
@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
def _to_world(q, b, lx, ly, lz):
    """World position of a point given in body b's frame."""
    x, y, z = rotate(q, b, lx, ly, lz)
    return q[b, 0] + x, q[b, 1] + y, q[b, 2] + z


@njit(cache=True, inline="always")
def _in_frame(q, b, x, y, z):
    """Coordinates in body b's frame of the world point (x, y, z)."""
    return rotate_back(q, b, x - q[b, 0], y - q[b, 1], z - q[b, 2])


@njit(cache=True, inline="always")
def _contact_angle(q, b, nx, ny, nz, px, py, pz):
    """atan2(|n_axial|, |n_radial|) of a world normal n at world point p, in body b's cylindrical frame."""
    lx, ly, lz = rotate_back(q, b, nx, ny, nz)
    ex, ey, _ = _in_frame(q, b, px, py, pz)
    r = math.sqrt(ex * ex + ey * ey)
    if r == 0.0:
        return 0.0
    return math.atan2(abs(lz), abs((lx * ex + ly * ey) / r))


@njit(cache=True, inline="always")
def _roller_axis(q, a, b):
    """Roller a's axis (its body z) in ring b's frame."""
    x, y, z = rotate(q, a, 0.0, 0.0, 1.0)
    return rotate_back(q, b, x, y, z)


@njit(cache=True, inline="always")
def _store(w, c, fn, delta, u, ft):
    w.contact_fn[c] = fn
    w.contact_delta[c] = delta
    w.contact_slip[c] = u
    w.contact_ft[c] = ft


@njit(cache=True)
def _ball_groove_pairs(m, q, v, eta, eta_dot, w):
    e_sum = 0.0
    bf, bt, fp = w.body_f, w.body_t, m.pair_fric_p
    imp, fpts, fcnt = m.body_fric_implicit, w.fric_pts, w.fric_n
    for c in range(m.pair_type.shape[0]):
        if m.pair_type[c] != BALL_GROOVE:
            continue
        a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
        ra = m.pair_radius[c]
        lx, ly, lz = _in_frame(q, b, q[a, 0], q[a, 1], q[a, 2])
        th, delta, nx, ny, nz = groove_point_in(
            lx, ly, lz, m.groove_rc[g], m.groove_zc[g], m.groove_r[g] - ra,
            m.groove_h, m.groove_h_off[g], m.groove_h_off[g + 1],
            m.groove_dr, m.groove_dr_off[g], m.groove_dr_off[g + 1],
        )
        if m.groove_modal[g] < 0:
            mx, my, mz = rotate(q, b, -nx, -ny, -nz)
            px, py, pz = q[a, 0] - ra * mx, q[a, 1] - ra * my, q[a, 2] - ra * mz
            fn, u, ft, e = contact_force(q, v, bf, bt, fp, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c],
                                         m.pair_c[c], m.pair_dmax[c], m.pair_fric[c], delta, mx, my, mz,
                                         px, py, pz)
            _note_friction(imp, fpts, fcnt, a, b, u, ft, mx, my, mz, px, py, pz)
        else:
            # a groove on a modal ring (see _nearest_deformed_centre); the arrays are sliced here so
            # that no per-contact function takes the model tuple
            jm, s0, s1 = m.groove_modal[g], m.groove_samp_off[g], m.groove_samp_off[g + 1]
            o0, o1 = m.modal_off[jm], m.modal_off[jm + 1]
            disp, rot, pts = m.samp_disp[s0:s1], m.samp_rot[s0:s1], m.samp_point[s0:s1]
            cx, cy, cz, i0, i1, w0, w1 = _nearest_deformed_centre(
                m.samp_theta[s0:s1], m.groove_periodic[g] == 1, disp, rot, pts, eta[o0:o1], w.groove_rows, m.groove_rc[g],
                m.groove_zc[g], m.groove_h, m.groove_h_off[g], m.groove_h_off[g + 1], m.groove_dr,
                m.groove_dr_off[g], m.groove_dr_off[g + 1], th, lx, ly, lz)
            dx, dy, dz = lx - cx, ly - cy, lz - cz
            dist = math.sqrt(dx * dx + dy * dy + dz * dz)
            if dist > 0.0:
                nx, ny, nz = dx / dist, dy / dist, dz / dist
            delta = dist - (m.groove_r[g] - ra)
            fn, u, ft, e = 0.0, 0.0, 0.0, 0.0
            if delta > 0.0:
                # contact point (ring frame), its lever about the raceway point, the modal velocity there
                plx, ply, plz = lx + ra * nx, ly + ra * ny, lz + ra * nz
                bx = plx - (w0 * pts[i0, 0] + w1 * pts[i1, 0])
                by = ply - (w0 * pts[i0, 1] + w1 * pts[i1, 1])
                bz = plz - (w0 * pts[i0, 2] + w1 * pts[i1, 2])
                vx, vy, vz = _section_velocity(disp, rot, i0, i1, w0, w1, eta_dot[o0:o1], bx, by, bz)
                vx, vy, vz = rotate(q, b, vx, vy, vz)
                px, py, pz = _to_world(q, b, plx, ply, plz)
                mx, my, mz = rotate(q, b, -nx, -ny, -nz)
                vax, vay, vaz = point_velocity(q, v, a, px, py, pz)
                vbx, vby, vbz = point_velocity(q, v, b, px, py, pz)
                fn, u, ft, e, fx, fy, fz = point_force(m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c],
                                                       m.pair_dmax[c], m.pair_fric[c], fp[c, 0], fp[c, 1], fp[c, 2],
                                                       fp[c, 3], delta, mx, my, mz, vax - vbx - vx, vay - vby - vy,
                                                       vaz - vbz - vz)
                _add_force(q, bf, bt, a, fx, fy, fz, px, py, pz)
                _add_force(q, bf, bt, b, -fx, -fy, -fz, px, py, pz)
                _note_friction(imp, fpts, fcnt, a, b, u, ft, mx, my, mz, px, py, pz)
                gx, gy, gz = rotate_back(q, b, -fx, -fy, -fz)
                _add_section_force(disp, rot, i0, i1, w0, w1, gx, gy, gz, by * gz - bz * gy, bz * gx - bx * gz,
                                   bx * gy - by * gx, w.modal_f[o0:o1])
        _store(w, c, fn, delta, u, ft)
        w.contact_theta[c] = th
        w.contact_angle[c] = math.atan2(abs(nz), abs(nx * math.cos(th) + ny * math.sin(th)))
        e_sum += e
    return e_sum


@njit(cache=True, inline="always")
def _table_slope(table, start, stop, th):
    """Value and dθ-slope of a uniform periodic table over [0, 2π) at θ (linear interpolation)."""
    n = stop - start
    if n == 1:
        return table[start], 0.0
    s = th / TWO_PI * n
    i0 = int(math.floor(s))
    w = s - i0
    i0 = i0 % n
    i1 = (i0 + 1) % n
    return (1.0 - w) * table[start + i0] + w * table[start + i1], (table[start + i1] - table[start + i0]) * n / TWO_PI


@njit(cache=True, inline="always")
def _section_velocity(disp, rot, i0, i1, w0, w1, ed, bx, by, bz):
    """Velocity (Dη̇) + (Ωη̇) × b of the raceway section's point at lever b from the sampled point,
    interpolated between samples i0, i1 (ring frame)."""
    vx = vy = vz = sx = sy = sz = 0.0
    for k in range(ed.shape[0]):
        e = ed[k]
        vx += (w0 * disp[i0, 0, k] + w1 * disp[i1, 0, k]) * e
        vy += (w0 * disp[i0, 1, k] + w1 * disp[i1, 1, k]) * e
        vz += (w0 * disp[i0, 2, k] + w1 * disp[i1, 2, k]) * e
        sx += (w0 * rot[i0, 0, k] + w1 * rot[i1, 0, k]) * e
        sy += (w0 * rot[i0, 1, k] + w1 * rot[i1, 1, k]) * e
        sz += (w0 * rot[i0, 2, k] + w1 * rot[i1, 2, k]) * e
    return vx + sy * bz - sz * by, vy + sz * bx - sx * bz, vz + sx * by - sy * bx


@njit(cache=True, inline="always")
def _add_section_force(disp, rot, i0, i1, w0, w1, fx, fy, fz, tx, ty, tz, qf):
    """qf += Dᵀf + Ωᵀt at the interpolated section: the modal force of a force f and moment t (ring
    frame) on the raceway section — the transpose of :func:`_section_velocity`."""
    for k in range(qf.shape[0]):
        qf[k] += (w0 * (disp[i0, 0, k] * fx + disp[i0, 1, k] * fy + disp[i0, 2, k] * fz
                        + rot[i0, 0, k] * tx + rot[i0, 1, k] * ty + rot[i0, 2, k] * tz)
                  + w1 * (disp[i1, 0, k] * fx + disp[i1, 1, k] * fy + disp[i1, 2, k] * fz
                          + rot[i1, 0, k] * tx + rot[i1, 1, k] * ty + rot[i1, 2, k] * tz))


@njit(cache=True, inline="always")
def _groove_rows(disp, rot, i0, i1, e_j, out):
    """out (4, 3) = D_i0 η, D_i1 η, Ω_i0 η, Ω_i1 η: the two samples around a contact, whose linear
    interpolation and difference quotient give the raceway's displacement, rotation and their slopes."""
    for r in range(4):
        for c in range(3):
            out[r, c] = 0.0
    for k in range(e_j.shape[0]):
        ek = e_j[k]
        for c in range(3):
            out[0, c] += disp[i0, c, k] * ek
            out[1, c] += disp[i1, c, k] * ek
            out[2, c] += rot[i0, c, k] * ek
            out[3, c] += rot[i1, c, k] * ek


@njit(cache=True, inline="always")
def _deformed_groove_centre(theta, periodic, pts, rows, rc, zc, h_all, h0, h1, dr_all, dr0, dr1, th, i0, i1, w0, w1):
    """Deformed curvature centre c'(θ) = c(θ) + u + ψ × (c − p_s) of a groove at angle θ ∈ [0, 2π) (ring
    frame) between samples i0, i1 (weights w0, w1; ``rows`` from :func:`_groove_rows`), and its
    θ-derivative. The derivative leaves out ψ × ∂(c − p_s)/∂θ, which turns the normal at the nearest
    point by about |ψ|·|c − p_s|/r (7e-5 of the force in the kernel tests); beyond the ends of a
    raceway sampled on an arc the deformation is held, so its slope there is zero."""
    dth = theta[i1] - theta[i0]
    if dth <= 0.0:
        dth += TWO_PI
    dr, dr_s = _table_slope(dr_all, dr0, dr1, th)
    h, h_s = _table_slope(h_all, h0, h1, th)
    r = rc + dr
    cs, sn = math.cos(th), math.sin(th)
    cx, cy, cz = r * cs, r * sn, zc + h
    ax = cx - (w0 * pts[i0, 0] + w1 * pts[i1, 0])
    ay = cy - (w0 * pts[i0, 1] + w1 * pts[i1, 1])
    az = cz - (w0 * pts[i0, 2] + w1 * pts[i1, 2])
    ux, uy, uz = w0 * rows[0, 0] + w1 * rows[1, 0], w0 * rows[0, 1] + w1 * rows[1, 1], w0 * rows[0, 2] + w1 * rows[1, 2]
    rx, ry, rz = w0 * rows[2, 0] + w1 * rows[3, 0], w0 * rows[2, 1] + w1 * rows[3, 1], w0 * rows[2, 2] + w1 * rows[3, 2]
    # θ-derivative: of the rigid centre, of u (difference quotient of the samples), of ψ × lever
    slope = 1.0 / dth
    if not periodic and (th < theta[0] or th > theta[theta.shape[0] - 1]):
        slope = 0.0
    dux, duy, duz = (rows[1, 0] - rows[0, 0]) * slope, (rows[1, 1] - rows[0, 1]) * slope, (rows[1, 2] - rows[0, 2]) * slope
    drx, dry, drz = (rows[3, 0] - rows[2, 0]) * slope, (rows[3, 1] - rows[2, 1]) * slope, (rows[3, 2] - rows[2, 2]) * slope
    tx = -r * sn + dr_s * cs + dux + dry * az - drz * ay
    ty = r * cs + dr_s * sn + duy + drz * ax - drx * az
    tz = h_s + duz + drx * ay - dry * ax
    return cx + ux + ry * az - rz * ay, cy + uy + rz * ax - rx * az, cz + uz + rx * ay - ry * ax, tx, ty, tz


@njit(cache=True, inline="always")
def _nearest_deformed_centre(theta, periodic, disp, rot, pts, e_j, rows, rc, zc, h_all, h0, h1, dr_all, dr0, dr1,
                             th, lx, ly, lz):
    """Ball–groove contact on a modal ring (:mod:`.raceway`): the groove section at θ moves with the
    raceway point's displacement u = Dη and small rotation ψ = Ωη, so its curvature centre c goes to
    c'(θ) = c + u + ψ × (c − p_s) (p_s the sampled raceway point). The ball at x (ring frame) touches
    the deformed centre curve at its nearest point θ*, (x − c'(θ*))·∂c'/∂θ = 0 (two Gauss–Newton
    steps from the ball's own angle θ), so that δ = |x − c'(θ*)| − (f·D − D/2) is the distance whose
    gradient the force follows: a deformation that only slides the groove along itself does not push
    the ball, a deflection slope does, as on an undulated groove. The caller returns the force to the
    modes through the transpose of the interpolation at θ*, Q += Dᵀf + Ωᵀ((p − p_s) × f) for the force
    f on the ring at the contact point p (work-consistent). The sample products D η, Ω η are formed
    once per pair of samples (``rows``, scratch (4, 3)). Returns (c'(θ*), i0, i1, w0, w1)."""
    ts = th
    r0, r1 = -1, -1
    for it in range(3):
        ts = ts % TWO_PI
        i0, i1, w0, w1 = interp_index(theta, ts, periodic)
        if i0 != r0 or i1 != r1:
            _groove_rows(disp, rot, i0, i1, e_j, rows)
            r0, r1 = i0, i1
        cx, cy, cz, tx, ty, tz = _deformed_groove_centre(theta, periodic, pts, rows, rc, zc, h_all, h0, h1, dr_all,
                                                         dr0, dr1, ts, i0, i1, w0, w1)
        if it < 2:
            ts += ((lx - cx) * tx + (ly - cy) * ty + (lz - cz) * tz) / (tx * tx + ty * ty + tz * tz)
    return cx, cy, cz, i0, i1, w0, w1


@njit(cache=True, inline="always")
def _cached_row(rows, field, n, row, disp, rot, e_j, ed_j):
    """Slot of sample row ``row`` in the row cache (``n`` slots in use); a new row gets its fields
    D η, Ω η, D η̇, Ω η̇ (``field[:, 0:12]``) and an empty load (``field[:, 12:18]``). Returns (slot, n)."""
    for k in range(n):
        if rows[k] == row:
            return k, n
    ux = uy = uz = rx = ry = rz = vx = vy = vz = sx = sy = sz = 0.0
    for k in range(e_j.shape[0]):
        e, ed = e_j[k], ed_j[k]
        d0, d1, d2 = disp[row, 0, k], disp[row, 1, k], disp[row, 2, k]
        o0, o1, o2 = rot[row, 0, k], rot[row, 1, k], rot[row, 2, k]
        ux += d0 * e
        uy += d1 * e
        uz += d2 * e
        rx += o0 * e
        ry += o1 * e
        rz += o2 * e
        vx += d0 * ed
        vy += d1 * ed
        vz += d2 * ed
        sx += o0 * ed
        sy += o1 * ed
        sz += o2 * ed
    rows[n] = row
    field[n, 0], field[n, 1], field[n, 2], field[n, 3], field[n, 4], field[n, 5] = ux, uy, uz, rx, ry, rz
    field[n, 6], field[n, 7], field[n, 8], field[n, 9], field[n, 10], field[n, 11] = vx, vy, vz, sx, sy, sz
    for i in range(12, 18):
        field[n, i] = 0.0
    return n, n + 1


@njit(cache=True, inline="always")
def _flush_rows(rows, field, n, disp, rot, qf):
    """Modal force of the loads gathered on the ``n`` cached rows: qf += D_rowᵀ f + Ω_rowᵀ μ."""
    for k in range(n):
        row = rows[k]
        f0, f1, f2, m0, m1, m2 = field[k, 12], field[k, 13], field[k, 14], field[k, 15], field[k, 16], field[k, 17]
        if f0 == 0.0 and f1 == 0.0 and f2 == 0.0 and m0 == 0.0 and m1 == 0.0 and m2 == 0.0:
            continue
        for i in range(qf.shape[0]):
            qf[i] += (disp[row, 0, i] * f0 + disp[row, 1, i] * f1 + disp[row, 2, i] * f2
                      + rot[row, 0, i] * m0 + rot[row, 1, i] * m1 + rot[row, 2, i] * m2)


@njit(cache=True, inline="always")
def _grid_corners(theta, periodic, circ, kind, s0, lx, ly, lz, corner, weight):
    """Sample rows and weights (4 corners) of the ring-frame point l on a (θ, s) grid whose circles (at
    ``circ``, each with the angles ``theta``) start at row s0 of samp_*."""
    n_th = theta.shape[0]
    th = math.atan2(ly, lx)
    if th < 0.0:  # sample angles lie in [0, 2π) (an arc from θ = 0)
        th += TWO_PI
    i0, i1, w0, w1 = interp_index(theta, th, periodic)
    j0, j1, v0, v1 = circle_index(circ, surface_coordinate(kind, lx, ly, lz))
    r0, r1 = s0 + j0 * n_th, s0 + j1 * n_th
    corner[0, 0], corner[1, 0], corner[2, 0], corner[3, 0] = r0 + i0, r0 + i1, r1 + i0, r1 + i1
    weight[0], weight[1], weight[2], weight[3] = v0 * w0, v0 * w1, v1 * w0, v1 * w1


@njit(cache=True, inline="always")
def _wall_corners(pts, row, lx, ly, lz, corner, weight):
    """Rows and weights of the ring-frame point l between the leading (``row``) and trailing (``row + 1``)
    wall samples of a pocket: its projection on the segment between them, clamped to it."""
    ex, ey, ez = pts[row, 0] - pts[row + 1, 0], pts[row, 1] - pts[row + 1, 1], pts[row, 2] - pts[row + 1, 2]
    t = ((lx - pts[row + 1, 0]) * ex + (ly - pts[row + 1, 1]) * ey + (lz - pts[row + 1, 2]) * ez) / (
        ex * ex + ey * ey + ez * ez)
    t = min(max(t, 0.0), 1.0)
    corner[0, 0], corner[1, 0], corner[2, 0], corner[3, 0] = row, row + 1, row, row + 1
    weight[0], weight[1], weight[2], weight[3] = t, 1.0 - t, 0.0, 0.0


# (at most 30 arguments: a call with more compiles to CALL_FUNCTION_EX, which numba cannot inline)
@njit(cache=True, inline="always")
def _flexible_contact(q, v, bf, bt, disp, rot, pts, e_j, ed_j, rows, field, corner, weight, n, a, b, law, k_c,
                      n_exp, damping, d_max, fric, fp_c, sd, sp, sn, k):
    """Contact point l = sp[k] (ring frame) of a pair on a sampled surface of modal body b, normal n = sn[k]
    of the force on a (ring frame), rigid-geometry penetration δ = sd[k]; the corners in ``corner[:, 0]``
    and ``weight``, the tables samp_disp, samp_rot, samp_point. Penetration δ + n·d, surface velocity in
    the slip, force on both frames, load gathered on the cached rows (module docstring; ``n`` slots of
    the cache ``rows``, ``field`` in use, at least four free). Returns (n, F_n, δ + n·d, |v_t|, |F_t|,
    energy, p world, m world)."""
    lx, ly, lz, nx, ny, nz, delta = sp[k, 0], sp[k, 1], sp[k, 2], sn[k, 0], sn[k, 1], sn[k, 2], sd[k]
    psx = psy = psz = ux = uy = uz = rx = ry = rz = vx = vy = vz = sx = sy = sz = 0.0
    for i in range(4):
        row = corner[i, 0]
        slot, n = _cached_row(rows, field, n, row, disp, rot, e_j, ed_j)
        corner[i, 1] = slot
        cw = weight[i]
        psx += cw * pts[row, 0]
        psy += cw * pts[row, 1]
        psz += cw * pts[row, 2]
        ux += cw * field[slot, 0]
        uy += cw * field[slot, 1]
        uz += cw * field[slot, 2]
        rx += cw * field[slot, 3]
        ry += cw * field[slot, 4]
        rz += cw * field[slot, 5]
        vx += cw * field[slot, 6]
        vy += cw * field[slot, 7]
        vz += cw * field[slot, 8]
        sx += cw * field[slot, 9]
        sy += cw * field[slot, 10]
        sz += cw * field[slot, 11]
    bx, by, bz = lx - psx, ly - psy, lz - psz
    delta += nx * (ux + ry * bz - rz * by) + ny * (uy + rz * bx - rx * bz) + nz * (uz + rx * by - ry * bx)
    px, py, pz = _to_world(q, b, lx, ly, lz)
    mx, my, mz = rotate(q, b, nx, ny, nz)
    if delta <= 0.0:
        return n, 0.0, delta, 0.0, 0.0, 0.0, px, py, pz, mx, my, mz
    wx, wy, wz = rotate(q, b, vx + sy * bz - sz * by, vy + sz * bx - sx * bz, vz + sx * by - sy * bx)
    vax, vay, vaz = point_velocity(q, v, a, px, py, pz)
    vbx, vby, vbz = point_velocity(q, v, b, px, py, pz)
    fn, u, ft, e, fx, fy, fz = point_force(law, k_c, n_exp, damping, d_max, fric, fp_c[0], fp_c[1], fp_c[2],
                                           fp_c[3], delta, mx, my, mz, vax - vbx - wx, vay - vby - wy, vaz - vbz - wz)
    _add_force(q, bf, bt, a, fx, fy, fz, px, py, pz)
    _add_force(q, bf, bt, b, -fx, -fy, -fz, px, py, pz)
    gx, gy, gz = rotate_back(q, b, -fx, -fy, -fz)
    tx, ty, tz = by * gz - bz * gy, bz * gx - bx * gz, bx * gy - by * gx
    for i in range(4):
        slot, cw = corner[i, 1], weight[i]
        field[slot, 12] += cw * gx
        field[slot, 13] += cw * gy
        field[slot, 14] += cw * gz
        field[slot, 15] += cw * tx
        field[slot, 16] += cw * ty
        field[slot, 17] += cw * tz
    return n, fn, delta, u, ft, e, px, py, pz, mx, my, mz


@njit(cache=True, inline="always")
def _flexible_point(m, q, v, eta, eta_dot, w, c, a, b, o0, o1, n, delta, lx, ly, lz, nx, ny, nz, imp, fpts, fcnt):
    """:func:`_flexible_contact` of one point of pair c (a roller end, a pocket wall; corners set, at most
    two points per pair, so the cache has room) through slot 0 of the slice scratch; returns (n, F_n,
    δ + n·d, |v_t|, |F_t|, energy)."""
    sd, sp, sn = w.slice_delta, w.slice_point, w.slice_normal
    sd[0], sp[0, 0], sp[0, 1], sp[0, 2], sn[0, 0], sn[0, 1], sn[0, 2] = delta, lx, ly, lz, nx, ny, nz
    n, fn, delta, u, ft, e, px, py, pz, mx, my, mz = _flexible_contact(
        q, v, w.body_f, w.body_t, m.samp_disp, m.samp_rot, m.samp_point, eta[o0:o1], eta_dot[o0:o1], w.flex_row,
        w.flex_field, w.flex_corner, w.flex_weight, n, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c],
        m.pair_dmax[c], m.pair_fric[c], m.pair_fric_p[c], sd, sp, sn, 0)
    _note_friction(imp, fpts, fcnt, a, b, u, ft, mx, my, mz, px, py, pz)
    return n, fn, delta, u, ft, e


@njit(cache=True, inline="always")
def _flexible_roller_raceway(m, q, v, eta, eta_dot, w, c, a, b, g, ns, imp, fpts, fcnt):
    """The slices of roller pair c (rigid geometry in ``w.slice_*``) on the (θ, s)-sampled surface g of
    modal ring b. Returns (ΣF_n, largest δ, slip at the most loaded slice, Σ|F_t|, its contact angle,
    energy)."""
    jm = m.race_modal[g]
    o0, o1 = m.modal_off[jm], m.modal_off[jm + 1]
    e_j, ed_j, qf = eta[o0:o1], eta_dot[o0:o1], w.modal_f[o0:o1]
    sd, sp, sn = w.slice_delta, w.slice_point, w.slice_normal
    bf, bt, disp, rot, pts = w.body_f, w.body_t, m.samp_disp, m.samp_rot, m.samp_point
    rows, field, corner, weight = w.flex_row, w.flex_field, w.flex_corner, w.flex_weight
    s0, s1 = m.race_samp_off[g], m.race_samp_off[g + 1]
    circ = m.race_circle_s[m.race_circle_off[g]:m.race_circle_off[g + 1]]
    theta = m.samp_theta[s0:s0 + (s1 - s0) // circ.shape[0]]
    periodic, kind = m.race_periodic[g] == 1, m.race_kind[g]
    law, k_c, n_exp, damp, d_mx = m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c], m.pair_dmax[c]
    fric, fp_c = m.pair_fric[c], m.pair_fric_p[c]
    fn_sum, dmax, u_at_max, ft_sum, f_max, angle, e_sum = 0.0, -math.inf, 0.0, 0.0, -1.0, 0.0, 0.0
    n = 0
    for k in range(ns):
        _grid_corners(theta, periodic, circ, kind, s0, sp[k, 0], sp[k, 1], sp[k, 2], corner, weight)
        if n > rows.shape[0] - 4:
            _flush_rows(rows, field, n, disp, rot, qf)
            n = 0
        n, fn, delta, u, ft, e, px, py, pz, mx, my, mz = _flexible_contact(
            q, v, bf, bt, disp, rot, pts, e_j, ed_j, rows, field, corner, weight, n, a, b, law, k_c, n_exp,
            damp, d_mx, fric, fp_c, sd, sp, sn, k)
        if delta > dmax:
            dmax = delta
        if delta <= 0.0:
            continue
        _note_friction(imp, fpts, fcnt, a, b, u, ft, mx, my, mz, px, py, pz)
        fn_sum += fn
        ft_sum += ft
        e_sum += e
        if fn > f_max:
            f_max, u_at_max = fn, u
            angle = _contact_angle(q, b, mx, my, mz, px, py, pz)
    _flush_rows(rows, field, n, disp, rot, qf)
    return fn_sum, dmax, u_at_max, ft_sum, angle, e_sum


@njit(cache=True)
def _ball_ball_pairs(m, q, v, w):
    e_sum = 0.0
    bf, bt, fp = w.body_f, w.body_t, m.pair_fric_p
    imp, fpts, fcnt = m.body_fric_implicit, w.fric_pts, w.fric_n
    for c in range(m.pair_type.shape[0]):
        if m.pair_type[c] != BALL_BALL:
            continue
        a, b = m.pair_a[c], m.pair_b[c]
        delta, mx, my, mz, px, py, pz = ball_ball(q[a], q[b], m.pair_radius[c], m.pair_radius_b[c])
        fn, u, ft, e = contact_force(q, v, bf, bt, fp, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c],
                                     m.pair_c[c], m.pair_dmax[c], m.pair_fric[c], delta, mx, my, mz, px, py, pz)
        _note_friction(imp, fpts, fcnt, a, b, u, ft, mx, my, mz, px, py, pz)
        _store(w, c, fn, delta, u, ft)
        w.contact_angle[c] = 0.0
        e_sum += e
    return e_sum


@njit(cache=True)
def _roller_raceway_pairs(m, q, v, eta, eta_dot, w):
    e_sum = 0.0
    bf, bt, fp = w.body_f, w.body_t, m.pair_fric_p
    center, axis = w.center, w.axis
    sd, sp, sn = w.slice_delta, w.slice_point, w.slice_normal
    imp, fpts, fcnt = m.body_fric_implicit, w.fric_pts, w.fric_n
    for c in range(m.pair_type.shape[0]):
        if m.pair_type[c] != ROLLER_RACEWAY:
            continue
        a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
        s0, s1 = m.pair_slice_off[c], m.pair_slice_off[c + 1]
        ns = s1 - s0
        center[0], center[1], center[2] = _in_frame(q, b, q[a, 0], q[a, 1], q[a, 2])
        axis[0], axis[1], axis[2] = _roller_axis(q, a, b)
        roller_slices(center, axis, m.pair_length[c], m.pair_radius[c], m.slice_drop[s0:s1],
                      m.race_kind[g], m.race_value[g], sd, sp, sn)
        if m.race_modal[g] >= 0:
            fn_sum, dmax, u_at_max, ft_sum, angle, e = _flexible_roller_raceway(m, q, v, eta, eta_dot, w, c, a, b, g,
                                                                                 ns, imp, fpts, fcnt)
            e_sum += e
            _store(w, c, fn_sum, dmax, u_at_max, ft_sum)
            w.contact_angle[c] = angle
            continue
        fn_sum, dmax, u_at_max, ft_sum, f_max, angle = 0.0, -math.inf, 0.0, 0.0, -1.0, 0.0
        # the slices share both bodies: their angular velocities once, forces summed per pair
        oax, oay, oaz = rotate(q, a, v[a, 3], v[a, 4], v[a, 5])
        obx, oby, obz = rotate(q, b, v[b, 3], v[b, 4], v[b, 5])
        law, k_s, n_exp, damp, d_mx, fric = m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c], m.pair_dmax[c], m.pair_fric[c]
        p0, p1, p2, p3 = fp[c, 0], fp[c, 1], fp[c, 2], fp[c, 3]
        fxs = fys = fzs = tax = tay = taz = tbx = tby = tbz = 0.0
        for k in range(ns):
            delta = sd[k]
            if delta > dmax:
                dmax = delta
            if delta <= 0.0:
                continue
            px, py, pz = _to_world(q, b, sp[k, 0], sp[k, 1], sp[k, 2])
            mx, my, mz = rotate(q, b, sn[k, 0], sn[k, 1], sn[k, 2])
            rax, ray, raz = px - q[a, 0], py - q[a, 1], pz - q[a, 2]
            rbx, rby, rbz = px - q[b, 0], py - q[b, 1], pz - q[b, 2]
            fn, u, ft, e, fx, fy, fz = point_force(
                law, k_s, n_exp, damp, d_mx, fric, p0, p1, p2, p3, delta, mx, my, mz,
                v[a, 0] + oay * raz - oaz * ray - v[b, 0] - (oby * rbz - obz * rby),
                v[a, 1] + oaz * rax - oax * raz - v[b, 1] - (obz * rbx - obx * rbz),
                v[a, 2] + oax * ray - oay * rax - v[b, 2] - (obx * rby - oby * rbx))
            _note_friction(imp, fpts, fcnt, a, b, u, ft, mx, my, mz, px, py, pz)
            fxs += fx
            fys += fy
            fzs += fz
            tax += ray * fz - raz * fy
            tay += raz * fx - rax * fz
            taz += rax * fy - ray * fx
            tbx += rby * fz - rbz * fy
            tby += rbz * fx - rbx * fz
            tbz += rbx * fy - rby * fx
            fn_sum += fn
            ft_sum += ft
            e_sum += e
            if fn > f_max:
                f_max, u_at_max = fn, u
                angle = _contact_angle(q, b, mx, my, mz, px, py, pz)
        bf[a, 0] += fxs
        bf[a, 1] += fys
        bf[a, 2] += fzs
        bf[b, 0] -= fxs
        bf[b, 1] -= fys
        bf[b, 2] -= fzs
        bt[a, 0] += tax
        bt[a, 1] += tay
        bt[a, 2] += taz
        bt[b, 0] -= tbx
        bt[b, 1] -= tby
        bt[b, 2] -= tbz
        _store(w, c, fn_sum, dmax, u_at_max, ft_sum)
        w.contact_angle[c] = angle
    return e_sum


@njit(cache=True)
def _roller_rib_pairs(m, q, v, eta, eta_dot, w):
    e_sum = 0.0
    bf, bt, fp = w.body_f, w.body_t, m.pair_fric_p
    center, axis, point = w.center, w.axis, w.point
    imp, fpts, fcnt = m.body_fric_implicit, w.fric_pts, w.fric_n
    for c in range(m.pair_type.shape[0]):
        if m.pair_type[c] != ROLLER_RIB:
            continue
        a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
        center[0], center[1], center[2] = _in_frame(q, b, q[a, 0], q[a, 1], q[a, 2])
        axis[0], axis[1], axis[2] = _roller_axis(q, a, b)
        delta, nx, ny, nz = roller_end(center, axis, m.pair_radius[c], m.pair_length[c], m.pair_aux[c, 0],
                                       m.pair_aux[c, 1], m.race_kind[g], m.race_value[g], point)
        if m.race_modal[g] >= 0:
            jm = m.race_modal[g]
            o0, o1 = m.modal_off[jm], m.modal_off[jm + 1]
            s0, s1 = m.race_samp_off[g], m.race_samp_off[g + 1]
            circ = m.race_circle_s[m.race_circle_off[g]:m.race_circle_off[g + 1]]
            _grid_corners(m.samp_theta[s0:s0 + (s1 - s0) // circ.shape[0]], m.race_periodic[g] == 1, circ,
                          m.race_kind[g], s0, point[0], point[1], point[2], w.flex_corner, w.flex_weight)
            n, fn, delta, u, ft, e = _flexible_point(m, q, v, eta, eta_dot, w, c, a, b, o0, o1, 0, delta,
                                                     point[0], point[1], point[2], nx, ny, nz, imp, fpts, fcnt)
            _flush_rows(w.flex_row, w.flex_field, n, m.samp_disp, m.samp_rot, w.modal_f[o0:o1])
            _store(w, c, fn, delta, u, ft)
            w.contact_angle[c] = 0.0
            e_sum += e
            continue
        px, py, pz = _to_world(q, b, point[0], point[1], point[2])
        mx, my, mz = rotate(q, b, nx, ny, nz)
        fn, u, ft, e = contact_force(q, v, bf, bt, fp, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c],
                                     m.pair_c[c], m.pair_dmax[c], m.pair_fric[c], delta, mx, my, mz, px, py, pz)
        _note_friction(imp, fpts, fcnt, a, b, u, ft, mx, my, mz, px, py, pz)
        _store(w, c, fn, delta, u, ft)
        w.contact_angle[c] = 0.0
        e_sum += e
    return e_sum


@njit(cache=True)
def _element_pocket_pairs(m, q, v, eta, eta_dot, w):
    e_sum = 0.0
    bf, bt, fp = w.body_f, w.body_t, m.pair_fric_p
    center = w.center
    imp, fpts, fcnt = m.body_fric_implicit, w.fric_pts, w.fric_n
    for c in range(m.pair_type.shape[0]):
        if m.pair_type[c] != ELEMENT_POCKET:
            continue
        a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
        lx, ly, lz = _in_frame(q, b, q[a, 0], q[a, 1], q[a, 2])
        ang, rp, zp, clr = m.pocket_angle[g], m.pocket_r[g], m.pocket_z[g], m.pocket_clearance[g]
        r = m.pair_radius[c]
        fn_sum, dmax, u_max, ft_sum, f_max = 0.0, -math.inf, 0.0, 0.0, -1.0
        slot = m.pocket_kind[g] != POCKET_CYLINDER
        ax, ay, az = _roller_axis(q, a, b)
        jm = m.pocket_modal[g]
        o0, o1 = (m.modal_off[jm], m.modal_off[jm + 1]) if jm >= 0 else (0, 0)
        n = 0
        for k in range(2 if slot else 1):
            center[0], center[1], center[2] = lx, ly, lz
            if slot:
                s = (k - 0.5) * m.pair_length[c]
                center[0] += s * ax
                center[1] += s * ay
                center[2] += s * az
                delta, nx, ny, nz, plx, ply, plz = pocket_slot(center, r, ang, rp, zp, clr)
            else:
                delta, nx, ny, nz, plx, ply, plz = pocket_cylinder(center, r, ang, rp, zp, clr)
            if jm >= 0:  # the force, if any, is applied here already
                _wall_corners(m.samp_point, m.pocket_samp[g], plx, ply, plz, w.flex_corner, w.flex_weight)
                n, fn, delta, u, ft, e = _flexible_point(m, q, v, eta, eta_dot, w, c, a, b, o0, o1, n, delta,
                                                         plx, ply, plz, nx, ny, nz, imp, fpts, fcnt)
            if delta > dmax:
                dmax = delta
            if delta <= 0.0:
                continue
            if jm < 0:
                px, py, pz = _to_world(q, b, plx, ply, plz)
                mx, my, mz = rotate(q, b, nx, ny, nz)
                fn, u, ft, e = contact_force(q, v, bf, bt, fp, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c],
                                             m.pair_c[c], m.pair_dmax[c], m.pair_fric[c], delta, mx, my, mz,
                                             px, py, pz)
                _note_friction(imp, fpts, fcnt, a, b, u, ft, mx, my, mz, px, py, pz)
            fn_sum += fn
            ft_sum += ft
            e_sum += e
            if fn > f_max:
                f_max, u_max = fn, u
        if jm >= 0:
            _flush_rows(w.flex_row, w.flex_field, n, m.samp_disp, m.samp_rot, w.modal_f[o0:o1])
        _store(w, c, fn_sum, dmax, u_max, ft_sum)
        w.contact_angle[c] = 0.0
    return e_sum


@njit(cache=True)
def _external_loads(m, q, w, t):
    for i in range(m.body_mass.shape[0]):
        for j in range(3):
            w.body_f[i, j] = m.body_force[i, j]
            w.body_t[i, j] = m.body_force[i, 3 + j]
    for l in range(m.load_body.shape[0]):
        spline_value(m.knot_t, m.knot_coef, m.load_off[l], m.load_off[l + 1], t, w.load)
        i = m.load_body[l]
        for j in range(3):
            w.body_f[i, j] += w.load[j]
            w.body_t[i, j] += w.load[3 + j]


@njit(cache=True)
def _small_rotation(qa, qb, qr):
    """Rotation vector (≈ small angles, rad) of q_a⁻¹ q_b relative to the reference q_r, in a's frame."""
    # e = (q_a⁻¹ q_b) q_r⁻¹ = q_a⁻¹ (q_b q_b,rest⁻¹) q_a: b's turn from its rest pose q_a q_r, in a's axes
    # (q_r⁻¹ (q_a⁻¹ q_b) would give it in b's axes). Small angles: rotation vector ≈ 2 e_vec sign(e_w)
    aw, ax, ay, az = qa[0], -qa[1], -qa[2], -qa[3]
    bw, bx, by, bz = qb[0], qb[1], qb[2], qb[3]
    dw = aw * bw - ax * bx - ay * by - az * bz
    dx = aw * bx + ax * bw + ay * bz - az * by
    dy = aw * by - ax * bz + ay * bw + az * bx
    dz = aw * bz + ax * by - ay * bx + az * bw
    rw, rx, ry, rz = qr[0], -qr[1], -qr[2], -qr[3]
    ew = dw * rw - dx * rx - dy * ry - dz * rz
    ex = dw * rx + dx * rw + dy * rz - dz * ry
    ey = dw * ry - dx * rz + dy * rw + dz * rx
    ez = dw * rz + dx * ry - dy * rx + dz * rw
    s = 2.0 if ew >= 0.0 else -2.0
    return s * ex, s * ey, s * ez


@njit(cache=True)
def _bushings(m, q, v, w):
    """Penalty bushings: diagonal stiffness/damping in body a's frame (translations, small rotations)."""
    energy = 0.0
    for j in range(m.bush_a.shape[0]):
        a, b = m.bush_a[j], m.bush_b[j]
        pax, pay, paz = _to_world(q, a, m.bush_p_a[j, 0], m.bush_p_a[j, 1], m.bush_p_a[j, 2])
        pbx, pby, pbz = _to_world(q, b, m.bush_p_b[j, 0], m.bush_p_b[j, 1], m.bush_p_b[j, 2])
        dx, dy, dz = rotate_back(q, a, pbx - pax, pby - pay, pbz - paz)
        vax, vay, vaz = point_velocity(q, v, a, pax, pay, paz)
        vbx, vby, vbz = point_velocity(q, v, b, pbx, pby, pbz)
        ux, uy, uz = rotate_back(q, a, vbx - vax, vby - vay, vbz - vaz)
        rx, ry, rz = _small_rotation(q[a, 3:], q[b, 3:], m.bush_q_ref[j])
        obx, oby, obz = rotate(q, b, v[b, 3], v[b, 4], v[b, 5])
        oax, oay, oaz = rotate(q, a, v[a, 3], v[a, 4], v[a, 5])
        wx, wy, wz = rotate_back(q, a, obx - oax, oby - oay, obz - oaz)
        k, cc = m.bush_k[j], m.bush_c[j]
        # force and moment on b, in a's frame
        fx, fy, fz = -k[0] * dx - cc[0] * ux, -k[1] * dy - cc[1] * uy, -k[2] * dz - cc[2] * uz
        tx, ty, tz = -k[3] * rx - cc[3] * wx, -k[4] * ry - cc[4] * wy, -k[5] * rz - cc[5] * wz
        energy += 0.5 * (k[0] * dx * dx + k[1] * dy * dy + k[2] * dz * dz
                         + k[3] * rx * rx + k[4] * ry * ry + k[5] * rz * rz)
        fx, fy, fz = rotate(q, a, fx, fy, fz)
        tx, ty, tz = rotate(q, a, tx, ty, tz)
        _add_force(q, w.body_f, w.body_t, b, fx, fy, fz, pbx, pby, pbz)
        _add_force(q, w.body_f, w.body_t, a, -fx, -fy, -fz, pbx, pby, pbz)
        w.body_t[b, 0] += tx
        w.body_t[b, 1] += ty
        w.body_t[b, 2] += tz
        w.body_t[a, 0] -= tx
        w.body_t[a, 1] -= ty
        w.body_t[a, 2] -= tz
    return energy


@njit(cache=True)
def compute_forces(m, t, q, v, eta, eta_dot, w):
    """Fill ``w.body_f``, ``w.body_t``, ``w.modal_f`` and the contact outputs at (t, q, v, η, η̇);
    returns (status, index)."""
    _external_loads(m, q, w, t)
    for k in range(w.modal_f.shape[0]):
        w.modal_f[k] = 0.0
    w.fric_n[0] = 0
    w.energy[1] = _bushings(m, q, v, w) if m.bush_a.shape[0] > 0 else 0.0
    e = 0.0
    n_of = w.type_count
    if n_of[BALL_GROOVE] > 0:
        e += _ball_groove_pairs(m, q, v, eta, eta_dot, w)
    if n_of[BALL_BALL] > 0:
        e += _ball_ball_pairs(m, q, v, w)
    if n_of[ROLLER_RACEWAY] > 0:
        e += _roller_raceway_pairs(m, q, v, eta, eta_dot, w)
    if n_of[ROLLER_RIB] > 0:
        e += _roller_rib_pairs(m, q, v, eta, eta_dot, w)
    if n_of[ELEMENT_POCKET] > 0:
        e += _element_pocket_pairs(m, q, v, eta, eta_dot, w)
    w.energy[0] = e
    if w.fric_pts.shape[0] > 0:
        _friction_damping_matrices(m, q, v, w)
    for c in range(m.pair_type.shape[0]):
        if not (math.isfinite(w.contact_fn[c]) and math.isfinite(w.contact_ft[c])):
            return STATUS_NONFINITE, c
        if w.contact_delta[c] > m.pair_delta_max[c]:
            return STATUS_PENETRATION, c
    for i in range(m.body_mass.shape[0]):
        for j in range(3):
            if not (math.isfinite(w.body_f[i, j]) and math.isfinite(w.body_t[i, j])):
                return STATUS_NONFINITE, m.pair_type.shape[0] + i
    return STATUS_OK, -1
