"""Hertz point (elliptical) contact between two elastic bodies.

Notation (Hamrock & Brewe 1983; Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., ch. 6):

* principal curvatures of body 1 and 2 in two perpendicular planes x and y, 1/m, positive for
  convex surfaces and negative for concave ones (a groove);
* curvature sum Σρ = ρ1x + ρ1y + ρ2x + ρ2y and effective radius R = 1/Σρ;
* curvature difference F(ρ) = |(ρ1x − ρ1y) + (ρ2x − ρ2y)| / Σρ;
* ellipticity k = a/b ≥ 1 (a semi-major, b semi-minor axis), fixed by F(ρ) alone:
  F(ρ) = ((k² + 1)·E(e) − 2·K(e)) / ((k² − 1)·E(e)),  e² = 1 − 1/k²,
  with K and E the complete elliptic integrals of the first and second kind;
* effective modulus E' = 2 / ((1 − ν1²)/E1 + (1 − ν2²)/E2).

For a normal load Q (N)::

    a  = (6 k² E Q R / (π E'))^(1/3)
    b  = (6 E Q R / (π k E'))^(1/3)
    p0 = 3 Q / (2 π a b)
    δ  = K · ((9 / (2 E R)) · (Q / (π k E'))²)^(1/3)         (mutual approach)
    Q  = K_N · δ^1.5,  K_N = δ(Q)^(-3/2) · Q

The Hamrock–Brewe approximations (ratio α_r = R_y/R_x ≥ 1 of the effective radii):
k ≈ 1.0339·α_r^0.6360, E ≈ 1.0003 + 0.5968/α_r, K ≈ 1.5277 + 0.6023·ln α_r.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from foundation.materials import BEARING_STEEL, ElasticMaterial, effective_modulus_Pa
from foundation.validation import check_positive

__all__ = [
    "HertzPointContact",
    "point_contact",
    "ball_on_groove",
    "sphere_on_sphere",
    "series_stiffness",
    "ellipticity_exact",
    "ellipticity_hamrock_brewe",
]

Method = Literal["exact", "hamrock-brewe"]


def _curvature_difference_of_m(m: float) -> float:
    """F(ρ) as a function of m = e² = 1 − 1/k² (exact elliptic-integral relation).

    With k² = 1/(1 − m) the relation F = ((k²+1)E − 2K)/((k²−1)E) becomes
    F = ((2 − m)E − 2(1 − m)K)/(m·E).
    """
    K, E = ellipk(m), ellipe(m)
    return ((2.0 - m) * E - 2.0 * (1.0 - m) * K) / (m * E)


#: Below this F the numerator of F(m) cancels badly; use the series F = 3m/8 + 3m²/16 + O(m³)
#: (from K = π/2·(1 + m/4 + 9m²/64 + …), E = π/2·(1 − m/4 − 3m²/64 − …)).
_F_SERIES_BELOW = 1e-4


def ellipticity_exact(curvature_difference: float) -> tuple[float, float, float]:
    """Ellipticity k = a/b and the complete elliptic integrals K(e), E(e) for a given F(ρ).

    Solves the exact Hertz relation F(ρ) = ((k²+1)E − 2K)/((k²−1)E) (Harris & Kotzalas,
    eq. 6.26–6.28) for m = e² = 1 − 1/k² by bracketing; for nearly circular contacts
    (F < 1e-4) from the series F = 3m/8 + 3m²/16, whose remainder is O(m³) < 1e-11·m there.

    Returns
    -------
    k, K, E : float
        Ellipticity (≥ 1) and the complete elliptic integrals of the first and second kind
        with parameter m = e² = 1 − 1/k².
    """
    F = float(curvature_difference)
    if not 0.0 <= F < 1.0:
        raise ValueError(f"curvature difference F(rho) must lie in [0, 1), got {F}")
    if F == 0.0:
        return 1.0, math.pi / 2.0, math.pi / 2.0
    if F < _F_SERIES_BELOW:
        m = (-0.375 + math.sqrt(0.375**2 + 0.75 * F)) / 0.375  # root of 3m²/16 + 3m/8 − F
    else:
        hi = float(np.nextafter(1.0, 0.0))
        if _curvature_difference_of_m(hi) <= F:
            raise ValueError(f"curvature difference {F} too close to 1 (line contact)")
        m = brentq(lambda mm: _curvature_difference_of_m(mm) - F, 2.0e-4, hi, xtol=1e-18, rtol=1e-15)
    k = 1.0 / math.sqrt(1.0 - m)
    return k, float(ellipk(m)), float(ellipe(m))


def ellipticity_hamrock_brewe(radius_ratio: float) -> tuple[float, float, float]:
    """Hamrock–Brewe (1983) approximations of k, K(e) and E(e) from α_r = R_y/R_x ≥ 1."""
    ar = float(radius_ratio)
    if ar < 1.0:
        raise ValueError(f"radius ratio R_y/R_x must be >= 1, got {ar}")
    k = 1.0339 * ar**0.6360
    E = 1.0003 + 0.5968 / ar
    K = 1.5277 + 0.6023 * math.log(ar)
    return k, K, E


@dataclass(frozen=True)
class HertzPointContact:
    """Elliptical Hertz contact of two bodies; load-independent constants plus load functions.

    All load functions accept a float or an array of loads ``Q_N`` (N) or approaches
    ``approach_m`` (m); a load or approach ≤ 0 means no contact and gives zeros.

    Attributes
    ----------
    curvature_sum_per_m : float
        Σρ, 1/m.
    curvature_difference : float
        F(ρ), dimensionless.
    E_eff_Pa : float
        E' = 2/((1−ν1²)/E1 + (1−ν2²)/E2), Pa.
    ellipticity : float
        k = a/b ≥ 1.
    elliptic_K, elliptic_E : float
        Complete elliptic integrals K(e), E(e) (or their Hamrock–Brewe approximations).
    method : str
        ``"exact"`` or ``"hamrock-brewe"``.
    """

    curvature_sum_per_m: float
    curvature_difference: float
    E_eff_Pa: float
    ellipticity: float
    elliptic_K: float
    elliptic_E: float
    method: str = "exact"

    @property
    def effective_radius_m(self) -> float:
        """R = 1/Σρ, m."""
        return 1.0 / self.curvature_sum_per_m

    def semi_axes_m(self, Q_N):
        """Semi-major a and semi-minor b axes of the contact ellipse, m."""
        Q = np.maximum(np.asarray(Q_N, dtype=float), 0.0)
        k, E, R, Ep = self.ellipticity, self.elliptic_E, self.effective_radius_m, self.E_eff_Pa
        a = np.cbrt(6.0 * k**2 * E * Q * R / (math.pi * Ep))
        b = np.cbrt(6.0 * E * Q * R / (math.pi * k * Ep))
        return a, b

    def max_pressure_Pa(self, Q_N):
        """Maximum Hertz pressure p0 = 3Q/(2πab), Pa."""
        Q = np.maximum(np.asarray(Q_N, dtype=float), 0.0)
        a, b = self.semi_axes_m(Q)
        with np.errstate(invalid="ignore", divide="ignore"):
            p0 = np.where(Q > 0.0, 1.5 * Q / (math.pi * a * b), 0.0)
        return p0

    @property
    def _approach_coefficient(self) -> float:
        """c with δ = c·Q^(2/3), m/N^(2/3)."""
        k, K, E = self.ellipticity, self.elliptic_K, self.elliptic_E
        R, Ep = self.effective_radius_m, self.E_eff_Pa
        return K * (9.0 / (2.0 * E * R) / (math.pi * k * Ep) ** 2) ** (1.0 / 3.0)

    def approach_m(self, Q_N):
        """Mutual approach δ of the two bodies under load Q, m."""
        Q = np.maximum(np.asarray(Q_N, dtype=float), 0.0)
        return self._approach_coefficient * np.cbrt(Q) ** 2  # not cbrt(Q²): no overflow at huge loads

    @property
    def stiffness_N_per_m1p5(self) -> float:
        """Load–deflection constant K_N in Q = K_N·δ^1.5, N/m^1.5."""
        return self._approach_coefficient ** (-1.5)

    def load_N(self, approach_m):
        """Normal load for a mutual approach δ (zero for δ ≤ 0), N."""
        d = np.maximum(np.asarray(approach_m, dtype=float), 0.0)
        return self.stiffness_N_per_m1p5 * d**1.5


def point_contact(
    rho_1x_per_m: float,
    rho_1y_per_m: float,
    rho_2x_per_m: float,
    rho_2y_per_m: float,
    material_1: ElasticMaterial = BEARING_STEEL,
    material_2: ElasticMaterial = BEARING_STEEL,
    method: Method = "exact",
) -> HertzPointContact:
    """Hertz contact from the principal curvatures of two bodies (1/m, concave < 0).

    The principal planes x and y of the two bodies are assumed to coincide, as for balls in
    grooves and rollers on raceways.
    """
    curv = (rho_1x_per_m, rho_1y_per_m, rho_2x_per_m, rho_2y_per_m)
    if not all(math.isfinite(c) for c in curv):
        raise ValueError(f"curvatures must be finite, got {curv}")
    s = sum(curv)
    if not s > 0.0:
        raise ValueError(
            f"curvature sum must be > 0 (got {s:.6g} 1/m): the concave body conforms to or "
            "encloses the convex one, which is not a Hertz contact"
        )
    rx, ry = rho_1x_per_m + rho_2x_per_m, rho_1y_per_m + rho_2y_per_m
    if rx <= 0.0 or ry <= 0.0:
        raise ValueError(
            f"relative curvatures must both be > 0 (got {rx:.6g} and {ry:.6g} 1/m): "
            "in one plane the concave body is not larger than the convex one"
        )
    F = abs(rx - ry) / s
    if method == "exact":
        k, K, E = ellipticity_exact(F)
    elif method == "hamrock-brewe":
        k, K, E = ellipticity_hamrock_brewe(max(rx, ry) / min(rx, ry))
    else:
        raise ValueError(f"method must be 'exact' or 'hamrock-brewe', got {method!r}")
    return HertzPointContact(
        curvature_sum_per_m=s,
        curvature_difference=F,
        E_eff_Pa=effective_modulus_Pa(material_1, material_2),
        ellipticity=k,
        elliptic_K=K,
        elliptic_E=E,
        method=method,
    )


def ball_on_groove(
    ball_diameter_m: float,
    conformity: float,
    pitch_diameter_m: float,
    contact_angle_rad: float,
    raceway: Literal["inner", "outer"] = "inner",
    ball_material: ElasticMaterial = BEARING_STEEL,
    race_material: ElasticMaterial = BEARING_STEEL,
    method: Method = "exact",
) -> HertzPointContact:
    """Ball in a raceway groove of radius f·D.

    Curvatures after Harris & Kotzalas (eq. 2.27–2.32), with γ = D·cos α / d_m:
    ball 2/D in both planes; inner raceway 2/D·γ/(1−γ) in the rolling direction, outer raceway
    −2/D·γ/(1+γ); groove −1/(f·D) across.

    Parameters
    ----------
    ball_diameter_m : float
        Ball diameter D, m.
    conformity : float
        Groove radius over ball diameter, f > 0.5.
    pitch_diameter_m : float
        Pitch diameter d_m, m (> D).
    contact_angle_rad : float
        Contact angle α, rad, 0 ≤ α ≤ π/2.
    raceway : {"inner", "outer"}
        Which raceway: convex (inner) or concave (outer) in the rolling direction.
    """
    check_positive(ball_diameter_m=ball_diameter_m, pitch_diameter_m=pitch_diameter_m)
    if not conformity > 0.5:
        raise ValueError(
            f"conformity must be > 0.5 (groove radius larger than the ball radius), got {conformity}"
        )
    if not 0.0 <= contact_angle_rad <= math.pi / 2 + 1e-12:
        raise ValueError(f"contact_angle must lie in [0, 90] deg, got {math.degrees(contact_angle_rad)}")
    if not pitch_diameter_m > ball_diameter_m:
        raise ValueError(
            f"pitch_diameter ({pitch_diameter_m} m) must exceed ball_diameter ({ball_diameter_m} m)"
        )
    D = ball_diameter_m
    gamma = D * math.cos(contact_angle_rad) / pitch_diameter_m
    if raceway == "inner":
        rho_race_roll = 2.0 / D * gamma / (1.0 - gamma)
    elif raceway == "outer":
        rho_race_roll = -2.0 / D * gamma / (1.0 + gamma)
    else:
        raise ValueError(f"raceway must be 'inner' or 'outer', got {raceway!r}")
    return point_contact(
        2.0 / D, 2.0 / D, rho_race_roll, -1.0 / (conformity * D), ball_material, race_material, method
    )


def sphere_on_sphere(
    diameter_1_m: float,
    diameter_2_m: float,
    material_1: ElasticMaterial = BEARING_STEEL,
    material_2: ElasticMaterial = BEARING_STEEL,
) -> HertzPointContact:
    """Two convex spheres (load ball against spacer ball): a circular contact, k = 1."""
    check_positive(diameter_1_m=diameter_1_m, diameter_2_m=diameter_2_m)
    r1, r2 = 2.0 / diameter_1_m, 2.0 / diameter_2_m
    return point_contact(r1, r1, r2, r2, material_1, material_2, "exact")


def series_stiffness(*stiffnesses_N_per_m1p5: float) -> float:
    """Load–deflection constant of point contacts in series (same load, approaches add).

    K = (Σ K_i^(−2/3))^(−3/2)  (Harris & Kotzalas, eq. 7.3).
    """
    if not stiffnesses_N_per_m1p5:
        raise ValueError("series_stiffness needs at least one stiffness")
    for i, K in enumerate(stiffnesses_N_per_m1p5):
        check_positive(**{f"stiffness[{i}]": K})
    return sum(K ** (-2.0 / 3.0) for K in stiffnesses_N_per_m1p5) ** -1.5
