"""Plain-numpy twin of the explicit time step of mbd_core.kernels.explicit, written from the scheme in
its module docstring (velocity Verlet in kick–drift–kick form):

    kick   v ← v + (h/2) M⁻¹ F;  rotation: see below                   (free components only)
    drift  r ← r + h v;  orientation: see below
    force  F, τ at (t + h, q, v)                                        (numpy twin of compute_forces)
    kick   as above.

Rotation by what is free of a body's three rotations (ω in body axes, principal inertia I):

* all three free: the body-frame angular momentum π = I ω gets the half-step torque kicks
  π ← π + (h/2) R(q)ᵀ τ, and the drift is the symplectic splitting of the free rotation
  (twin in ``rigid_rotation``), which turns both the orientation and π;
* some free: the free components of ω get (h/2) I⁻¹ (R(q)ᵀ τ − ω × I ω) (Euler's equations, the
  gyroscopic term explicit), and the drift turns the body at its constant body-frame ω:
  R ← R exp([h ω]×), i.e. q ← q ⊗ exp(h ω/2);
* none free: ω keeps its prescribed value, and the drift turns the body at it as above.

Held (prescribed) velocity components keep their values. Orientations are handled as rotation
matrices (scipy.spatial.transform.Rotation) and stored back as the unit quaternion (w, x, y, z) on
the same side of the sphere as before the step (q and −q are the same rotation; the kernel's
quaternion moves continuously).

Modal bodies (body_modal ≥ 0) are moved by the twin of the modal step (``modal_step``) only: in
:func:`modal_step`, the rigid kick and drift, then their half kick and drift; the forces; the rigid
kick, then their corrected half kick.
"""

from collections import namedtuple

import numpy as np
from scipy.spatial.transform import Rotation

from . import modal_step as ms
from . import multibody as mb
from . import rigid_rotation

#: One recorded sample: global step, time s, q (n_b, 7), v (n_b, 6), and the forces of that step.
Sample = namedtuple("Sample", "step t q v forces")


def _quat_of(R, near):
    """Unit quaternion (w, x, y, z) of rotation matrix R, with the sign that keeps it nearest ``near``."""
    quat = Rotation.from_matrix(R).as_quat(scalar_first=True)
    return -quat if quat @ near < 0 else quat


def kick(m, q, v, body_f, body_t, hh):
    """Half kick of size hh = h/2 with world forces body_f and moments body_t (n_b, 3); returns the new v."""
    v = v.copy()
    free = m.body_free.astype(bool)
    R = mb.matrix(q[:, 3:])
    for i in range(len(m.body_mass)):
        lin, rot = free[i, :3], free[i, 3:]
        v[i, :3][lin] += hh * body_f[i][lin] / m.body_mass[i]
        if not rot.any():
            continue
        inertia, omega = m.body_inertia[i], v[i, 3:]
        tau = R[i].T @ body_t[i]
        if rot.all():
            v[i, 3:] = (inertia * omega + hh * tau) / inertia
        else:
            tau = tau - np.cross(omega, inertia * omega)
            v[i, 3:][rot] += hh * tau[rot] / inertia[rot]
    return v


def drift(m, q, v, h):
    """Positions by h v; orientations by the free-rotation splitting (unequal inertias) or at
    constant ω (spheres, whose free rotation keeps ω; driven bodies); returns (q, v). Modal bodies
    are left as they are (their drift is the modal twin's)."""
    q, v = q.copy(), v.copy()
    free = m.body_free.astype(bool)
    rigid = m.body_modal < 0
    q[rigid, :3] += h * v[rigid, :3]
    for i in np.flatnonzero(rigid):
        R = mb.matrix(q[i, 3:])
        inertia = m.body_inertia[i]
        if free[i, 3:].all() and np.ptp(inertia) > 0:
            R, pi = rigid_rotation.free_rotation_step(R, inertia * v[i, 3:], inertia, h)
            v[i, 3:] = pi / inertia
        else:
            R = R @ Rotation.from_rotvec(h * v[i, 3:]).as_matrix()
        q[i, 3:] = _quat_of(R, q[i, 3:])
    return q, v


def step(m, q, v, forces, t, h):
    """One step of size h ending at time t from (q, v) with ``forces`` (twin Forces) at (q, v).

    Returns (q, v, forces at the new state).
    """
    v = kick(m, q, v, forces.body_f, forces.body_t, 0.5 * h)
    q, v = drift(m, q, v, h)
    forces = mb.compute_forces(m, t, q, v)
    v = kick(m, q, v, forces.body_f, forces.body_t, 0.5 * h)
    return q, v, forces


def modal_step(m, q, v, eta, eta_dot, forces, t, h, groove_angle=None):
    """One step of size h ending at time t of a model with modal bodies, from (q, v, η, η̇) with ``forces``
    (twin Forces, with modal forces) at that state; ``groove_angle`` as in the twin of compute_forces.
    Returns (q, v, η, η̇, forces at the new state)."""
    v = kick(m, q, v, forces.body_f, forces.body_t, 0.5 * h)
    q, v = drift(m, q, v, h)
    v, eta_dot = ms.kick(m, q, v, eta, eta_dot, forces.body_f, forces.body_t, forces.modal_f, 0.5 * h, False)
    q, v, eta, eta_dot = ms.drift(m, q, v, eta, eta_dot, h)
    forces = mb.compute_forces(m, t, q, v, eta, eta_dot, groove_angle)
    v = kick(m, q, v, forces.body_f, forces.body_t, 0.5 * h)
    v, eta_dot = ms.kick(m, q, v, eta, eta_dot, forces.body_f, forces.body_t, forces.modal_f, 0.5 * h, True)
    return q, v, eta, eta_dot, forces


def run(m, q, v, forces, t_origin, step0, n_steps, h, every):
    """n_steps steps after global step ``step0`` (t = t_origin + step·h).

    Returns (q, v, forces, samples): the state after the last step, its forces, and a
    :data:`Sample` after every global step that is a multiple of ``every``.
    """
    samples = []
    for k in range(step0 + 1, step0 + n_steps + 1):
        t = t_origin + k * h
        q, v, forces = step(m, q, v, forces, t, h)
        if k % every == 0:
            samples.append(Sample(k, t, q, v, forces))
    return q, v, forces, samples
