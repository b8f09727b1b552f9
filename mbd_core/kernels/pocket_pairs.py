"""Element–pocket contact stage: a ball or roller in its cage pocket (cylindrical or slot pocket,
rigid or modal cage)."""

from __future__ import annotations

import math

from numba import njit

from .body_frames import rotate, _in_frame, _roller_axis, _to_world
from .element_contacts import POCKET_CYLINDER, pocket_cylinder, pocket_slot
from .flexible_surface import _flexible_point, _flush_rows, _wall_corners
from .friction_damping import _note_friction
from .pair_types import ELEMENT_POCKET
from .point_contact import contact_force, _store


@njit(cache=True, _nrt=False)
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
        bpx = bpy = bpz = bmx = bmy = bmz = 0.0
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
                n, fn, delta, u, ft, e, px, py, pz, mx, my, mz = _flexible_point(
                    m, q, v, eta, eta_dot, w, c, a, b, o0, o1, n, delta, plx, ply, plz, nx, ny, nz, imp, fpts, fcnt)
            else:
                px, py, pz = _to_world(q, b, plx, ply, plz)
                mx, my, mz = rotate(q, b, nx, ny, nz)
            if delta > dmax:
                dmax = delta
                if f_max < 0.0:  # the deepest wall while none is loaded
                    bpx, bpy, bpz, bmx, bmy, bmz = px, py, pz, mx, my, mz
            if delta <= 0.0:
                continue
            if jm < 0:
                fn, u, ft, e = contact_force(q, v, bf, bt, fp, c, a, b, m.pair_law[c], m.pair_k[c], m.pair_n[c],
                                             m.pair_c[c], m.pair_dmax[c], m.pair_fric[c], delta, mx, my, mz,
                                             px, py, pz)
                _note_friction(imp, fpts, fcnt, a, b, c, fn, u, ft, mx, my, mz, px, py, pz)
            fn_sum += fn
            ft_sum += ft
            e_sum += e
            if fn > f_max:
                f_max, u_max = fn, u
                bpx, bpy, bpz, bmx, bmy, bmz = px, py, pz, mx, my, mz
        if jm >= 0:
            _flush_rows(w.flex_row, w.flex_field, n, m.samp_disp, m.samp_rot, w.modal_f[o0:o1])
        _store(w, c, fn_sum, dmax, u_max, ft_sum, bpx, bpy, bpz, bmx, bmy, bmz)
        w.contact_angle[c] = 0.0
    return e_sum
