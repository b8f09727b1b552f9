"""The case file of the 12 MW wind main bearing (Pang et al., *Lubricants* 12 (2024) 252): what a run needs.

Tables: ``rollers`` (material, slices, rib and pocket play, thrust roller ends), ``bodies``
(rigid or modal rings and cages), ``contact`` (stiffness preset, damping, friction), ``loads``
(the synthetic 32-case spectrum of :mod:`.spectrum`, a user CSV, or one load case held constant),
``analysis`` (driving speed, simulated time) and ``study``. Every value is SI; construction checks
each field and names it on error (see :mod:`cases.config`).

Geometry (:class:`fem_rings.sections.ThreeRowGeometry`): 98 radial rollers Ø55 × 55 mm on pitch
Ø1963 mm, 2 × 94 thrust rollers Ø60 × 60 mm on pitch Ø2182 mm, clearances in the middle of the
stated ranges; +z points from the rotor (front) to the rear, y is vertical (up). The inner ring
(both pieces as one body, 3971 kg) turns at the driving speed and is free to translate and tilt
under the loads applied at its centre; the outer ring with the nose is fixed.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar, Literal

from mbd_core.contact.friction import Coulomb

from ..config import CaseTables

__all__ = ["Rollers", "Bodies", "Contact", "Loads", "Analysis", "Study", "WindCase", "ADAMS_CONTACT",
           "INNER_RING_MASS_KG", "OUTER_RING_MASS_KG", "RADIAL_CAGE_MASS_KG", "THRUST_CAGE_MASS_KG"]

#: masses of the paper's Table 2, kg (first + second inner ring; outer ring; cages)
INNER_RING_MASS_KG = 2271.0 + 1700.0
OUTER_RING_MASS_KG = 3055.0
THRUST_CAGE_MASS_KG = 90.2
RADIAL_CAGE_MASS_KG = 70.0


def _positive(**values) -> None:
    for name, v in values.items():
        if not v > 0:
            raise ValueError(f"{name} must be positive, got {v!r}")


@dataclass(frozen=True)
class Rollers:
    """Roller material (``steel`` or the paper's aluminium bronze E = 110 GPa, ν = 0.32), slices
    per roller, the play of a roller along its axis between its end guides (radial row: ribs of
    the inner ring at z0 ± h; thrust rows: the ends of the cage's window pockets at R ± h), the
    radius of the thrust rollers' domed end faces and the play of every roller in its cage
    pocket, m.

    Thrust roller ends are domed (end radius 27 mm on a Ø60 mm roller, a flat rim of 3 mm): a flat
    end against the cylindrical stop of radius R ± L/2 would touch it with its rim first (the rim
    sits ρ²/(2R) ≈ 0.26 mm deeper at ρ = 24 mm) and wedge between the two stops once skewed.
    Radial rollers keep flat ends with a 5.5 mm edge radius (0.1 D) against their flat ribs."""

    material: Literal["steel", "bronze"] = "steel"
    n_slices: int = 10
    rib_clearance_m: float = 0.5e-3
    thrust_end_radius_m: float = 0.027
    pocket_clearance_m: float = 0.5e-3

    def __post_init__(self) -> None:
        if self.n_slices < 1:
            raise ValueError(f"n_slices must be ≥ 1, got {self.n_slices}")
        _positive(rib_clearance_m=self.rib_clearance_m, thrust_end_radius_m=self.thrust_end_radius_m,
                  pocket_clearance_m=self.pocket_clearance_m)


@dataclass(frozen=True)
class Bodies:
    """Rigid or modal rings and cages (the paper: 20 modes each).

    ``auto`` (:mod:`.auto`): a cheap pass decides the rings (rigid, or modal with its modes) from
    the ring's deflection under the rigid-ring roller loads against the rollers' Hertz approach,
    and keeps the cages rigid, saying why in ``summary.json`` (``fidelity_decisions``).

    Modal rings: the inner ring floats on free–free modes (its frame carries the drive, the loads
    and gravity), the outer ring is held at ``bolts`` patches of its rear (bolt) face; their
    raceways are sampled on ``n_theta`` × ``n_across`` grids (roller slices interpolate between
    them). Modal cages: free–free modes, pocket walls sampled. Meshes: quadratic hexahedra of
    ``ring_element_size_m`` for the rings, quadratic tetrahedra of ``cage_element_size_m`` for
    the cages; ``modal_damping_ratio`` of critical on every mode.
    """

    rings: Literal["rigid", "modal", "auto"] = "rigid"
    cages: Literal["rigid", "modal", "auto"] = "rigid"
    n_modes: int = 20
    modal_damping_ratio: float = 0.02
    n_theta: int = 360
    n_across: int = 3
    bolts: int = 48
    ring_element_size_m: float = 0.06
    cage_element_size_m: float = 0.02

    def __post_init__(self) -> None:
        if self.n_modes < 1:
            raise ValueError(f"n_modes must be ≥ 1, got {self.n_modes}")
        if not 0.0 <= self.modal_damping_ratio < 1.0:
            raise ValueError(f"modal_damping_ratio must lie in [0, 1), got {self.modal_damping_ratio}")
        if self.n_theta < 8 or self.n_across < 2 or self.bolts < 3:
            raise ValueError(f"n_theta ≥ 8, n_across ≥ 2 and bolts ≥ 3 are needed, got {self.n_theta}, "
                             f"{self.n_across}, {self.bolts}")
        _positive(ring_element_size_m=self.ring_element_size_m, cage_element_size_m=self.cage_element_size_m)
        self._check_auto()

    @property
    def any_modal(self) -> bool:
        return "modal" in (self.rings, self.cages)

    def _check_auto(self) -> None:
        if self.rings == "auto" and self.cages == "modal":
            raise ValueError('cages: with rings = "auto" the cages are "rigid" or "auto" (one n_modes serves rings '
                             'and cages, and auto chooses it for the rings)')


#: the paper's Adams IMPACT settings for every roller contact (Pang et al. 2024, §3): K = 1e5 N/mm^1.5,
#: n = 1.5, c = 70 N·s/mm, d_max = 0.1 mm — in SI
ADAMS_CONTACT = dict(stiffness_N_per_m1p5=1e5 * 1e3**1.5, exponent=1.5, damping_N_s_m=70e3, d_max_m=0.1e-3)


@dataclass(frozen=True)
class Contact:
    """Roller contacts: stiffness, damping and friction.

    ``hertz`` (default): each slice follows the ISO/TS 16281 line-contact law of the roller
    (exponent 10/9), damped at ``damping_ratio`` of the critical damping of a roller on the
    linearised stiffness of one contact at the mean radial roller load. ``adams``: the paper's
    IMPACT values (:data:`ADAMS_CONTACT`) for each whole roller contact, shared by its slices
    (``damping_ratio`` unused). Friction (Adams step law):
    μ_static at v_static, μ_dynamic from v_dynamic on, the paper's μ_s = 0.2, μ_d = 0.1; transition
    speeds 0.3/0.6 m/s by default, below the rollers' surface speed (3 m/s at 30 rpm). The paper's
    10/100 mm/s are used by the presets ``wind-driving-speed``, ``wind-friction`` and
    ``wind-speeds-adams``: the cage forces depend on them, the roller speeds hardly (within 0.3 %);
    with them the friction carries about 0.4 % of the load in the inner ring's balance, which the
    equilibrium figure (normal forces only) does not count.
    ``implicit_friction`` (default on): the friction of rollers and rigid cages is integrated
    implicitly (:class:`mbd_core.multibody.ModelBuilder`), so that the slope of the friction law
    does not limit the explicit step; off, the step is 5–6× smaller at the default transition
    speeds.
    """

    preset: Literal["hertz", "adams"] = "hertz"
    damping_ratio: float = 0.1
    mu_static: float = 0.2
    mu_dynamic: float = 0.1
    v_static_m_s: float = 0.3
    v_dynamic_m_s: float = 0.6
    pocket_stiffness_N_per_m: float = 1e8
    implicit_friction: bool = True

    def __post_init__(self) -> None:
        if not 0.0 <= self.damping_ratio <= 2.0:
            raise ValueError(f"damping_ratio must lie in [0, 2], got {self.damping_ratio}")
        _positive(pocket_stiffness_N_per_m=self.pocket_stiffness_N_per_m)
        self.friction_law()  # the law checks its own parameters

    def friction_law(self) -> Coulomb:
        return Coulomb(self.mu_static, self.mu_dynamic, self.v_static_m_s, self.v_dynamic_m_s)


@dataclass(frozen=True)
class Loads:
    """Loads at the inner-ring centre.

    ``source``: ``synthetic`` (the documented 32-case spectrum, :mod:`.spectrum`), ``csv`` (a user
    file at ``csv_path``, same columns, see :func:`.spectrum.read_csv`) or ``constant`` (load case
    ``case_index`` of the synthetic spectrum held over the whole run). The cases are laid out
    over ``spectrum_duration_s`` (the paper: 8 s) and joined by a cubic spline; ``scale``
    multiplies every component; ``include_torque``: the driving torque Mz is applied (the driven
    inner ring takes it up either way).
    """

    source: Literal["synthetic", "csv", "constant"] = "synthetic"
    csv_path: str | None = None
    case_index: int = 18
    spectrum_duration_s: float = 8.0
    scale: float = 1.0
    include_torque: bool = False

    def __post_init__(self) -> None:
        if self.source == "csv" and not self.csv_path:
            raise ValueError("csv_path is needed when source = 'csv'")
        if not 0 <= self.case_index < 32:
            raise ValueError(f"case_index must lie in 0…31, got {self.case_index}")
        _positive(spectrum_duration_s=self.spectrum_duration_s)
        if not self.scale >= 0:
            raise ValueError(f"scale must be ≥ 0, got {self.scale}")


@dataclass(frozen=True)
class Analysis:
    """Driving speed of the inner ring (rpm), simulated time (s), the settling time excluded from
    the averages (s), how often a sample is recorded (steps; 50 steps ≈ 0.6–0.8 ms at the steps
    of implicit friction) and the explicit step as a share of the automatic stable step
    (``step_factor`` in (0, 1]; 1: the automatic step, :func:`mbd_core.multibody.stable_timestep`)."""

    speed_rpm: float = 30.0
    duration_s: float = 8.0
    settle_s: float = 0.5
    record_every: int = 50
    step_factor: float = 1.0

    def __post_init__(self) -> None:
        _positive(speed_rpm=self.speed_rpm, duration_s=self.duration_s, record_every=self.record_every)
        if not 0.0 < self.step_factor <= 1.0:
            raise ValueError(f"step_factor must lie in (0, 1] (a share of the automatic stable step), got "
                             f"{self.step_factor!r}")
        if not 0 <= self.settle_s < self.duration_s:
            raise ValueError(f"settle_s must lie in [0, duration_s), got {self.settle_s}")


@dataclass(frozen=True)
class Study:
    """``static``: quasi-static load distribution under every load case (each a ``load-case``
    run); ``load-case``: the one under ``loads.case_index``; ``speeds``: roller and cage speeds
    against rolling kinematics; ``rigid-flexible``: the same with rigid and with modal rings and
    cages, and the ratio of their errors;
    ``driving-speed``: cage and raceway forces at each of ``speeds_rpm``; ``friction``: cage
    forces for each (μ_dynamic, μ_static) of ``friction_sets``."""

    kind: Literal["static", "load-case", "speeds", "rigid-flexible", "driving-speed", "friction"] = "speeds"
    speeds_rpm: tuple[float, ...] = (20.0, 25.0, 30.0)
    friction_sets: tuple[tuple[float, float], ...] = ((0.025, 0.05), (0.05, 0.1), (0.075, 0.15), (0.1, 0.2))

    def __post_init__(self) -> None:
        if not self.speeds_rpm or min(self.speeds_rpm) <= 0:
            raise ValueError(f"speeds_rpm must be positive speeds, got {self.speeds_rpm}")
        for mu_d, mu_s in self.friction_sets:
            if not 0 <= mu_d <= mu_s:
                raise ValueError(f"friction_sets: each pair is (μ_dynamic, μ_static) with 0 ≤ μ_d ≤ μ_s, got {(mu_d, mu_s)}")


@dataclass(frozen=True)
class WindCase(CaseTables):
    """A run of the wind main bearing (module docstring)."""

    FAMILY: ClassVar[str] = "wind"  # the ``family`` key of its case files
    name: str = "wind"
    description: str = ""
    rollers: Rollers = field(default_factory=Rollers)
    bodies: Bodies = field(default_factory=Bodies)
    contact: Contact = field(default_factory=Contact)
    loads: Loads = field(default_factory=Loads)
    analysis: Analysis = field(default_factory=Analysis)
    study: Study = field(default_factory=Study)

    def __post_init__(self) -> None:
        if "auto" in (self.bodies.rings, self.bodies.cages) and self.study.kind == "rigid-flexible":
            raise ValueError('bodies.rings: the rigid-flexible study runs rigid and modal rings and cages itself; '
                             '"auto" is for the other dynamic studies')
        if self.contact.preset == "adams" and self.analysis.step_factor != 1.0:
            raise ValueError("analysis.step_factor: the adams preset takes the automatic step of each piece of "
                             "the run (its soft contacts stiffen as the loads grow); leave step_factor at 1")
        self._check_model_sizes()

    def _check_model_sizes(self) -> None:
        """Each modal ring and cage can give its modes and fits in memory (before anything is meshed)."""
        from fem_rings.cages import three_row_cages
        from fem_rings.sections import three_row_inner_ring, three_row_outer_ring

        from ..mesh_budget import cached_profile, check_model_size

        b = self.bodies
        if b.rings in ("modal", "auto"):
            for profile in (cached_profile(three_row_inner_ring), cached_profile(three_row_outer_ring)):
                check_model_size(profile, b.ring_element_size_m, b.n_modes, "bodies.ring_element_size_m",
                                 "bodies.n_modes")
        if b.cages == "modal":
            for profile, _ in cached_profile(three_row_cages).values():
                check_model_size(profile, b.cage_element_size_m, b.n_modes, "bodies.cage_element_size_m",
                                 "bodies.n_modes")

    def input_files(self) -> dict[str, str]:
        """The files the case reads, by key (checked when a run is resolved)."""
        return {"loads.csv_path": self.loads.csv_path} if self.loads.source == "csv" else {}

