"""A case that points at a bearing description file: ``flexbearing run my-case.toml`` on any bearing.

The case file names the bearing (a built-in bearing or a description file, :mod:`cases.bearing_file`),
whether its ``[rings.X]`` tables make rings modal, the rating-life conditions and the study:

- ``load-distribution``: every load case of the file (its load, spectrum or time history): element
  and contact loads, static safety s0 per row (ISO 76), the stiffness matrix, L10 when the life
  conditions are given — the outputs of ``flexbearing loaddist`` in ``loaddist/``;
- ``limiting-curve``: the same and the limiting load curve at ``study.s0`` (or
  ``study.p0_limit_MPa``), with modal and rigid rings where the file makes rings modal;
- ``rotation``: a dynamic run: the moving ring turning at ``rotation.speed_rpm`` under the file's
  load, the balls with their cage, spacer balls or as a full complement (each row's
  ``[rows.separator]``), against the quasi-static load distribution (:mod:`.rotation`).

``[rings]`` sets the fidelity of the file's modal rings for this run, over every ``[rings.X]`` table
of the file (modes, raceway load shapes, element size as a factor of each ring's, element load
shapes): the knobs of the family's fidelity ladder (:mod:`.fidelity`, ``flexbearing tradeoff``).

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

__all__ = ["Source", "RingFidelity", "Life", "Study", "Rotation", "DescribedCase"]


@dataclass(frozen=True)
class Source:
    """``[bearing]``: ``file`` — a built-in bearing's name (``flexbearing loaddist`` lists them) or a
    description file (.toml, path relative to the current folder); ``rings`` — ``"file"`` (modal where
    the file has ``[rings.X]`` tables), ``"rigid"``, or ``"auto"`` (the load-distribution study: a
    cheap pass keeps each of the file's modal rings rigid where its deflection cannot change the
    element loads by the tolerance, else chooses its modal model, and says why; :mod:`.auto`)."""

    file: str = "slewing-ring"
    rings: Literal["file", "rigid", "auto"] = "file"

    def __post_init__(self) -> None:
        if self.rings not in ("file", "rigid", "auto"):
            raise ValueError(f"rings: file, rigid or auto, got {self.rings!r}")
        if not self.file.strip():
            raise ValueError("file: must name a built-in bearing or a description file (.toml)")


@dataclass(frozen=True)
class RingFidelity:
    """``[rings]``: the modal rings' fidelity for this run, over what every ``[rings.X]`` table of the
    bearing file says (unset: the file's value): ``n_modes``, ``raceway_harmonics``,
    ``element_load_shapes`` (the keys of the file's tables, cases/bearings/README.md) and
    ``element_size_factor`` (each ring's element size times this)."""

    n_modes: int | None = None
    raceway_harmonics: int | None = None
    element_size_factor: float = 1.0
    element_load_shapes: bool | None = None

    def __post_init__(self) -> None:
        if self.n_modes is not None and not 1 <= self.n_modes <= 400:
            raise ValueError(f"n_modes: must lie in 1 … 400, got {self.n_modes}")
        if self.raceway_harmonics is not None and not 0 <= self.raceway_harmonics <= 60:
            raise ValueError(f"raceway_harmonics: must lie in 0 … 60, got {self.raceway_harmonics}")
        if not (math.isfinite(self.element_size_factor) and 0.05 <= self.element_size_factor <= 10.0):
            raise ValueError(f"element_size_factor: must lie in [0.05, 10], got {self.element_size_factor!r}")

    @property
    def overrides(self) -> dict:
        """The ``[rings.X]`` keys this table sets (element size as a factor), for :func:`cases.bearing_rings.with_fidelity`."""
        out = {k: getattr(self, k) for k in ("n_modes", "raceway_harmonics", "element_load_shapes")
               if getattr(self, k) is not None}
        if self.element_size_factor != 1.0:
            out["element_size_factor"] = self.element_size_factor
        return out


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

    kind: Literal["load-distribution", "limiting-curve", "rotation"] = "load-distribution"
    s0: float = 1.0
    p0_limit_MPa: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.s0) and self.s0 > 0.0):
            raise ValueError(f"s0: must be > 0, got {self.s0!r}")
        if not (math.isfinite(self.p0_limit_MPa) and self.p0_limit_MPa >= 0.0):
            raise ValueError(f"p0_limit_MPa: must be ≥ 0 (0: the ISO 76 limit over s0), got {self.p0_limit_MPa!r}")


@dataclass(frozen=True)
class Rotation:
    """``[rotation]``: the dynamic study (rigid or modal rings, explicit or implicit integration).

    Attributes
    ----------
    speed_rpm : float
        Speed of the moving ring about the bearing axis, rev/min (> 0).
    moving_ring_mass_kg : float or None
        Mass of the moving ring and of what turns with it, kg (required with a rigid moving ring;
        its inertia is that of a thin ring on the largest pitch circle); a modal moving ring has
        its finite-element model's mass and refuses the key.
    duration_s : float
        Simulated time, s.
    timestep_s : float or None
        Explicit step, s (None: the automatic step from the stiffest contact).
    record_every : int
        Steps between recorded samples.
    damping_ratio : float
        Normal damping of every element contact, as a share of the critical damping of one element
        on its linearised Hertz stiffness at the row's largest quasi-static load.
    mu_static, mu_dynamic, v_static_m_s, v_dynamic_m_s : float
        Friction at the raceways, between elements and in the pockets (regularised Coulomb:
        μ_static at v_static, μ_dynamic from v_dynamic on). The defaults stand for the traction
        of lubricated contacts (some 0.02–0.06); the transition speeds bound the explicit step.
    friction : bool
        False: frictionless contacts (the elements then keep their start speeds).
    implicit_friction : bool
        True: the friction of the balls, spacers, cage and moving ring enters their kicks implicitly
        (:mod:`mbd_core.kernels.explicit`), so the friction law's slope no longer limits the
        automatic step (the contacts do); False (default): explicit friction.
    integrator : {"explicit", "implicit"}
        ``explicit`` (default): velocity Verlet in pieces (checkpoints, resume); ``implicit``: the
        generalized-α integrator (:func:`cases.integrate.integrate_implicit`, spectral radius at
        infinity ``rho_inf``) in one piece at ``timestep_s`` (None:
        :data:`cases.described.rotation.IMPLICIT_STEP_FACTOR`, 3 × the automatic explicit step), a
        reference for the explicit run; its step has no Richardson estimate.
    rho_inf : float
        Spectral radius at infinity of the implicit integrator, [0, 1] (1: no numerical damping).
    gravity_m_s2 : float
        Gravity along −z on the rolling elements, spacers and cages (9.81 for a bearing with a
        vertical axis: spacer balls then rest in the lower groove); the moving ring's own weight
        is part of the file's load and is not added again.
    """

    speed_rpm: float = 60.0
    moving_ring_mass_kg: float | None = None
    duration_s: float = 0.1
    timestep_s: float | None = None
    record_every: int = 50
    damping_ratio: float = 0.2
    mu_static: float = 0.05
    mu_dynamic: float = 0.04
    v_static_m_s: float = 0.05
    v_dynamic_m_s: float = 0.1
    friction: bool = True
    implicit_friction: bool = False
    integrator: Literal["explicit", "implicit"] = "explicit"
    rho_inf: float = 0.9
    gravity_m_s2: float = 0.0

    def __post_init__(self) -> None:
        for key in ("speed_rpm", "duration_s"):
            if not (math.isfinite(getattr(self, key)) and getattr(self, key) > 0.0):
                raise ValueError(f"{key}: must be > 0, got {getattr(self, key)!r}")
        for key in ("moving_ring_mass_kg", "timestep_s"):
            value = getattr(self, key)
            if value is not None and not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{key}: must be > 0, got {value!r}")
        if self.timestep_s is not None and self.timestep_s > self.duration_s:
            raise ValueError(f"timestep_s: must not exceed duration_s ({self.duration_s!r}), got {self.timestep_s!r}")
        if not 1 <= self.record_every <= 1_000_000:
            raise ValueError(f"record_every: must lie in 1 … 1e6, got {self.record_every!r}")
        if not 0.0 <= self.damping_ratio <= 2.0:
            raise ValueError(f"damping_ratio: must lie in [0, 2], got {self.damping_ratio!r}")
        if not 0.0 <= self.gravity_m_s2 <= 100.0:
            raise ValueError(f"gravity_m_s2: must lie in [0, 100], got {self.gravity_m_s2!r}")
        if self.integrator not in ("explicit", "implicit"):
            raise ValueError(f"integrator: explicit or implicit, got {self.integrator!r}")
        if not (math.isfinite(self.rho_inf) and 0.0 <= self.rho_inf <= 1.0):
            raise ValueError(f"rho_inf: must lie in [0, 1], got {self.rho_inf!r}")
        self.friction_law()

    def friction_law(self):
        """The contacts' :class:`~mbd_core.contact.friction.Coulomb` law (None: frictionless)."""
        from mbd_core.contact.friction import Coulomb

        if not self.friction:
            return None
        try:
            return Coulomb(self.mu_static, self.mu_dynamic, self.v_static_m_s, self.v_dynamic_m_s)
        except ValueError as exc:
            message = str(exc).partition(": ")[2]
            key = next((k for k in ("mu_static", "mu_dynamic", "v_static_m_s", "v_dynamic_m_s")
                        if message.startswith(k) or message.startswith(f"need 0 < {k}")), "mu_static")
            raise ValueError(f"{key}: {message}") from None


@dataclass(frozen=True)
class DescribedCase(CaseTables):
    """A run of a described bearing (module docstring)."""

    FAMILY: ClassVar[str] = "bearing"  # the ``family`` key of its case files
    name: str = "bearing"
    description: str = ""
    bearing: Source = field(default_factory=Source)
    rings: RingFidelity = field(default_factory=RingFidelity)
    life: Life = field(default_factory=Life)
    study: Study = field(default_factory=Study)
    rotation: Rotation = field(default_factory=Rotation)

    def __post_init__(self) -> None:
        if self.bearing.rings == "auto":
            from .auto import refused_reason

            why = refused_reason(self)
            if why:
                raise ValueError(f'bearing.rings: "auto" decides the rings of a load distribution; {why}')

    def input_files(self) -> dict[str, str]:
        """The files the case reads, by key (checked when a run is resolved)."""
        from ..catalog import BUILTIN_BEARINGS

        return {} if self.bearing.file in BUILTIN_BEARINGS else {"bearing.file": self.bearing.file}

