"""Plain-numpy twins of the multibody kernels (mbd_core.kernels.element_contacts, .splines, .forces,
.explicit), written from the formulas in their docstrings with rotation matrices
(scipy.spatial.transform.Rotation) instead of quaternion algebra.

The force stage is vectorised differently from the kernels: every contact first yields its contact
points (δ, unit normal m of the force on the element, point p; world frame), then one function
applies the penalty and friction laws to a point, using the twins of the laws
(``contact_laws``), of the groove geometry (``contact_laws.ball_groove``) and of the roller slices
(``roller_slices``).

Modal bodies' surfaces (grooves, roller raceways and ribs, pockets) are in
:mod:`tests.reference.multibody_flexible`.
"""

from collections import namedtuple

import numpy as np
from scipy.interpolate import CubicSpline, PPoly
from scipy.spatial.transform import Rotation

from mbd_core.squeeze_film.force_table import FilmForceTable

from . import contact_laws as laws
from . import strip_traction as strips
from .roller_slices import roller_slices

# integer codes of the kernels (mbd_core.kernels.forces, .roller_slices, .element_contacts)
BALL_GROOVE, BALL_BALL, ROLLER_RACEWAY, ROLLER_RIB, ELEMENT_POCKET = range(5)
INNER_CYLINDER, OUTER_CYLINDER, PLANE_UP, PLANE_DOWN = range(4)
POCKET_CYLINDER, POCKET_SLOT = range(2)
PARALLEL_TOL = 1e-12  # |projection of d normal to the axis| below which the roller end is parallel to the rib

#: body_f_scale, body_t_scale (n_b,): Σ of the magnitudes of the terms summed into each body's force and
#: moment (|F|, |p − r| |F|, |M|), the scale of their round-off.
#: modal_f (n_η,): the contacts' modal forces (flexible grooves), √kg·m/s².
#: point, normal (n_c, 3): each pair's contact point and the unit normal of the force on its element (world):
#: those of its most loaded point, or of its deepest point when none is loaded.
Forces = namedtuple("Forces", "body_f body_t fn delta slip ft angle theta energy_contact energy_bushing "
                              "body_f_scale body_t_scale modal_f point normal",
                    defaults=(np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3))))


# -- rotations ---------------------------------------------------------------------------------
def matrix(quat):
    """Rotation matrix (3, 3) (or (n, 3, 3)) of unit quaternion(s) (w, x, y, z), body → world."""
    return Rotation.from_quat(np.asarray(quat, float), scalar_first=True).as_matrix()


def rotate(q7, x):
    """R(q) x for a pose q7 = (r, quaternion)."""
    return matrix(q7[3:]) @ np.asarray(x, float)


def rotate_back(q7, x):
    """R(q)ᵀ x."""
    return matrix(q7[3:]).T @ np.asarray(x, float)


def point_velocity(q7, v6, p):
    """World velocity of the body's material point at world position p: v + (R ω_B) × (p − r)."""
    return v6[:3] + np.cross(rotate(q7, v6[3:]), np.asarray(p, float) - q7[:3])


def spin(quat, omega_body, h):
    """Orientation matrix after turning for h at the constant body-frame rate ω: R exp([h ω]×)."""
    return matrix(quat) @ Rotation.from_rotvec(h * np.asarray(omega_body, float)).as_matrix()


def kinetic_energy(mass, inertia, v):
    """½ Σ m |v|² + ½ Σ I_i ω_i² (principal body axes), J."""
    return 0.5 * np.sum(mass * np.sum(v[:, :3] ** 2, axis=1)) + 0.5 * np.sum(inertia * v[:, 3:] ** 2)


def small_rotation(qa, qb, q_ref):
    """Rotation vector (small-angle form 2 e_vec sign e_w) of E = R_aᵀ R_b R_refᵀ, in a's frame.

    With b turned by a small world rotation φ from its rest pose R_b = R_a R_ref, E = R_aᵀ exp([φ]×) R_a,
    whose rotation vector is R_aᵀ φ.
    """
    e = (Rotation.from_quat(qa, scalar_first=True).inv() * Rotation.from_quat(qb, scalar_first=True)
         * Rotation.from_quat(q_ref, scalar_first=True).inv()).as_quat(scalar_first=True)
    return (2.0 if e[0] >= 0 else -2.0) * e[1:]


# -- element contact geometry ----------------------------------------------------------------------
def ball_ball(xa, xb, ra, rb):
    """(δ, m, p) of two spheres; m on sphere a, pointing from b to a."""
    d = np.asarray(xa, float) - np.asarray(xb, float)
    dist = np.linalg.norm(d)
    m = d / dist
    return ra + rb - dist, m, xa - ra * m


def into_surface(kind, x):
    """Unit direction into a surface of the roller_slices kinds at point x."""
    if kind in (INNER_CYLINDER, OUTER_CYLINDER):
        e_r = np.array([x[0], x[1], 0.0]) / np.hypot(x[0], x[1])
        return -e_r if kind == INNER_CYLINDER else e_r
    return np.array([0.0, 0.0, -1.0 if kind == PLANE_UP else 1.0])


def _depth(kind, value, x):
    return {INNER_CYLINDER: value - np.hypot(x[0], x[1]), OUTER_CYLINDER: np.hypot(x[0], x[1]) - value,
            PLANE_UP: value - x[2], PLANE_DOWN: x[2] - value}[kind]


def roller_end(center, axis, radius, length, end_sign, edge_radius, kind, value):
    """(δ, m, p) of a roller end (flat, rim rounded with edge_radius) against a rib surface.

    Torus: centre circle of radius ρ = r − r_e about e = c + σ (L/2 − r_e) a, normal to a. Its point
    deepest along d is on the centre circle towards the projection u of d normal to a (the circle's
    centre when u = 0, end face parallel to the rib), plus r_e along d at that point.
    """
    axis = np.asarray(axis, float)
    e = np.asarray(center, float) + end_sign * (0.5 * length - edge_radius) * axis
    d = into_surface(kind, e)
    u = np.cross(axis, np.cross(d, axis))      # d without its axial part, ⟂ a to round-off even when |u| ≪ 1
    tube = e + (radius - edge_radius) * u / np.linalg.norm(u) if np.linalg.norm(u) > PARALLEL_TOL else e
    d = into_surface(kind, tube)
    p = tube + edge_radius * d
    return _depth(kind, value, p), -d, p


def _pocket_frame(angle, r_p, z_p):
    e_r = np.array([np.cos(angle), np.sin(angle), 0.0])
    e_t = np.array([-np.sin(angle), np.cos(angle), 0.0])
    return r_p * e_r + [0.0, 0.0, z_p], e_r, e_t


def pocket_cylinder(x, radius, angle, r_p, z_p, clearance):
    """(δ, m, p) of a ball centred at x (cage frame) in a radial cylindrical pocket.

    At the pocket axis (|w| = 0) the normal is undefined: m = 0 there.
    """
    centre, e_r, _ = _pocket_frame(angle, r_p, z_p)
    w = np.asarray(x, float) - centre
    w = w - (w @ e_r) * e_r
    dist = np.linalg.norm(w)
    m = -w / dist if dist > 0 else np.zeros(3)
    return dist - clearance, m, x - radius * m


def pocket_slot(xs, radius, angle, r_p, z_p, clearance):
    """(δ, m, p) of a roller end point xs (cage frame) between the two flat faces of a slot pocket."""
    centre, _, e_t = _pocket_frame(angle, r_p, z_p)
    u = (np.asarray(xs, float) - centre) @ e_t
    m = -np.copysign(1.0, u) * e_t
    return abs(u) - clearance, m, xs - radius * m


# -- load histories ---------------------------------------------------------------------------
def spline_value(times, loads, t):
    """CubicSpline through (times, loads) at t, the end values held outside [t_0, t_m]."""
    return CubicSpline(times, loads, axis=0)(np.clip(t, times[0], times[-1]))


def _stored_spline(m, l, t):
    """Load history l of the model arrays at t, evaluated as a scipy PPoly of the stored coefficients."""
    lo, hi = m.load_off[l], m.load_off[l + 1]
    knots = m.knot_t[lo:hi]
    pp = PPoly(np.transpose(m.knot_coef[lo:hi - 1], (1, 0, 2)), knots)
    return pp(np.clip(t, knots[0], knots[-1]))


# -- force stage --------------------------------------------------------------------------------
class _Bodies:
    """Poses and velocities of all bodies as matrices and world vectors; accumulated forces and moments."""

    def __init__(self, q, v):
        self.r = q[:, :3]
        self.R = matrix(q[:, 3:])
        self.v = v[:, :3]
        self.omega = np.einsum("nij,nj->ni", self.R, v[:, 3:])   # world angular velocities
        n = len(q)
        self.f, self.t = np.zeros((n, 3)), np.zeros((n, 3))
        self.f_scale, self.t_scale = np.zeros(n), np.zeros(n)

    def add(self, i, force, p):
        """Force (world) applied at world point p to body i."""
        self.f[i] += force
        self.t[i] += np.cross(p - self.r[i], force)
        self.f_scale[i] += np.linalg.norm(force)
        self.t_scale[i] += np.linalg.norm(p - self.r[i]) * np.linalg.norm(force)

    def add_moment(self, i, moment):
        self.t[i] += moment
        self.t_scale[i] += np.linalg.norm(moment)

    def velocity(self, i, p):
        return self.v[i] + np.cross(self.omega[i], p - self.r[i])

    def to_local(self, i, p):
        return self.R[i].T @ (p - self.r[i])

    def to_world(self, i, x):
        return self.r[i] + self.R[i] @ x


def contact_point_force(m, bodies, c, delta, normal, p, surface_velocity=None):
    """Penalty and friction force of one contact point.

    ``surface_velocity`` (3,) world: velocity of body b's surface at p beyond its rigid motion (the
    modal velocity of a flexible raceway). Returns (F_n, |v_t|, |F_t|, elastic energy, force (3,) on
    body a in world axes).
    """
    if not delta > 0:
        return 0.0, 0.0, 0.0, 0.0, np.zeros(3)
    a, b = m.pair_a[c], m.pair_b[c]
    rel = bodies.velocity(a, p) - bodies.velocity(b, p)
    if surface_velocity is not None:
        rel = rel - surface_velocity
    k, n = m.pair_k[c], m.pair_n[c]
    fn = float(laws.normal_force(m.pair_law[c], delta, -(rel @ normal), k, n, m.pair_c[c], m.pair_dmax[c]))
    v_t = rel - (rel @ normal) * normal
    slip = np.linalg.norm(v_t)
    mu = float(laws.friction_coefficient(m.pair_fric[c], slip, m.pair_fric_p[c])) if slip > 0 and fn > 0 else 0.0
    f_t = -mu * fn * v_t / slip if slip > 0 else np.zeros(3)
    return fn, slip, mu * fn, k * delta ** (n + 1) / (n + 1), fn * normal + f_t


def strip_point_force(m, bodies, c, delta, normal, p, theta, surface=None):
    """A ball–groove point with strip traction (pair_strips > 0): the slip and relative angular velocity at
    the contact centre in the frame x = rolling direction e_θ (projected), y = m × x, z = m — against the
    ring's frame and (``surface``, a modal ring's groove) its section's own velocity and angular velocity —
    then the strips' twin over the curved surface z = κ y² (κ = pair_strip_curv).
    Returns (F_n, |v_t|, |F_t|, energy, force (3,) and spin moment (3,) on body a, world)."""
    if not delta > 0:
        return 0.0, 0.0, 0.0, 0.0, np.zeros(3), np.zeros(3)
    a, b = m.pair_a[c], m.pair_b[c]
    rel = bodies.velocity(a, p) - bodies.velocity(b, p)
    if surface is not None:
        rel = rel - surface.velocity
    k, n = m.pair_k[c], m.pair_n[c]
    fn = float(laws.normal_force(m.pair_law[c], delta, -(rel @ normal), k, n, m.pair_c[c], m.pair_dmax[c]))
    e_theta = bodies.R[b] @ np.array([-np.sin(theta), np.cos(theta), 0.0])
    x = e_theta - (e_theta @ normal) * normal
    x /= np.linalg.norm(x)
    y = np.cross(normal, x)
    omega = bodies.omega[a] - bodies.omega[b] - (0.0 if surface is None else surface.omega)
    fx, fy, mx, my, mz = strips.strip_traction_curved(
        fn, m.pair_semi_major[c] * fn ** (1.0 / 3.0), rel @ x, rel @ y, (omega @ x, omega @ y, omega @ normal),
        m.pair_strip_curv[c], lambda u: float(laws.friction_coefficient(m.pair_fric[c], u, m.pair_fric_p[c])),
        int(m.pair_strips[c]))
    return (fn, float(np.hypot(rel @ x, rel @ y)), float(np.hypot(fx, fy)), k * delta ** (n + 1) / (n + 1),
            fn * normal + fx * x + fy * y, mx * x + my * y + mz * normal)


def contact_force(m, q, v, c, delta, normal, p):
    """One contact point of pair c at state (q, v): (F_n, |v_t|, |F_t|, energy, force (3,) on body a)."""
    return contact_point_force(m, _Bodies(q, v), c, delta, np.asarray(normal, float), np.asarray(p, float))


def _angle_in_ring(R_b, r_b, normal, p):
    """Contact angle atan2(|n_axial|, |n_radial|) of a world normal at world point p, in the ring's frame."""
    n_l, p_l = R_b.T @ normal, R_b.T @ (p - r_b)
    return np.arctan2(abs(n_l[2]), abs(n_l[:2] @ p_l[:2]) / np.hypot(p_l[0], p_l[1]))


def _points_ball_groove(m, bodies, c):
    a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
    ra = m.pair_radius[c]
    x = bodies.to_local(b, bodies.r[a])
    th, delta, n = laws.ball_groove(
        x, m.groove_rc[g], m.groove_zc[g], m.groove_r[g] - ra,
        m.groove_h[m.groove_h_off[g]:m.groove_h_off[g + 1]], m.groove_dr[m.groove_dr_off[g]:m.groove_dr_off[g + 1]])
    n_w = bodies.R[b] @ n[0]
    # force on the ball towards the curvature centre; contact on the ball's far side from it
    point = (delta[0], -n_w, bodies.r[a] + ra * n_w)
    angle = np.arctan2(abs(n[0, 2]), abs(n[0, 0] * np.cos(th[0]) + n[0, 1] * np.sin(th[0])))
    return [point], angle, th[0]



def _points_ball_ball(m, bodies, c):
    return [ball_ball(bodies.r[m.pair_a[c]], bodies.r[m.pair_b[c]], m.pair_radius[c], m.pair_radius_b[c])], 0.0, 0.0


def _roller_in_ring(bodies, a, b):
    """Centre and axis (body z) of roller a in ring b's frame."""
    return bodies.to_local(b, bodies.r[a]), bodies.R[b].T @ bodies.R[a][:, 2]


def _points_roller_raceway(m, bodies, c):
    a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
    center, axis = _roller_in_ring(bodies, a, b)
    drop = m.slice_drop[m.pair_slice_off[c]:m.pair_slice_off[c + 1]]
    delta, q, n = roller_slices(center, axis, m.pair_length[c], m.pair_radius[c], drop, m.race_kind[g], m.race_value[g])
    return [(d, bodies.R[b] @ nk, bodies.to_world(b, qk)) for d, qk, nk in zip(delta, q, n)], None, 0.0


def _points_roller_rib(m, bodies, c):
    a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
    center, axis = _roller_in_ring(bodies, a, b)
    delta, n, p = roller_end(center, axis, m.pair_radius[c], m.pair_length[c], m.pair_aux[c, 0], m.pair_aux[c, 1],
                             m.race_kind[g], m.race_value[g])
    return [(delta, bodies.R[b] @ n, bodies.to_world(b, p))], 0.0, 0.0


def _points_element_pocket(m, bodies, c):
    a, b, g = m.pair_a[c], m.pair_b[c], m.pair_geom[c]
    center, axis = _roller_in_ring(bodies, a, b)
    args = (m.pair_radius[c], m.pocket_angle[g], m.pocket_r[g], m.pocket_z[g], m.pocket_clearance[g])
    if m.pocket_kind[g] == POCKET_CYLINDER:
        local = [pocket_cylinder(center, *args)]
    else:
        half = 0.5 * m.pair_length[c]
        local = [pocket_slot(center + s * axis, *args) for s in (-half, half)]
    return [(d, bodies.R[b] @ n, bodies.to_world(b, p)) for d, n, p in local], 0.0, 0.0


POINTS = {BALL_GROOVE: _points_ball_groove, BALL_BALL: _points_ball_ball, ROLLER_RACEWAY: _points_roller_raceway,
          ROLLER_RIB: _points_roller_rib, ELEMENT_POCKET: _points_element_pocket}


def contact_points(m, q, v, c, eta=None, eta_dot=None):
    """The contact points of pair c at state (q, v, η, η̇): tuples (δ, unit normal of the force on the element,
    point; world frame) followed, on a modal body's sampled surface, by its
    :data:`tests.reference.multibody_flexible.Surface`."""
    n_eta = int(m.modal_off[-1]) if len(m.modal_off) else 0
    eta = np.zeros(n_eta) if eta is None else np.asarray(eta, float)
    eta_dot = np.zeros(n_eta) if eta_dot is None else np.asarray(eta_dot, float)
    bodies, kind, g = _Bodies(q, v), m.pair_type[c], m.pair_geom[c]
    if kind == BALL_GROOVE and m.groove_modal[g] >= 0:
        return _points_flexible_groove(m, bodies, c, eta, eta_dot)[0]
    if kind in (ROLLER_RACEWAY, ROLLER_RIB) and m.race_modal[g] >= 0:
        return _points_flexible_roller(m, bodies, c, eta, eta_dot)[0]
    if kind == ELEMENT_POCKET and m.pocket_modal[g] >= 0:
        return _points_flexible_pocket(m, bodies, c, eta, eta_dot)[0]
    return POINTS[kind](m, bodies, c)[0]


def _bushings(m, q, bodies):
    """Diagonal stiffness and damping in body a's frame on the deflection of b relative to a; returns the energy."""
    energy = 0.0
    for j in range(len(m.bush_a)):
        a, b = m.bush_a[j], m.bush_b[j]
        pa, pb = bodies.to_world(a, m.bush_p_a[j]), bodies.to_world(b, m.bush_p_b[j])
        Ra = bodies.R[a]
        disp = Ra.T @ (pb - pa)
        rate = Ra.T @ (bodies.velocity(b, pb) - bodies.velocity(a, pa))
        rot = small_rotation(q[a, 3:], q[b, 3:], m.bush_q_ref[j])
        spin_rate = Ra.T @ (bodies.omega[b] - bodies.omega[a])
        k, damp = m.bush_k[j], m.bush_c[j]
        force = Ra @ (-k[:3] * disp - damp[:3] * rate)          # on b, at p_b; a gets the reaction there
        torque = Ra @ (-k[3:] * rot - damp[3:] * spin_rate)
        bodies.add(b, force, pb)
        bodies.add(a, -force, pb)
        bodies.add_moment(b, torque)
        bodies.add_moment(a, -torque)
        energy += 0.5 * (k[:3] @ disp**2 + k[3:] @ rot**2)
    return energy


def _squeeze_films(m, bodies):
    """Film forces on the journals (at their centres) and the housings, from each damper's table read
    by :meth:`mbd_core.squeeze_film.force_table.FilmForceTable.force_N`."""
    for j in range(len(m.sfd_a)):
        a, b = m.sfd_a[j], m.sfd_b[j]
        o0, o1 = m.sfd_table_off[j], m.sfd_table_off[j + 1]
        n_eps, n_psi = m.sfd_table_size[j]
        table = FilmForceTable(m.sfd_table[o0:o1].reshape(n_eps, n_psi, 2), m.sfd_eps_max[j], "grid", m.sfd_clearance[j])
        n = bodies.R[b] @ m.sfd_axis[j]
        p = bodies.to_world(a, m.sfd_p_a[j])
        d = p - bodies.to_world(b, m.sfd_p_b[j])
        d -= (d @ n) * n
        u = bodies.velocity(a, p) - bodies.velocity(b, p)
        u -= (u @ n) * n
        e = np.linalg.norm(d)
        if not np.any(u):
            continue
        e_r = d / e if e > 1e-12 * table.clearance_m else u / np.linalg.norm(u)
        e_t = np.cross(n, e_r)
        fr, ft = table.force_N(e / table.clearance_m, u @ e_r, u @ e_t)
        bodies.add(a, fr * e_r + ft * e_t, p)
        bodies.add(b, -(fr * e_r + ft * e_t), p)


def _unbalances(m, bodies, eta, modal_f):
    """Centrifugal force m_u (ω² e − (ω·e) ω) of each unbalance (body frame), at its point displaced by
    its mode shapes D η; Dᵀ F to the modes of a modal body."""
    for j, i in enumerate(m.unb_body):
        R = bodies.R[i]
        omega = R.T @ bodies.omega[i]
        u = m.unb_kg_m[j]
        force = (omega @ omega) * u - (omega @ u) * omega
        p = m.unb_point[j].copy()
        mb = m.body_modal[i]
        if mb >= 0:
            modes = slice(m.modal_off[mb], m.modal_off[mb + 1])
            D = m.unb_disp[j][:, :modes.stop - modes.start]
            p += D @ eta[modes]
            modal_f[modes] += D.T @ force
        bodies.add(i, R @ force, bodies.to_world(i, p))


def compute_forces(m, t, q, v, eta=None, eta_dot=None, groove_angle=None):
    """Twin of mbd_core.kernels.forces.compute_forces on the model arrays ``m`` at state (t, q, v, η, η̇).

    ``eta``, ``eta_dot`` (n_η,): modal coordinates and rates (None: zero). ``groove_angle``: a function
    (m, g, η of the ring, ball centre x in the ring frame, ball angle) → θ that replaces the nearest-point
    search of flexible grooves (:func:`nearest_groove_angle`), so that what follows it can be compared
    alone. Returns :data:`Forces`: body forces and moments about the bodies' centres (n_b, 3)
    world frame; per contact F_n (sum over points), largest δ, slip at the most loaded point, Σ|F_t|,
    contact angle (raceway: at the most loaded slice), ball angle θ (grooves; 0 otherwise); energies;
    modal forces (n_η,).
    """
    nc = len(m.pair_type)
    n_eta = int(m.modal_off[-1]) if len(m.modal_off) else 0
    eta = np.zeros(n_eta) if eta is None else np.asarray(eta, float)
    eta_dot = np.zeros(n_eta) if eta_dot is None else np.asarray(eta_dot, float)
    nearest = groove_angle or nearest_groove_angle
    modal_f = np.zeros(n_eta)
    bodies = _Bodies(q, v)
    loads = [(i, m.body_force[i]) for i in range(len(m.body_mass))]
    loads += [(m.load_body[l], _stored_spline(m, l, t)) for l in range(len(m.load_body))]
    for i, load in loads:                      # at the body's centre
        bodies.add(i, load[:3], bodies.r[i])
        bodies.add_moment(i, load[3:])
    e_bushing = _bushings(m, q, bodies)
    for j, i in enumerate(m.drag_body):        # fluid drag at the centre, F = −(c₁ + c₂|v|) v
        bodies.add(i, -(m.drag_c[j, 0] + m.drag_c[j, 1] * np.linalg.norm(bodies.v[i])) * bodies.v[i], bodies.r[i])
    _unbalances(m, bodies, eta, modal_f)
    _squeeze_films(m, bodies)
    out = {k: np.zeros(nc) for k in ("fn", "delta", "slip", "ft", "angle", "theta")}
    point, normal_out = np.zeros((nc, 3)), np.zeros((nc, 3))
    e_contact = 0.0
    for c in range(nc):
        a, b = m.pair_a[c], m.pair_b[c]
        kind, g = m.pair_type[c], m.pair_geom[c]
        if kind == BALL_GROOVE and m.groove_modal[g] >= 0:
            points, angle, theta = _points_flexible_groove(m, bodies, c, eta, eta_dot, nearest)
        elif kind in (ROLLER_RACEWAY, ROLLER_RIB) and m.race_modal[g] >= 0:
            points, angle, theta = _points_flexible_roller(m, bodies, c, eta, eta_dot)
        elif kind == ELEMENT_POCKET and m.pocket_modal[g] >= 0:
            points, angle, theta = _points_flexible_pocket(m, bodies, c, eta, eta_dot)
        else:
            points, angle, theta = POINTS[m.pair_type[c]](m, bodies, c)
        loaded = []
        for delta, normal, p, *surface in points:
            if not delta > 0:
                continue
            surface = surface[0] if surface else None
            moment = np.zeros(3)
            if kind == BALL_GROOVE and m.pair_strips[c] > 0:
                fn, slip, ft, e, force, moment = strip_point_force(m, bodies, c, delta, normal, p, theta, surface)
                bodies.add_moment(a, moment)
                bodies.add_moment(b, -moment)
            else:
                fn, slip, ft, e, force = contact_point_force(m, bodies, c, delta, normal, p,
                                                             None if surface is None else surface.velocity)
            bodies.add(a, force, p)
            bodies.add(b, -force, p)
            if surface is not None:
                modal_f[surface.modes] += surface.modal_force(force, moment)
            loaded.append((fn, slip, ft, normal, p))
            e_contact += e
        out["delta"][c] = max(pt[0] for pt in points)
        if loaded:
            top = loaded[int(np.argmax([x[0] for x in loaded]))]
            point[c], normal_out[c] = top[4], top[3]
        else:
            deepest = points[int(np.argmax([pt[0] for pt in points]))]
            point[c], normal_out[c] = deepest[2], deepest[1]
        out["fn"][c] = sum(x[0] for x in loaded)
        out["ft"][c] = sum(x[2] for x in loaded)
        if loaded:
            top = loaded[int(np.argmax([x[0] for x in loaded]))]
            out["slip"][c] = top[1]
        if angle is None:      # roller–raceway: at the most loaded slice
            angle = _angle_in_ring(bodies.R[b], bodies.r[b], top[3], top[4]) if loaded else 0.0
        out["angle"][c], out["theta"][c] = angle, theta
    return Forces(bodies.f, bodies.t, out["fn"], out["delta"], out["slip"], out["ft"], out["angle"], out["theta"],
                  e_contact, e_bushing, bodies.f_scale, bodies.t_scale, modal_f, point, normal_out)


# the surfaces of modal bodies build on the rigid geometry above (imported last: that module reads it)
from .multibody_flexible import (  # noqa: E402
    _points_flexible_groove, _points_flexible_pocket, _points_flexible_roller, nearest_groove_angle)
