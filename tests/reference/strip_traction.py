"""Plain-numpy twin of :func:`mbd_core.kernels.strip_traction.strip_traction`: the same strips
(exact loads of the Hertz line load q(y) ∝ 1 − y²/a², slip of each strip's load centroid), summed
with numpy arrays instead of a loop."""

from __future__ import annotations

import numpy as np

__all__ = ["strip_traction", "strip_traction_curved"]


def strip_traction(load_N, a_m, slip_x, slip_y, spin_rad_s, mu, n_strips):
    """(F_x, F_y, M_z) on body 1 over a flat contact; ``mu(u)`` the friction coefficient at slip speed u."""
    fx, fy, _, _, mz = strip_traction_curved(load_N, a_m, slip_x, slip_y, (0.0, 0.0, spin_rad_s), 0.0, mu, n_strips)
    return np.array([fx, fy, mz])


def strip_traction_curved(load_N, a_m, slip_x, slip_y, omega, curvature_per_m, mu, n_strips):
    """(F_x, F_y, M_x, M_y, M_z) on body 1 over the curved surface z = κ y²: the strips' points
    r = (0, ȳ, κȳ²) slip at (v_x, v_y, 0) + ω × r (its tangential part), their forces act at r."""
    s = np.linspace(-1.0, 1.0, n_strips + 1)
    q = load_N * np.diff(0.75 * (s - s**3 / 3) + 0.5)
    y = a_m * np.diff(s**2 / 2 - s**4 / 4) / np.diff(s - s**3 / 3)
    r = np.column_stack([np.zeros_like(y), y, curvature_per_m * y**2])
    slip = np.array([slip_x, slip_y, 0.0]) + np.cross(np.asarray(omega, float), r)
    slip[:, 2] = 0.0
    u = np.linalg.norm(slip, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.where(u > 0.0, np.array([mu(ui) for ui in u]) * q / u, 0.0)  # no slip, no traction
    force = -f[:, None] * slip
    moment = np.cross(r, force).sum(axis=0)
    return np.array([force[:, 0].sum(), force[:, 1].sum(), *moment])
