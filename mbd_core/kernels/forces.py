"""Forces on all bodies of a multibody model at one state (the force stage of a step).

The contact families are in :mod:`.ball_pairs`, :mod:`.roller_pairs` and :mod:`.pocket_pairs`; this
module holds the external loads, the bushings and the stage order.

The model ``m`` is a namedtuple of flat arrays (:class:`mbd_core.multibody.model.ModelArrays`), the
work ``w`` one of preallocated scratch arrays (:class:`mbd_core.multibody.model.WorkArrays`).
State: ``q`` (n_b, 7) = position r (world, m) and unit quaternion (w, x, y, z) body → world;
``v`` (n_b, 6) = velocity (world, m/s) and angular velocity ω (body frame, rad/s).

Stages: external loads (constant + cubic-spline histories) → bushings → fluid drag → unbalances
(:mod:`.unbalance`) → squeeze-film
dampers (:mod:`.squeeze_film`) → contacts. Each
contact gives a penetration δ, the unit normal m of the force on its element (body a), and a
contact point p; then

    F_n = normal_force(δ, δ̇) ≥ 0,        δ̇ = −(v_a(p) − v_b(p))·m,
    v_t = (v_a(p) − v_b(p)) − ((v_a(p) − v_b(p))·m) m,     F_t = −μ(|v_t|) F_n v_t/|v_t|,

with v_i(p) = v_i + ω_i × (p − r_i) the velocity of body i's material point at p. Body a gets
F_n m + F_t at p, body b the opposite. Results: ``w.body_f`` (n_b, 3) N and ``w.body_t`` (n_b, 3) N·m
(world frame, about the body's reference point = centre of mass) and the per-contact outputs.

Returns (status, index): 0 ok; ``STATUS_NONFINITE`` (non-finite force at contact ``index``, or at
body ``index`` − n_contacts when ``index`` ≥ n_contacts; messages in :mod:`mbd_core.multibody.explicit`);
``STATUS_PENETRATION`` (penetration beyond the pair's bound at contact ``index``);
``STATUS_SQUEEZE_FILM`` (the journal of damper ``index`` beyond its table's eccentricity).
``STATUS_ENERGY`` is set by the step loop (:mod:`.explicit`) on a kinetic-energy runaway,
``STATUS_MODAL`` when the mass matrix of a modal body is no longer positive definite.

Contacts on a modal ring or cage deform with it (:mod:`.flexible_surface`). A groove follows its
sampled raceway (:func:`.flexible_surface._nearest_deformed_centre`); a roller slice or roller end on a
surface sampled on a (θ, s) grid (:mod:`.roller_slices`) and an element in a pocket whose two walls are sampled (leading and trailing
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

Open contacts on sampled surfaces. The sampled points of modal body j move at most
U_j = Σ_k |η_k| max_s |D_s,k| and turn at most R_j = Σ_k |η_k| max_s |Ω_s,k| (``m.modal_disp_max``,
``m.modal_rot_max``), so the deformation changes a contact's penetration by at most U_j + R_j |p − p_s|
(weights ≥ 0, summing to one). On an evaluation that may skip (``w.flex_skip[1]``, set by the explicit
step loop on the steps whose contact outputs are not recorded) a contact whose rigid-geometry
penetration stays below −1.1 × that bound (10 % for the nearest-point search of a ball in a groove) is
open whatever the deformation: its sample rows are not formed, and its outputs are those of the rigid
geometry. Forces are unchanged bit for bit; ``w.flex_bound`` counts the checks and skips.

Bodies that integrate their friction implicitly (``m.body_fric_implicit``) also get, per contact
point, the damping matrix c Jᵀ(I − m mᵀ)J of the friction in (v, ω) world, c = |F_t|/|v_t| the secant
coefficient (``w.fric_c``, from the points noted in ``w.fric_pts``), and the velocity of this
evaluation (``w.fric_v``), for the kick of :mod:`.explicit`.
"""

from __future__ import annotations

import math

from numba import njit

from .ball_pairs import _ball_ball_pairs, _ball_groove_pairs
from .body_frames import _add_force, _to_world, point_velocity, rotate, rotate_back
from .friction_damping import _friction_damping_matrices
from .pair_types import (BALL_BALL, BALL_GROOVE, ELEMENT_POCKET, ROLLER_RACEWAY, ROLLER_RIB, STATUS_ENERGY,
                         STATUS_MODAL, STATUS_NONFINITE, STATUS_OK, STATUS_PENETRATION, STATUS_SQUEEZE_FILM)
from .pocket_pairs import _element_pocket_pairs
from .point_contact import contact_force
from .roller_pairs import _roller_raceway_pairs, _roller_rib_pairs
from .splines import spline_value
from .squeeze_film import _squeeze_films
from .unbalance import _unbalances

# the stages and helpers the callers (and their tests) reach through this module
__all__ = ["compute_forces", "contact_force", "point_velocity", "rotate", "rotate_back", "BALL_BALL", "BALL_GROOVE",
           "ELEMENT_POCKET", "ROLLER_RACEWAY", "ROLLER_RIB", "STATUS_ENERGY", "STATUS_MODAL", "STATUS_NONFINITE",
           "STATUS_OK", "STATUS_PENETRATION", "STATUS_SQUEEZE_FILM"]


@njit(cache=True, _nrt=False)
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


@njit(cache=True, _nrt=False)
def _drag(m, v, w):
    """Fluid drag at the centres of the bodies that have one: F = −(c₁ + c₂|v|) v (world)."""
    for j in range(m.drag_body.shape[0]):
        i = m.drag_body[j]
        speed = math.sqrt(v[i, 0] ** 2 + v[i, 1] ** 2 + v[i, 2] ** 2)
        c = m.drag_c[j, 0] + m.drag_c[j, 1] * speed
        w.body_f[i, 0] -= c * v[i, 0]
        w.body_f[i, 1] -= c * v[i, 1]
        w.body_f[i, 2] -= c * v[i, 2]


@njit(cache=True, _nrt=False)
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


@njit(cache=True, _nrt=False)
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


@njit(cache=True, _nrt=False)
def _surface_bounds(m, eta, w):
    """w.flex_bound[j, 0:2] = (U_j m, R_j rad) of every modal body (module docstring), inf when this
    evaluation does not skip."""
    skip = w.flex_skip[1] != 0
    for j in range(m.modal_body.shape[0]):
        u = r = math.inf
        if skip:
            u = r = 0.0
            for k in range(m.modal_off[j], m.modal_off[j + 1]):
                a = abs(eta[k])
                u += a * m.modal_disp_max[k]
                r += a * m.modal_rot_max[k]
        w.flex_bound[j, 0] = u
        w.flex_bound[j, 1] = r


@njit(cache=True, _nrt=False)
def compute_forces(m, t, q, v, eta, eta_dot, w):
    """Fill ``w.body_f``, ``w.body_t``, ``w.modal_f`` and the contact outputs at (t, q, v, η, η̇);
    returns (status, index)."""
    _external_loads(m, q, w, t)
    for k in range(w.modal_f.shape[0]):
        w.modal_f[k] = 0.0
    w.fric_n[0] = 0
    w.energy[1] = _bushings(m, q, v, w) if m.bush_a.shape[0] > 0 else 0.0
    if m.drag_body.shape[0] > 0:
        _drag(m, v, w)
    if m.unb_body.shape[0] > 0:
        _unbalances(m, q, v, eta, w)
    if m.sfd_a.shape[0] > 0:
        j = _squeeze_films(m, q, v, w)
        if j >= 0:
            return STATUS_SQUEEZE_FILM, j
    if m.modal_body.shape[0] > 0:
        _surface_bounds(m, eta, w)
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
