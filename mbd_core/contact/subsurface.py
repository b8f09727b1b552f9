"""Stresses below the centre of an elliptical Hertz contact.

Along the load axis (x = y = 0, depth z ≥ 0) the three normal stresses are principal. With
a ≥ b the semi-axes (x along a, y along b), κ = b/a, e² = 1 − κ², ζ = z/a,
η = sqrt((κ² + ζ²)/(1 + ζ²)), φ = arctan(1/ζ) and the incomplete elliptic integrals
F = F(φ, e²), E = E(φ, e²) (Thomas & Hoersch 1930, in the form of Harris & Kotzalas,
*Rolling Bearing Analysis*, ch. 6)::

    σx/p0 = (2κ/e²)·(Ωx + ν Ω'x),  Ωx = −(1 − η)/2 + ζ (F − E),
                                   Ω'x = 1 − η/κ² + ζ (E/κ² − F)
    σy/p0 = (2κ/e²)·(Ωy + ν Ω'y),  Ωy = 1/(2η) + 1/2 − η/κ² + ζ (E/κ² − F),
                                   Ω'y = −1 + η + ζ (F − E)
    σz/p0 = −(κ/e²)·(1/η − η)

(compression negative). The maximum shear stress is half the spread of the principal stresses.
For a nearly circular contact (e² < 1e-6) the axisymmetric solution is used (Johnson,
*Contact Mechanics*, eq. 3.45). The orthogonal shear stress τ0 (largest τ_yz, Lundberg &
Palmgren 1947) follows from t with b/a = sqrt((t² − 1)(2t − 1)):
τ0 = p0·sqrt(2t − 1)/(2t(t + 1)) at depth z0 = b/((t + 1)·sqrt(2t − 1)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar
from scipy.special import ellipeinc, ellipkinc

__all__ = [
    "axis_stresses_Pa",
    "max_shear_profile_Pa",
    "line_max_shear_profile_Pa",
    "SubsurfaceShear",
    "subsurface_shear",
    "orthogonal_shear",
]


def _check_contact(p0_Pa: float, a_m: float, b_m: float, nu: float) -> None:
    if not (p0_Pa >= 0.0 and a_m > 0.0 and b_m > 0.0):
        raise ValueError(f"need p0 >= 0 and semi-axes > 0, got p0={p0_Pa}, a={a_m}, b={b_m}")
    if b_m > a_m * (1.0 + 1e-12):
        raise ValueError(f"semi-minor axis b ({b_m}) must not exceed semi-major axis a ({a_m})")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu must lie in (-1, 0.5), got {nu}")


def axis_stresses_Pa(p0_Pa: float, a_m: float, b_m: float, depth_m, nu: float):
    """Principal stresses σx (along a), σy (along b), σz at depths z on the contact axis, Pa.

    Parameters
    ----------
    p0_Pa : float
        Maximum Hertz pressure, Pa.
    a_m, b_m : float
        Semi-major and semi-minor axis, m (a ≥ b).
    depth_m : float or (n,) array
        Depths below the surface, m (≥ 0).
    nu : float
        Poisson's ratio of the body in which the stresses are wanted.

    Returns
    -------
    sx, sy, sz : arrays like ``depth_m``, Pa (compression negative).
    """
    _check_contact(p0_Pa, a_m, b_m, nu)
    z = np.asarray(depth_m, dtype=float)
    if np.any(z < 0.0):
        raise ValueError("depth_m must be >= 0")
    kap = min(b_m / a_m, 1.0)
    e2 = 1.0 - kap**2
    if e2 < 1e-6:
        c = z / a_m
        with np.errstate(divide="ignore", invalid="ignore"):
            atan_term = np.where(c > 0.0, c * np.arctan(1.0 / np.where(c > 0, c, 1.0)), 0.0)
        sr = -(1.0 + nu) * (1.0 - atan_term) + 0.5 / (1.0 + c**2)
        sz = -1.0 / (1.0 + c**2)
        return p0_Pa * sr, p0_Pa * sr.copy(), p0_Pa * sz
    zeta = z / a_m
    eta = np.sqrt((kap**2 + zeta**2) / (1.0 + zeta**2))
    phi = np.arctan2(1.0, zeta)  # π/2 at the surface
    F = ellipkinc(phi, e2)
    E = ellipeinc(phi, e2)
    om_x = -(1.0 - eta) / 2.0 + zeta * (F - E)
    om_x2 = 1.0 - eta / kap**2 + zeta * (E / kap**2 - F)
    om_y = 1.0 / (2.0 * eta) + 0.5 - eta / kap**2 + zeta * (E / kap**2 - F)
    om_y2 = -1.0 + eta + zeta * (F - E)
    scale = 2.0 * kap / e2
    sx = p0_Pa * scale * (om_x + nu * om_x2)
    sy = p0_Pa * scale * (om_y + nu * om_y2)
    sz = -p0_Pa * (kap / e2) * (1.0 / eta - eta)
    return sx, sy, sz


def max_shear_profile_Pa(p0_Pa: float, a_m: float, b_m: float, depth_m, nu: float):
    """Maximum (Tresca) shear stress τ_max(z) = (σ_max − σ_min)/2 on the contact axis, Pa."""
    s = np.stack(axis_stresses_Pa(p0_Pa, a_m, b_m, depth_m, nu))
    return 0.5 * (s.max(axis=0) - s.min(axis=0))


def line_max_shear_profile_Pa(p0_Pa: float, b_m: float, depth_m, nu: float):
    """τ_max(z) on the axis of a Hertz line contact of half-width b in plane strain, Pa.

    McEwen's stresses on the axis (Johnson, *Contact Mechanics*, 1985, eq. 4.75)::

        σx = −(p0/b)·((b² + 2z²)/sqrt(b² + z²) − 2z),   σz = −p0·b/sqrt(b² + z²),
        σy = ν·(σx + σz)   (plane strain along the line)

    and τ_max = (σ_max − σ_min)/2 of the three; depth_m float or (n,) array, m (≥ 0).
    """
    _check_contact(p0_Pa, b_m, b_m, nu)
    z = np.asarray(depth_m, dtype=float)
    if np.any(z < 0.0):
        raise ValueError(f"depth_m must be >= 0, got {depth_m!r}")
    root = np.sqrt(b_m * b_m + z * z)
    sx = -(p0_Pa / b_m) * ((b_m * b_m + 2.0 * z * z) / root - 2.0 * z)
    sz = -p0_Pa * b_m / root
    s = np.stack((sx, nu * (sx + sz), sz))
    return 0.5 * (s.max(axis=0) - s.min(axis=0))


@dataclass(frozen=True)
class SubsurfaceShear:
    """Peak shear stresses below a Hertz contact.

    Attributes
    ----------
    tau_max_Pa, depth_tau_max_m : float
        Peak of the maximum shear stress on the axis and its depth.
    tau_orthogonal_Pa, depth_tau_orthogonal_m : float
        Lundberg–Palmgren orthogonal shear amplitude τ0 and its depth z0.
    """

    tau_max_Pa: float
    depth_tau_max_m: float
    tau_orthogonal_Pa: float
    depth_tau_orthogonal_m: float


def orthogonal_shear(p0_Pa: float, a_m: float, b_m: float) -> tuple[float, float]:
    """Orthogonal shear amplitude τ0 and its depth z0 (Lundberg & Palmgren 1947), Pa and m."""
    _check_contact(p0_Pa, a_m, b_m, 0.3)
    ratio = min(b_m / a_m, 1.0)
    if ratio < 1e-12:
        t = 1.0
    else:
        t = brentq(lambda tt: math.sqrt((tt * tt - 1.0) * (2.0 * tt - 1.0)) - ratio, 1.0, 10.0, xtol=1e-15)
    s = math.sqrt(2.0 * t - 1.0)
    return p0_Pa * s / (2.0 * t * (t + 1.0)), b_m / ((t + 1.0) * s)


def subsurface_shear(p0_Pa: float, a_m: float, b_m: float, nu: float) -> SubsurfaceShear:
    """Peak τ_max on the axis (bounded search over 0 < z < 3b) and the orthogonal shear τ0."""
    _check_contact(p0_Pa, a_m, b_m, nu)

    def neg_tau(z_over_b: float) -> float:
        return -float(max_shear_profile_Pa(1.0, a_m, b_m, z_over_b * b_m, nu))

    # coarse scan then a bounded refinement: τ_max(z) has a single interior peak
    grid = np.linspace(0.02, 3.0, 150)
    vals = max_shear_profile_Pa(1.0, a_m, b_m, grid * b_m, nu)
    i = int(np.argmax(vals))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    res = minimize_scalar(neg_tau, bounds=(lo, hi), method="bounded", options={"xatol": 1e-9})
    tau0, z0 = orthogonal_shear(p0_Pa, a_m, b_m)
    return SubsurfaceShear(
        tau_max_Pa=-res.fun * p0_Pa,
        depth_tau_max_m=float(res.x) * b_m,
        tau_orthogonal_Pa=tau0,
        depth_tau_orthogonal_m=z0,
    )
