"""The frictional moment of a cylindrical roller bearing by SKF's catalogue model (the form published in
its rolling bearing catalogues since 2004, "The SKF model for calculating the frictional moment"): an
independent, empirical estimate to set beside the contact-by-contact one of
:mod:`mbd_core.bearing.roller_friction`.

Catalogue units: moments in N·mm, d_m, d, D in mm, loads in N, n in rev/min, ν the oil's kinematic
viscosity at the operating temperature in mm²/s. For a cylindrical roller bearing with a cage:

    M_rr = φ_ish·φ_rs·G_rr·(ν·n)^0.6,        G_rr = R1·d_m^2.41·F_r^0.31
    M_sl = μ_sl·G_sl,                          G_sl = S1·d_m^0.9·F_a + S2·d_m·F_r
    μ_sl = φ_bl·μ_bl + (1 − φ_bl)·μ_EHL,       φ_bl = exp(−2.6·10⁻⁸·(n·ν)^1.4·d_m)
    φ_ish = 1/(1 + 1.84·10⁻⁹·(n·d_m)^1.28·ν^0.64)           (inlet shear heating)
    φ_rs = exp(−K_rs·ν·n·(d + D)·√(K_Z/(2(D − d))))          (replenishment/starvation)

with the constants of the catalogue's tables for the bearing series (defaults: cylindrical roller bearings
with a cage, series 2: R1 = 1.09·10⁻⁶, S1 = 0.16, S2 = 0.0015; μ_bl = 0.15, μ_EHL = 0.02 for cylindrical
roller bearings; K_Z = 5.1; K_rs = 3·10⁻⁸ for a low oil level or oil jet, 6·10⁻⁸ for grease or oil–air).
The drag of an oil bath (M_drag) and seals are left out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from foundation.validation import check_positive

__all__ = ["CatalogueConstants", "catalogue_cylindrical_roller_moment"]


@dataclass(frozen=True)
class CatalogueConstants:
    """The catalogue model's constants (module docstring)."""

    R1: float = 1.09e-6
    S1: float = 0.16
    S2: float = 0.0015
    mu_bl: float = 0.15
    mu_ehl: float = 0.02
    K_rs: float = 3e-8
    K_Z: float = 5.1

    def __post_init__(self) -> None:
        check_positive(R1=self.R1, S1=self.S1, S2=self.S2, mu_bl=self.mu_bl, mu_ehl=self.mu_ehl, K_rs=self.K_rs,
                       K_Z=self.K_Z)


def catalogue_cylindrical_roller_moment(bore_m: float, outside_diameter_m: float, radial_load_N: float,
                                        axial_load_N: float, speed_rpm: float, viscosity_m2_s: float,
                                        constants: CatalogueConstants = CatalogueConstants()) -> dict:
    """Rolling, sliding and total frictional moment (N·m) of a cylindrical roller bearing (module
    docstring), with the factors φ_ish, φ_rs, φ_bl and μ_sl."""
    check_positive("catalogue friction", bore_m=bore_m, outside_diameter_m=outside_diameter_m,
                   speed_rpm=speed_rpm, viscosity_m2_s=viscosity_m2_s)
    if not outside_diameter_m > bore_m:
        raise ValueError(f"outside_diameter_m ({outside_diameter_m}) must exceed bore_m ({bore_m})")
    c = constants
    d, D = bore_m * 1e3, outside_diameter_m * 1e3
    dm = (d + D) / 2
    nu, n = viscosity_m2_s * 1e6, speed_rpm
    G_rr = c.R1 * dm**2.41 * radial_load_N**0.31
    G_sl = c.S1 * dm**0.9 * axial_load_N + c.S2 * dm * radial_load_N
    phi_ish = 1.0 / (1.0 + 1.84e-9 * (n * dm) ** 1.28 * nu**0.64)
    phi_rs = math.exp(-c.K_rs * nu * n * (d + D) * math.sqrt(c.K_Z / (2.0 * (D - d))))
    phi_bl = math.exp(-2.6e-8 * (n * nu) ** 1.4 * dm)
    mu_sl = phi_bl * c.mu_bl + (1.0 - phi_bl) * c.mu_ehl
    rolling = phi_ish * phi_rs * G_rr * (nu * n) ** 0.6 * 1e-3
    sliding = mu_sl * G_sl * 1e-3
    return {"torque_Nm": rolling + sliding, "rolling_Nm": rolling, "sliding_Nm": sliding, "phi_ish": phi_ish,
            "phi_rs": phi_rs, "phi_bl": phi_bl, "mu_sl": mu_sl}
