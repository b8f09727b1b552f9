"""numpy twin of mbd_core.kernels.rigid, with rotation matrices instead of quaternions."""

import numpy as np


def quat_to_matrix(q):
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def axis_matrix(axis, phi):
    """Rotation by phi about coordinate axis ``axis``."""
    c, s = np.cos(phi), np.sin(phi)
    R = np.eye(3)
    j, k = (axis + 1) % 3, (axis + 2) % 3
    R[j, j], R[j, k], R[k, j], R[k, k] = c, -s, s, c
    return R


def free_rotation_step(R, pi, inertia, h):
    """Strang splitting R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2) on (R, π)."""
    for axis, frac in ((0, 0.5), (1, 0.5), (2, 1.0), (1, 0.5), (0, 0.5)):
        phi = frac * h * pi[axis] / inertia[axis]
        A = axis_matrix(axis, phi)
        R = R @ A
        pi = A.T @ pi
    return R, pi
