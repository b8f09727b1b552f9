"""Rigid-body frame helpers of the force kernels: rotations by a body's quaternion, world/body points,
material-point velocities, adding a force at a point, contact angles (state layout in :mod:`.forces`)."""

from __future__ import annotations

import math

from numba import njit



@njit(cache=True, inline="always", _nrt=False)
def rotate(q, i, x, y, z):
    """R(q_i) (x, y, z): body frame → world."""
    w, a, b, c = q[i, 3], q[i, 4], q[i, 5], q[i, 6]
    tx = 2.0 * (b * z - c * y)
    ty = 2.0 * (c * x - a * z)
    tz = 2.0 * (a * y - b * x)
    return x + w * tx + (b * tz - c * ty), y + w * ty + (c * tx - a * tz), z + w * tz + (a * ty - b * tx)


@njit(cache=True, inline="always", _nrt=False)
def rotate_back(q, i, x, y, z):
    """R(q_i)ᵀ (x, y, z): world → body frame."""
    w, a, b, c = q[i, 3], -q[i, 4], -q[i, 5], -q[i, 6]
    tx = 2.0 * (b * z - c * y)
    ty = 2.0 * (c * x - a * z)
    tz = 2.0 * (a * y - b * x)
    return x + w * tx + (b * tz - c * ty), y + w * ty + (c * tx - a * tz), z + w * tz + (a * ty - b * tx)


@njit(cache=True, inline="always", _nrt=False)
def point_velocity(q, v, i, px, py, pz):
    """World velocity of body i's material point at world position p."""
    ox, oy, oz = rotate(q, i, v[i, 3], v[i, 4], v[i, 5])
    rx, ry, rz = px - q[i, 0], py - q[i, 1], pz - q[i, 2]
    return v[i, 0] + oy * rz - oz * ry, v[i, 1] + oz * rx - ox * rz, v[i, 2] + ox * ry - oy * rx


@njit(cache=True, inline="always", _nrt=False)
def relative_velocity_across(q, v, a, b, px, py, pz, nx, ny, nz):
    """Velocity of body a's material point at world p relative to body b's, without its part along
    the unit vector n: (u_x, u_y, u_z, u·n before the projection)."""
    vax, vay, vaz = point_velocity(q, v, a, px, py, pz)
    vbx, vby, vbz = point_velocity(q, v, b, px, py, pz)
    rx, ry, rz = vax - vbx, vay - vby, vaz - vbz
    vn = rx * nx + ry * ny + rz * nz
    return rx - vn * nx, ry - vn * ny, rz - vn * nz, vn


@njit(cache=True, inline="always", _nrt=False)
def _add_force(q, bf, bt, i, fx, fy, fz, px, py, pz):
    """Add force (fx, fy, fz) at world point p to body i's force and moment about its centre."""
    rx, ry, rz = px - q[i, 0], py - q[i, 1], pz - q[i, 2]
    bf[i, 0] += fx
    bf[i, 1] += fy
    bf[i, 2] += fz
    bt[i, 0] += ry * fz - rz * fy
    bt[i, 1] += rz * fx - rx * fz
    bt[i, 2] += rx * fy - ry * fx


@njit(cache=True, inline="always", _nrt=False)
def _to_world(q, b, lx, ly, lz):
    """World position of a point given in body b's frame."""
    x, y, z = rotate(q, b, lx, ly, lz)
    return q[b, 0] + x, q[b, 1] + y, q[b, 2] + z


@njit(cache=True, inline="always", _nrt=False)
def _in_frame(q, b, x, y, z):
    """Coordinates in body b's frame of the world point (x, y, z)."""
    return rotate_back(q, b, x - q[b, 0], y - q[b, 1], z - q[b, 2])


@njit(cache=True, inline="always", _nrt=False)
def _contact_angle(q, b, nx, ny, nz, px, py, pz):
    """atan2(|n_axial|, |n_radial|) of a world normal n at world point p, in body b's cylindrical frame."""
    lx, ly, lz = rotate_back(q, b, nx, ny, nz)
    ex, ey, _ = _in_frame(q, b, px, py, pz)
    r = math.sqrt(ex * ex + ey * ey)
    if r == 0.0:
        return 0.0
    return math.atan2(abs(lz), abs((lx * ex + ly * ey) / r))


@njit(cache=True, inline="always", _nrt=False)
def _roller_axis(q, a, b):
    """Roller a's axis (its body z) in ring b's frame."""
    x, y, z = rotate(q, a, 0.0, 0.0, 1.0)
    return rotate_back(q, b, x, y, z)
