"""Friction laws as validated parameter objects, mapped to the kernels' integer codes.

The formulas are in :mod:`mbd_core.kernels.laws`. Parameters are checked on creation (Drake's
practice: static ≥ dynamic friction ≥ 0, transition speeds ordered) and the errors name the field.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Coulomb", "DrebLinear", "DrebConstant", "DrebFalling", "Kragelskii", "LimitingShear", "MixedFriction",
           "asperity_load_share", "THESIS_FRICTION", "ADAMS_PAPER_FRICTION"]


def _finite(owner: str, **values: float) -> None:
    for k, v in values.items():
        if not math.isfinite(v):
            raise ValueError(f"{owner}: {k} must be finite, got {v!r}")


@dataclass(frozen=True)
class Coulomb:
    """Regularised Coulomb friction (Adams STEP blend): μ_static at v_static, μ_dynamic from v_dynamic on.

    μ_static = μ_dynamic = 0 is valid and frictionless (as no friction law at all).
    """

    mu_static: float
    mu_dynamic: float
    v_static_m_s: float = 1e-3
    v_dynamic_m_s: float = 2e-3

    code = 0

    def __post_init__(self) -> None:
        _finite("Coulomb friction", mu_static=self.mu_static, mu_dynamic=self.mu_dynamic,
                v_static_m_s=self.v_static_m_s, v_dynamic_m_s=self.v_dynamic_m_s)
        if not self.mu_dynamic >= 0.0:
            raise ValueError(f"Coulomb friction: mu_dynamic must be ≥ 0, got {self.mu_dynamic}")
        if not self.mu_static >= self.mu_dynamic:
            raise ValueError(f"Coulomb friction: mu_static ({self.mu_static}) must be ≥ mu_dynamic ({self.mu_dynamic})")
        if not 0.0 < self.v_static_m_s < self.v_dynamic_m_s:
            raise ValueError(f"Coulomb friction: need 0 < v_static_m_s ({self.v_static_m_s}) "
                             f"< v_dynamic_m_s ({self.v_dynamic_m_s})")

    @property
    def params(self) -> np.ndarray:
        return np.array([self.mu_static, self.mu_dynamic, self.v_static_m_s, self.v_dynamic_m_s])


@dataclass(frozen=True)
class DrebLinear:
    """Traction κ = B·u (DREB, Gupta 1977), B in s/m."""

    B_s_m: float

    code = 1

    def __post_init__(self) -> None:
        if not (math.isfinite(self.B_s_m) and self.B_s_m >= 0.0):
            raise ValueError(f"DREB linear traction: B_s_m must be ≥ 0, got {self.B_s_m}")

    @property
    def params(self) -> np.ndarray:
        return np.array([self.B_s_m, 0.0, 0.0, 0.0])


@dataclass(frozen=True)
class DrebConstant:
    """Traction κ = A for slip above u0 (blended from 0 below, m/s)."""

    A: float
    u0_m_s: float = 1e-4

    code = 2

    def __post_init__(self) -> None:
        if not (math.isfinite(self.A) and self.A >= 0.0):
            raise ValueError(f"DREB constant traction: A must be ≥ 0, got {self.A}")
        if not self.u0_m_s > 0.0:
            raise ValueError(f"DREB constant traction: u0_m_s must be > 0, got {self.u0_m_s}")

    @property
    def params(self) -> np.ndarray:
        return np.array([self.A, self.u0_m_s, 0.0, 0.0])


@dataclass(frozen=True)
class DrebFalling:
    """Traction κ = A − B·u, not below zero; blended from 0 below ``u0_m_s`` (m/s) when it is > 0
    (0: none, κ jumps to A at the first slip, which no explicit step resolves)."""

    A: float
    B_s_m: float
    u0_m_s: float = 0.0

    code = 3

    def __post_init__(self) -> None:
        _finite("DREB falling traction", A=self.A, B_s_m=self.B_s_m)
        if not (self.A >= 0.0 and self.B_s_m >= 0.0):
            raise ValueError(f"DREB falling traction: A and B_s_m must be ≥ 0, got {self.A}, {self.B_s_m}")
        if not (math.isfinite(self.u0_m_s) and self.u0_m_s >= 0.0):
            raise ValueError(f"DREB falling traction: u0_m_s must be ≥ 0, got {self.u0_m_s}")

    @property
    def params(self) -> np.ndarray:
        return np.array([self.A, self.B_s_m, self.u0_m_s, 0.0])


@dataclass(frozen=True)
class Kragelskii:
    """Traction κ = (A + B·u)·exp(−C·u) + D (Kragelskii; as used by A. Ashtekar, L. Tian and
    C. Lancaster, Cummins Turbo Technologies, *An analytical investigation of turbocharger
    rotor-bearing dynamics with rolling element bearings and squeeze film dampers*)."""

    A: float
    B_s_m: float
    C_s_m: float
    D: float

    code = 4

    def __post_init__(self) -> None:
        _finite("Kragelskii traction", A=self.A, B_s_m=self.B_s_m, C_s_m=self.C_s_m, D=self.D)
        if not self.C_s_m >= 0.0:
            raise ValueError(f"Kragelskii traction: C_s_m must be ≥ 0, got {self.C_s_m}")
        if not self.A + self.D >= 0.0:
            raise ValueError(f"Kragelskii traction: A + D (the value at zero slip) must be ≥ 0, got {self.A + self.D}")

    @property
    def params(self) -> np.ndarray:
        return np.array([self.A, self.B_s_m, self.C_s_m, self.D])


@dataclass(frozen=True)
class LimitingShear:
    """Traction of a lubricant film, κ = κ_L·(1 − exp(−u/u_c)): viscous at small slip, at the limiting
    shear stress τ_L = κ_L·p̄ beyond (Bair & Winer, J. Lubr. Technol. 101 (1979) 258–265:
    τ/τ_L = 1 − exp(−η·γ̇/τ_L), γ̇ = u/h). :meth:`from_film` takes κ_L and u_c = h·τ_L/η from the
    film, the mean pressure and the viscosity in the contact."""

    kappa_L: float
    u_c_m_s: float

    code = 5

    def __post_init__(self) -> None:
        if not (math.isfinite(self.kappa_L) and self.kappa_L >= 0.0):
            raise ValueError(f"limiting-shear traction: kappa_L must be ≥ 0, got {self.kappa_L}")
        if not (math.isfinite(self.u_c_m_s) and self.u_c_m_s > 0.0):
            raise ValueError(f"limiting-shear traction: u_c_m_s must be > 0, got {self.u_c_m_s}")

    @classmethod
    def from_film(cls, film_m: float, mean_pressure_Pa: float, viscosity_Pa_s: float,
                  limiting_shear_coefficient: float = 0.075) -> "LimitingShear":
        """κ_L = τ_L/p̄ = ``limiting_shear_coefficient`` (τ_L ∝ p, Bair & Winer; 0.05–0.1 for mineral
        oils) and u_c = h·τ_L/η with η the viscosity in the contact (at its pressure)."""
        for name, v in (("film_m", film_m), ("mean_pressure_Pa", mean_pressure_Pa),
                        ("viscosity_Pa_s", viscosity_Pa_s), ("limiting_shear_coefficient", limiting_shear_coefficient)):
            if not (math.isfinite(v) and v > 0.0):
                raise ValueError(f"limiting-shear traction: {name} must be > 0, got {v!r}")
        tau_L = limiting_shear_coefficient * mean_pressure_Pa
        return cls(limiting_shear_coefficient, film_m * tau_L / viscosity_Pa_s)

    @property
    def params(self) -> np.ndarray:
        return np.array([self.kappa_L, self.u_c_m_s, 0.0, 0.0])


def asperity_load_share(film_parameter: float, B: float, C: float) -> float:
    """φ = N_asperity/N = exp(−B·Λ^C) (Zhou & Hoeprich, J. Tribol. 113 (1991) 590–597); B and C
    belong to the surfaces (their paper gives them for three finishes; measured surfaces their own)."""
    for name, v in (("film_parameter", film_parameter), ("B", B), ("C", C)):
        if not (math.isfinite(v) and v >= 0.0):
            raise ValueError(f"asperity load share: {name} must be ≥ 0, got {v!r}")
    return math.exp(-B * film_parameter**C)


@dataclass(frozen=True)
class MixedFriction:
    """Mixed lubrication: the asperities carry the share φ(Λ) of the load with the boundary friction
    μ_b, the film the rest with its traction κ_L, both reached over the film's slip scale u_c:
    κ = (φ·μ_b + (1 − φ)·κ_L)·(1 − exp(−u/u_c)) (Zhou & Hoeprich's weighting,
    :func:`asperity_load_share`). Φ is that of the operating point (the film parameter Λ given)."""

    mu_boundary: float
    fluid: LimitingShear
    film_parameter: float
    B: float
    C: float

    code = 5

    def __post_init__(self) -> None:
        if not (math.isfinite(self.mu_boundary) and self.mu_boundary >= 0.0):
            raise ValueError(f"mixed friction: mu_boundary must be ≥ 0, got {self.mu_boundary}")
        if not isinstance(self.fluid, LimitingShear):
            raise TypeError("mixed friction: fluid must be a LimitingShear traction")
        asperity_load_share(self.film_parameter, self.B, self.C)

    @property
    def asperity_share(self) -> float:
        return asperity_load_share(self.film_parameter, self.B, self.C)

    @property
    def params(self) -> np.ndarray:
        phi = self.asperity_share
        return np.array([phi * self.mu_boundary + (1.0 - phi) * self.fluid.kappa_L, self.fluid.u_c_m_s, 0.0, 0.0])


#: The slewing-ring thesis' friction: μs = 0.24, μd = 0.14, vs = 1 mm/s, vd = 2 mm/s.
THESIS_FRICTION = Coulomb(0.24, 0.14, 1e-3, 2e-3)
#: The wind-bearing paper's Adams friction with μ_static ≥ μ_dynamic (Pang et al. 2024; the paper's
#: tables swap them): μs = 0.2, μd = 0.1, vs = 10 mm/s, vd = 100 mm/s.
ADAMS_PAPER_FRICTION = Coulomb(0.2, 0.1, 10e-3, 100e-3)
