"""Elastohydrodynamic film thickness of rolling contacts (isothermal regression formulas with
optional inlet-heating and starvation factors) and the film parameter Λ.

Dimensionless groups (Hamrock & Dowson; E' = 2 / ((1 − ν1²)/E1 + (1 − ν2²)/E2), the convention of
:mod:`mbd_core.contact.hertz`):

- speed U = η0·u / (E'·R_x), u the entrainment (mean rolling) speed (u1 + u2)/2, R_x the
  effective radius in the rolling direction;
- material G = α·E', α the pressure–viscosity coefficient;
- load W = Q / (E'·R_x²) for a point contact, W' = w / (E'·R_x) per unit length for a line contact;
- film H = h / R_x.

Point contacts (Hamrock & Dowson, "Isothermal elastohydrodynamic lubrication of point contacts,
Part III", J. Lubr. Technol. 99 (1977) 264–276), ellipticity k = 1.0339·(R_y/R_x)^0.636:

    H_c   = 2.69·U^0.67·G^0.53·W^−0.067·(1 − 0.61·exp(−0.73·k))
    H_min = 3.63·U^0.68·G^0.49·W^−0.073·(1 − exp(−0.68·k))

Line contacts: central and minimum film of Pan & Hamrock (J. Tribol. 111 (1989) 246–251),

    H_c   = 3.06·U^0.69·G^0.56·W'^−0.10,    H_min = 1.714·U^0.694·G^0.568·W'^−0.128,

and Dowson & Higginson's minimum film (Elasto-hydrodynamic Lubrication, 1977),
H_min = 2.65·U^0.70·G^0.54·W'^−0.13, kept as a second, independent fit.

Inlet shear heating reduces the film by Murch & Wilson's factor (J. Lubr. Technol. 97 (1975)
212–216), φ_T = 3.94 / (3.94 + L^0.62) with the thermal loading L = β_T·η0·u² / k_f
(β_T = −d ln η/dT in 1/K, k_f the oil's thermal conductivity). A starved inlet (meniscus at m
contact half-widths b from the centre) reduces the film by Hamrock & Dowson's factor (Part IV,
J. Lubr. Technol. 99 (1977) 15–23): ((m − 1)/(m* − 1))^0.29 below the fully flooded inlet
m* = 1 + 3.06·((R_x/b)²·H_c)^0.58.

Film parameter Λ = h_min / √(Rq1² + Rq2²) (composite RMS roughness).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from foundation.validation import check_positive

__all__ = ["Film", "point_contact_film", "line_contact_film", "thermal_loading", "thermal_reduction_factor",
           "starvation_factor", "film_parameter", "ellipticity"]


@dataclass(frozen=True)
class Film:
    """Central and minimum film thickness (m) with the dimensionless groups they come from."""

    central_m: float
    minimum_m: float
    U: float
    G: float
    W: float


def ellipticity(Rx_m: float, Ry_m: float) -> float:
    """k = a/b of the Hertz ellipse, Hamrock & Brewe's fit 1.0339·(R_y/R_x)^0.636."""
    return 1.0339 * (Ry_m / Rx_m) ** 0.636


def _groups(owner: str, u_m_s: float, Rx_m: float, E_eff_Pa: float, eta0_Pa_s: float, alpha_Pa_inv: float):
    check_positive(owner, entrainment_speed_m_s=u_m_s, Rx_m=Rx_m, E_eff_Pa=E_eff_Pa, eta0_Pa_s=eta0_Pa_s,
                   alpha_Pa_inv=alpha_Pa_inv)
    return eta0_Pa_s * u_m_s / (E_eff_Pa * Rx_m), alpha_Pa_inv * E_eff_Pa


def point_contact_film(load_N: float, entrainment_speed_m_s: float, Rx_m: float, Ry_m: float, E_eff_Pa: float,
                       eta0_Pa_s: float, alpha_Pa_inv: float) -> Film:
    """Isothermal, fully flooded film of an elliptical contact (Hamrock & Dowson 1977)."""
    U, G = _groups("point contact film", entrainment_speed_m_s, Rx_m, E_eff_Pa, eta0_Pa_s, alpha_Pa_inv)
    check_positive("point contact film", load_N=load_N, Ry_m=Ry_m)
    W = load_N / (E_eff_Pa * Rx_m**2)
    k = ellipticity(Rx_m, Ry_m)
    Hc = 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1.0 - 0.61 * math.exp(-0.73 * k))
    Hm = 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1.0 - math.exp(-0.68 * k))
    return Film(Hc * Rx_m, Hm * Rx_m, U, G, W)


def line_contact_film(load_per_length_N_m: float, entrainment_speed_m_s: float, Rx_m: float, E_eff_Pa: float,
                      eta0_Pa_s: float, alpha_Pa_inv: float, fit: str = "pan-hamrock") -> Film:
    """Isothermal, fully flooded film of a line contact: ``fit`` "pan-hamrock" (central and
    minimum) or "dowson-higginson" (its minimum; the central film then Pan & Hamrock's)."""
    U, G = _groups("line contact film", entrainment_speed_m_s, Rx_m, E_eff_Pa, eta0_Pa_s, alpha_Pa_inv)
    check_positive("line contact film", load_per_length_N_m=load_per_length_N_m)
    W = load_per_length_N_m / (E_eff_Pa * Rx_m)
    Hc = 3.06 * U**0.69 * G**0.56 * W**-0.10
    if fit == "pan-hamrock":
        Hm = 1.714 * U**0.694 * G**0.568 * W**-0.128
    elif fit == "dowson-higginson":
        Hm = 2.65 * U**0.70 * G**0.54 * W**-0.13
    else:
        raise ValueError(f"fit must be 'pan-hamrock' or 'dowson-higginson', got {fit!r}")
    return Film(Hc * Rx_m, Hm * Rx_m, U, G, W)


def thermal_loading(beta_T_per_K: float, eta0_Pa_s: float, entrainment_speed_m_s: float,
                    conductivity_W_mK: float) -> float:
    """Murch & Wilson's thermal loading L = β_T·η0·u²/k_f (β_T = −d ln η/dT, 1/K)."""
    return abs(beta_T_per_K) * eta0_Pa_s * entrainment_speed_m_s**2 / conductivity_W_mK


def thermal_reduction_factor(L: float) -> float:
    """Film reduction by inlet shear heating, φ_T = 3.94 / (3.94 + L^0.62) (Murch & Wilson 1975)."""
    if not L >= 0.0:
        raise ValueError(f"thermal loading must be ≥ 0, got {L}")
    return 3.94 / (3.94 + L**0.62)


def starvation_factor(meniscus_half_widths: float, central_film_m: float, Rx_m: float,
                      half_width_b_m: float) -> float:
    """Film reduction of a starved point contact whose inlet meniscus lies ``meniscus_half_widths``
    contact half-widths b upstream of the centre (m > 1; Hamrock & Dowson 1977, Part IV); 1 when
    the inlet is fully flooded (m ≥ m*)."""
    check_positive("starvation", central_film_m=central_film_m, Rx_m=Rx_m, half_width_b_m=half_width_b_m)
    m = meniscus_half_widths
    if not m > 1.0:
        raise ValueError(f"meniscus_half_widths: the inlet meniscus must lie more than one half-width upstream "
                         f"(m > 1), got {m}")
    m_star = 1.0 + 3.06 * ((Rx_m / half_width_b_m) ** 2 * central_film_m / Rx_m) ** 0.58
    return 1.0 if m >= m_star else ((m - 1.0) / (m_star - 1.0)) ** 0.29


def film_parameter(minimum_film_m: float, roughness_1_rms_m: float, roughness_2_rms_m: float) -> float:
    """Λ = h_min / √(Rq1² + Rq2²)."""
    sigma = math.hypot(roughness_1_rms_m, roughness_2_rms_m)
    if not sigma > 0.0:
        raise ValueError("the composite roughness must be > 0 (give the RMS roughness of at least one surface)")
    return minimum_film_m / sigma
