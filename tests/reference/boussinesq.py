"""Independent reference: stresses below an elliptical Hertz contact by superposing Boussinesq
point-load solutions (plain numpy, no library code).

The Hertz pressure p = p0·sqrt(1 − x²/a² − y²/b²) acts on the surface z = 0 of a half-space.
The stress at a field point below the surface is the integral over the contact ellipse of the
Boussinesq solution for a compressive point load dP = p dA (Johnson, *Contact Mechanics*, 1985,
eq. 3.20). With the load point at (ξ, η) = (a r cos θ, b r sin θ) the area element is
dA = a·b·r dr dθ. The substitution r = sin t (t ∈ [0, π/2]) turns p·r dr into
p0·r·cos² t dt, which removes the square-root edge singularity of the pressure, so plain
Gauss–Legendre quadrature in t and θ converges fast for field points with z > 0.

Sign convention: compression negative. x is along the semi-axis ``a`` and y along ``b``.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

__all__ = ["axis_stresses", "shear_yz"]


@lru_cache(maxsize=16)
def _gauss(n: int):
    """Gauss–Legendre nodes and weights on [-1, 1] (read-only, cached: leggauss is slow)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x.flags.writeable = False
    w.flags.writeable = False
    return x, w


def _load_points(a: float, b: float, n_r: int, n_theta: int):
    """Load-point coordinates (ξ, η) and the weights w with Σ w·f = ∫∫ p/p0 · f dA."""
    t, wt = _gauss(n_r)
    t = 0.25 * np.pi * (t + 1.0)  # map [-1, 1] -> [0, π/2]
    wt = 0.25 * np.pi * wt
    th, wth = _gauss(n_theta)
    th = np.pi * (th + 1.0)  # map [-1, 1] -> [0, 2π]
    wth = np.pi * wth
    r = np.sin(t)
    # p/p0 · r dr = sqrt(1 − r²) · r · cos t dt = r cos² t dt
    w_r = wt * r * np.cos(t) ** 2
    xi = a * np.outer(r, np.cos(th))
    eta = b * np.outer(r, np.sin(th))
    w = a * b * np.outer(w_r, wth)
    return xi.ravel(), eta.ravel(), w.ravel()


def axis_stresses(p0: float, a: float, b: float, z, nu: float, n_r: int = 200, n_theta: int = 400):
    """Normal stresses σx (along a), σy (along b), σz on the axis x = y = 0 at depth(s) z > 0.

    Parameters
    ----------
    p0 : float
        Peak Hertz pressure.
    a, b : float
        Semi-axes of the contact ellipse along x and y (any order).
    z : float or array
        Depths, all > 0.
    nu : float
        Poisson's ratio.
    n_r, n_theta : int
        Gauss–Legendre points in the radial (t) and angular directions.

    Returns
    -------
    sx, sy, sz : arrays shaped like ``z`` (same unit as ``p0``).
    """
    z_arr = np.atleast_1d(np.asarray(z, dtype=float))
    if np.any(z_arr <= 0.0):
        raise ValueError("the Boussinesq reference needs z > 0")
    xi, eta, w = _load_points(a, b, n_r, n_theta)
    # field point (0, 0, z) relative to the load point: x = −ξ, y = −η
    x2, y2 = xi**2, eta**2
    rho2 = x2 + y2
    out = np.empty((3, z_arr.size))
    for i, zz in enumerate(z_arr):
        R2 = rho2 + zz * zz
        R = np.sqrt(R2)
        R3 = R2 * R
        R5 = R3 * R2
        one_minus_z_over_R = rho2 / (R * (R + zz))  # 1 − z/R without cancellation
        c = (1.0 - 2.0 * nu) / rho2
        sx = c * (one_minus_z_over_R * (x2 - y2) / rho2 + zz * y2 / R3) - 3.0 * zz * x2 / R5
        sy = c * (one_minus_z_over_R * (y2 - x2) / rho2 + zz * x2 / R3) - 3.0 * zz * y2 / R5
        sz = -3.0 * zz**3 / R5
        f = p0 / (2.0 * np.pi)
        out[0, i] = f * np.dot(w, sx)
        out[1, i] = f * np.dot(w, sy)
        out[2, i] = f * np.dot(w, sz)
    shape = np.shape(z)
    return out[0].reshape(shape), out[1].reshape(shape), out[2].reshape(shape)


def shear_yz(p0: float, a: float, b: float, y: float, z: float, n_r: int = 200, n_theta: int = 400):
    """Shear stress τ_yz at the field point (0, y, z), z > 0, below the Hertz pressure.

    Boussinesq point load P at the origin (Johnson eq. 3.20): τ_yz = −3P·y·z²/(2π R⁵), with
    (x, y) the field point relative to the load point.
    """
    if not z > 0.0:
        raise ValueError("the Boussinesq reference needs z > 0")
    xi, eta, w = _load_points(a, b, n_r, n_theta)
    dx, dy = -xi, y - eta
    R2 = dx * dx + dy * dy + z * z
    R5 = R2 * R2 * np.sqrt(R2)
    return p0 / (2.0 * np.pi) * np.dot(w, -3.0 * dy * z * z / R5)
