"""Elastic materials of bearing parts (SI units)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["ElasticMaterial", "BEARING_STEEL", "SILICON_NITRIDE", "effective_modulus_Pa"]


@dataclass(frozen=True)
class ElasticMaterial:
    """Isotropic linear-elastic material.

    Parameters
    ----------
    name : str
        Label shown in reports.
    E_Pa : float
        Young's modulus, Pa.
    nu : float
        Poisson's ratio, -1 < nu < 0.5.
    density_kg_m3 : float
        Mass density, kg/m³.
    """

    name: str
    E_Pa: float
    nu: float
    density_kg_m3: float = 7850.0

    def __post_init__(self) -> None:
        if not self.E_Pa > 0.0:
            raise ValueError(f"material {self.name!r}: E_Pa must be > 0, got {self.E_Pa}")
        if not -1.0 < self.nu < 0.5:
            raise ValueError(f"material {self.name!r}: nu must lie in (-1, 0.5), got {self.nu}")
        if not self.density_kg_m3 > 0.0:
            raise ValueError(
                f"material {self.name!r}: density_kg_m3 must be > 0, got {self.density_kg_m3}"
            )


#: Through-hardened ball steel against AISI 4140 races, as in the slewing-ring thesis (Table 7):
#: E = 207 GPa, nu = 0.29.
BEARING_STEEL = ElasticMaterial("bearing steel (AISI 52100 / 4140)", 207e9, 0.29, 7850.0)
#: hybrid bearings' ceramic balls: hot isostatically pressed silicon nitride, the typical properties of
#: ASTM F2094 grades (E 310 GPa, ν 0.27, ρ 3200 kg/m³)
SILICON_NITRIDE = ElasticMaterial("silicon nitride (Si3N4, ASTM F2094)", 310e9, 0.27, 3200.0)


def effective_modulus_Pa(m1: ElasticMaterial, m2: ElasticMaterial) -> float:
    """Effective modulus E' = 2 / ((1 - nu1²)/E1 + (1 - nu2²)/E2), Pa.

    Hamrock's convention (Hamrock & Brewe 1983); Johnson's E* is E'/2.
    """
    return 2.0 / ((1.0 - m1.nu**2) / m1.E_Pa + (1.0 - m2.nu**2) / m2.E_Pa)
