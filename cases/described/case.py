"""A case that points at a bearing description file: ``flexbearing run my-case.toml`` on any bearing.

The case file names the bearing (a built-in bearing or a description file, :mod:`cases.bearing_file`),
whether its ``[rings.X]`` tables make rings modal, the rating-life conditions and the study:

- ``load-distribution``: every load case of the file (its load, spectrum or time history): element
  and contact loads, static safety s0 per row (ISO 76), the stiffness matrix, L10 when the life
  conditions are given — the outputs of ``flexbearing loaddist`` in ``loaddist/``;
- ``limiting-curve``: the same and the limiting load curve at ``study.s0`` (or
  ``study.p0_limit_MPa``), with modal and rigid rings where the file makes rings modal.

Example (``family = "bearing"`` first)::

    family = "bearing"
    name = "pitch-bearing"
    [bearing]
    file = "examples/bearings/modal/pitch-bearing-modal-rings.toml"   # relative to the current folder
    [study]
    kind = "limiting-curve"
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar, Literal

from ..config import CaseTables

__all__ = ["Source", "Life", "Study", "DescribedCase"]


@dataclass(frozen=True)
class Source:
    """``[bearing]``: ``file`` — a built-in bearing's name (``flexbearing loaddist`` lists them) or a
    description file (.toml, path relative to the current folder); ``rings`` — ``"file"`` (modal where
    the file has ``[rings.X]`` tables) or ``"rigid"``."""

    file: str = "slewing-ring"
    rings: Literal["file", "rigid"] = "file"

    def __post_init__(self) -> None:
        if not self.file.strip():
            raise ValueError("file: must name a built-in bearing or a description file (.toml)")


@dataclass(frozen=True)
class Life:
    """``[life]``: the ring that turns relative to the load (``"none"``: no rating life) and the speed, rev/min."""

    rotating_ring: Literal["none", "moving", "fixed"] = "none"
    speed_rpm: float = 0.0

    def __post_init__(self) -> None:
        if self.rotating_ring == "none" and self.speed_rpm != 0.0:
            raise ValueError("speed_rpm: give rotating_ring too (the life needs both)")
        if self.rotating_ring != "none" and not (math.isfinite(self.speed_rpm) and self.speed_rpm > 0.0):
            raise ValueError(f"speed_rpm: must be > 0 with a rotating ring, got {self.speed_rpm!r}")


@dataclass(frozen=True)
class Study:
    """``[study]``: ``kind``; the limiting load curve's criterion: ``s0`` (ISO 76) or ``p0_limit_MPa``
    (0: use s0)."""

    kind: Literal["load-distribution", "limiting-curve"] = "load-distribution"
    s0: float = 1.0
    p0_limit_MPa: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.s0) and self.s0 > 0.0):
            raise ValueError(f"s0: must be > 0, got {self.s0!r}")
        if not (math.isfinite(self.p0_limit_MPa) and self.p0_limit_MPa >= 0.0):
            raise ValueError(f"p0_limit_MPa: must be ≥ 0 (0: the ISO 76 limit over s0), got {self.p0_limit_MPa!r}")


@dataclass(frozen=True)
class DescribedCase(CaseTables):
    """A run of a described bearing (module docstring)."""

    FAMILY: ClassVar[str] = "bearing"  # the ``family`` key of its case files
    name: str = "bearing"
    description: str = ""
    bearing: Source = field(default_factory=Source)
    life: Life = field(default_factory=Life)
    study: Study = field(default_factory=Study)

    def input_files(self) -> dict[str, str]:
        """The files the case reads, by key (checked when a run is resolved)."""
        from ..catalog import BUILTIN_BEARINGS

        return {} if self.bearing.file in BUILTIN_BEARINGS else {"bearing.file": self.bearing.file}

