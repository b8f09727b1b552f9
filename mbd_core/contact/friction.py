"""Friction laws as validated parameter objects, mapped to the kernels' integer codes.

The formulas are in :mod:`mbd_core.kernels.laws`. Parameters are checked on creation (Drake's
practice: static ≥ dynamic friction ≥ 0, transition speeds ordered) and the errors name the field.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Coulomb", "DrebLinear", "DrebConstant", "DrebFalling", "Kragelskii", "THESIS_FRICTION", "ADAMS_PAPER_FRICTION"]


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


#: The slewing-ring thesis' friction: μs = 0.24, μd = 0.14, vs = 1 mm/s, vd = 2 mm/s.
THESIS_FRICTION = Coulomb(0.24, 0.14, 1e-3, 2e-3)
#: The wind-bearing paper's Adams friction with μ_static ≥ μ_dynamic (Pang et al. 2024; the paper's
#: tables swap them): μs = 0.2, μd = 0.1, vs = 10 mm/s, vd = 100 mm/s.
ADAMS_PAPER_FRICTION = Coulomb(0.2, 0.1, 10e-3, 100e-3)
