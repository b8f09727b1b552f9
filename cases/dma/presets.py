"""Named cases of the DMA bearing (the DREB torque report's bearing, README Sources)."""

from __future__ import annotations

from ..config import from_mapping
from ..quick import quick_variant
from .case import DmaCase

__all__ = ["PRESETS", "quick"]

_PRESET_TABLES = {
    "dma-torque": dict(
        name="dma-torque", description="the DREB report's cageless 24-ball DMA bearing at 267 N thrust and 60 rev/min "
        "of the outer race, each of its traction models (κ = 1·u, 0.015, 0.03, 0.03 − 1·u) over the contact "
        "ellipses, ball drag in the oil: mean race torques per ball beside the report's, their ripple and spectra",
        study={"kind": "traction-models"}),
    "dma-torque-speed": dict(
        name="dma-torque-speed", description="the DMA bearing's race torques over the outer race speed (10, 30, 60 "
        "rev/min) at 89 and 267 N with the EHL-like traction κ = 1·u (the report's Fig. 12)",
        study={"kind": "speed"}),
}

PRESETS = {name: from_mapping(DmaCase, tables) for name, tables in _PRESET_TABLES.items()}


def quick(case: DmaCase) -> DmaCase:
    """``--quick``: 20 ms simulated instead of 50 (the means over its last 12 ms)."""
    return quick_variant(case, {"analysis": {"duration_s": min(0.02, case.analysis.duration_s)}})
