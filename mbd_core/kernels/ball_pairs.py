"""Ball contact stages: ball–groove pairs (rigid or modal rings) and ball–ball pairs (spacer balls,
full-complement neighbours).

A ball–groove pair with strips (``m.pair_strips[c] > 0``) takes its traction from the
slip distribution over the contact ellipse (:mod:`.strip_traction`): x the rolling direction (the
groove's circumferential direction e_θ at the ball, projected on the tangent plane), y = m × x the
major axis, z = x × y = m the normal of the force on the ball; the slip is that of the ball's surface
relative to the ring's at the contact centre, ω_ball − ω_ring in that frame, the semi-major axis
a = c·F_n^(1/3) and the curvature κ = 1/(2R_d) of the deformed contact surface across it
(``m.pair_strip_curv``). The ball gets F_n m + F_x x + F_y y at the contact point and the strips'
moment M_x x + M_y y + M_z m about it; the ring the opposite. On a modal ring's groove the slip and the
spin are taken against the section's own motion as well, and the ring's share goes to its modal forces
(:func:`_flexible_strips`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .ball_groove import groove_point_in
from .body_frames import point_velocity, rotate, rotate_back, _add_force, _in_frame, _to_world
from .element_contacts import ball_ball
from .flexible_surface import (_add_section_force, _nearest_deformed_centre, _section_motion, _section_velocity,
                               open_beyond_bound)
from .friction_damping import _note_friction
from .pair_types import BALL_BALL, BALL_GROOVE
from .laws import normal_force_elastic
from .point_contact import contact_force, point_force, _store
from .raceway import interp_index
from .strip_traction import strip_traction_forces


@njit(cache=True, _nrt=False)
def _strip_contact(q, v, bf, bt, fp, c, a, b, law, k, n_exp, damping, d_max, fric, n_strips, a_coef, curvature,
                   delta, mx, my, mz, px, py, pz, ex, ey, ez, wx, wy, wz, sx_b, sy_b, sz_b, imp, fpts, fcnt, each, table):
    """Normal force and strip traction of a ball contact (module docstring); (ex, ey, ez) the rolling
    direction, world; (wx, wy, wz) and (sx_b, sy_b, sz_b) the velocity and the angular velocity of
    ring b's surface at the contact beyond its frame's motion (a modal ring's section; zeros on a
    rigid ring), world. Applies the force and the strips' moment to a and b's frames, notes each
    slipping strip at its point p + ȳ y + z(ȳ) m for implicit friction (``imp``, ``fpts``, ``fcnt`` as
    in :func:`.friction_damping._note_friction`; ``each`` scratch (≥ n_strips, 5); ``table`` the strips'
    geometry, :func:`.strip_traction.strip_table`) and returns (F_n N,
    |v_t| m/s at the centre, |F_t| N, elastic energy J, the force (3) N and moment (3) N·m on a, world)."""
    if delta <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    vax, vay, vaz = point_velocity(q, v, a, px, py, pz)
    vbx, vby, vbz = point_velocity(q, v, b, px, py, pz)
    rx, ry, rz = vax - vbx - wx, vay - vby - wy, vaz - vbz - wz
    vn = rx * mx + ry * my + rz * mz
    elastic = k * delta**n_exp
    fn = normal_force_elastic(law, elastic, delta, -vn, damping, d_max)
    d = ex * mx + ey * my + ez * mz
    xx, xy, xz = ex - d * mx, ey - d * my, ez - d * mz
    nx = math.sqrt(xx * xx + xy * xy + xz * xz)
    xx, xy, xz = xx / nx, xy / nx, xz / nx
    yx, yy, yz = my * xz - mz * xy, mz * xx - mx * xz, mx * xy - my * xx
    sx = rx * xx + ry * xy + rz * xz
    sy = rx * yx + ry * yy + rz * yz
    oax, oay, oaz = rotate(q, a, v[a, 3], v[a, 4], v[a, 5])
    obx, oby, obz = rotate(q, b, v[b, 3], v[b, 4], v[b, 5])
    ox, oy, oz = oax - obx - sx_b, oay - oby - sy_b, oaz - obz - sz_b
    tx, ty, tmx, tmy, tmz = 0.0, 0.0, 0.0, 0.0, 0.0
    if fn > 0.0:
        semi_major = a_coef * np.cbrt(fn)
        # the relative angular velocity in the contact frame (x rolling direction, y major axis, z normal)
        omx, omy, omz = ox * xx + oy * xy + oz * xz, ox * yx + oy * yy + oz * yz, ox * mx + oy * my + oz * mz
        if imp[a] == 0 and imp[b] == 0:   # no strip to note: the loop does not store them
            tx, ty, tmx, tmy, tmz = strip_traction_forces(fn, semi_major, sx, sy, omx, omy, omz, curvature, fric,
                                                          fp[c, 0], fp[c, 1], fp[c, 2], fp[c, 3], n_strips, None,
                                                          table)
        else:
            tx, ty, tmx, tmy, tmz = strip_traction_forces(fn, semi_major, sx, sy, omx, omy, omz, curvature, fric,
                                                          fp[c, 0], fp[c, 1], fp[c, 2], fp[c, 3], n_strips, each,
                                                          table)
            for i in range(n_strips):
                y, z, qi, ui, f = each[i, 0], each[i, 1], each[i, 2], each[i, 3], each[i, 4]
                _note_friction(imp, fpts, fcnt, a, b, c, qi, ui, f * ui, mx, my, mz, px + y * yx + z * mx,
                               py + y * yy + z * my, pz + y * yz + z * mz)
    fx = fn * mx + tx * xx + ty * yx
    fy = fn * my + tx * xy + ty * yy
    fz = fn * mz + tx * xz + ty * yz
    _add_force(q, bf, bt, a, fx, fy, fz, px, py, pz)
    _add_force(q, bf, bt, b, -fx, -fy, -fz, px, py, pz)
    # the strips' moment about the contact centre: M_x x + M_y y + M_z m
    gx = tmx * xx + tmy * yx + tmz * mx
    gy = tmx * xy + tmy * yy + tmz * my
    gz = tmx * xz + tmy * yz + tmz * mz
    bt[a, 0] += gx
    bt[a, 1] += gy
    bt[a, 2] += gz
    bt[b, 0] -= gx
    bt[b, 1] -= gy
    bt[b, 2] -= gz
    return (fn, math.sqrt(sx * sx + sy * sy), math.sqrt(tx * tx + ty * ty), elastic * delta / (n_exp + 1.0),
            fx, fy, fz, gx, gy, gz)


@njit(cache=True, inline="always", _nrt=False)
def _open_beyond_bound(theta, periodic, pts, bound, th, lx, ly, lz, delta, clearance_radius, nx, ny, nz):
    """Whether a ball at l (ring frame, rigid-groove penetration δ, unit normal n from the groove's
    curvature centre) stays out of a modal ring's groove whatever its deformation: the deformed centre
    moves by at most U + R·|c − p_s| (``bound`` = the body's row of ``w.flex_bound``, :mod:`.forces`),
    and the nearest point of the deformed groove is no farther than that of θ."""
    if bound[0] == math.inf:
        return False
    i0, i1, w0, w1 = interp_index(theta, th, periodic)
    r = delta + clearance_radius
    return open_beyond_bound(bound, delta, lx - r * nx - (w0 * pts[i0, 0] + w1 * pts[i1, 0]),
                             ly - r * ny - (w0 * pts[i0, 1] + w1 * pts[i1, 1]),
                             lz - r * nz - (w0 * pts[i0, 2] + w1 * pts[i1, 2]))


@njit(cache=True, _nrt=False)
def _flexible_strips(m, q, v, eta_dot, w, c, a, b, o0, o1, disp, rot, i0, i1, w0, w1, bx, by, bz, th, delta,
                     mx, my, mz, px, py, pz, imp, fpts, fcnt):
    """Strip traction of a ball on a modal ring's groove (a loaded contact): the slip and spin taken
    against the section's own motion (velocity Dη̇ + (Ωη̇) × b and angular velocity Ωη̇ at the lever b
    from the raceway point), the force and the strips' moment on the ring also as its modal force
    Dᵀg + Ωᵀ(b × g + t) (g, t the force and moment on the ring, ring frame). Returns (F_n N, |v_t| m/s,
    |F_t| N, elastic energy J)."""
    vx, vy, vz, sx, sy, sz = _section_motion(disp, rot, i0, i1, w0, w1, eta_dot[o0:o1], bx, by, bz)
    vx, vy, vz = rotate(q, b, vx, vy, vz)
    sx, sy, sz = rotate(q, b, sx, sy, sz)
    ex, ey, ez = rotate(q, b, -math.sin(th), math.cos(th), 0.0)
    fn, u, ft, e, fx, fy, fz, tx, ty, tz = _strip_contact(
        q, v, w.body_f, w.body_t, m.pair_fric_p, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c],
        m.pair_dmax[c], m.pair_fric[c], m.pair_strips[c], m.pair_semi_major[c], m.pair_strip_curv[c], delta,
        mx, my, mz, px, py, pz, ex, ey, ez, vx, vy, vz, sx, sy, sz, imp, fpts, fcnt, w.strip_each, w.strip_table)
    gx, gy, gz = rotate_back(q, b, -fx, -fy, -fz)
    hx, hy, hz = rotate_back(q, b, -tx, -ty, -tz)
    _add_section_force(disp, rot, i0, i1, w0, w1, gx, gy, gz, by * gz - bz * gy + hx, bz * gx - bx * gz + hy,
                       bx * gy - by * gx + hz, w.modal_f[o0:o1])
    return fn, u, ft, e


@njit(cache=True, _nrt=False)
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
            if m.pair_strips[c] > 0:
                ex, ey, ez = rotate(q, b, -math.sin(th), math.cos(th), 0.0)
                fn, u, ft, e, _, _, _, _, _, _ = _strip_contact(
                    q, v, bf, bt, fp, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c], m.pair_dmax[c],
                    m.pair_fric[c], m.pair_strips[c], m.pair_semi_major[c], m.pair_strip_curv[c], delta, mx, my, mz,
                    px, py, pz, ex, ey, ez, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, imp, fpts, fcnt, w.strip_each, w.strip_table)
            else:
                fn, u, ft, e = contact_force(q, v, bf, bt, fp, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c],
                                             m.pair_c[c], m.pair_dmax[c], m.pair_fric[c], delta, mx, my, mz,
                                             px, py, pz)
                _note_friction(imp, fpts, fcnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz)
        else:
            # a groove on a modal ring (see _nearest_deformed_centre); the arrays are sliced here so
            # that no per-contact function takes the model tuple
            jm, s0, s1 = m.groove_modal[g], m.groove_samp_off[g], m.groove_samp_off[g + 1]
            o0, o1 = m.modal_off[jm], m.modal_off[jm + 1]
            disp, rot, pts = m.samp_disp[s0:s1], m.samp_rot[s0:s1], m.samp_point[s0:s1]
            i0, i1, w0, w1 = 0, 0, 0.0, 0.0
            if not _open_beyond_bound(m.samp_theta[s0:s1], m.groove_periodic[g] == 1, pts, w.flex_bound[jm], th,
                                      lx, ly, lz, delta, m.groove_r[g] - ra, nx, ny, nz):
                cx, cy, cz, i0, i1, w0, w1 = _nearest_deformed_centre(
                    m.samp_theta[s0:s1], m.groove_periodic[g] == 1, disp, rot, pts, eta[o0:o1], w.groove_rows,
                    m.groove_rc[g], m.groove_zc[g], m.groove_h, m.groove_h_off[g], m.groove_h_off[g + 1], m.groove_dr,
                    m.groove_dr_off[g], m.groove_dr_off[g + 1], th, lx, ly, lz)
                dx, dy, dz = lx - cx, ly - cy, lz - cz
                dist = math.sqrt(dx * dx + dy * dy + dz * dz)
                if dist > 0.0:
                    nx, ny, nz = dx / dist, dy / dist, dz / dist
                delta = dist - (m.groove_r[g] - ra)
            fn, u, ft, e = 0.0, 0.0, 0.0, 0.0
            # contact point (ring frame and world), normal of the force on the ball
            plx, ply, plz = lx + ra * nx, ly + ra * ny, lz + ra * nz
            px, py, pz = _to_world(q, b, plx, ply, plz)
            mx, my, mz = rotate(q, b, -nx, -ny, -nz)
            if delta > 0.0:
                # its lever about the raceway point, the modal velocity there
                bx = plx - (w0 * pts[i0, 0] + w1 * pts[i1, 0])
                by = ply - (w0 * pts[i0, 1] + w1 * pts[i1, 1])
                bz = plz - (w0 * pts[i0, 2] + w1 * pts[i1, 2])
                if m.pair_strips[c] > 0:
                    fn, u, ft, e = _flexible_strips(m, q, v, eta_dot, w, c, a, b, o0, o1, disp, rot, i0, i1, w0, w1,
                                                    bx, by, bz, th, delta, mx, my, mz, px, py, pz, imp, fpts,
                                                    fcnt)
                else:
                    vx, vy, vz = _section_velocity(disp, rot, i0, i1, w0, w1, eta_dot[o0:o1], bx, by, bz)
                    vx, vy, vz = rotate(q, b, vx, vy, vz)
                    vax, vay, vaz = point_velocity(q, v, a, px, py, pz)
                    vbx, vby, vbz = point_velocity(q, v, b, px, py, pz)
                    fn, u, ft, e, fx, fy, fz = point_force(m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c],
                                                           m.pair_dmax[c], m.pair_fric[c], fp[c, 0], fp[c, 1], fp[c, 2],
                                                           fp[c, 3], delta, mx, my, mz, vax - vbx - vx, vay - vby - vy,
                                                           vaz - vbz - vz)
                    _add_force(q, bf, bt, a, fx, fy, fz, px, py, pz)
                    _add_force(q, bf, bt, b, -fx, -fy, -fz, px, py, pz)
                    _note_friction(imp, fpts, fcnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz)
                    gx, gy, gz = rotate_back(q, b, -fx, -fy, -fz)
                    _add_section_force(disp, rot, i0, i1, w0, w1, gx, gy, gz, by * gz - bz * gy, bz * gx - bx * gz,
                                       bx * gy - by * gx, w.modal_f[o0:o1])
        _store(w, c, fn, delta, u, ft, px, py, pz, mx, my, mz)
        w.contact_theta[c] = th
        w.contact_angle[c] = math.atan2(abs(nz), abs(nx * math.cos(th) + ny * math.sin(th)))
        e_sum += e
    return e_sum


@njit(cache=True, _nrt=False)
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
        _note_friction(imp, fpts, fcnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz)
        _store(w, c, fn, delta, u, ft, px, py, pz, mx, my, mz)
        w.contact_angle[c] = 0.0
        e_sum += e
    return e_sum
