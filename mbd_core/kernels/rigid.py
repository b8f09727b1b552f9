"""Rigid-body rotation kernels: unit quaternions and a symplectic splitting of the free rotation.

Orientation q = (w, x, y, z) maps body to inertial axes (v_I = R(q) v_B). The body-frame angular
momentum π = I ω (principal inertia I = diag(I1, I2, I3)) of a torque-free body evolves by
Euler's equations. The free motion is split into three exactly solvable rotations about the body's
principal axes, H = Σ π_i²/(2 I_i), composed symmetrically (Strang):

    R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2),

where R_i(τ) turns the body about its axis i by φ = τ π_i / I_i (q ← q ⊗ (cos φ/2, sin φ/2 e_i))
and rotates π by −φ about the same axis (the inertial momentum stays put). The scheme is
symplectic, second order and time-reversible; it conserves |π| and the inertial angular momentum
to round-off and keeps the energy error bounded (no drift) — Dullweber, Leimkuhler & McLachlan,
J. Chem. Phys. 107 (1997) 5840. Torques enter as half-step kicks π += (h/2) τ_B around it
(velocity-Verlet form), done by the caller.
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True, _nrt=False)
def quat_rotate(q, v, out):
    """out = R(q) v for a unit quaternion q (4,) and a vector v (3,)."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    # t = 2 (q_vec × v); v' = v + w t + q_vec × t
    tx = 2.0 * (y * v[2] - z * v[1])
    ty = 2.0 * (z * v[0] - x * v[2])
    tz = 2.0 * (x * v[1] - y * v[0])
    out[0] = v[0] + w * tx + (y * tz - z * ty)
    out[1] = v[1] + w * ty + (z * tx - x * tz)
    out[2] = v[2] + w * tz + (x * ty - y * tx)


@njit(cache=True, _nrt=False)
def _axis_rotation(q, pi, axis, phi):
    """Turn the body by phi about its own principal axis, in place on q and pi."""
    c, s = math.cos(0.5 * phi), math.sin(0.5 * phi)
    w, x, y, z = q[0], q[1], q[2], q[3]
    if axis == 0:
        q[0], q[1], q[2], q[3] = w * c - x * s, x * c + w * s, y * c + z * s, z * c - y * s
    elif axis == 1:
        q[0], q[1], q[2], q[3] = w * c - y * s, x * c - z * s, y * c + w * s, z * c + x * s
    else:
        q[0], q[1], q[2], q[3] = w * c - z * s, x * c + y * s, y * c - x * s, z * c + w * s
    # body components of a fixed inertial vector turn the other way
    cp, sp = math.cos(phi), math.sin(phi)
    j, k = (axis + 1) % 3, (axis + 2) % 3
    a, b = pi[j], pi[k]
    pi[j] = cp * a + sp * b
    pi[k] = -sp * a + cp * b


@njit(cache=True, _nrt=False)
def free_rotation_step(q, pi, inertia, h):
    """Advance orientation q (4,) and body angular momentum pi (3,) of a torque-free body by h, in place."""
    _axis_rotation(q, pi, 0, 0.5 * h * pi[0] / inertia[0])
    _axis_rotation(q, pi, 1, 0.5 * h * pi[1] / inertia[1])
    _axis_rotation(q, pi, 2, h * pi[2] / inertia[2])
    _axis_rotation(q, pi, 1, 0.5 * h * pi[1] / inertia[1])
    _axis_rotation(q, pi, 0, 0.5 * h * pi[0] / inertia[0])
    n = math.sqrt(q[0] ** 2 + q[1] ** 2 + q[2] ** 2 + q[3] ** 2)
    q[0] /= n
    q[1] /= n
    q[2] /= n
    q[3] /= n


@njit(cache=True, _nrt=False)
def turn_quaternion(qw, qx, qy, qz, ox, oy, oz):
    """q ⊗ (cos(φ/2), sin(φ/2) e) for the body-frame rotation vector φ e = (ox, oy, oz), renormalised."""
    phi = math.sqrt(ox * ox + oy * oy + oz * oz)
    c = math.cos(0.5 * phi)
    # sin(φ/2)/φ, its Taylor series where the quotient loses digits
    s = math.sin(0.5 * phi) / phi if phi > 1e-4 else 0.5 - phi * phi / 48.0
    ex, ey, ez = s * ox, s * oy, s * oz
    nw = qw * c - qx * ex - qy * ey - qz * ez
    nx = qw * ex + qx * c + qy * ez - qz * ey
    ny = qw * ey - qx * ez + qy * c + qz * ex
    nz = qw * ez + qx * ey - qy * ex + qz * c
    n = math.sqrt(nw * nw + nx * nx + ny * ny + nz * nz)
    return nw / n, nx / n, ny / n, nz / n
