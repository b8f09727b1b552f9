"""Line contact of a roller on a raceway: Hertz half-width and pressure, load–deflection laws, slices.

Units: SI inside. Empirical laws quoted in their native units (N, mm) are converted once.

References
----------
* Johnson, *Contact Mechanics* (1985), §4.3: two cylinders with parallel axes.
* Palmgren, *Ball and Roller Bearing Engineering* (1959): δ = 3.84·10⁻⁵ Q^0.9 / l^0.8
  (mm, N, mm), the approach of one roller–raceway contact, steel on steel.
* ISO/TS 16281:2008: c_L = 35 948·L_we^(8/9) (N/mm^(10/9), L_we in mm), the load–deflection
  constant Q = c_L·δ^(10/9) of a roller between its two raceways (δ the total approach of both
  contacts); for n_s slices each slice carries q_k = (c_L/n_s)·δ_k^(10/9).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from foundation.materials import BEARING_STEEL, ElasticMaterial, effective_modulus_Pa
from foundation.validation import check_positive

__all__ = [
    "LINE_EXPONENT",
    "HertzLineContact",
    "line_contact",
    "palmgren_stiffness",
    "iso16281_stiffness",
    "slice_stiffness",
    "series_line_stiffness",
]

#: Exponent n of the line-contact law Q = K·δ^n (Palmgren, ISO/TS 16281).
LINE_EXPONENT = 10.0 / 9.0

#: E' of the steel taken for the empirical constants (E = 207 GPa, ν = 0.29 as BEARING_STEEL), Pa.
_STEEL_E_EFF_PA = 207e9 / (1.0 - 0.29**2)


@dataclass(frozen=True)
class HertzLineContact:
    """Hertz contact of two parallel cylinders of length ``length_m`` (plane strain).

    Attributes
    ----------
    effective_radius_m : float
        R with 1/R = 1/R1 + 1/R2 (R2 < 0 for a concave raceway, ∞ for a plane), m.
    length_m : float
        Effective contact length l, m.
    E_eff_Pa : float
        E' = 2/((1−ν1²)/E1 + (1−ν2²)/E2), Pa.
    """

    effective_radius_m: float
    length_m: float
    E_eff_Pa: float

    def half_width_m(self, Q_N):
        """Semi-width b = sqrt(8 Q R / (π l E')) of the contact band, m (Johnson eq. 4.45)."""
        Q = np.maximum(np.asarray(Q_N, dtype=float), 0.0)
        return np.sqrt(8.0 * Q * self.effective_radius_m / (math.pi * self.length_m * self.E_eff_Pa))

    def max_pressure_Pa(self, Q_N):
        """p0 = 2Q / (π b l), Pa."""
        Q = np.maximum(np.asarray(Q_N, dtype=float), 0.0)
        b = self.half_width_m(Q)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(Q > 0.0, 2.0 * Q / (math.pi * b * self.length_m), 0.0)


def line_contact(
    roller_diameter_m: float,
    raceway_diameter_m: float,
    length_m: float,
    roller_material: ElasticMaterial = BEARING_STEEL,
    race_material: ElasticMaterial = BEARING_STEEL,
    concave: bool = False,
) -> HertzLineContact:
    """Roller on a cylindrical raceway (``raceway_diameter_m = math.inf`` for a flat one).

    ``concave=True`` for an outer raceway that wraps around the roller.
    """
    check_positive(roller_diameter_m=roller_diameter_m, length_m=length_m)
    if not raceway_diameter_m > 0.0:
        raise ValueError(f"raceway_diameter must be > 0 (use inf for a plane), got {raceway_diameter_m}")
    curv = 2.0 / roller_diameter_m + (-1.0 if concave else 1.0) * 2.0 / raceway_diameter_m
    if not curv > 0.0:
        raise ValueError(
            f"roller ({roller_diameter_m} m) must be smaller than the concave raceway "
            f"({raceway_diameter_m} m)"
        )
    return HertzLineContact(1.0 / curv, length_m, effective_modulus_Pa(roller_material, race_material))


def _material_scale(E_eff_Pa: float | None) -> float:
    return 1.0 if E_eff_Pa is None else E_eff_Pa / _STEEL_E_EFF_PA


def palmgren_stiffness(length_m: float, E_eff_Pa: float | None = None) -> float:
    """K in Q = K·δ^(10/9) for one roller–raceway contact after Palmgren, N/m^(10/9).

    From δ[mm] = 3.84·10⁻⁵ Q^0.9 / l[mm]^0.8: K = 3.84·10⁻⁵^(−10/9)·10⁶·l[m]^(8/9).
    For materials other than steel the constant is scaled by E'/E'_steel (Q ∝ E' at a given
    approach in the Hertz line-contact solution).
    """
    check_positive(length_m=length_m)
    return (3.84e-5) ** (-LINE_EXPONENT) * 1e6 * length_m ** (8.0 / 9.0) * _material_scale(E_eff_Pa)


def iso16281_stiffness(length_m: float, E_eff_Pa: float | None = None) -> float:
    """c_L in Q = c_L·δ^(10/9) for a roller between its two raceways (ISO/TS 16281), N/m^(10/9).

    c_L = 35 948·L_we[mm]^(8/9) N/mm^(10/9) = 35 948·10⁶·L_we[m]^(8/9) in SI; δ is the total
    approach of both contacts. Scaled by E'/E'_steel for other materials.
    """
    check_positive(length_m=length_m)
    return 35948.0 * 1e6 * length_m ** (8.0 / 9.0) * _material_scale(E_eff_Pa)


def slice_stiffness(contact_stiffness: float, n_slices: int) -> float:
    """Stiffness of one of n equal slices, c_L/n_s (ISO/TS 16281), same unit as the input."""
    if int(n_slices) != n_slices or n_slices < 1:
        raise ValueError(f"n_slices must be a positive integer, got {n_slices}")
    check_positive(contact_stiffness=contact_stiffness)
    return contact_stiffness / n_slices


def series_line_stiffness(*stiffnesses: float) -> float:
    """Two or more line contacts in series: K = (Σ K_i^(−9/10))^(−10/9)."""
    if not stiffnesses:
        raise ValueError("series_line_stiffness needs at least one stiffness")
    for i, K in enumerate(stiffnesses):
        check_positive(**{f"stiffness[{i}]": K})
    return sum(K ** (-1.0 / LINE_EXPONENT) for K in stiffnesses) ** (-LINE_EXPONENT)
