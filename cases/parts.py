"""Built-in ring and cage parts of the two studies, ready to mesh (``flexbearing modes``).

Materials: the slewing-ring parts are steel E = 200 GPa, ν = 0.3, ρ = 7850 kg/m³;
the three-row bearing's rings 42CrMo E = 210 GPa, ν = 0.28 and its cages E = 200 GPa, ν = 0.3
(Pang et al. 2024), density 7850 kg/m³. Cross-sections: :mod:`fem_rings.sections` and
:mod:`fem_rings.cages`, where every chosen dimension is documented.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from fem_rings.cages import CagePockets, three_row_cages
from fem_rings.profile import Profile
from fem_rings.step_solid import StepSolid
from fem_rings.sections import (
    slewing_bottom_race,
    slewing_tmr,
    slewing_top_race,
    three_row_inner_ring,
    three_row_outer_ring,
)
from foundation.materials import ElasticMaterial

__all__ = ["RingPart", "RING_PARTS", "ring_part"]

SLEWING_STEEL = ElasticMaterial("steel (slewing ring)", 200e9, 0.3, 7850.0)
STEEL_42CRMO = ElasticMaterial("42CrMo", 210e9, 0.28, 7850.0)
CAGE_STEEL = ElasticMaterial("cage steel", 200e9, 0.3, 7850.0)


@dataclass(frozen=True)
class RingPart:
    """A named ring or cage: section, pockets, material and a sensible default element size."""

    name: str
    make: Callable[[], tuple[Profile, CagePockets | None]]
    material: ElasticMaterial
    default_size_m: float
    default_element: str
    description: str
    solid: StepSolid | None = None  # a ring meshed from a STEP solid, its profile naming the faces


def _ring(factory, *args):
    return lambda: (factory(*args), None)


def _cage(key):
    return lambda: three_row_cages()[key]


_PARTS = [
    RingPart("slewing-bottom-race-1m", _ring(slewing_bottom_race, 1.0), SLEWING_STEEL, 0.04, "hex27",
             "bottom race of the 1 m slewing ring (groove, bolt face)"),
    RingPart("slewing-top-race-1m", _ring(slewing_top_race, 1.0), SLEWING_STEEL, 0.04, "hex27",
             "top race of the 1 m slewing ring"),
    RingPart("slewing-bottom-race-2m", _ring(slewing_bottom_race, 2.0), SLEWING_STEEL, 0.05, "hex27",
             "bottom race of the 2 m slewing ring"),
    RingPart("slewing-bottom-race", _ring(slewing_bottom_race, 6.69), SLEWING_STEEL, 0.08, "hex27",
             "bottom race of the full-scale Ø6.69 m slewing ring"),
    RingPart("slewing-top-race", _ring(slewing_top_race, 6.69), SLEWING_STEEL, 0.08, "hex27",
             "top race of the full-scale Ø6.69 m slewing ring"),
    RingPart("slewing-tmr", _ring(slewing_tmr, 6.69), SLEWING_STEEL, 0.15, "hex27",
             "top-and-middle ring (TMR) of the full-scale slewing ring"),
    RingPart("three-row-inner-ring", _ring(three_row_inner_ring), STEEL_42CRMO, 0.06, "hex27",
             "inner ring (C-shaped, one body) of the 12 MW three-row roller bearing"),
    RingPart("three-row-outer-ring", _ring(three_row_outer_ring), STEEL_42CRMO, 0.06, "hex27",
             "outer ring (with nose) of the 12 MW three-row roller bearing"),
    RingPart("three-row-radial-cage", _cage("radial"), CAGE_STEEL, 0.02, "tet10",
             "radial-row cage (98 pockets) of the three-row bearing"),
    RingPart("three-row-front-cage", _cage("front_thrust"), CAGE_STEEL, 0.02, "tet10",
             "front thrust-row cage (94 pockets) of the three-row bearing"),
    RingPart("three-row-rear-cage", _cage("rear_thrust"), CAGE_STEEL, 0.02, "tet10",
             "rear thrust-row cage (94 pockets) of the three-row bearing"),
]

RING_PARTS = {p.name: p for p in _PARTS}


def ring_part(name: str) -> RingPart:
    if name not in RING_PARTS:
        raise ValueError(f"unknown part {name!r}; built-in parts: {', '.join(sorted(RING_PARTS))}")
    return RING_PARTS[name]
