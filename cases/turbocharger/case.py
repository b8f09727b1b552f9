"""A turbocharger rotor on two angular-contact ball bearings in squeeze-film dampers, run in time.

The rotor (a steel shaft with a turbine wheel at one end, a compressor wheel at the other and the
two bearings' inner rings between them, all one solid of revolution, ``[rotor]``) is a modal body:
free–free modes of its 3-D solid model, with the centrifugal stress stiffening at the running speed
folded in (:func:`cms_reduction.prestressed`), in a frame driven at ``operation.speed_rpm`` about
its axis and free to translate and tilt. The inner raceways deform with the rotor at the bearing
seats. Each bearing (``[bearings]``, two identical rows back to back) has its balls, a cage guided
on the outer ring's land, and an outer ring that floats in a squeeze-film damper (``[damper]``): the
film's force from a table of Reynolds' equation (grid solver or its short/long limits), a centring
spring, and an anti-rotation pin that holds the outer ring's rotations. The compressor-side outer
ring is pushed axially by the preload spring (``bearings.preload_N``, a constant force); the
turbine-side one is held axially. An unbalance (``operation.unbalance_g_mm``) sits at the rim of
one wheel. ``[defect]`` adds a spall to the inner or outer raceway of the turbine-side bearing.

Studies:

- ``run``: one run at the operating point: ball loads and contact losses over time, shaft-centre
  orbits at the bearings and wheels, damper forces and eccentricities, cage whirl, the spectrum of
  the housing force with the bearing's defect frequencies marked, and the 5×5 stiffness of a row at
  the operating point;
- ``run-up``: the same at each of ``study.speeds_rpm`` (each run settled at its speed): the
  unbalance response over speed beside the rotor's Campbell diagram on the rows' stiffness;
- ``damper``: the run at each of ``study.damper_lengths_m`` and ``study.damper_clearances_m``: the
  force transmitted to the housing and the orbit at the bearings over the damper's land length and
  clearance.

Gravity is left out (the rotor weighs 2.5 N beside 274 N of unbalance force at 50 000 rev/min).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar, Literal

from foundation.validation import check_positive

from ..config import CaseTables

__all__ = ["Rotor", "Bearings", "Damper", "Operation", "Defect", "Run", "Study", "TurbochargerCase"]


def _in(key: str, value, lo: float, hi: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and lo <= value <= hi):
        raise ValueError(f"{key}: must lie in {lo:g} … {hi:g}, got {value!r}")


@dataclass(frozen=True)
class Rotor:
    """``[rotor]``: the rotor's solid of revolution (m), measured from the turbine wheel's face: the
    wheels as solid discs of the shaft's steel, the bearings' inner rings bonded to the shaft; its
    3-D model's element size and the modes kept; material damping ratio of every mode."""

    length_m: float = 0.110
    shaft_diameter_m: float = 0.012
    turbine_diameter_m: float = 0.044
    turbine_width_m: float = 0.012
    compressor_diameter_m: float = 0.040
    compressor_width_m: float = 0.015
    bearing_span_m: float = 0.032
    turbine_bearing_at_m: float = 0.035
    inner_ring_width_m: float = 0.008
    mesh_size_m: float = 0.004
    n_modes: int = 10
    damping_ratio: float = 0.01

    def __post_init__(self) -> None:
        check_positive(length_m=self.length_m, shaft_diameter_m=self.shaft_diameter_m,
                       turbine_diameter_m=self.turbine_diameter_m, turbine_width_m=self.turbine_width_m,
                       compressor_diameter_m=self.compressor_diameter_m, compressor_width_m=self.compressor_width_m,
                       bearing_span_m=self.bearing_span_m, turbine_bearing_at_m=self.turbine_bearing_at_m,
                       inner_ring_width_m=self.inner_ring_width_m, mesh_size_m=self.mesh_size_m)
        if not (isinstance(self.n_modes, int) and 2 <= self.n_modes <= 60):
            raise ValueError(f"n_modes: must be an integer in 2 … 60, got {self.n_modes!r}")
        _in("damping_ratio", self.damping_ratio, 0.0, 0.5)
        half = self.inner_ring_width_m / 2
        if not self.turbine_width_m < self.turbine_bearing_at_m - half:
            raise ValueError(f"turbine_bearing_at_m: the turbine-side inner ring ({self.turbine_bearing_at_m:g} ± "
                             f"{half:g} m) must clear the turbine wheel (to {self.turbine_width_m:g} m)")
        if not (self.turbine_bearing_at_m + self.bearing_span_m + half
                < self.length_m - self.compressor_width_m):
            raise ValueError(f"bearing_span_m: the compressor-side inner ring (at "
                             f"{self.turbine_bearing_at_m + self.bearing_span_m:g} m) must clear the compressor wheel "
                             f"(from {self.length_m - self.compressor_width_m:g} m)")
        if not self.bearing_span_m > self.inner_ring_width_m:
            raise ValueError(f"bearing_span_m: the inner rings ({self.inner_ring_width_m:g} m wide) overlap")
        if not self.mesh_size_m <= self.shaft_diameter_m / 2:
            raise ValueError(f"mesh_size_m: at most the shaft's radius {self.shaft_diameter_m / 2:g} m, got "
                             f"{self.mesh_size_m!r}")


@dataclass(frozen=True)
class Bearings:
    """``[bearings]``: the two identical angular-contact rows (back to back), SI units, angles in
    degrees; ``ball_material`` silicon nitride (hybrid bearing) or bearing steel; the preload (N)
    of the spring on the compressor-side outer ring; the cage (its mass, the pocket play and its
    guidance on the outer ring's land, a stiffness and damping across)."""

    n_balls: int = 8
    ball_diameter_m: float = 5.556e-3
    pitch_diameter_m: float = 0.026
    contact_angle_deg: float = 15.0
    conformity_inner: float = 0.52
    conformity_outer: float = 0.53
    ball_material: Literal["silicon_nitride", "steel"] = "silicon_nitride"
    preload_N: float = 300.0
    friction: float = 0.08
    cage_mass_kg: float = 2e-3
    pocket_clearance_m: float = 0.1e-3
    land_stiffness_N_m: float = 2e5
    land_damping_N_s_m: float = 5.0

    def __post_init__(self) -> None:
        if not (isinstance(self.n_balls, int) and 4 <= self.n_balls <= 40):
            raise ValueError(f"n_balls: must be an integer in 4 … 40, got {self.n_balls!r}")
        check_positive(ball_diameter_m=self.ball_diameter_m, pitch_diameter_m=self.pitch_diameter_m,
                       preload_N=self.preload_N, cage_mass_kg=self.cage_mass_kg,
                       pocket_clearance_m=self.pocket_clearance_m, land_stiffness_N_m=self.land_stiffness_N_m)
        _in("contact_angle_deg", self.contact_angle_deg, 5.0, 45.0)
        _in("conformity_inner", self.conformity_inner, 0.505, 0.6)
        _in("conformity_outer", self.conformity_outer, 0.505, 0.6)
        _in("friction", self.friction, 0.0, 0.5)
        _in("land_damping_N_s_m", self.land_damping_N_s_m, 0.0, 1e6)
        if self.n_balls * self.ball_diameter_m >= math.pi * self.pitch_diameter_m:
            raise ValueError(f"n_balls: {self.n_balls} balls of {self.ball_diameter_m} m do not fit on the pitch "
                             f"circle of {self.pitch_diameter_m} m")


@dataclass(frozen=True)
class Damper:
    """``[damper]``: the squeeze-film land around each outer ring (journal radius = the outer ring's
    outside radius, m), its length and radial clearance (m), the oil's dynamic viscosity (Pa·s), the
    cavitation model (``gumbel``: π film; ``none``: 2π film), how its force table is computed
    (``grid``: Reynolds' equation with side leakage; ``short`` / ``long``: the closed-form limits),
    the centring spring (N/m, 0: none), and how far the table reaches (ε = e/c): the explicit step must
    resolve the film's damping at the table's end, which grows like (1 − ε²)^−5/2 (so a journal that
    goes beyond it stops the run, naming the damper, rather than the table reaching further at the
    cost of every step)."""

    journal_radius_m: float = 0.0175
    length_m: float = 0.008
    clearance_m: float = 100e-6
    viscosity_Pa_s: float = 0.01
    cavitation: Literal["gumbel", "none"] = "gumbel"
    method: Literal["grid", "short", "long"] = "short"
    centring_stiffness_N_m: float = 5e5
    max_eccentricity_ratio: float = 0.8

    def __post_init__(self) -> None:
        check_positive(journal_radius_m=self.journal_radius_m, length_m=self.length_m, clearance_m=self.clearance_m,
                       viscosity_Pa_s=self.viscosity_Pa_s)
        _in("clearance_m", self.clearance_m, 1e-6, 1e-3)
        _in("centring_stiffness_N_m", self.centring_stiffness_N_m, 0.0, 1e9)
        _in("max_eccentricity_ratio", self.max_eccentricity_ratio, 0.1, 0.98)


@dataclass(frozen=True)
class Operation:
    """``[operation]``: the rotor's speed (rev/min) and its unbalance (g·mm) at the rim of one wheel."""

    speed_rpm: float = 50_000.0
    unbalance_g_mm: float = 10.0
    unbalance_at: Literal["turbine", "compressor"] = "turbine"

    def __post_init__(self) -> None:
        _in("speed_rpm", self.speed_rpm, 1000.0, 250_000.0)
        _in("unbalance_g_mm", self.unbalance_g_mm, 0.0, 1000.0)


@dataclass(frozen=True)
class Defect:
    """``[defect]``: a spall on the turbine-side bearing's ``race`` (``none``, ``inner``, ``outer``):
    its length along the raceway and depth (m), centred at ``angle_deg`` of that ring's frame."""

    race: Literal["none", "inner", "outer"] = "none"
    length_m: float = 1.0e-3
    depth_m: float = 20e-6
    angle_deg: float = 0.0

    def __post_init__(self) -> None:
        check_positive(length_m=self.length_m, depth_m=self.depth_m)
        _in("angle_deg", self.angle_deg, -360.0, 360.0)


@dataclass(frozen=True)
class Run:
    """``[run]``: simulated time of each run (s), of which the first ``settle_s`` are left out of
    the statistics and spectra, and the output sample interval (s)."""

    duration_s: float = 0.03
    settle_s: float = 0.01
    sample_s: float = 1e-5

    def __post_init__(self) -> None:
        check_positive(duration_s=self.duration_s, settle_s=self.settle_s, sample_s=self.sample_s)
        if not self.settle_s < self.duration_s:
            raise ValueError(f"settle_s: must be shorter than duration_s = {self.duration_s!r}, got {self.settle_s!r}")
        if not self.duration_s <= 2.0:
            raise ValueError(f"duration_s: at most 2 s of simulated time per run, got {self.duration_s!r}")


@dataclass(frozen=True)
class Study:
    """``[study]``: ``kind``; the speeds of ``run-up`` (rev/min); the land lengths and clearances of
    ``damper`` (m)."""

    kind: Literal["run", "run-up", "damper"] = "run"
    speeds_rpm: tuple[float, ...] = (20_000.0, 40_000.0, 60_000.0, 80_000.0, 100_000.0, 120_000.0)
    damper_lengths_m: tuple[float, ...] = (0.002, 0.003, 0.006, 0.010)
    damper_clearances_m: tuple[float, ...] = (50e-6, 100e-6, 200e-6)

    def __post_init__(self) -> None:
        for key, lo, hi in (("speeds_rpm", 1000.0, 250_000.0), ("damper_lengths_m", 1e-4, 0.1),
                            ("damper_clearances_m", 1e-6, 1e-3)):
            values = getattr(self, key)
            if not values or len(values) > 30:
                raise ValueError(f"{key}: must hold 1 … 30 values, got {values!r}")
            for v in values:
                _in(key, v, lo, hi)


@dataclass(frozen=True)
class TurbochargerCase(CaseTables):
    """A turbocharger rotor case (module docstring)."""

    FAMILY: ClassVar[str] = "turbocharger"  # the ``family`` key of its case files
    name: str = "turbocharger"
    description: str = ""
    rotor: Rotor = field(default_factory=Rotor)
    bearings: Bearings = field(default_factory=Bearings)
    damper: Damper = field(default_factory=Damper)
    operation: Operation = field(default_factory=Operation)
    defect: Defect = field(default_factory=Defect)
    run: Run = field(default_factory=Run)
    study: Study = field(default_factory=Study)
