"""Lubricating oils: viscosity, density and pressure–viscosity against temperature (SI units,
temperatures in °C where the name says so).

- Kinematic viscosity (Walther's equation, ASTM D341): log10 log10(ν + c) = A − B·log10(T),
  ν in mm²/s, T in K; c = 0.7 in ASTM D341, other fits take their own c.
- Density: linear in temperature, ρ(T) = ρ_ref − G·(T − T_ref).
- Pressure–viscosity coefficient α of Barus' law η(p) = η0·exp(α·p): a constant, or the power
  law α = K / T^C with T in °C (the form Tyler et al. give for Lubricant A).
- Dynamic viscosity η = ρ·ν; temperature–viscosity coefficient β = d ln η / d(1/T) (K), the
  constant of η = η0·exp(β·(1/T − 1/T0)).

:data:`LUBRICANT_A` is the DMA bearing's oil (the DREB torque report, README Sources: Apiezon C with
1.5 % antioxidant, data of Tyler et al. quoted there). :meth:`Lubricant.from_viscosities` builds an oil from the two
viscosities of its data sheet (usually at 40 and 100 °C); :func:`iso_vg_mineral_oil` an ISO VG grade of
mineral oil.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from .validation import check_positive

__all__ = ["Lubricant", "LUBRICANT_A", "ASTM_D341_C_MM2_S", "ISO_VG_MINERAL_100C_MM2_S", "iso_vg_mineral_oil",
           "wooster_pressure_viscosity_Pa_inv"]

#: the constant c of Walther's equation in ASTM D341, mm²/s
ASTM_D341_C_MM2_S = 0.7
_KELVIN = 273.15


@dataclass(frozen=True)
class Lubricant:
    """An oil (module docstring). ``alpha_K_Pa_inv`` and ``alpha_C``: α = K / T_C^C (1/Pa, T in °C;
    ``alpha_C = 0``: the constant α = K)."""

    name: str
    walther_A: float
    walther_B: float
    density_ref_kg_m3: float
    density_ref_temperature_C: float = 15.0
    density_slope_kg_m3_K: float = 0.0
    alpha_K_Pa_inv: float = 2.0e-8
    alpha_C: float = 0.0
    walther_c_mm2_s: float = ASTM_D341_C_MM2_S
    thermal_conductivity_W_mK: float = 0.13

    def __post_init__(self) -> None:
        check_positive(f"lubricant {self.name!r}", walther_B=self.walther_B, density_ref_kg_m3=self.density_ref_kg_m3,
                       alpha_K_Pa_inv=self.alpha_K_Pa_inv, walther_c_mm2_s=self.walther_c_mm2_s,
                       thermal_conductivity_W_mK=self.thermal_conductivity_W_mK)
        if not (math.isfinite(self.walther_A) and math.isfinite(self.alpha_C) and self.alpha_C >= 0.0):
            raise ValueError(f"lubricant {self.name!r}: walther_A must be finite and alpha_C ≥ 0")

    @classmethod
    def from_viscosities(cls, name: str, points_C_mm2_s: tuple[tuple[float, float], tuple[float, float]],
                         density_15C_kg_m3: float, alpha_Pa_inv: float, **kw) -> "Lubricant":
        """The oil whose Walther line (ASTM D341) passes through two (temperature °C, kinematic
        viscosity mm²/s) points of its data sheet; density at 15 °C, a constant α."""
        (t1, v1), (t2, v2) = points_C_mm2_s
        check_positive(f"lubricant {name!r}", viscosity_1_mm2_s=v1, viscosity_2_mm2_s=v2)
        if t1 == t2:
            raise ValueError(f"lubricant {name!r}: the two viscosities need two temperatures, got {t1} °C twice")
        c = kw.pop("walther_c_mm2_s", ASTM_D341_C_MM2_S)
        y1, y2 = (math.log10(math.log10(v + c)) for v in (v1, v2))
        x1, x2 = (math.log10(t + _KELVIN) for t in (t1, t2))
        b = (y1 - y2) / (x2 - x1)
        return cls(name, walther_A=y1 + b * x1, walther_B=b, density_ref_kg_m3=density_15C_kg_m3,
                   alpha_K_Pa_inv=alpha_Pa_inv, walther_c_mm2_s=c, **kw)

    def kinematic_viscosity_m2_s(self, temperature_C: float) -> float:
        """ν(T), m²/s (Walther, ASTM D341)."""
        log_log = self.walther_A - self.walther_B * math.log10(temperature_C + _KELVIN)
        return (10.0 ** (10.0 ** log_log) - self.walther_c_mm2_s) * 1e-6

    def density_kg_m3(self, temperature_C: float) -> float:
        return self.density_ref_kg_m3 - self.density_slope_kg_m3_K * (temperature_C - self.density_ref_temperature_C)

    def dynamic_viscosity_Pa_s(self, temperature_C: float) -> float:
        """η = ρ·ν at ambient pressure, Pa·s."""
        return self.density_kg_m3(temperature_C) * self.kinematic_viscosity_m2_s(temperature_C)

    def pressure_viscosity_Pa_inv(self, temperature_C: float) -> float:
        """α of Barus' law, 1/Pa."""
        if self.alpha_C == 0.0:
            return self.alpha_K_Pa_inv
        if not temperature_C > 0.0:
            raise ValueError(f"lubricant {self.name!r}: its α = K/T^C needs a temperature above 0 °C, "
                             f"got {temperature_C}")
        return self.alpha_K_Pa_inv / temperature_C ** self.alpha_C

    def temperature_viscosity_K(self, temperature_C: float) -> float:
        """β = d ln η / d(1/T) at ``temperature_C`` (K; central difference over ±0.05 K)."""
        h = 0.05
        t1, t2 = temperature_C - h, temperature_C + h
        d_ln = math.log(self.dynamic_viscosity_Pa_s(t2) / self.dynamic_viscosity_Pa_s(t1))
        return d_ln / (1.0 / (t2 + _KELVIN) - 1.0 / (t1 + _KELVIN))


#: The DMA bearing's "Lubricant A" (DREB torque report, from Tyler et al.): log log(ν + 0.60) = 9.41058 −
#: 3.65489·log(T + 273), ν in mm²/s; α = 12.13e-8 / T^0.471 m²/N with T in °C; specific gravity
#: 0.879 at 15.6 °C falling by 0.00070 per K; thermal conductivity 0.10 W/(m·K) (assumed there).
LUBRICANT_A = Lubricant("Lubricant A (Apiezon C + 1.5 % antioxidant)", walther_A=9.41058, walther_B=3.65489,
                        walther_c_mm2_s=0.60, density_ref_kg_m3=879.0, density_ref_temperature_C=15.6,
                        density_slope_kg_m3_K=0.70, alpha_K_Pa_inv=12.13e-8, alpha_C=0.471,
                        thermal_conductivity_W_mK=0.10)


#: ν at 100 °C (mm²/s) of paraffinic mineral oils of viscosity index 95–100 per ISO VG grade (ISO 3448
#: fixes only the 40 °C mid-point, the grade number; these are the 100 °C values that industrial
#: mineral oils' data sheets list for that index). For another oil use :meth:`Lubricant.from_viscosities`.
ISO_VG_MINERAL_100C_MM2_S = {32: 5.4, 46: 6.8, 68: 8.7, 100: 11.1, 150: 14.7, 220: 19.0, 320: 24.0, 460: 30.5,
                             680: 38.0}


def wooster_pressure_viscosity_Pa_inv(viscosity_Pa_s: float) -> float:
    """α = (0.6 + 0.965·log10 η_cP)·10⁻⁸ m²/N: Wooster's correlation of mineral oils' pressure–viscosity
    coefficient with their viscosity at ambient pressure (Stachowiak & Batchelor, Engineering
    Tribology)."""
    check_positive("Wooster's α", viscosity_Pa_s=viscosity_Pa_s)
    return (0.6 + 0.965 * math.log10(viscosity_Pa_s * 1e3)) * 1e-8


def iso_vg_mineral_oil(grade: int, alpha_temperature_C: float = 40.0) -> Lubricant:
    """A mineral oil of ISO VG ``grade``: the Walther line through the grade at 40 °C (ISO 3448
    mid-point) and :data:`ISO_VG_MINERAL_100C_MM2_S` at 100 °C; density 880 kg/m³ at 15 °C falling by
    0.63 kg/m³ per K (thermal expansion 7·10⁻⁴/K); a constant α from Wooster's correlation at
    ``alpha_temperature_C`` (use the operating temperature)."""
    if grade not in ISO_VG_MINERAL_100C_MM2_S:
        raise ValueError(f"ISO VG grade: one of {', '.join(map(str, ISO_VG_MINERAL_100C_MM2_S))}, got {grade!r}")
    oil = Lubricant.from_viscosities(f"ISO VG {grade} mineral oil",
                                     ((40.0, float(grade)), (100.0, ISO_VG_MINERAL_100C_MM2_S[grade])),
                                     density_15C_kg_m3=880.0, alpha_Pa_inv=2e-8, density_slope_kg_m3_K=0.63)
    alpha = wooster_pressure_viscosity_Pa_inv(oil.dynamic_viscosity_Pa_s(alpha_temperature_C))
    return dataclasses.replace(oil, alpha_K_Pa_inv=alpha)
