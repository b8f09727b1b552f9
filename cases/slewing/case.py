"""The slewing-ring case: what a run of the fast-reactor slewing ring is made of.

A case is a frozen dataclass tree, validated on creation and read from / written to TOML with
:mod:`cases.config` (errors name the dotted key). SI units, with the unit in every key name;
angles in degrees in case files. The tables of a case file:

=============  ===================================================================================
``geometry``   variant (full Ø6.69 m / 1 m / 2 m scaled) and the cross-sections chosen for the
               races and the top-and-middle ring (TMR), which the thesis does not give
``load``       dead load carried by the top structure (default: the variant's, from the thesis) and gravity
``undulation`` bottom-race axial undulation: ``scale`` × :data:`UNDULATION_PROFILE_DEG_MM` (periodic cubic spline)
``thermal``    radial offset Δ of the top race over one sector and of the bottom race over another
               (differential thermal expansion), smooth raised-cosine edges
``contact``    ``hertz`` (exact Hertz constants of each groove, default) or ``thesis`` (the
               thesis' RecurDyn values: K = 2 581 637 N/mm^1.5, c = K/1000 s), damping, friction
``top``        fidelity of the top structure (top race, with the TMR bolted to it as one body)
``bottom``     fidelity of the bottom race (rigid on its support, or modal, bolted at ``bolts``)
``analysis``   ``quasi_static`` (load distribution; with ``travel_steps`` the balls roll through
               one revolution of the top race as a sequence of equilibria) or ``dynamic_explicit``
``study``      which study (a)–(g) the run is, and the values it sweeps
=============  ===================================================================================

The dead load is carried as mass of the top structure (its density raised so that its weight is
the dead load): the rotatable plug rests on the TMR all round and turns with it, so its weight is
spread like the ring's and its inertia turns with the ring. A load spread like the mass does no
work on the free–free elastic modes; the ring bends under the ball reactions only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar, Literal

import numpy as np

from fem_rings.sections import SlewingSection
from mbd_core.contact.friction import Coulomb

from ..config import CaseTables

__all__ = ["VARIANTS", "Geometry", "Load", "Undulation", "Thermal", "Contact", "BodyFidelity", "Analysis",
           "Study", "SlewingCase", "UNDULATION_PROFILE_DEG_MM", "THESIS_CONTACT_STIFFNESS_N_PER_M1P5", "THESIS_CONTACT_DAMPING_N_S_PER_M",
           "REDUCED_E_PA"]

#: variant → (pitch diameter m, load balls, spacer ball diameter m, dead load t incl. the top race), the
#: thesis' full-scale ring and its 1 m and 2 m models
VARIANTS = {
    "full": (6.69, 116, 85.25e-3, 503.25),
    "1m": (1.0, 16, 85.25e-3, 68.9),
    "2m": (2.0, 33, 92.0e-3, 140.0),
}
#: undulation profile, (θ deg, h mm), peak-to-valley 1.0 mm; periodic cubic spline through it. Chosen
#: here: the thesis shows its profile in a figure only, without the data
UNDULATION_PROFILE_DEG_MM = ((0.0, 0.0), (30.0, 0.5), (65.0, 0.0), (103.0, -0.5), (142.0, 0.0), (180.0, 0.5),
                             (215.0, 0.2), (240.0, 0.0), (251.0, -0.4), (262.0, 0.0), (300.0, 0.3), (330.0, 0.5))
#: the thesis' ball–race contact (Table 2): K = 2 581 637 N/mm^1.5 per contact, in N/m^1.5
THESIS_CONTACT_STIFFNESS_N_PER_M1P5 = 2581637.0 * 1000.0**1.5
#: and its damping c = K/1000 = 2581.637 N·s/mm, in N·s/m
THESIS_CONTACT_DAMPING_N_S_PER_M = 2581.637e3
#: the thesis' reduced modulus E·(2/6.69)⁴ that gives the 2 m ring the full-scale bending stiffness
REDUCED_E_PA = 1.5975e9

Variant = Literal["full", "1m", "2m"]


def _positive(owner: str, **values) -> None:
    for k, v in values.items():
        if v is not None and not (math.isfinite(v) and v > 0.0):
            raise ValueError(f"{k} must be a positive number, got {v!r}")


@dataclass(frozen=True)
class Geometry:
    """Bearing variant and the chosen cross-sections (defaults: :mod:`fem_rings.sections`)."""

    variant: Variant = "2m"
    ball_diameter_m: float = 95.25e-3
    conformity: float = 0.525
    contact_angle_deg: float = 60.0
    groove_depth_m: float = 0.030
    race_width_m: float = 0.220
    race_height_m: float = 0.100
    tmr_width_m: float = 0.500
    tmr_height_m: float = 0.400
    spacer_diameter_m: float | None = None  # None: the variant's (thesis)

    def __post_init__(self) -> None:
        _positive("geometry", ball_diameter_m=self.ball_diameter_m, spacer_diameter_m=self.spacer_diameter_m)
        if not 0.0 < self.contact_angle_deg < 90.0:
            raise ValueError(f"contact_angle_deg must lie in (0, 90), got {self.contact_angle_deg}")
        if not (math.isfinite(self.conformity) and self.conformity > 0.5):
            raise ValueError(f"conformity must be > 0.5 (the ball must be smaller than its groove), "
                             f"got {self.conformity}")
        if self.spacer_diameter_m is not None and not self.spacer_diameter_m < self.ball_diameter_m:
            raise ValueError(f"spacer_diameter_m ({self.spacer_diameter_m}) must be below ball_diameter_m "
                             f"({self.ball_diameter_m}): spacer balls touch the bottom race only")
        self.section()  # the section checks its own sizes (groove depth, widths)
        self._races()  # and the sections made from it theirs
        pitch, n, spacer, _ = VARIANTS[self.variant]
        pair = self.ball_diameter_m + (spacer if self.spacer_diameter_m is None else self.spacer_diameter_m)
        if n * pair > math.pi * pitch:
            raise ValueError(f"spacer_diameter_m: {n} load and {n} spacer balls do not fit on the "
                             f"{pitch} m pitch circle")

    def _races(self) -> None:
        """Build every section of the variant: each checks its own shape (a groove the ball can
        touch, a TMR of non-zero thickness on the top race)."""
        from fem_rings.sections import slewing_bottom_race, slewing_tmr, slewing_top_race, slewing_top_structure

        from ..mesh_budget import cached_profile

        for make in (slewing_bottom_race, slewing_top_race, slewing_tmr, slewing_top_structure):
            cached_profile(make, self.pitch_diameter_m, self.section())

    def section(self) -> SlewingSection:
        return SlewingSection(self.ball_diameter_m, self.conformity, self.contact_angle_deg, self.groove_depth_m,
                              self.race_width_m, self.race_height_m, self.tmr_width_m, self.tmr_height_m)

    @property
    def pitch_diameter_m(self) -> float:
        return VARIANTS[self.variant][0]

    @property
    def n_balls(self) -> int:
        return VARIANTS[self.variant][1]

    @property
    def spacer_m(self) -> float:
        return VARIANTS[self.variant][2] if self.spacer_diameter_m is None else self.spacer_diameter_m


@dataclass(frozen=True)
class Load:
    """Dead load on the balls (plug, TMR and top race), t; None: the variant's (thesis)."""

    dead_load_t: float | None = None
    gravity_m_s2: float = 9.81

    def __post_init__(self) -> None:
        _positive("load", dead_load_t=self.dead_load_t, gravity_m_s2=self.gravity_m_s2)


@dataclass(frozen=True)
class Undulation:
    """Axial undulation of the bottom race: h(θ) = scale × periodic cubic spline through the profile."""

    scale: float = 0.0
    profile_deg_mm: tuple[tuple[float, float], ...] = UNDULATION_PROFILE_DEG_MM

    def __post_init__(self) -> None:
        if not (math.isfinite(self.scale) and self.scale >= 0.0):
            raise ValueError(f"scale must be ≥ 0, got {self.scale}")
        if not all(len(p) == 2 and all(math.isfinite(v) for v in p) for p in self.profile_deg_mm):
            raise ValueError(f"profile_deg_mm must list finite (θ deg, h mm) pairs, got {list(self.profile_deg_mm)}")
        deg = [p[0] for p in self.profile_deg_mm]
        if len(deg) < 4 or deg[0] != 0.0 or any(b <= a for a, b in zip(deg, deg[1:])) or deg[-1] >= 360.0:
            raise ValueError("profile_deg_mm must list ≥ 4 points (θ deg, h mm) with θ rising from 0 to "
                             "below 360 (the spline closes at 360 ≡ 0)")


@dataclass(frozen=True)
class Thermal:
    """Radial (outward) groove offset Δ of the top race over ``top_sector_deg`` (in the top race's
    own angle, so it turns with it) and of the bottom race over ``bottom_sector_deg``; the offset
    rises from 0 to Δ over ``edge_deg`` inside each sector by a raised cosine."""

    offset_m: float = 0.0
    top_sector_deg: tuple[float, float] = (80.0, 100.0)
    bottom_sector_deg: tuple[float, float] = (260.0, 280.0)
    edge_deg: float = 5.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.offset_m) and abs(self.offset_m) < 0.01):
            raise ValueError(f"offset_m must be a finite offset below 10 mm, got {self.offset_m}")
        for name in ("top_sector_deg", "bottom_sector_deg"):
            a, b = getattr(self, name)
            if not (0.0 <= a < b <= 360.0 and b - a >= 2.0 * self.edge_deg):
                raise ValueError(f"{name} must be (start, end) in degrees, 0 ≤ start < end ≤ 360, at least "
                                 f"2 × edge_deg = {2 * self.edge_deg} wide; got {(a, b)}")
        if not self.edge_deg >= 0.0:
            raise ValueError(f"edge_deg must be ≥ 0, got {self.edge_deg}")


@dataclass(frozen=True)
class Contact:
    """Ball contacts: stiffness preset, damping and friction (dynamic runs).

    ``damping_ratio``: normal damping of each ball contact as a fraction of the critical damping
    of a load ball on its linearised Hertz stiffness at the nominal load (the ``thesis`` preset
    uses its c = K/1000 s instead). Friction (RecurDyn/Adams step law): μ_static at v_static,
    μ_dynamic from v_dynamic on, the thesis' coefficients. Its transition speeds (1 and 2 mm/s)
    make the friction force so steep in the slip that an explicit step with explicit friction has to
    stay below 4e-8 s (measured: 12.9 million steps, 6 min for 0.4 s of the 1 m ring); the defaults
    50/100 mm/s, still well below the balls' rolling speed (0.34 m/s at 1 m, 6.55 rpm), allow
    1.5e-6 s. ``implicit_friction`` (default on): the friction of the balls and spacer balls is
    integrated implicitly (:class:`mbd_core.multibody.ModelBuilder`), so that the slope of the
    friction law no longer limits the explicit step (1 m ring: 1.65e-5 s; ball loads as with explicit
    friction to 5e-6 at 50/100 mm/s; at 1/2 mm/s the top structure rings on the balls, ±0.25 % at
    about 50 Hz, which explicit friction does not show: the slewing README).
    """

    preset: Literal["hertz", "thesis"] = "hertz"
    damping_ratio: float = 0.2
    mu_static: float = 0.24
    mu_dynamic: float = 0.14
    v_static_m_s: float = 0.05
    v_dynamic_m_s: float = 0.1
    friction: bool = True
    implicit_friction: bool = True

    def __post_init__(self) -> None:
        if not 0.0 <= self.damping_ratio <= 2.0:
            raise ValueError(f"damping_ratio must lie in [0, 2], got {self.damping_ratio}")
        self.friction_law()  # the friction law checks its own parameters

    def friction_law(self):
        """The ball contacts' :class:`~mbd_core.contact.friction.Coulomb` law (None: frictionless)."""
        if not self.friction:
            return None
        return Coulomb(self.mu_static, self.mu_dynamic, self.v_static_m_s, self.v_dynamic_m_s)


def _check_spread(profile, contact_rz_m, spread_m: float, key: str) -> None:
    """The groove patch of ``spread_m`` lies in the section (checked before anything is meshed)."""
    from fem_rings.nodesets import raceway_patch, section_raceway_curve

    curve = section_raceway_curve(profile, "groove", (0.0,), contact_rz_m)
    try:
        with np.errstate(over="ignore", invalid="ignore"):  # an absurd spread is refused below, quietly
            raceway_patch(curve, profile, spread_m)
    except ValueError as exc:
        raise ValueError(f"{key}.raceway_spread_m: {exc}") from None


@dataclass(frozen=True)
class BodyFidelity:
    """How a ring is modelled: ``rigid`` or ``modal`` (n_modes normal modes + raceway load shapes up
    to harmonic ``groove_harmonics``, −1: none), or (quasi-static equilibria with the balls at their
    places: study ``single`` without travel, each equilibrium of ``undulation``) ``auto``: a cheap
    pass chooses rigid or modal and the modal keys, and says why (:mod:`.auto`). ``E_Pa`` is its Young's modulus (the thesis'
    reduced-stiffness ring: 1.5975 GPa); ``element_size_m`` None takes a size from the variant.
    ``raceway_spread_m`` > 0 samples the groove averaged over a patch of that size around the
    contact point, and spreads the load shapes' line loads over it (:class:`cms_reduction.RacewaySpec`);
    0 samples on the contact line itself. ``ball_load_shapes`` (needs a spread) adds the static
    shapes of radial and axial forces at the load balls' places of the first position: with them an
    equilibrium there is the finite-element solution of the ring under the ball forces.
    ``stress_modes`` (dynamic runs, :mod:`.dynamic_stress`): the reduction also recovers each mode's
    nodal stress, and the run reports the ring's largest von Mises stress over time and the instant
    of its peak."""

    kind: Literal["rigid", "modal", "auto"] = "rigid"
    n_modes: int = 20
    groove_harmonics: int = 16
    E_Pa: float = 200e9
    damping_ratio: float = 0.02
    element_size_m: float | None = None
    include_tmr: bool = True      # top structure only: TMR bolted to the top race as one body
    bolts: int = 12               # bottom race only: bolt patches on the support when modal
    raceway_spread_m: float = 0.0
    ball_load_shapes: bool = False
    stress_modes: bool = False

    def __post_init__(self) -> None:
        if self.n_modes < 1:
            raise ValueError(f"n_modes must be ≥ 1, got {self.n_modes}")
        if self.groove_harmonics < -1:
            raise ValueError(f"groove_harmonics must be ≥ −1 (−1: no raceway load shapes), got {self.groove_harmonics}")
        _positive("body", E_Pa=self.E_Pa, element_size_m=self.element_size_m)
        if not 0.0 <= self.damping_ratio < 1.0:
            raise ValueError(f"damping_ratio must lie in [0, 1), got {self.damping_ratio}")
        if self.bolts < 3:
            raise ValueError(f"bolts must be ≥ 3, got {self.bolts}")
        if not (math.isfinite(self.raceway_spread_m) and self.raceway_spread_m >= 0.0):
            raise ValueError(f"raceway_spread_m must be a finite number ≥ 0, got {self.raceway_spread_m!r}")
        if self.ball_load_shapes and not self.raceway_spread_m > 0.0:
            raise ValueError("ball_load_shapes needs raceway_spread_m > 0: a ball force on a line or a point of "
                             "the ring has an unbounded displacement there")


@dataclass(frozen=True)
class Analysis:
    """``quasi_static``: equilibria with the balls held at their azimuths (``travel_steps`` > 0: the
    top race turns through ``travel_revolutions`` and the balls with it at their orbit speed);
    ``dynamic_explicit``: the top race driven at ``speed_rpm`` for ``duration_s`` from the static
    equilibrium, spacer balls included when ``spacers``, at the step ``timestep_s`` (None: the
    automatic stable step; a step above the explicit stability limit is refused, naming the limit).
    ``dynamic_implicit``: the same run with the implicit generalized-α integrator
    (:func:`mbd_core.multibody.implicit.simulate_implicit`, spectral radius at infinity ``rho_inf``)
    at ``timestep_s`` (None: :data:`cases.integrate.IMPLICIT_STEP_FACTOR` × the automatic explicit step); the rotation
    study takes it when asked, else runs explicitly. A dynamic run compares its ball loads at
    ``reference_samples`` samples after the start-up with the quasi-static equilibrium at the run's
    top rotation and ball phase there (:mod:`.dynamic_reference`; 0: no comparison). ``implicit_modes``
    (explicit runs with a modal ring): the rings' modes integrated with the augmented mass
    (:mod:`mbd_core.kernels.modal_step`), so that neither the stiffest mode nor its coupling with the top
    structure's free motion limits the automatic step, the contacts do; modes above 2/h then respond
    quasi-statically."""

    type: Literal["quasi_static", "dynamic_explicit", "dynamic_implicit"] = "quasi_static"
    speed_rpm: float = 6.55
    travel_steps: int = 0
    travel_revolutions: float = 2.0
    duration_s: float = 10.0
    timestep_s: float | None = None
    record_every: int = 20
    spacers: bool = True
    rho_inf: float = 0.9
    reference_samples: int = 5
    implicit_modes: bool = False

    def __post_init__(self) -> None:
        _positive("analysis", speed_rpm=self.speed_rpm, duration_s=self.duration_s, timestep_s=self.timestep_s,
                  travel_revolutions=self.travel_revolutions)
        if not (math.isfinite(self.rho_inf) and 0.0 <= self.rho_inf <= 1.0):
            raise ValueError(f"rho_inf must lie in [0, 1], got {self.rho_inf}")
        if self.travel_steps < 0:
            raise ValueError(f"travel_steps must be ≥ 0, got {self.travel_steps}")
        if self.record_every < 1:
            raise ValueError(f"record_every must be ≥ 1, got {self.record_every}")
        if self.reference_samples < 0:
            raise ValueError(f"reference_samples must be ≥ 0, got {self.reference_samples}")


Kind = Literal["single", "static", "rotation", "undulation", "thermal", "combined", "life", "full-scale"]


@dataclass(frozen=True)
class Study:
    """The study (a)–(g) of the slewing ring this run is, and the values it sweeps.

    ``single``: one run of the case as it stands. ``static`` (a): rigid and modal top structure
    against Q = W/(Z sin α). ``rotation`` (b): the top race turning. ``undulation`` (c): every
    ``undulation_scales`` × every ``top_E_Pa``. ``thermal`` (d): every ``offsets_m``, balls
    travelling. ``combined`` (e): undulation × ``combined_offsets_m``. ``life`` (f): the worst
    ball of ``combined`` at ``life_offset_m``. ``undulation`` also runs the undulated ring (×1)
    dynamically for ``spacer_run_s`` (0: not) for the spacer–load ball forces, with a rigid top
    structure or (``spacer_run_top = "modal"``) the study's modal one at E = ``top_E_Pa[0]``,
    started at its flexible equilibrium. ``full-scale`` (g): the Ø6.69 m ring with its own
    stiffness beside the 2 m ring with E = ``top_E_Pa[-1]``.
    """

    kind: Kind = "single"
    undulation_scales: tuple[float, ...] = (0.5, 1.0, 1.5)
    top_E_Pa: tuple[float, ...] = (200e9, REDUCED_E_PA)
    offsets_m: tuple[float, ...] = (0.3e-3, 0.4e-3, 0.5e-3)
    combined_offsets_m: tuple[float, ...] = (0.4e-3, 1.11e-3)
    life_offset_m: float = 0.4e-3
    case_depth_m: float = 8e-3
    spacer_run_s: float = 1.0
    spacer_run_top: Literal["rigid", "modal"] = "rigid"

    def __post_init__(self) -> None:
        for name in ("undulation_scales", "top_E_Pa", "offsets_m", "combined_offsets_m"):
            values = getattr(self, name)
            if not values or not all(math.isfinite(v) and v >= 0.0 for v in values):
                raise ValueError(f"{name} must be a non-empty list of numbers ≥ 0, got {list(values)}")
        if not all(e > 0.0 for e in self.top_E_Pa):
            raise ValueError(f"top_E_Pa must be positive, got {list(self.top_E_Pa)}")
        _positive("study", case_depth_m=self.case_depth_m)
        if not (math.isfinite(self.spacer_run_s) and self.spacer_run_s >= 0.0):
            raise ValueError(f"spacer_run_s must be ≥ 0, got {self.spacer_run_s}")


@dataclass(frozen=True)
class SlewingCase(CaseTables):
    """A run of the slewing ring (module docstring)."""

    FAMILY: ClassVar[str] = "slewing"  # the ``family`` key of its case files

    name: str = "slewing"
    description: str = ""
    geometry: Geometry = field(default_factory=Geometry)
    load: Load = field(default_factory=Load)
    undulation: Undulation = field(default_factory=Undulation)
    thermal: Thermal = field(default_factory=Thermal)
    contact: Contact = field(default_factory=Contact)
    top: BodyFidelity = field(default_factory=BodyFidelity)
    bottom: BodyFidelity = field(default_factory=BodyFidelity)
    analysis: Analysis = field(default_factory=Analysis)
    study: Study = field(default_factory=Study)

    def __post_init__(self) -> None:
        if not self.name or not all(c.isalnum() or c in "-_." for c in self.name):
            raise ValueError(f"name must be a non-empty word of letters, digits, '-', '_' or '.', got {self.name!r}")
        self._check_auto()
        self._check_model_sizes()

    def _check_auto(self) -> None:
        """``auto`` only where its cheap pass can decide (:mod:`.auto`)."""
        if self.study.kind == "undulation" and self.top.kind == "rigid":
            raise ValueError('top.kind: the undulation study compares top structures of the moduli in '
                             'study.top_E_Pa, and a rigid one has none: set top.kind = "auto" (each equilibrium '
                             'chooses) or "modal"')
        for race in ("top", "bottom"):
            if getattr(self, race).kind != "auto" or self.study.kind == "undulation":
                continue  # (the undulation study's equilibria decide for themselves)
            if self.study.kind != "single":
                runs = f"the {self.study.kind} study"
            elif self.analysis.type != "quasi_static":
                runs = "the dynamics"
            elif self.analysis.travel_steps:
                runs = "a travel (analysis.travel_steps > 0)"
            else:
                continue
            raise ValueError(f'{race}.kind: "auto" decides a race for quasi-static equilibria with the balls at '
                             f'their places (study single without travel, or undulation); this case runs {runs}: '
                             f'set {race}.kind = "rigid" or "modal"')

    def _check_model_sizes(self) -> None:
        """Each modal race can give its modes, fits in memory and has raceway load shapes its
        samples resolve (before anything is meshed)."""
        from fem_rings.sections import slewing_bottom_race, slewing_top_race, slewing_top_structure

        from ..mesh_budget import cached_profile, check_model_size
        from .scene import DEFAULT_ELEMENT_SIZE_M, N_THETA

        g = self.geometry
        from .studies import modal_top

        top_modal = modal_top(self)  # some studies make it modal whatever top.kind says
        make_top = slewing_top_structure if self.top.include_tmr else slewing_top_race
        for key, fidelity, modal, make in (("top", self.top, top_modal, make_top),
                                           ("bottom", self.bottom, self.bottom.kind == "modal", slewing_bottom_race)):
            if modal and fidelity.groove_harmonics >= N_THETA // 2:
                raise ValueError(f"{key}.groove_harmonics must be below {N_THETA // 2}: the {N_THETA} raceway "
                                 f"samples round the ring resolve no higher harmonic; got {fidelity.groove_harmonics}")
            if modal:
                size = fidelity.element_size_m or DEFAULT_ELEMENT_SIZE_M[g.variant]
                profile = cached_profile(make, g.pitch_diameter_m, g.section())
                check_model_size(profile, size, fidelity.n_modes, f"{key}.element_size_m", f"{key}.n_modes")
                if fidelity.raceway_spread_m > 0.0:
                    _check_spread(profile, g.section().groove(key, g.pitch_diameter_m).contact_point_m,
                                  fidelity.raceway_spread_m, key)

    @property
    def dead_load_t(self) -> float:
        return VARIANTS[self.geometry.variant][3] if self.load.dead_load_t is None else self.load.dead_load_t

    @property
    def dead_load_N(self) -> float:
        return 1000.0 * self.dead_load_t * self.load.gravity_m_s2

