"""Named cases of cylindrical roller bearings: the NJ 216 of the MEGT friction study (README Sources)."""

from __future__ import annotations

from ..config import from_mapping
from ..quick import quick_variant
from .case import CrbCase

__all__ = ["PRESETS", "quick"]

_PRESET_TABLES = {
    "nj216-friction": dict(
        name="nj216-friction", description="friction torque of an NJ 216 cylindrical roller bearing at 20 kN radial "
        "load, ISO VG 100 mineral oil at 50 °C, over the shaft speed (100 … 4000 rev/min) for axial loads 0, 1, 2 "
        "and 4 kN: raceway rolling losses and mixed friction at the ribs, contact by contact, beside the SKF "
        "catalogue model", study={"kind": "speed-axial"}),
}

PRESETS = {name: from_mapping(CrbCase, tables) for name, tables in _PRESET_TABLES.items()}


def quick(case: CrbCase) -> CrbCase:
    """``--quick``: the case itself (a speed–axial map takes about a second)."""
    return quick_variant(case, {})
