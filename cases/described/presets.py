"""Named cases of described bearings: the built-in slewing ring through its description file."""

from __future__ import annotations

from ..config import from_mapping
from ..quick import quick_variant
from .case import DescribedCase

__all__ = ["PRESETS", "quick"]

_PRESET_TABLES = {
    "bearing-loaddist": dict(
        name="bearing-loaddist", description="the Ø6.69 m slewing ring from its built-in description file: ball "
        "loads, contact angles, p0, s0 and the stiffness matrix under the dead load (rigid rings)",
        bearing={"file": "slewing-ring"}, study={"kind": "load-distribution"}),
    "bearing-limiting-curve": dict(
        name="bearing-limiting-curve", description="the Ø6.69 m slewing ring from its built-in description file: "
        "its static limiting load curve (axial force vs tilting moment at s0 = 1, ISO 76)",
        bearing={"file": "slewing-ring"}, study={"kind": "limiting-curve"}),
}

PRESETS = {name: from_mapping(DescribedCase, tables) for name, tables in _PRESET_TABLES.items()}


def quick(case: DescribedCase) -> DescribedCase:
    """``--quick``: the same case (a quasi-static run is quick already)."""
    return quick_variant(case, {})
