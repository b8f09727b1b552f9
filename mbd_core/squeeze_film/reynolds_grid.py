"""Pressure and force of a squeeze-film damper: Reynolds' equation with side leakage on a grid.

The damper: a journal (a bearing's outer race, kept from turning by an anti-rotation pin) of radius
R in a housing bore with radial clearance c, over a land of length L, open to ambient pressure at
both ends, filled with oil of viscosity μ. The journal centre is displaced by e = ε·c. With θ
measured from the direction of the displacement and z along the axis (z = 0 mid-land),

    h = c·(1 − ε cos θ),     ∂h/∂t = −(ė cos θ + e·φ̇ sin θ),

ė the radial and e·φ̇ the tangential (whirl) velocity of the journal centre. The journal does not
turn, so the only source in Reynolds' equation is the squeeze term (Reynolds; San Andrés,
Modern Lubrication Theory, Texas A&M notes, ch. 8 "Squeeze film dampers"; Vance, Rotordynamics of
Turbomachinery, 1988, ch. 6):

    (1/R²) ∂/∂θ (h³ ∂p/∂θ) + ∂/∂z (h³ ∂p/∂z) = 12 μ ∂h/∂t,     p(z = ±L/2) = 0.

With H = h/c = 1 − ε cos θ, ζ = z/R and p = (12 μ R²/c³)·(ė P₁ + e φ̇ P₂), the two dimensionless
fields solve

    ∂θ(H³ ∂θ Pₖ) + H³ ∂ζζ Pₖ = −(cos θ, sin θ)ₖ,

so one factorised matrix per ε gives the pressure for any velocity. The film cannot hold a
tension: ``cavitation = "gumbel"`` (half-Sommerfeld / π-film) sets the negative pressures of the
full-film solution to the ambient one; ``"none"`` keeps the full 2π film. Either way the pressure
is homogeneous of degree one in the velocity, so a damper's force is |V| times a function of ε and
the direction ψ of V = (ė, e φ̇) — the table of :mod:`.force_table`.

The force of the film on the journal, in the (radial = along e, tangential) frame:

    (F_r, F_t) = −∫∫ p (cos θ, sin θ) R dθ dz.

Discretisation: second-order central differences in flux form (H³ at the half-points in θ),
periodic in θ; the half land 0 ≤ z ≤ L/2 (the pressure is even in z), a mirror condition at z = 0
and p = 0 at the end; the force by the rectangle rule in θ (periodic) and the trapezoidal rule in
z. Both errors are O(Δθ², Δz²); the tests measure the order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from foundation.validation import check_positive

__all__ = ["SqueezeFilmDamper", "CAVITATION_MODELS", "FilmGrid", "film_pressure_fields", "film_force_N",
           "film_force_of_fields"]

#: how the film treats sub-ambient pressure (module docstring)
CAVITATION_MODELS = ("gumbel", "none")


@dataclass(frozen=True)
class SqueezeFilmDamper:
    """An open-ended squeeze-film damper land (module docstring).

    radius_m : journal radius R (the outer race's outside radius), m
    length_m : land length L, m
    clearance_m : radial clearance c, m
    viscosity_Pa_s : oil dynamic viscosity μ at the film temperature, Pa·s
    cavitation : ``"gumbel"`` (π-film, the negative pressures dropped) or ``"none"`` (2π film)
    """

    radius_m: float
    length_m: float
    clearance_m: float
    viscosity_Pa_s: float
    cavitation: str = "gumbel"

    def __post_init__(self):
        check_positive("squeeze-film damper", radius_m=self.radius_m, length_m=self.length_m,
                       clearance_m=self.clearance_m, viscosity_Pa_s=self.viscosity_Pa_s)
        if self.clearance_m >= self.radius_m:
            raise ValueError(f"clearance_m = {self.clearance_m:g} m must be smaller than radius_m = {self.radius_m:g} m")
        if self.cavitation not in CAVITATION_MODELS:
            raise ValueError(f"cavitation must be one of {', '.join(CAVITATION_MODELS)}, got {self.cavitation!r}")

    @property
    def pressure_scale_Pa_s_m(self) -> float:
        """12 μ R²/c³: the pressure per unit journal velocity of the dimensionless fields, Pa·s/m."""
        return 12.0 * self.viscosity_Pa_s * self.radius_m**2 / self.clearance_m**3

    @property
    def force_scale_N_s_m(self) -> float:
        """12 μ R⁴/c³: pressure scale × R² (the area element R dθ dz = R² dθ dζ), N·s/m."""
        return self.pressure_scale_Pa_s_m * self.radius_m**2


@dataclass(frozen=True)
class FilmGrid:
    """Grid of the film: ``n_theta`` points around (periodic), ``n_z`` intervals over the half land."""

    n_theta: int = 96
    n_z: int = 24

    def __post_init__(self):
        if self.n_theta < 8 or self.n_z < 2:
            raise ValueError(f"FilmGrid needs n_theta ≥ 8 and n_z ≥ 2, got {self.n_theta}, {self.n_z}")

    @property
    def theta_rad(self) -> np.ndarray:
        return np.arange(self.n_theta) * (2.0 * math.pi / self.n_theta)


def _reynolds_matrix(eps: float, half_length_over_R: float, grid: FilmGrid):
    """The discrete operator on the unknowns P[i, j] (θ_i, ζ_j, j < n_z; ζ_{n_z} = L/2R holds P = 0)."""
    nt, nz = grid.n_theta, grid.n_z
    dth = 2.0 * math.pi / nt
    dz = half_length_over_R / nz
    th = grid.theta_rad
    H3 = (1.0 - eps * np.cos(th)) ** 3
    H3_half = (1.0 - eps * np.cos(th + 0.5 * dth)) ** 3     # at θ_{i+½}
    idx = np.arange(nt * nz).reshape(nt, nz)
    rows, cols, vals = [], [], []

    def add(r, c, v):
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(np.broadcast_to(v, r.shape).ravel())

    east = H3_half[:, None] / dth**2 * np.ones((1, nz))
    west = np.roll(H3_half, 1)[:, None] / dth**2 * np.ones((1, nz))
    add(idx, np.roll(idx, -1, axis=0), east)
    add(idx, np.roll(idx, 1, axis=0), west)
    axial = H3[:, None] / dz**2 * np.ones((1, nz))
    # north neighbour j + 1 (the end row j + 1 = n_z is P = 0: dropped); south j − 1, mirrored at j = 0
    add(idx[:, :-1], idx[:, 1:], axial[:, :-1])
    add(idx[:, 1:], idx[:, :-1], axial[:, 1:])
    add(idx[:, :1], idx[:, 1:2], axial[:, :1])
    add(idx, idx, -(east + west + 2.0 * axial))
    A = sp.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(nt * nz, nt * nz))
    return A


@lru_cache(maxsize=64)
def _fields(eps: float, half_length_over_R: float, grid: FilmGrid) -> tuple[np.ndarray, np.ndarray]:
    A = _reynolds_matrix(eps, half_length_over_R, grid)
    th = grid.theta_rad
    rhs = np.empty((grid.n_theta * grid.n_z, 2))
    rhs[:, 0] = np.repeat(-np.cos(th), grid.n_z)
    rhs[:, 1] = np.repeat(-np.sin(th), grid.n_z)
    P = splu(A).solve(rhs)
    out = tuple(P[:, k].reshape(grid.n_theta, grid.n_z) for k in range(2))
    for a in out:
        a.setflags(write=False)
    return out


def film_pressure_fields(damper: SqueezeFilmDamper, eccentricity_ratio: float,
                         grid: FilmGrid = FilmGrid()) -> tuple[np.ndarray, np.ndarray]:
    """The dimensionless full-film fields (P₁, P₂), each (n_theta, n_z) over θ and the half land
    0 ≤ z < L/2: p = (12 μ R²/c³)(ė P₁ + e φ̇ P₂) before cavitation (module docstring)."""
    eps = float(eccentricity_ratio)
    if not 0.0 <= eps < 1.0:
        raise ValueError(f"eccentricity ratio must lie in [0, 1), got {eps!r}")
    return _fields(eps, 0.5 * damper.length_m / damper.radius_m, grid)


def film_force_of_fields(damper: SqueezeFilmDamper, grid: FilmGrid, pressure: np.ndarray) -> np.ndarray:
    """(…, 2) force (F_r, F_t) on the journal, N per unit velocity scale, of dimensionless full-film
    pressures ``pressure`` (…, n_theta, n_z): cavitation applied, then the rectangle rule in θ and the
    trapezoidal rule over both halves of the land in ζ = z/R."""
    if damper.cavitation == "gumbel":
        pressure = np.maximum(pressure, 0.0)
    dz = 0.5 * damper.length_m / damper.radius_m / grid.n_z
    wz = np.full(grid.n_z, 2.0 * dz)
    wz[0] = dz          # the mid-land row counts once (shared by the two halves, half weight each)
    line = pressure @ wz                                # ∫ P dζ at each θ
    th = grid.theta_rad
    s = -damper.force_scale_N_s_m * 2.0 * math.pi / grid.n_theta
    return s * np.stack([line @ np.cos(th), line @ np.sin(th)], axis=-1)


def film_force_N(damper: SqueezeFilmDamper, eccentricity_ratio: float, radial_velocity_m_s: float,
                 tangential_velocity_m_s: float, grid: FilmGrid = FilmGrid()) -> tuple[float, float]:
    """Force of the film on the journal (F_r along the displacement, F_t along the whirl), N.

    Parameters
    ----------
    eccentricity_ratio : ε = e/c, in [0, 1)
    radial_velocity_m_s : ė, journal centre velocity along its displacement, m/s
    tangential_velocity_m_s : e·φ̇, its velocity across the displacement, m/s
    grid : the film grid (:class:`FilmGrid`)
    """
    P1, P2 = film_pressure_fields(damper, eccentricity_ratio, grid)
    f = film_force_of_fields(damper, grid, radial_velocity_m_s * P1 + tangential_velocity_m_s * P2)
    return float(f[0]), float(f[1])
