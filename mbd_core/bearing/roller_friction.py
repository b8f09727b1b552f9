"""Friction torque of a cylindrical roller bearing under radial and axial load (quasi-static, inner ring
turning, outer ring held), contact by contact.

1. **Loads.** The rings are rigid; the inner ring moves by δ_r towards the load, a roller at ψ from
   the load line is pressed by δ_r·cos ψ − P_d/2 (P_d the radial internal clearance) and carries
   Q = c_L·δ^(10/9) (ISO/TS 16281 line contact between both raceways), δ_r such that Σ Q·cos ψ = F_r.
   The axial load runs from the inner ring's rib through the rollers' ends to the outer ring's rib;
   each roller takes the share of it that its raceway load has (a roller outside the load zone tilts
   away and carries none).
2. **Kinematics.** Pure rolling on both raceways: cage speed ω_c = ω(1 − γ)/2, γ = D/d_m; the surfaces
   of both raceway contacts pass the contact at u = ω·d_m(1 − γ²)/4. At a rib contact a distance e
   from the roller's axis the roller's end and the rib pass at u·2e/D and u·(d_m/2 ∓ e)/r_{i,o}
   (inner, outer rib), in the same direction: they slide at the difference and entrain the oil at the
   mean.
3. **Raceways: rolling loss.** Each loaded raceway contact rolls on its film: film and Poiseuille
   rolling resistance of the inlet (:func:`mbd_core.contact.ehl_inlet.grubin_line_contact`), power
   F_R·u.
4. **Ribs: mixed friction.** The roller end (a sphere of radius R_e) on the flat rib is a circular
   Hertz contact with the film of Hamrock & Dowson (:func:`mbd_core.contact.ehl.point_contact_film`,
   minimum film) reduced by inlet heating (Murch & Wilson); the film parameter Λ gives the asperity
   load share φ = exp(−B·Λ^C) (Zhou & Hoeprich) and the friction coefficient
   μ = φ·μ_b + (1 − φ)·κ_L·(1 − exp(−v_s/u_c)), the fluid's part a limiting-shear traction at the
   contact's mean pressure (:meth:`mbd_core.contact.friction.LimitingShear.from_film`); power μ·F·v_s.
5. **Torque.** In steady running the torque on the turning ring is the power lost in all contacts over
   its speed: M = ΣP/ω (energy balance; no torque reading needs a sign convention).

Not modelled: rolling losses of rollers outside the load zone, roller–cage sliding, churning and drag of
the oil bath, seals, elastic hysteresis, roller skew and tilt (the rib load share is fixed by 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from foundation.lubricants import Lubricant
from foundation.validation import check_positive
from mbd_core.contact.ehl import film_parameter, point_contact_film, thermal_loading, thermal_reduction_factor
from mbd_core.contact.ehl_inlet import grubin_line_contact
from mbd_core.contact.friction import LimitingShear, asperity_load_share
from mbd_core.contact.line import LINE_EXPONENT, iso16281_stiffness

from .kinematics import element_speed_magnitude_rad_s, rpm_to_rad_s

__all__ = ["CylindricalRollerBearing", "MixedLubrication", "RollerFriction", "radial_roller_loads", "rib_speeds_m_s",
           "roller_bearing_friction", "rolling_speed_m_s"]

_KELVIN = 273.15


@dataclass(frozen=True)
class CylindricalRollerBearing:
    """Geometry (m) and steel of a single-row cylindrical roller bearing with ribs (NJ type)."""

    n_rollers: int
    roller_diameter_m: float
    roller_length_m: float
    pitch_diameter_m: float
    radial_clearance_m: float = 0.0
    rib_contact_height_m: float = 0.0
    roller_end_radius_m: float = 0.06
    E_eff_Pa: float = 207e9 / (1.0 - 0.29**2)  # steel on steel, E' = E/(1 − ν²)

    def __post_init__(self) -> None:
        check_positive("cylindrical roller bearing", roller_diameter_m=self.roller_diameter_m,
                       roller_length_m=self.roller_length_m, pitch_diameter_m=self.pitch_diameter_m,
                       roller_end_radius_m=self.roller_end_radius_m, E_eff_Pa=self.E_eff_Pa)
        if not (isinstance(self.n_rollers, int) and self.n_rollers >= 4):
            raise ValueError(f"n_rollers: must be an integer ≥ 4, got {self.n_rollers!r}")
        if not 0.0 <= self.rib_contact_height_m < self.roller_diameter_m / 2:
            raise ValueError(f"rib_contact_height_m: must lie in [0, D/2 = {self.roller_diameter_m / 2:g} m), "
                             f"got {self.rib_contact_height_m!r}")
        if not self.radial_clearance_m >= 0.0:
            raise ValueError(f"radial_clearance_m: must be ≥ 0, got {self.radial_clearance_m!r}")

    @property
    def gamma(self) -> float:
        return self.roller_diameter_m / self.pitch_diameter_m

    @property
    def inner_raceway_radius_m(self) -> float:
        return (self.pitch_diameter_m - self.roller_diameter_m) / 2

    @property
    def outer_raceway_radius_m(self) -> float:
        return (self.pitch_diameter_m + self.roller_diameter_m) / 2

    def roller_angles_rad(self) -> np.ndarray:
        """ψ of each roller from the load line (a roller on it)."""
        return 2.0 * math.pi * np.arange(self.n_rollers) / self.n_rollers


@dataclass(frozen=True)
class MixedLubrication:
    """Surfaces and boundary friction: composite RMS roughness (m) of the raceway and rib contacts,
    Zhou & Hoeprich's B and C, the boundary friction μ_b and the fluid's limiting shear coefficient
    τ_L/p."""

    raceway_roughness_m: float = 0.13e-6
    rib_roughness_m: float = 0.34e-6
    B: float = 1.8
    C: float = 1.2
    mu_boundary: float = 0.1
    limiting_shear_coefficient: float = 0.05

    def __post_init__(self) -> None:
        check_positive(raceway_roughness_m=self.raceway_roughness_m, rib_roughness_m=self.rib_roughness_m, B=self.B,
                       C=self.C, mu_boundary=self.mu_boundary, limiting_shear_coefficient=self.limiting_shear_coefficient)
        for key in ("mu_boundary", "limiting_shear_coefficient"):
            if getattr(self, key) > 0.5:
                raise ValueError(f"{key} must be ≤ 0.5, got {getattr(self, key)!r}")


@dataclass(frozen=True)
class RollerFriction:
    """The losses of one operating point: per roller (arrays over the rollers) and in total.

    Powers in W, the torque in N·m, films in m; ``rib_*`` of the inner ring's rib (the outer rib's
    in ``outer_rib_*``)."""

    speed_rpm: float
    radial_load_N: float
    axial_load_N: float
    angles_rad: np.ndarray
    roller_load_N: np.ndarray
    rib_load_N: np.ndarray
    raceway_lambda: np.ndarray  # film parameter of the inner raceway contact (the thinner film)
    rolling_power_W: np.ndarray  # both raceways
    rib_lambda: np.ndarray
    rib_asperity_share: np.ndarray
    rib_friction: np.ndarray
    rib_power_W: np.ndarray  # both ribs
    outer_rib_lambda: np.ndarray
    rolling_speed_m_s: float

    @property
    def omega_rad_s(self) -> float:
        return self.speed_rpm * math.pi / 30.0

    @property
    def rolling_torque_Nm(self) -> float:
        return float(self.rolling_power_W.sum()) / self.omega_rad_s

    @property
    def rib_torque_Nm(self) -> float:
        return float(self.rib_power_W.sum()) / self.omega_rad_s

    @property
    def torque_Nm(self) -> float:
        return self.rolling_torque_Nm + self.rib_torque_Nm

    def summary(self) -> dict:
        loaded = self.roller_load_N > 0.0
        rib = self.rib_load_N > 0.0
        return {"speed_rpm": self.speed_rpm, "radial_load_N": self.radial_load_N, "axial_load_N": self.axial_load_N,
                "torque_Nm": self.torque_Nm, "rolling_torque_Nm": self.rolling_torque_Nm,
                "rib_torque_Nm": self.rib_torque_Nm, "loaded_rollers": int(loaded.sum()),
                "max_roller_load_N": float(self.roller_load_N.max()),
                "min_raceway_lambda": float(self.raceway_lambda[loaded].min()),
                "min_rib_lambda": float(self.rib_lambda[rib].min()) if rib.any() else None,
                "max_rib_asperity_share": float(self.rib_asperity_share[rib].max()) if rib.any() else 0.0,
                "mean_rib_friction": (float(np.average(self.rib_friction[rib], weights=self.rib_load_N[rib]))
                                      if rib.any() else None)}


def radial_roller_loads(bearing: CylindricalRollerBearing, radial_load_N: float) -> np.ndarray:
    """Q of each roller (N) under ``radial_load_N`` (module docstring, step 1)."""
    check_positive("radial roller loads", radial_load_N=radial_load_N)
    c_L = iso16281_stiffness(bearing.roller_length_m, bearing.E_eff_Pa)
    cos_psi = np.cos(bearing.roller_angles_rad())
    half_play = bearing.radial_clearance_m / 2.0

    def loads(shift_m: float) -> np.ndarray:
        return c_L * np.maximum(shift_m * cos_psi - half_play, 0.0) ** LINE_EXPONENT

    def residual(shift_m: float) -> float:
        return float(loads(shift_m) @ cos_psi) - radial_load_N

    hi = half_play + 1e-6
    while residual(hi) < 0.0:
        hi = 2.0 * hi
    return loads(brentq(residual, half_play, hi, xtol=1e-15, rtol=1e-13))


def rolling_speed_m_s(bearing: CylindricalRollerBearing, speed_rpm: float) -> float:
    """u = ω·d_m(1 − γ²)/4: the speed at which both raceway contacts' surfaces pass the contact
    (the roller's spin relative to the cage times D/2, :mod:`mbd_core.bearing.kinematics`)."""
    spin = element_speed_magnitude_rad_s(bearing.roller_diameter_m, bearing.pitch_diameter_m, 0.0,
                                         inner_speed_rad_s=rpm_to_rad_s(speed_rpm))
    return spin * bearing.roller_diameter_m / 2.0


def _inlet_heating(oil: Lubricant, temperature_C: float, entrain_m_s: float) -> float:
    """Murch & Wilson's film reduction factor at the oil's temperature and the entraining speed."""
    beta_T = oil.temperature_viscosity_K(temperature_C) / (temperature_C + _KELVIN) ** 2
    return thermal_reduction_factor(thermal_loading(beta_T, oil.dynamic_viscosity_Pa_s(temperature_C), entrain_m_s,
                                                    oil.thermal_conductivity_W_mK))


def rib_speeds_m_s(bearing: CylindricalRollerBearing, speed_rpm: float) -> tuple[tuple[float, float], ...]:
    """(sliding, entraining) speed of the inner and the outer rib contact (module docstring, step 2)."""
    u = rolling_speed_m_s(bearing, speed_rpm)
    e, dm = bearing.rib_contact_height_m, bearing.pitch_diameter_m
    roller_end = u * 2.0 * e / bearing.roller_diameter_m
    rings = (u * (dm / 2 - e) / bearing.inner_raceway_radius_m, u * (dm / 2 + e) / bearing.outer_raceway_radius_m)
    return tuple((abs(ring - roller_end), (ring + roller_end) / 2) for ring in rings)


def _rib_contact(load_N: float, entrain_m_s: float, slide_m_s: float, bearing: CylindricalRollerBearing,
                 oil: Lubricant, temperature_C: float, surfaces: MixedLubrication):
    """(Λ, φ, μ) of one roller end on its rib (module docstring, step 4)."""
    eta0 = oil.dynamic_viscosity_Pa_s(temperature_C)
    alpha = oil.pressure_viscosity_Pa_inv(temperature_C)
    R = bearing.roller_end_radius_m
    film = point_contact_film(load_N, entrain_m_s, R, R, bearing.E_eff_Pa, eta0, alpha)
    phi_T = _inlet_heating(oil, temperature_C, entrain_m_s)
    lam = film_parameter(phi_T * film.minimum_m, surfaces.rib_roughness_m, 0.0)
    share = asperity_load_share(lam, surfaces.B, surfaces.C)
    a = (3.0 * load_N * R / (2.0 * bearing.E_eff_Pa)) ** (1.0 / 3.0)
    p_mean = load_N / (math.pi * a * a)
    eta_p = eta0 * math.exp(min(alpha * p_mean, 700.0))
    fluid = LimitingShear.from_film(phi_T * film.central_m, p_mean, eta_p, surfaces.limiting_shear_coefficient)
    mu = share * surfaces.mu_boundary + (1.0 - share) * fluid.kappa_L * (1.0 - math.exp(-slide_m_s / fluid.u_c_m_s))
    return lam, share, mu


def roller_bearing_friction(bearing: CylindricalRollerBearing, oil: Lubricant, temperature_C: float,
                            speed_rpm: float, radial_load_N: float, axial_load_N: float = 0.0,
                            surfaces: MixedLubrication = MixedLubrication()) -> RollerFriction:
    """The losses and friction torque at one operating point (module docstring)."""
    check_positive("roller bearing friction", speed_rpm=speed_rpm)
    if not axial_load_N >= 0.0:
        raise ValueError(f"axial_load_N: must be ≥ 0, got {axial_load_N!r}")
    Q = radial_roller_loads(bearing, radial_load_N)
    rib_load = axial_load_N * Q / Q.sum()
    D, r_i, r_o = bearing.roller_diameter_m, bearing.inner_raceway_radius_m, bearing.outer_raceway_radius_m
    u = rolling_speed_m_s(bearing, speed_rpm)
    eta0 = oil.dynamic_viscosity_Pa_s(temperature_C)
    alpha = oil.pressure_viscosity_Pa_inv(temperature_C)
    phi_T = _inlet_heating(oil, temperature_C, u)
    radii = (D / 2 * r_i / (D / 2 + r_i), D / 2 * r_o / (r_o - D / 2))  # inner, outer contact R_x
    ribs = rib_speeds_m_s(bearing, speed_rpm)  # inner, outer

    n = bearing.n_rollers
    lam_race, rolling = np.zeros(n), np.zeros(n)
    lam_rib, lam_outer_rib, share, mu, rib_power = (np.zeros(n) for _ in range(5))
    for j in np.flatnonzero(Q > 0.0):
        films = [grubin_line_contact(Q[j] / bearing.roller_length_m, u, R, bearing.E_eff_Pa, eta0, alpha)
                 for R in radii]
        rolling[j] = sum(f.rolling_force_per_length_N_m for f in films) * bearing.roller_length_m * u
        lam_race[j] = film_parameter(phi_T * films[0].central_film_m, surfaces.raceway_roughness_m, 0.0)
        if rib_load[j] <= 0.0:
            continue
        for k, (slide, entrain) in enumerate(ribs):
            lam, phi, m = _rib_contact(rib_load[j], entrain, slide, bearing, oil, temperature_C, surfaces)
            rib_power[j] += m * rib_load[j] * slide
            if k == 0:
                lam_rib[j], share[j], mu[j] = lam, phi, m
            else:
                lam_outer_rib[j] = lam
    return RollerFriction(speed_rpm, radial_load_N, axial_load_N, bearing.roller_angles_rad(), Q, rib_load, lam_race,
                          rolling, lam_rib, share, mu, rib_power, lam_outer_rib, u)
