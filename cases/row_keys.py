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

__all__ = ["MAX_ELEMENTS", "CORE_STRENGTH_KEYS", "RowContext", "Direction"]

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
