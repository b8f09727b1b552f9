"""Roller contact stages: roller–raceway pairs by slices (rigid or modal rings) and roller end–rib pairs."""

from __future__ import annotations

import math

from numba import njit

from .body_frames import rotate, _contact_angle, _in_frame, _roller_axis, _to_world
from .element_contacts import roller_end
from .flexible_surface import _flexible_point, _flexible_roller_raceway, _flush_rows, _grid_corners
from .friction_damping import _note_friction
from .pair_types import ROLLER_RACEWAY, ROLLER_RIB
from .point_contact import contact_force, point_force, _store
from .roller_slices import roller_slices


@njit(cache=True, _nrt=False)
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
            fn_sum, dmax, u_at_max, ft_sum, angle, e, px, py, pz, mx, my, mz = _flexible_roller_raceway(
                m, q, v, eta, eta_dot, w, c, a, b, g, ns, imp, fpts, fcnt)
            e_sum += e
            _store(w, c, fn_sum, dmax, u_at_max, ft_sum, px, py, pz, mx, my, mz)
            w.contact_angle[c] = angle
            continue
        fn_sum, dmax, u_at_max, ft_sum, f_max, angle = 0.0, -math.inf, 0.0, 0.0, -1.0, 0.0
        # the slices share both bodies: their angular velocities once, forces summed per pair
        oax, oay, oaz = rotate(q, a, v[a, 3], v[a, 4], v[a, 5])
        obx, oby, obz = rotate(q, b, v[b, 3], v[b, 4], v[b, 5])
        law, k_s, n_exp, damp, d_mx, fric = m.pair_law[c], m.pair_k[c], m.pair_n[c], m.pair_c[c], m.pair_dmax[c], m.pair_fric[c]
        p0, p1, p2, p3 = fp[c, 0], fp[c, 1], fp[c, 2], fp[c, 3]
        fxs = fys = fzs = tax = tay = taz = tbx = tby = tbz = 0.0
        k_deep, k_max = 0, -1
        for k in range(ns):
            delta = sd[k]
            if delta > dmax:
                dmax, k_deep = delta, k
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
            _note_friction(imp, fpts, fcnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz)
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
                k_max = k
        # the point and normal of the most loaded slice, or of the deepest when none is loaded
        k = k_max if k_max >= 0 else k_deep
        px, py, pz = _to_world(q, b, sp[k, 0], sp[k, 1], sp[k, 2])
        mx, my, mz = rotate(q, b, sn[k, 0], sn[k, 1], sn[k, 2])
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
        _store(w, c, fn_sum, dmax, u_at_max, ft_sum, px, py, pz, mx, my, mz)
        w.contact_angle[c] = angle
    return e_sum


@njit(cache=True, _nrt=False)
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
            n, fn, delta, u, ft, e, px, py, pz, mx, my, mz = _flexible_point(
                m, q, v, eta, eta_dot, w, c, a, b, o0, o1, 0, delta, point[0], point[1], point[2], nx, ny, nz, imp,
                fpts, fcnt)
            _flush_rows(w.flex_row, w.flex_field, n, m.samp_disp, m.samp_rot, w.modal_f[o0:o1])
            _store(w, c, fn, delta, u, ft, px, py, pz, mx, my, mz)
            w.contact_angle[c] = 0.0
            e_sum += e
            continue
        px, py, pz = _to_world(q, b, point[0], point[1], point[2])
        mx, my, mz = rotate(q, b, nx, ny, nz)
        fn, u, ft, e = contact_force(q, v, bf, bt, fp, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c],
                                     m.pair_c[c], m.pair_dmax[c], m.pair_fric[c], delta, mx, my, mz, px, py, pz)
        _note_friction(imp, fpts, fcnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz)
        _store(w, c, fn, delta, u, ft, px, py, pz, mx, my, mz)
        w.contact_angle[c] = 0.0
        e_sum += e
    return e_sum
