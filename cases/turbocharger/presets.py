"""Named turbocharger cases: the rotor of :mod:`.case` at 50 000 rev/min with 10 g·mm of unbalance,
preloaded and not, with a spall on either race, over speed, and over the damper's land and clearance."""

from __future__ import annotations

from ..config import from_mapping
from ..quick import quick_variant
from .case import TurbochargerCase

__all__ = ["PRESETS", "quick"]

_BASE = "turbocharger rotor (Ø12 mm shaft, Ø44/Ø40 mm wheels) on two hybrid angular-contact rows back to back in " \
        "squeeze-film dampers, 10 g·mm of unbalance at the turbine wheel"

_PRESET_TABLES = {
    "turbocharger": dict(name="turbocharger", description=f"{_BASE}, 300 N preload, 50 000 rev/min: ball loads, "
                         "orbits, damper forces, spectrum"),
    "turbocharger-no-preload": dict(name="turbocharger-no-preload", description=f"{_BASE}, 10 N axial load only "
                                    "(not preloaded), 50 000 rev/min: the balls lose contact once per turn",
                                    bearings={"preload_N": 10.0}),
    "turbocharger-spall-outer": dict(name="turbocharger-spall-outer", description=f"{_BASE}, 300 N preload, "
                                     "50 000 rev/min, a 1 mm × 20 µm spall on the turbine-side outer race",
                                     defect={"race": "outer"}),
    "turbocharger-spall-inner": dict(name="turbocharger-spall-inner", description=f"{_BASE}, 300 N preload, "
                                     "50 000 rev/min, a 1 mm × 20 µm spall on the turbine-side inner race",
                                     defect={"race": "inner"}),
    "turbocharger-run-up": dict(name="turbocharger-run-up", description=f"{_BASE}, 300 N preload: steady runs "
                                "at 20 000 … 120 000 rev/min", study={"kind": "run-up"}),
    "turbocharger-damper": dict(name="turbocharger-damper", description=f"{_BASE}, 300 N preload, 50 000 rev/min: "
                                "damper land 2 … 10 mm, clearance 50 … 200 µm", study={"kind": "damper"}),
}

PRESETS = {name: from_mapping(TurbochargerCase, tables) for name, tables in _PRESET_TABLES.items()}


def quick(case: TurbochargerCase) -> TurbochargerCase:
    """``--quick``: a coarser rotor with 6 modes, 8 ms runs (the first 3 ms left out), three speeds of a
    run-up, two lengths and two clearances of the damper study."""
    s = case.study
    tables = {"rotor": {"mesh_size_m": 0.005, "n_modes": 6}, "run": {"duration_s": 0.008, "settle_s": 0.003}}
    if s.kind == "run-up":          # only what the study reads: a quick case file reads back
        tables["study"] = {"speeds_rpm": s.speeds_rpm[::max(1, len(s.speeds_rpm) // 3)][:3]}
    elif s.kind == "damper":
        tables["study"] = {"damper_lengths_m": s.damper_lengths_m[::2][:2],
                           "damper_clearances_m": s.damper_clearances_m[-2:]}
    return quick_variant(case, tables)
