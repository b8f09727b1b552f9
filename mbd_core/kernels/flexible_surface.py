"""Contacts on the sampled surfaces of modal bodies: deformed grooves, (θ, s)-sampled raceways and
pocket walls, the cache of sample rows and the projection of the loads onto the modes (the scheme is
described in :mod:`.forces`)."""

from __future__ import annotations

import math

from numba import njit

from .ball_groove import TWO_PI
from .body_frames import point_velocity, rotate, rotate_back, _add_force, _contact_angle, _to_world
from .friction_damping import _note_friction
from .point_contact import point_force
from .raceway import interp_index
from .roller_slices import circle_index, surface_coordinate


@njit(cache=True, inline="always", _nrt=False)
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


#: factor on the motion bound of a sampled surface beyond which a contact's rigid-geometry gap counts
#: as open (:mod:`.forces`)
SKIP_MARGIN = 1.1

@njit(cache=True, inline="always", _nrt=False)
def open_beyond_bound(bound, delta, bx, by, bz):
    """Whether a contact of rigid-geometry penetration δ, at lever b from its interpolated sample
    point, stays open whatever its surface's deformation: δ + SKIP_MARGIN·(U + R·|b|) < 0, with
    ``bound`` the body's row (U, R, checks, skips) of ``w.flex_bound`` (:mod:`.forces`); counts the
    check and the skip."""
    bound[2] += 1.0
    if delta + SKIP_MARGIN * (bound[0] + bound[1] * math.sqrt(bx * bx + by * by + bz * bz)) < 0.0:
        bound[3] += 1.0
        return True
    return False


# The modal sums below run over the modes innermost, along the tables' contiguous axis, and may
# reassociate: LLVM then vectorises them (they differ from sequential sums by round-off only). They
# are not inlined into the force kernel, so that the flag stays theirs.
_SUMS = {"reassoc", "contract"}


@njit(cache=True, fastmath=_SUMS, _nrt=False)
def _section_velocity(disp, rot, i0, i1, w0, w1, ed, bx, by, bz):
    """Velocity (Dη̇) + (Ωη̇) × b of the raceway section's point at lever b from the sampled point,
    interpolated between samples i0, i1 (ring frame)."""
    vx, vy, vz, _, _, _ = _section_motion(disp, rot, i0, i1, w0, w1, ed, bx, by, bz)
    return vx, vy, vz


@njit(cache=True, fastmath=_SUMS, _nrt=False)
def _section_motion(disp, rot, i0, i1, w0, w1, ed, bx, by, bz):
    """:func:`_section_velocity` and the section's angular velocity Ωη̇ (ring frame): (v (3), ω (3))."""
    m = ed.shape[0]
    vx = vy = vz = sx = sy = sz = 0.0
    for k in range(m):
        vx += (w0 * disp[i0, 0, k] + w1 * disp[i1, 0, k]) * ed[k]
        sx += (w0 * rot[i0, 0, k] + w1 * rot[i1, 0, k]) * ed[k]
    for k in range(m):
        vy += (w0 * disp[i0, 1, k] + w1 * disp[i1, 1, k]) * ed[k]
        sy += (w0 * rot[i0, 1, k] + w1 * rot[i1, 1, k]) * ed[k]
    for k in range(m):
        vz += (w0 * disp[i0, 2, k] + w1 * disp[i1, 2, k]) * ed[k]
        sz += (w0 * rot[i0, 2, k] + w1 * rot[i1, 2, k]) * ed[k]
    return vx + sy * bz - sz * by, vy + sz * bx - sx * bz, vz + sx * by - sy * bx, sx, sy, sz


@njit(cache=True, fastmath=_SUMS, _nrt=False)
def _add_section_force(disp, rot, i0, i1, w0, w1, fx, fy, fz, tx, ty, tz, qf):
    """qf += Dᵀf + Ωᵀt at the interpolated section: the modal force of a force f and moment t (ring
    frame) on the raceway section — the transpose of :func:`_section_velocity`."""
    for k in range(qf.shape[0]):
        qf[k] += (w0 * (disp[i0, 0, k] * fx + disp[i0, 1, k] * fy + disp[i0, 2, k] * fz
                        + rot[i0, 0, k] * tx + rot[i0, 1, k] * ty + rot[i0, 2, k] * tz)
                  + w1 * (disp[i1, 0, k] * fx + disp[i1, 1, k] * fy + disp[i1, 2, k] * fz
                          + rot[i1, 0, k] * tx + rot[i1, 1, k] * ty + rot[i1, 2, k] * tz))


@njit(cache=True, fastmath=_SUMS, _nrt=False)
def _groove_rows(disp, rot, i0, i1, e_j, out):
    """out (4, 3) = D_i0 η, D_i1 η, Ω_i0 η, Ω_i1 η: the two samples around a contact, whose linear
    interpolation and difference quotient give the raceway's displacement, rotation and their slopes."""
    m = e_j.shape[0]
    for c in range(3):
        a0 = a1 = b0 = b1 = 0.0
        for k in range(m):
            ek = e_j[k]
            a0 += disp[i0, c, k] * ek
            a1 += disp[i1, c, k] * ek
            b0 += rot[i0, c, k] * ek
            b1 += rot[i1, c, k] * ek
        out[0, c], out[1, c], out[2, c], out[3, c] = a0, a1, b0, b1


@njit(cache=True, inline="always", _nrt=False)
def _deformed_groove_centre(theta, periodic, pts, rows, rc, zc, h_all, h0, h1, dr_all, dr0, dr1, th, cs, sn, i0, i1,
                            w0, w1):
    """Deformed curvature centre c'(θ) = c(θ) + u + ψ × (c − p_s) of a groove at angle θ ∈ [0, 2π) (ring
    frame; cs, sn = cos θ, sin θ) between samples i0, i1 (weights w0, w1; ``rows`` from :func:`_groove_rows`), and its
    θ-derivative. The derivative leaves out ψ × ∂(c − p_s)/∂θ, which turns the normal at the nearest
    point by about |ψ|·|c − p_s|/r (7e-5 of the force in the kernel tests); beyond the ends of a
    raceway sampled on an arc the deformation is held, so its slope there is zero."""
    dth = theta[i1] - theta[i0]
    if dth <= 0.0:
        dth += TWO_PI
    dr, dr_s = _table_slope(dr_all, dr0, dr1, th)
    h, h_s = _table_slope(h_all, h0, h1, th)
    r = rc + dr
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


@njit(cache=True, inline="always", _nrt=False)
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
    once per pair of samples (``rows``, scratch (4, 3)). θ is the ball's angle atan2(l_y, l_x), whose cosine
    and sine are l_x/ρ, l_y/ρ; a step d turns them by the rotation (cos d, sin d), taken from their
    Taylor series to d⁵ when |d| < 1e-4 (truncation below 2e-27), so that the iteration needs no cos and sin
    (:func:`_turn`). Returns (c'(θ*), i0, i1, w0, w1)."""
    ts = th
    rho = math.sqrt(lx * lx + ly * ly)
    cs, sn = (lx / rho, ly / rho) if rho > 0.0 else (math.cos(th), math.sin(th))
    r0, r1 = -1, -1
    for it in range(3):
        ts = ts % TWO_PI
        i0, i1, w0, w1 = interp_index(theta, ts, periodic)
        if i0 != r0 or i1 != r1:
            _groove_rows(disp, rot, i0, i1, e_j, rows)
            r0, r1 = i0, i1
        cx, cy, cz, tx, ty, tz = _deformed_groove_centre(theta, periodic, pts, rows, rc, zc, h_all, h0, h1, dr_all,
                                                         dr0, dr1, ts, cs, sn, i0, i1, w0, w1)
        if it < 2:
            d = ((lx - cx) * tx + (ly - cy) * ty + (lz - cz) * tz) / (tx * tx + ty * ty + tz * tz)
            ts += d
            cs, sn = _turn(cs, sn, d, ts)
    return cx, cy, cz, i0, i1, w0, w1


@njit(cache=True, inline="always", _nrt=False)
def _turn(cs, sn, d, th):
    """(cos, sin) of θ = θ₀ + d from those of θ₀: by the rotation through d (series to d⁵ for |d| < 1e-4),
    else cos θ, sin θ."""
    if abs(d) < 1e-4:
        d2 = d * d
        cd = 1.0 - d2 * (0.5 - d2 / 24.0)
        sd = d * (1.0 - d2 * (1.0 / 6.0 - d2 / 120.0))
        return cs * cd - sn * sd, sn * cd + cs * sd
    return math.cos(th), math.sin(th)


@njit(cache=True, inline="always", _nrt=False)
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


@njit(cache=True, inline="always", _nrt=False)
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


@njit(cache=True, inline="always", _nrt=False)
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


@njit(cache=True, inline="always", _nrt=False)
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
@njit(cache=True, inline="always", _nrt=False)
def _flexible_contact(q, v, bf, bt, disp, rot, pts, e_j, ed_j, rows, field, corner, weight, n, a, b, law, k_c,
                      n_exp, damping, d_max, fric, fp_c, sd, sp, sn, k, bound):
    """Contact point l = sp[k] (ring frame) of a pair on a sampled surface of modal body b, normal n = sn[k]
    of the force on a (ring frame), rigid-geometry penetration δ = sd[k]; the corners in ``corner[:, 0]``
    and ``weight``, the tables samp_disp, samp_rot, samp_point. Penetration δ + n·d, surface velocity in
    the slip, force on both frames, load gathered on the cached rows (module docstring; ``n`` slots of
    the cache ``rows``, ``field`` in use, at least four free). ``bound``: the body's row of
    ``w.flex_bound`` (a contact open beyond it is skipped, :mod:`.forces`). Returns (n, F_n, δ + n·d,
    |v_t|, |F_t|, energy, p world, m world)."""
    lx, ly, lz, nx, ny, nz, delta = sp[k, 0], sp[k, 1], sp[k, 2], sn[k, 0], sn[k, 1], sn[k, 2], sd[k]
    if bound[0] < math.inf:
        psx = psy = psz = 0.0
        for i in range(4):
            row, cw = corner[i, 0], weight[i]
            psx += cw * pts[row, 0]
            psy += cw * pts[row, 1]
            psz += cw * pts[row, 2]
        if open_beyond_bound(bound, delta, lx - psx, ly - psy, lz - psz):
            px, py, pz = _to_world(q, b, lx, ly, lz)
            mx, my, mz = rotate(q, b, nx, ny, nz)
            return n, 0.0, delta, 0.0, 0.0, 0.0, px, py, pz, mx, my, mz
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


@njit(cache=True, inline="always", _nrt=False)
def _flexible_point(m, q, v, eta, eta_dot, w, c, a, b, o0, o1, n, delta, lx, ly, lz, nx, ny, nz, imp, fpts, fcnt):
    """:func:`_flexible_contact` of one point of pair c (a roller end, a pocket wall; corners set, at most
    two points per pair, so the cache has room) through slot 0 of the slice scratch; returns (n, F_n,
    δ + n·d, |v_t|, |F_t|, energy, p world, m world)."""
    sd, sp, sn = w.slice_delta, w.slice_point, w.slice_normal
    sd[0], sp[0, 0], sp[0, 1], sp[0, 2], sn[0, 0], sn[0, 1], sn[0, 2] = delta, lx, ly, lz, nx, ny, nz
    n, fn, delta, u, ft, e, px, py, pz, mx, my, mz = _flexible_contact(
        q, v, w.body_f, w.body_t, m.samp_disp, m.samp_rot, m.samp_point, eta[o0:o1], eta_dot[o0:o1], w.flex_row,
        w.flex_field, w.flex_corner, w.flex_weight, n, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c],
        m.pair_dmax[c], m.pair_fric[c], m.pair_fric_p[c], sd, sp, sn, 0, w.flex_bound[m.body_modal[b]])
    _note_friction(imp, fpts, fcnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz)
    return n, fn, delta, u, ft, e, px, py, pz, mx, my, mz


@njit(cache=True, inline="always", _nrt=False)
def _flexible_roller_raceway(m, q, v, eta, eta_dot, w, c, a, b, g, ns, imp, fpts, fcnt):
    """The slices of roller pair c (rigid geometry in ``w.slice_*``) on the (θ, s)-sampled surface g of
    modal ring b. Returns (ΣF_n, largest δ, slip at the most loaded slice, Σ|F_t|, its contact angle,
    energy, the point and normal (world) of the most loaded slice, or of the deepest when none is loaded)."""
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
    fric, fp_c, bound = m.pair_fric[c], m.pair_fric_p[c], w.flex_bound[jm]
    fn_sum, dmax, u_at_max, ft_sum, f_max, angle, e_sum = 0.0, -math.inf, 0.0, 0.0, -1.0, 0.0, 0.0
    bpx = bpy = bpz = bmx = bmy = bmz = 0.0
    n = 0
    for k in range(ns):
        _grid_corners(theta, periodic, circ, kind, s0, sp[k, 0], sp[k, 1], sp[k, 2], corner, weight)
        if n > rows.shape[0] - 4:
            _flush_rows(rows, field, n, disp, rot, qf)
            n = 0
        n, fn, delta, u, ft, e, px, py, pz, mx, my, mz = _flexible_contact(
            q, v, bf, bt, disp, rot, pts, e_j, ed_j, rows, field, corner, weight, n, a, b, law, k_c, n_exp,
            damp, d_mx, fric, fp_c, sd, sp, sn, k, bound)
        if delta > dmax:
            dmax = delta
            if f_max < 0.0:
                bpx, bpy, bpz, bmx, bmy, bmz = px, py, pz, mx, my, mz
        if delta <= 0.0:
            continue
        _note_friction(imp, fpts, fcnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz)
        fn_sum += fn
        ft_sum += ft
        e_sum += e
        if fn > f_max:
            f_max, u_at_max = fn, u
            angle = _contact_angle(q, b, mx, my, mz, px, py, pz)
            bpx, bpy, bpz, bmx, bmy, bmz = px, py, pz, mx, my, mz
    _flush_rows(rows, field, n, disp, rot, qf)
    return fn_sum, dmax, u_at_max, ft_sum, angle, e_sum, bpx, bpy, bpz, bmx, bmy, bmz
