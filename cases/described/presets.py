"""Named cases of described bearings: the built-in slewing rings through their description files."""

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
    "bearing-rotation": dict(
        name="bearing-rotation", description="the 1 m slewing ring from its built-in description file turning at "
        "6.55 rpm under its dead load (68.9 t), spacer balls between the load balls, the thesis' friction "
        "coefficients: ball loads against the quasi-static ones, ball orbit against the no-slip speed",
        bearing={"file": "slewing-ring-1m"}, study={"kind": "rotation"},
        rotation={"speed_rpm": 6.55, "moving_ring_mass_kg": 68.9e3, "gravity_m_s2": 9.81, "duration_s": 0.4,
                  "mu_static": 0.24, "mu_dynamic": 0.14}),
}

PRESETS = {name: from_mapping(DescribedCase, tables) for name, tables in _PRESET_TABLES.items()}


def quick(case: DescribedCase) -> DescribedCase:
    """``--quick``: a rotation for 0.1 s; the quasi-static studies unchanged (quick already)."""
    if case.study.kind == "rotation":
        return quick_variant(case, {"rotation": {"duration_s": min(0.1, case.rotation.duration_s)}})
    return quick_variant(case, {})
