"""The friction torque of a cageless angular-contact ball bearing of a despun mechanical assembly
(DMA): the DREB torque report's bearing (README Sources), run dynamically.

The inner race is held (it carries the torque meter), the outer race turns at ``operation.outer_speed_rpm``
under the thrust ``operation.thrust_N``; the 24 balls roll without a cage, each against its
neighbours (frictionless Hertz contacts). The traction at the raceways is one of the report's three
models, integrated over each contact ellipse in ``traction.strips`` strips (0: at the contact
centre): ``linear`` κ = B·u (an EHL traction curve's slope), ``constant`` κ = A (boundary friction),
``falling`` κ = A − B·u, both blended to 0 below ``blend_m_s``. The balls are slowed by the drag of the
air–oil mixture, a Stokes drag 3π·μ·D·v with the viscosity μ of the oil (``foundation.lubricants.LUBRICANT_A``)
at ``operation.temperature_C`` (the report's drag, C_D = 24/Re in the oil's viscosity).

Studies:

- ``torque``: one run; the torque of each race about the bearing axis over time, its mean over the
  settled part of the run, its ripple and spectrum, and the spectrum of a ball's centre motion;
- ``traction-models``: the same run with each of the report's traction sets (κ = 1.0·u, κ = 0.015,
  κ = 0.030, κ = 0.030 − 1.0·u): the mean race torques side by side;
- ``speed``: κ = the case's traction at every ``study.speeds_rpm`` and ``study.loads_N``: torque over
  speed (the report's Fig. 12).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar, Literal

from ..config import CaseTables

__all__ = ["DmaBearing", "Operation", "Traction", "Analysis", "Study", "DmaCase"]


def _positive(obj, *keys) -> None:
    for key in keys:
        value = getattr(obj, key)
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
            raise ValueError(f"{key}: must be a number > 0, got {value!r}")


@dataclass(frozen=True)
class DmaBearing:
    """``[bearing]``: the report's bearing (its geometry and steel); SI units, angles in degrees."""

    n_balls: int = 24
    ball_diameter_m: float = 0.015875
    pitch_diameter_m: float = 0.125
    contact_angle_deg: float = 26.0
    conformity_inner: float = 0.52
    conformity_outer: float = 0.52
    E_Pa: float = 200e9
    poisson: float = 0.25
    density_kg_m3: float = 7750.0

    def __post_init__(self) -> None:
        if not (isinstance(self.n_balls, int) and 3 <= self.n_balls <= 200):
            raise ValueError(f"n_balls: must be an integer in 3 … 200, got {self.n_balls!r}")
        _positive(self, "ball_diameter_m", "pitch_diameter_m", "E_Pa", "density_kg_m3")
        if not 5.0 <= self.contact_angle_deg <= 60.0:
            raise ValueError(f"contact_angle_deg: must lie in 5 … 60, got {self.contact_angle_deg!r}")
        for key in ("conformity_inner", "conformity_outer"):
            if not 0.505 <= getattr(self, key) <= 0.6:
                raise ValueError(f"{key}: must lie in 0.505 … 0.6, got {getattr(self, key)!r}")
        if not 0.0 <= self.poisson < 0.5:
            raise ValueError(f"poisson: must lie in [0, 0.5), got {self.poisson!r}")
        if self.n_balls * self.ball_diameter_m >= math.pi * self.pitch_diameter_m:
            raise ValueError(f"n_balls: {self.n_balls} balls of {self.ball_diameter_m} m do not fit on the pitch "
                             f"circle of {self.pitch_diameter_m} m")


@dataclass(frozen=True)
class Operation:
    """``[operation]``: thrust on the outer race (N), its speed (rev/min, the inner race held), the
    oil temperature (°C) and whether the balls feel the mixture's drag."""

    thrust_N: float = 267.0
    outer_speed_rpm: float = 60.0
    temperature_C: float = 15.0
    drag: bool = True

    def __post_init__(self) -> None:
        _positive(self, "thrust_N", "outer_speed_rpm")
        if not -40.0 <= self.temperature_C <= 150.0:
            raise ValueError(f"temperature_C: must lie in −40 … 150, got {self.temperature_C!r}")


@dataclass(frozen=True)
class Traction:
    """``[traction]``: the raceway traction model, its coefficients and the strips (module docstring).

    ``A`` (κ = A, A − B·u), ``B`` s/m (κ = B·u, A − B·u), ``blend_m_s`` the slip below which the
    constant and falling models fade to 0 (the report's have none; a blend keeps the step finite),
    ``strips`` across each contact ellipse (0: the centre-point law)."""

    model: Literal["linear", "constant", "falling"] = "linear"
    A: float = 0.015
    B: float = 1.0
    blend_m_s: float = 1e-4
    strips: int = 20

    def __post_init__(self) -> None:
        if self.model not in ("linear", "constant", "falling"):
            raise ValueError(f"model: linear, constant or falling, got {self.model!r}")
        for key in ("A", "B", "blend_m_s"):
            value = getattr(self, key)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
                raise ValueError(f"{key}: must be a number > 0, got {value!r}")
        if not (isinstance(self.strips, int) and 0 <= self.strips <= 400):
            raise ValueError(f"strips: must be an integer in 0 … 400, got {self.strips!r}")

    def law(self):
        """The friction law object of :mod:`mbd_core.contact.friction`."""
        from mbd_core.contact.friction import DrebConstant, DrebFalling, DrebLinear

        if self.model == "linear":
            return DrebLinear(self.B)
        if self.model == "constant":
            return DrebConstant(self.A, self.blend_m_s)
        return DrebFalling(self.A, self.B, self.blend_m_s)

    @property
    def label(self) -> str:
        return {"linear": f"κ = {self.B:g}·u", "constant": f"κ = {self.A:g}",
                "falling": f"κ = {self.A:g} − {self.B:g}·u"}[self.model]


@dataclass(frozen=True)
class Analysis:
    """``[analysis]``: simulated time (s), the share of it left out of the means as start-up, the
    largest time between recorded samples (s; the torque and the spectra are taken at the samples: 20 µs
    resolve up to 25 kHz), and the explicit step as a share of the automatic stable step (1: the step
    :func:`mbd_core.multibody.stable_timestep` picks; smaller: a finer, slower run)."""

    duration_s: float = 0.05
    settle_fraction: float = 0.4
    sample_interval_s: float = 2e-5
    step_factor: float = 1.0

    def __post_init__(self) -> None:
        _positive(self, "duration_s")
        if self.duration_s > 10.0:
            raise ValueError(f"duration_s: must be ≤ 10 s, got {self.duration_s!r}")
        if not 0.0 <= self.settle_fraction <= 0.9:
            raise ValueError(f"settle_fraction: must lie in [0, 0.9], got {self.settle_fraction!r}")
        _positive(self, "sample_interval_s")
        if self.sample_interval_s > self.duration_s / 10:
            raise ValueError(f"sample_interval_s: must be ≤ duration_s/10 ({self.duration_s / 10:g} s), got "
                             f"{self.sample_interval_s!r}")
        if not (isinstance(self.step_factor, (int, float)) and 0.01 <= self.step_factor <= 1.0):
            raise ValueError(f"step_factor: must lie in 0.01 … 1 (a share of the stable step), got {self.step_factor!r}")


@dataclass(frozen=True)
class Study:
    """``[study]``: ``kind``; the ``speed`` study's outer race speeds (rev/min) and thrusts (N)."""

    kind: Literal["torque", "traction-models", "speed"] = "torque"
    speeds_rpm: tuple[float, ...] = (10.0, 30.0, 60.0)
    loads_N: tuple[float, ...] = (89.0, 267.0)

    def __post_init__(self) -> None:
        for key in ("speeds_rpm", "loads_N"):
            values = getattr(self, key)
            if not values or len(values) > 20 or not all(
                    isinstance(v, (int, float)) and math.isfinite(v) and v > 0.0 for v in values):
                raise ValueError(f"{key}: must hold 1 … 20 numbers > 0, got {values!r}")


@dataclass(frozen=True)
class DmaCase(CaseTables):
    """A run of the DMA bearing (module docstring)."""

    FAMILY: ClassVar[str] = "dma"  # the ``family`` key of its case files
    name: str = "dma"
    description: str = ""
    bearing: DmaBearing = field(default_factory=DmaBearing)
    operation: Operation = field(default_factory=Operation)
    traction: Traction = field(default_factory=Traction)
    analysis: Analysis = field(default_factory=Analysis)
    study: Study = field(default_factory=Study)
