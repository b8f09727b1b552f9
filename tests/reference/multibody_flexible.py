"""Plain-numpy twins of the force stage on modal bodies' surfaces (part of :mod:`tests.reference.multibody`).

A groove on a modal ring (groove_modal ≥ 0) deforms with the ring's modal coordinates η: its curvature
centre goes to c'(θ) = c(θ) + u(θ) + ψ(θ) × (c(θ) − p_s(θ)), u = D(θ) η and ψ = Ω(θ) η with D, Ω and the
raceway point p_s interpolated linearly in θ between the samples. The ball touches at the nearest
point θ* of that curve, found here by a bounded scalar minimisation of |x − c'(θ)|² near the ball's
angle and polished to round-off on the exact stationarity condition (x − c')·∂c'/∂θ = 0 (with the
lever's θ-derivative). The raceway's material point at the contact point p moves with
u̇ + ψ̇ × (p − p_s); the force g on the ring there gives the modal force Dᵀg + Ωᵀ((p − p_s) × g).

A roller raceway or rib on a modal ring (race_modal ≥ 0) is sampled on circles of samples at coordinates
s_j across it (z on a cylinder, r on a plane): the tables at a point (θ, s) are each circle's table
interpolated in θ as above, then combined with the weights of s on the circles (np.interp of the unit
vectors: linear between neighbours, the end circle beyond the ends). A cage pocket (pocket_modal ≥ 0) has
its two wall samples, combined with the weights of the contact point's projection on the segment between
them (clamped). In both the contact point p and the normal n are those of the rigid geometry; the
penetration grows by n·(u + ψ × (p − p_s)), and velocity and modal force are as for grooves.
"""

from collections import namedtuple

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from .multibody import (INNER_CYLINDER, OUTER_CYLINDER, ROLLER_RACEWAY, _points_element_pocket, _roller_in_ring,
                        roller_end)
from .roller_slices import roller_slices

# -- flexible grooves on modal rings ---------------------------------------------------------------
#: A flexible ring's surface at a contact point: its modal coordinates (slice of η), the world velocity of
#: its material point there beyond the rigid frame motion, the map of a force (and a moment) on the element
#: (world) to the ring's modal force, and (grooves) the section's angular velocity Ωη̇ beyond the frame's, world.
Surface = namedtuple("Surface", "modes velocity modal_force omega", defaults=(None,))
TWO_PI = 2.0 * np.pi


def _linear(grid, values, x):
    """Value and slope at x of the piecewise-linear interpolation of values (n, ...) on the ascending grid,
    on the interval [grid[i], grid[i + 1]) that holds x (the last one at its right end)."""
    i = int(np.clip(np.searchsorted(grid, x, side="right") - 1, 0, len(grid) - 2))
    slope = (values[i + 1] - values[i]) / (grid[i + 1] - grid[i])
    return values[i] + (x - grid[i]) * slope, slope


def _periodic(grid, values, x):
    """:func:`_linear` on a full circle: grid (n,) ascending within [grid[0], grid[0] + 2π), x any angle."""
    if len(values) == 1:
        return values[0], np.zeros_like(values[0])
    x0 = grid[0]
    return _linear(np.append(grid, x0 + TWO_PI), np.concatenate([values, values[:1]]), x0 + np.mod(x - x0, TWO_PI))


def _groove_table(table, off, g, th):
    """Undulation or radial offset of groove g (uniform table over [0, 2π)) and its θ-slope."""
    t = table[off[g]:off[g + 1]]
    return _periodic(TWO_PI * np.arange(len(t)) / len(t), t, th)


def raceway_tables(m, g):
    """The raceway samples of flexible groove g: (θ (n,), p_s (n, 3), D (n, 3, k), Ω (n, 3, k), periodic,
    slice of η of its ring), the tables cut to the ring's k modes."""
    j, s0, s1 = m.groove_modal[g], m.groove_samp_off[g], m.groove_samp_off[g + 1]
    o0, o1 = m.modal_off[j], m.modal_off[j + 1]
    k = o1 - o0
    return (m.samp_theta[s0:s1], m.samp_point[s0:s1], m.samp_disp[s0:s1, :, :k], m.samp_rot[s0:s1, :, :k],
            m.groove_periodic[g] == 1, slice(o0, o1))


def _sampled(theta, table, periodic, th):
    """A sampled table (n, ...) at angle θ and its θ-slope: periodic, or held at the ends of its range."""
    if periodic:
        return _periodic(theta, table, th)
    if th <= theta[0] or th >= theta[-1]:
        return table[0 if th <= theta[0] else -1], np.zeros_like(table[0])
    return _linear(theta, table, th)


def deformed_groove_centre(m, g, eta_ring, th):
    """c'(θ) = c + u + ψ × (c − p_s) of flexible groove g (ring frame), its exact θ-derivative (the
    lever's change included), and the interpolated (D (3, k), Ω (3, k), p_s (3,)) at θ."""
    theta, points, disp, rot, periodic, _ = raceway_tables(m, g)
    h, h_s = _groove_table(m.groove_h, m.groove_h_off, g, th)
    dr, dr_s = _groove_table(m.groove_dr, m.groove_dr_off, g, th)
    e_r, e_t = np.array([np.cos(th), np.sin(th), 0.0]), np.array([-np.sin(th), np.cos(th), 0.0])
    c = (m.groove_rc[g] + dr) * e_r + [0.0, 0.0, m.groove_zc[g] + h]
    c_s = (m.groove_rc[g] + dr) * e_t + dr_s * e_r + [0.0, 0.0, h_s]
    D, D_s = _sampled(theta, disp, periodic, th)
    W, W_s = _sampled(theta, rot, periodic, th)
    P, P_s = _sampled(theta, points, periodic, th)
    psi = W @ eta_ring
    centre = c + D @ eta_ring + np.cross(psi, c - P)
    tangent = c_s + D_s @ eta_ring + np.cross(W_s @ eta_ring, c - P) + np.cross(psi, c_s - P_s)
    return centre, tangent, (D, W, P)


def nearest_groove_angle(m, g, eta_ring, x, th_ball, span=0.05):
    """θ* minimising |x − c'(θ)| within th_ball ± span (rad): bounded Brent on the squared distance, then
    the root of (x − c')·∂c'/∂θ in the smallest bracket around it that changes sign (brentq)."""
    def dist2(s):
        d = x - deformed_groove_centre(m, g, eta_ring, th_ball + s)[0]
        return d @ d

    def slope(s):
        centre, tangent, _ = deformed_groove_centre(m, g, eta_ring, th_ball + s)
        return (x - centre) @ tangent

    s = minimize_scalar(dist2, bounds=(-span, span), method="bounded", options={"xatol": 1e-14}).x
    if slope(s) == 0.0:
        return th_ball + s
    for w in 10.0 ** np.arange(-13, 0):
        lo, hi = max(s - w, -span), min(s + w, span)
        if slope(lo) * slope(hi) <= 0.0:
            return th_ball + brentq(slope, lo, hi, xtol=1e-19, rtol=4 * np.finfo(float).eps)
    raise ValueError(f"groove {g}: no nearest point within ±{span} rad of the ball angle {th_ball}")


def _points_flexible_groove(m, bodies, c, eta, eta_dot, nearest=nearest_groove_angle):
    """Contact point of a ball on a flexible groove at the groove angle ``nearest(m, g, η_ring, x, θ_ball)``
    (x the ball centre in the ring frame), by default the nearest point θ*."""
    a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
    ra = m.pair_radius[c]
    x = bodies.to_local(b, bodies.r[a])
    th_ball = np.mod(np.arctan2(x[1], x[0]), TWO_PI)
    th_ball = th_ball - TWO_PI if th_ball >= TWO_PI else th_ball
    modes = raceway_tables(m, g)[-1]
    th = nearest(m, g, eta[modes], x, th_ball)
    centre, _, (D, W, P) = deformed_groove_centre(m, g, eta[modes], th)
    d = x - centre
    dist = np.linalg.norm(d)
    n = d / dist
    p_ring = x + ra * n
    lever = p_ring - P
    R = bodies.R[b]
    velocity = R @ (D @ eta_dot[modes] + np.cross(W @ eta_dot[modes], lever))

    def modal_force(force_on_element, moment_on_element=np.zeros(3)):
        on_ring, turning = R.T @ -force_on_element, R.T @ -moment_on_element
        return D.T @ on_ring + W.T @ (np.cross(lever, on_ring) + turning)

    point = (dist - (m.groove_r[g] - ra), -(R @ n), bodies.to_world(b, p_ring),
             Surface(modes, velocity, modal_force, R @ (W @ eta_dot[modes])))
    angle_out = np.arctan2(abs(n[2]), abs(n[0] * np.cos(th_ball) + n[1] * np.sin(th_ball)))
    return [point], angle_out, th_ball


def _modes_of(m, j):
    """Slice of η and number of modes of modal body j."""
    o0, o1 = m.modal_off[j], m.modal_off[j + 1]
    return slice(o0, o1), o1 - o0


def surface_tables(m, r, x):
    """(D (3, k), Ω (3, k), p_s (3,)) of sampled surface r at the ring-frame point x: per circle in θ
    (:func:`_sampled`), then across the circles with the weights of s (module docstring)."""
    modes, k = _modes_of(m, m.race_modal[r])
    s0, s1 = m.race_samp_off[r], m.race_samp_off[r + 1]
    circle_s = m.race_circle_s[m.race_circle_off[r]:m.race_circle_off[r + 1]]
    n_th = (s1 - s0) // len(circle_s)
    th = np.mod(np.arctan2(x[1], x[0]), TWO_PI)
    s = x[2] if m.race_kind[r] in (INNER_CYLINDER, OUTER_CYLINDER) else np.hypot(x[0], x[1])
    weights = np.array([np.interp(s, circle_s, e) for e in np.eye(len(circle_s))])
    periodic = m.race_periodic[r] == 1
    D, W, P = np.zeros((3, k)), np.zeros((3, k)), np.zeros(3)
    for j, wj in enumerate(weights):
        rows = slice(s0 + j * n_th, s0 + (j + 1) * n_th)
        theta = m.samp_theta[rows]
        D += wj * _sampled(theta, m.samp_disp[rows, :, :k], periodic, th)[0]
        W += wj * _sampled(theta, m.samp_rot[rows, :, :k], periodic, th)[0]
        P += wj * _sampled(theta, m.samp_point[rows], periodic, th)[0]
    return D, W, P


def pocket_tables(m, g, x):
    """(D (3, k), Ω (3, k), p_s (3,)) of the walls of sampled pocket g at the cage-frame point x."""
    _, k = _modes_of(m, m.pocket_modal[g])
    lead, trail = m.pocket_samp[g], m.pocket_samp[g] + 1
    e = m.samp_point[lead] - m.samp_point[trail]
    t = float(np.clip((x - m.samp_point[trail]) @ e / (e @ e), 0.0, 1.0))
    def mix(table):
        return t * table[lead] + (1.0 - t) * table[trail]
    return mix(m.samp_disp[:, :, :k]), mix(m.samp_rot[:, :, :k]), mix(m.samp_point)


def _deformed_surface_point(bodies, b, modes, tables, eta, eta_dot, delta, n, x):
    """Contact point of the rigid geometry (δ, normal n of the force on the element and point x, ring frame)
    on a sampled surface of modal body b whose tables at x are (D, Ω, p_s)."""
    D, W, P = tables
    lever = x - P
    R = bodies.R[b]
    e, ed = eta[modes], eta_dot[modes]
    velocity = R @ (D @ ed + np.cross(W @ ed, lever))

    def modal_force(force_on_element, moment_on_element=np.zeros(3)):
        on_ring, turning = R.T @ -force_on_element, R.T @ -moment_on_element
        return D.T @ on_ring + W.T @ (np.cross(lever, on_ring) + turning)

    return (delta + n @ (D @ e + np.cross(W @ e, lever)), R @ n, bodies.to_world(b, x),
            Surface(modes, velocity, modal_force))


def _points_flexible_roller(m, bodies, c, eta, eta_dot):
    """Roller slices or a roller end on a sampled surface of a modal ring."""
    a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
    center, axis = _roller_in_ring(bodies, a, b)
    if m.pair_type[c] == ROLLER_RACEWAY:
        drop = m.slice_drop[m.pair_slice_off[c]:m.pair_slice_off[c + 1]]
        local = zip(*roller_slices(center, axis, m.pair_length[c], m.pair_radius[c], drop, m.race_kind[g],
                                   m.race_value[g]))
        angle = None
    else:
        delta, n, p = roller_end(center, axis, m.pair_radius[c], m.pair_length[c], m.pair_aux[c, 0],
                                 m.pair_aux[c, 1], m.race_kind[g], m.race_value[g])
        local, angle = [(delta, p, n)], 0.0
    modes = _modes_of(m, m.race_modal[g])[0]
    return [_deformed_surface_point(bodies, b, modes, surface_tables(m, g, x), eta, eta_dot, d, n, x)
            for d, x, n in local], angle, 0.0


def _points_flexible_pocket(m, bodies, c, eta, eta_dot):
    """An element in a pocket of a modal cage whose walls are sampled."""
    b, g = m.pair_b[c], m.pair_geom[c]
    modes = _modes_of(m, m.pocket_modal[g])[0]
    local, _, _ = _points_element_pocket(m, bodies, c)
    out = []
    for delta, n_world, p_world in local:
        n, x = bodies.R[b].T @ n_world, bodies.to_local(b, p_world)
        out.append(_deformed_surface_point(bodies, b, modes, pocket_tables(m, g, x), eta, eta_dot, delta, n, x))
    return out, 0.0, 0.0
