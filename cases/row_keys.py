"""What every row type of a bearing description file shares: the context a builder gets, the fit
and sign helpers, and the case-depth keys of any row (:mod:`cases.bearing_rows`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

from foundation.materials import ElasticMaterial
from mbd_core.bearing.case_depth import core_shear_fatigue_strength_Pa

from .config import CaseError

__all__ = ["MAX_ELEMENTS", "CORE_STRENGTH_KEYS", "RowContext", "Direction", "SeparatorKeys", "DEFAULT_POCKET_CLEARANCE"]

Direction = Literal["+z", "-z"]
#: Most rolling elements in one row (a guard against a mistyped count, before any array is built).
MAX_ELEMENTS = 10_000


@dataclass(frozen=True)
class RowContext:
    """What a row builder needs beyond its own keys: the moving ring, the materials by name and the
    dotted path of the row (for messages)."""

    moving_ring: Literal["inner", "outer"]
    materials: Mapping[str, ElasticMaterial]
    where: str

    @property
    def radial_sign(self) -> int:
        return 1 if self.moving_ring == "inner" else -1

    def material(self, key: str, name: str) -> ElasticMaterial:
        if name not in self.materials:
            raise CaseError(f"{self.where}.{key}: unknown material {name!r}; one of {', '.join(sorted(self.materials))} "
                            "(add a [materials.NAME] table)")
        return self.materials[name]


def _check(where: str, ok: bool, message: str) -> None:
    if not ok:
        raise CaseError(f"{where}: {message}")


def _check_fits(where: str, count: int, diameter_m: float, pitch_diameter_m: float, what: str) -> None:
    """Z elements of diameter D fit on the pitch circle: Z·D ≤ π·d_m."""
    _check(f"{where}.count", count <= MAX_ELEMENTS, f"at most {MAX_ELEMENTS} {what} per row, got {count}")
    if not count * diameter_m <= math.pi * pitch_diameter_m * (1 + 1e-9):  # the message only then: π·d_m may overflow
        raise CaseError(f"{where}.count: {count} {what} of {diameter_m:g} m do not fit on the pitch circle of "
                        f"{pitch_diameter_m:g} m (at most {int(math.pi * pitch_diameter_m / diameter_m)})")


#: a cage pocket's circumferential play when the file gives none, as a share of the element diameter
#: (ball and roller cages run with some 1–3 % of D; the rotation study reports the value it took)
DEFAULT_POCKET_CLEARANCE = 0.02


@dataclass(frozen=True)
class SeparatorKeys:
    """``[rows.separator]``: what keeps a row's elements apart. The dynamic ``rotation`` study of a
    described bearing (:mod:`cases.described.rotation`) builds it; a quasi-static load distribution
    holds every element at its azimuth and does not depend on it.

    Attributes
    ----------
    kind : {"cage", "spacer_balls", "full_complement"}
        A cage with a pocket per element; a spacer ball between each pair of neighbouring balls
        (ball rows); or neither: neighbouring balls touch each other.
    mass_kg : float or None
        The cage's mass, kg (``cage``: required).
    pocket_clearance_m : float or None
        Circumferential play of an element in its pocket, m (``cage``; default
        ``DEFAULT_POCKET_CLEARANCE`` × the element diameter).
    spacer_diameter_m : float or None
        Diameter of the spacer balls, m (``spacer_balls``: required; below the ball diameter, so
        that they carry no load).
    """

    kind: Literal["cage", "spacer_balls", "full_complement"]
    mass_kg: float | None = None
    pocket_clearance_m: float | None = None
    spacer_diameter_m: float | None = None

    def __post_init__(self) -> None:
        used = {"cage": ("mass_kg", "pocket_clearance_m"), "spacer_balls": ("spacer_diameter_m",),
                "full_complement": ()}[self.kind]
        for key in ("mass_kg", "pocket_clearance_m", "spacer_diameter_m"):
            value = getattr(self, key)
            if value is None:
                continue
            if key not in used:
                raise ValueError(f"{key}: not used with kind = {self.kind!r}")
            if not (value >= 0.0 if key == "pocket_clearance_m" else value > 0.0):
                raise ValueError(f"{key}: must be {'≥' if key == 'pocket_clearance_m' else '>'} 0, got {value!r}")
        if self.kind == "cage" and self.mass_kg is None:
            raise ValueError("mass_kg: missing key (the cage's mass, kg)")
        if self.kind == "spacer_balls" and self.spacer_diameter_m is None:
            raise ValueError("spacer_diameter_m: missing key (the spacer balls' diameter, m)")

    def check_row(self, where: str, count: int, diameter_m: float, pitch_diameter_m: float, what: str) -> None:
        """The separator fits the row: spacer balls smaller than the balls and fitting between them,
        a pocket play below the element's radius."""
        at = f"{where}.separator"
        if self.kind == "spacer_balls":
            if what != "balls":
                raise CaseError(f"{at}.kind: spacer balls separate balls; a roller row takes 'cage' or "
                                "'full_complement'")
            d = self.spacer_diameter_m
            _check(f"{at}.spacer_diameter_m", d < diameter_m,
                   f"must be below the ball diameter ({diameter_m:g} m; a spacer ball carries no load), got {d!r}")
            _check(f"{at}.spacer_diameter_m", count * (diameter_m + d) <= math.pi * pitch_diameter_m * (1 + 1e-9),
                   f"{count} balls of {diameter_m:g} m and {count} spacer balls of {d:g} m do not fit on the "
                   f"pitch circle of {pitch_diameter_m:g} m")
        if self.kind == "cage" and self.pocket_clearance_m is not None:
            _check(f"{at}.pocket_clearance_m", self.pocket_clearance_m < 0.5 * diameter_m,
                   f"must be below half the element diameter ({0.5 * diameter_m:g} m), got {self.pocket_clearance_m!r}")

    def pocket_clearance(self, diameter_m: float) -> float:
        """The pocket play, m (the file's, or the default share of ``diameter_m``)."""
        given = self.pocket_clearance_m
        return DEFAULT_POCKET_CLEARANCE * diameter_m if given is None else given


# --- keys every row has --------------------------------------------------------------------------

#: core strength keys of a case-hardened row, one of which goes with ``case_depth_m``
CORE_STRENGTH_KEYS = ("core_uts_Pa", "core_yield_Pa", "core_shear_yield_Pa")


@dataclass(frozen=True, kw_only=True)
class _CaseDepthKeys:
    """Case hardening of the raceways, for the DG03 case-depth life factor
    (:mod:`mbd_core.bearing.distribution_case_depth`); all or nothing.

    Attributes
    ----------
    case_depth_m : float or None
        Effective case depth h of the raceways, m.
    core_uts_Pa, core_yield_Pa, core_shear_yield_Pa : float or None
        One core strength: ultimate tensile, tensile yield or shear yield strength, Pa
        (:func:`mbd_core.bearing.case_depth.core_shear_fatigue_strength_Pa`).
    """

    case_depth_m: float | None = None
    core_uts_Pa: float | None = None
    core_yield_Pa: float | None = None
    core_shear_yield_Pa: float | None = None

    def __post_init__(self) -> None:
        given = [k for k in CORE_STRENGTH_KEYS if getattr(self, k) is not None]
        for key in ("case_depth_m", *given):
            value = getattr(self, key)
            if value is not None and not value > 0.0:
                raise ValueError(f"{key}: must be > 0, got {value!r}")
        if len(given) > 1:
            raise ValueError(f"{given[1]}: give one core strength, not both {given[0]} and {given[1]}")
        if given and self.case_depth_m is None:
            raise ValueError(f"{given[0]}: the core strength goes with the raceways' effective case depth: "
                             "give case_depth_m too")
        if self.case_depth_m is not None and not given:
            raise ValueError(f"case_depth_m: give the core strength too, one of {', '.join(CORE_STRENGTH_KEYS)}")
        if given and not self.core_shear_fatigue_Pa > 0.0:
            raise ValueError(f"{given[0]}: too small: the core shear fatigue strength 0.6·τ_y is 0")

    def _check_case_depth_below(self, diameter_m: float, key: str) -> None:
        """A case deeper than the rolling element is a through-hardened ring (and beyond the stresses)."""
        if self.case_depth_m is not None and not self.case_depth_m < diameter_m:
            raise ValueError(f"case_depth_m: must be smaller than {key} ({diameter_m!r}; a deeper case is a "
                             f"through-hardened ring: leave the case-depth keys out), got {self.case_depth_m!r}")

    @property
    def core_shear_fatigue_Pa(self) -> float | None:
        """τ_f = 0.6·τ_y,core of DG03, Pa; None without a case depth."""
        if self.case_depth_m is None:
            return None
        return core_shear_fatigue_strength_Pa(**{k: getattr(self, k) for k in CORE_STRENGTH_KEYS})


def _sign(direction: str) -> int:
    return 1 if direction == "+z" else -1
