"""Squeeze-film dampers between a journal (a bearing's outer race, body a) and its housing (body b).

The film force comes from the damper's table (:class:`mbd_core.squeeze_film.force_table.FilmForceTable`):
with d the journal centre's offset from the bore centre across the bore axis n (housing frame
turned to world), e = |d|, ε = e/c, e_r = d/e (at e = 0 the direction of the relative velocity),
e_t = n × e_r, and V the journal centre's velocity relative to the housing's material point there,

    F = |V|/(1 − ε²)² · (T_r e_r + T_t e_t),   T bilinear in (u(ε), ψ),   ψ = atan2(V·e_t, V·e_r),

u(ε) = 1 − √(1 − ε/ε_max) the table's ε coordinate. The journal gets F at its centre, the housing
−F there. Only the film's force is modelled (no moment of a tilted journal). Returns the index of a
damper whose ε exceeds its table's end (the journal then rides on the housing), or −1.
"""

from __future__ import annotations

import math

from numba import njit

from .body_frames import _add_force, _to_world, relative_velocity_across, rotate


@njit(cache=True, _nrt=False)
def film_table_force(table, n_eps, n_psi, eps_max, eps, vr, vt):
    """(F_r, F_t) of one damper from its table rows ``table`` (n_eps·n_psi, 2), N."""
    speed = math.sqrt(vr * vr + vt * vt)
    if speed == 0.0:
        return 0.0, 0.0
    x = (1.0 - math.sqrt(max(1.0 - eps / eps_max, 0.0))) * (n_eps - 1)
    i = min(int(x), n_eps - 2)
    a = x - i
    psi = math.atan2(vt, vr)
    if psi < 0.0:
        psi += 2.0 * math.pi
    y = psi / (2.0 * math.pi) * n_psi
    j = int(y)
    b = y - j
    j = j % n_psi
    j1 = (j + 1) % n_psi
    r00, r10 = i * n_psi + j, (i + 1) * n_psi + j
    r01, r11 = i * n_psi + j1, (i + 1) * n_psi + j1
    s = speed / (1.0 - eps * eps) ** 2
    fr = (1 - a) * (1 - b) * table[r00, 0] + a * (1 - b) * table[r10, 0] + (1 - a) * b * table[r01, 0] + a * b * table[r11, 0]
    ft = (1 - a) * (1 - b) * table[r00, 1] + a * (1 - b) * table[r10, 1] + (1 - a) * b * table[r01, 1] + a * b * table[r11, 1]
    return s * fr, s * ft


@njit(cache=True, _nrt=False)
def _squeeze_films(m, q, v, w):
    """Add every damper's film force to ``w.body_f``/``w.body_t``; the index of a damper beyond its
    table's ε_max, or −1."""
    for j in range(m.sfd_a.shape[0]):
        a, b = m.sfd_a[j], m.sfd_b[j]
        pax, pay, paz = _to_world(q, a, m.sfd_p_a[j, 0], m.sfd_p_a[j, 1], m.sfd_p_a[j, 2])
        pbx, pby, pbz = _to_world(q, b, m.sfd_p_b[j, 0], m.sfd_p_b[j, 1], m.sfd_p_b[j, 2])
        nx, ny, nz = rotate(q, b, m.sfd_axis[j, 0], m.sfd_axis[j, 1], m.sfd_axis[j, 2])
        dx, dy, dz = pax - pbx, pay - pby, paz - pbz
        s = dx * nx + dy * ny + dz * nz
        dx, dy, dz = dx - s * nx, dy - s * ny, dz - s * nz
        ux, uy, uz, _ = relative_velocity_across(q, v, a, b, pax, pay, paz, nx, ny, nz)
        e = math.sqrt(dx * dx + dy * dy + dz * dz)
        eps = e / m.sfd_clearance[j]
        if eps > m.sfd_eps_max[j]:
            return j
        speed = math.sqrt(ux * ux + uy * uy + uz * uz)
        if speed == 0.0:
            continue
        if e > 1e-12 * m.sfd_clearance[j]:
            rx, ry, rz = dx / e, dy / e, dz / e
        else:
            rx, ry, rz = ux / speed, uy / speed, uz / speed
        tx, ty, tz = ny * rz - nz * ry, nz * rx - nx * rz, nx * ry - ny * rx
        o0, o1 = m.sfd_table_off[j], m.sfd_table_off[j + 1]
        fr, ft = film_table_force(m.sfd_table[o0:o1], m.sfd_table_size[j, 0], m.sfd_table_size[j, 1],
                                  m.sfd_eps_max[j], eps, ux * rx + uy * ry + uz * rz, ux * tx + uy * ty + uz * tz)
        fx, fy, fz = fr * rx + ft * tx, fr * ry + ft * ty, fr * rz + ft * tz
        _add_force(q, w.body_f, w.body_t, a, fx, fy, fz, pax, pay, paz)
        _add_force(q, w.body_f, w.body_t, b, -fx, -fy, -fz, pax, pay, paz)
    return -1
