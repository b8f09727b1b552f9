"""Plain-numpy twin of :func:`mbd_core.kernels.strip_traction.strip_traction`: the same strips
(exact loads of the Hertz line load q(y) ∝ 1 − y²/a², slip of each strip's load centroid), summed
with numpy arrays instead of a loop."""

from __future__ import annotations

import numpy as np

__all__ = ["strip_traction"]


def strip_traction(load_N, a_m, slip_x, slip_y, spin_rad_s, mu, n_strips):
    """(F_x, F_y, M_z) on body 1; ``mu(u)`` the friction coefficient at slip speed u."""
    s = np.linspace(-1.0, 1.0, n_strips + 1)
    q = load_N * np.diff(0.75 * (s - s**3 / 3) + 0.5)
    y = a_m * np.diff(s**2 / 2 - s**4 / 4) / np.diff(s - s**3 / 3)
    ux = slip_x - spin_rad_s * y
    u = np.hypot(ux, slip_y)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.where(u > 0.0, np.array([mu(ui) for ui in u]) * q / u, 0.0)  # no slip, no traction
    return np.array([-(f * ux).sum(), -(f * slip_y).sum(), (y * f * ux).sum()])
