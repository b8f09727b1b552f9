"""The squeeze-film force as a table, for the time loop.

The film pressure is homogeneous of degree one in the journal velocity V = (ė, e φ̇) (Reynolds'
equation is linear in it, and dropping negative pressures commutes with a positive factor), so

    (F_r, F_t) = |V| · (f_r, f_t)(ε, ψ),     ψ = atan2(e φ̇, ė),

two functions of two variables. They are tabulated once per damper (one factorised grid operator
per ε, :mod:`.reynolds_grid`, or the short/long limits of :mod:`.limits`) on a uniform ε grid up
to ``max_eccentricity_ratio`` (uniform in u, ε = ε_max·(1 − (1 − u)²): points close up towards
ε_max, where the force changes fastest) and a uniform periodic ψ grid, times (1 − ε²)² so that what is
interpolated stays bounded as ε → 1 (the short π-film's radial force grows like (1 − ε²)⁻²,
Vance 1988). A 2π film is linear in V: ψ then needs only its two axes, but the same table serves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .limits import LIMITS, limit_force_N
from .reynolds_grid import FilmGrid, SqueezeFilmDamper, film_force_of_fields, film_pressure_fields

__all__ = ["FilmForceTable", "tabulate", "TABLE_METHODS", "TABLE_VERSION"]

#: part of a stored table's cache key: bump when what :func:`tabulate` computes changes
TABLE_VERSION = 1

#: how a table's entries are computed: the grid solver, or one of the closed-form limits
TABLE_METHODS = ("grid",) + LIMITS


@dataclass(frozen=True)
class FilmForceTable:
    """(f_r, f_t)·(1 − ε²)² on the grid ε_i = ε_max·(1 − (1 − u_i)²), u_i = i/(n_ε − 1), and
    ψ_j = 2πj/n_ψ, N·s/m.

    scaled_N_s_m : (n_eps, n_psi, 2) float64
    max_eccentricity_ratio : ε_max, the table's end (the journal is then (1 − ε_max)·c from the housing)
    method : how the entries were computed (:data:`TABLE_METHODS`)
    clearance_m : the damper's radial clearance c, m (ε = e/c)
    """

    scaled_N_s_m: np.ndarray
    max_eccentricity_ratio: float
    method: str
    clearance_m: float

    @property
    def n_eps(self) -> int:
        return self.scaled_N_s_m.shape[0]

    @property
    def n_psi(self) -> int:
        return self.scaled_N_s_m.shape[1]

    def force_N(self, eccentricity_ratio: float, radial_velocity_m_s: float,
                tangential_velocity_m_s: float) -> tuple[float, float]:
        """(F_r, F_t) on the journal by bilinear interpolation (ε beyond ε_max is an error)."""
        eps = float(eccentricity_ratio)
        if not 0.0 <= eps <= self.max_eccentricity_ratio:
            raise ValueError(f"eccentricity ratio {eps:.4g} is outside the table's [0, {self.max_eccentricity_ratio:g}]")
        speed = math.hypot(radial_velocity_m_s, tangential_velocity_m_s)
        if speed == 0.0:
            return 0.0, 0.0
        x = (1.0 - math.sqrt(max(1.0 - eps / self.max_eccentricity_ratio, 0.0))) * (self.n_eps - 1)
        i = min(int(x), self.n_eps - 2)
        a = x - i
        y = (math.atan2(tangential_velocity_m_s, radial_velocity_m_s) % (2.0 * math.pi)) / (2.0 * math.pi) * self.n_psi
        j = int(y) % self.n_psi
        b = y - int(y)
        T = self.scaled_N_s_m
        j1 = (j + 1) % self.n_psi
        f = ((1 - a) * (1 - b) * T[i, j] + a * (1 - b) * T[i + 1, j] + (1 - a) * b * T[i, j1] + a * b * T[i + 1, j1])
        s = speed / (1.0 - eps**2) ** 2
        return s * float(f[0]), s * float(f[1])


def _grid_row(damper: SqueezeFilmDamper, eps: float, psi: np.ndarray, grid: FilmGrid) -> np.ndarray:
    """(n_psi, 2) force per unit speed at ε for every direction ψ, from one pair of fields."""
    P1, P2 = film_pressure_fields(damper, eps, grid)
    p = np.cos(psi)[:, None, None] * P1[None] + np.sin(psi)[:, None, None] * P2[None]
    return film_force_of_fields(damper, grid, p)


def tabulate(damper: SqueezeFilmDamper, method: str = "grid", n_eps: int = 41, n_psi: int = 288,
             max_eccentricity_ratio: float = 0.95, grid: FilmGrid = FilmGrid()) -> FilmForceTable:
    """The damper's force table (module docstring); ``method`` one of :data:`TABLE_METHODS`."""
    if method not in TABLE_METHODS:
        raise ValueError(f"method must be one of {', '.join(TABLE_METHODS)}, got {method!r}")
    if not 0.0 < max_eccentricity_ratio < 1.0:
        raise ValueError(f"max_eccentricity_ratio must lie in (0, 1), got {max_eccentricity_ratio!r}")
    if n_eps < 2 or n_psi < 4:
        raise ValueError(f"a table needs n_eps ≥ 2 and n_psi ≥ 4, got {n_eps}, {n_psi}")
    eps = max_eccentricity_ratio * (1.0 - (1.0 - np.linspace(0.0, 1.0, n_eps)) ** 2)
    psi = np.arange(n_psi) * (2.0 * math.pi / n_psi)
    T = np.empty((n_eps, n_psi, 2))
    for i, e in enumerate(eps):
        if method == "grid":
            T[i] = _grid_row(damper, float(e), psi, grid)
        else:
            T[i] = [limit_force_N(damper, method, float(e), math.cos(p), math.sin(p)) for p in psi]
        T[i] *= (1.0 - e**2) ** 2
    T.setflags(write=False)
    return FilmForceTable(T, float(max_eccentricity_ratio), method, damper.clearance_m)
