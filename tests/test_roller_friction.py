"""Friction torque of a cylindrical roller bearing, contact by contact (mbd_core.bearing.roller_friction),
its inlet film and rolling loss (mbd_core.contact.ehl_inlet).

References:
- Grubin's closed form of the inlet film of a line contact, H_c = 1.95·(G·U)^(8/11)·W^(−1/11) (Grubin 1949;
  Hamrock, Fundamentals of Fluid Film Lubrication, on Ertel–Grubin), fitted by Grubin to the same
  inlet integral that the module solves exactly; Pan & Hamrock's central film (J. Tribol. 111 (1989)).
- The rolling loss from its definition: Reynolds' inlet pressure integrated as an ODE here (scipy
  solve_ivp in x, not the module's reduced-pressure quadrature), then P/l = ∫ h³/(12η)·(dp/dx)² dx.
- Radial load distribution: for many rollers and no clearance the largest roller load is F_r/(Z·J_r) with
  J_r = (1/2π)∫ cos^(19/9)ψ dψ over the half circle = Γ(14/9)/(2√π·Γ(37/18)) (Stribeck's integral for
  the exponent 10/9; Harris & Kotzalas vol. 1, ch. 7: Q_max ≈ 4.08·F_r/Z).
- Rib contact speeds from rigid-body velocities of the roller, cage and rings written here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from foundation.lubricants import iso_vg_mineral_oil
from mbd_core.bearing.roller_friction import (CylindricalRollerBearing, radial_roller_loads, rib_speeds_m_s,
                                              roller_bearing_friction)
from mbd_core.contact.ehl_inlet import grubin_line_contact, hertz_gap

E_EFF = 2.27e11
ALPHA = 2.2e-8
ETA = 0.05
# (load per length N/m, mean speed m/s, R_x m): a roller bearing's raceways from slow to fast
POINTS = [(1e5, 0.01, 0.007), (1e5, 0.3, 0.007), (2.5e5, 3.0, 0.0065), (1e6, 10.0, 0.01), (2.5e5, 30.0, 0.0065)]


@pytest.mark.parametrize("w, u, R", POINTS)
def test_inlet_film_is_grubins(w, u, R):
    """Within 3 % of Grubin's closed form (measured −2.6 … +1.1 %) and 20 % of Pan & Hamrock's central film
    (measured −19 % at 1 cm/s, where the two fits' speed exponents 0.727 and 0.69 part, −5 … +10 % above)."""
    film = grubin_line_contact(w, u, R, E_EFF, ETA, ALPHA)
    U, G, W = ETA * u / (E_EFF * R), ALPHA * E_EFF, w / (E_EFF * R)
    assert film.central_film_m == pytest.approx(1.95 * (G * U) ** (8 / 11) * W ** (-1 / 11) * R, rel=0.03)
    assert film.central_film_m == pytest.approx(3.06 * U**0.69 * G**0.56 * W**-0.10 * R, rel=0.20)


def _rolling_loss_by_ode(w, u, R):
    """P/l from Reynolds' equation integrated from 20 000 half-widths upstream to the contact's edge with
    the module's film h_c (x = −b·(1 + s²) clusters the steps at the edge), the Poiseuille dissipation
    h³/(12η)·(dp/dx)² = 12·η·u²·(h − h_c)²/h³ summed alongside; stopped where α·p = 30."""
    film = grubin_line_contact(w, u, R, E_EFF, ETA, ALPHA)
    b, hc = film.half_width_m, film.central_film_m

    def rates(s, y):
        p, _ = y
        xi = 1.0 + s * s
        h = hc + b * b / (2 * R) * float(hertz_gap(xi))
        eta = ETA * math.exp(ALPHA * p)
        dx_ds = -2.0 * b * s
        return [12.0 * eta * u * (h - hc) / h**3 * dx_ds, 12.0 * eta * u * u * (h - hc) ** 2 / h**3 * dx_ds]

    edge = lambda s, y: ALPHA * y[0] - 30.0  # noqa: E731
    edge.terminal = True
    sol = solve_ivp(rates, (math.sqrt(2e4), 0.0), [0.0, 0.0], method="LSODA", rtol=1e-9, atol=[1e-3, 1e-12],
                    events=edge)
    return sol.y[1, -1], film


@pytest.mark.parametrize("w, u, R", POINTS)
def test_rolling_loss_is_the_inlets_poiseuille_dissipation(w, u, R):
    """The module's F_R·u against the dissipation of the pressure flow from an ODE integration of Reynolds'
    equation: within 0.2 % (measured 2.7e-4 … 3.8e-4, the ODE's cut-offs upstream and at α·p = 30)."""
    power, film = _rolling_loss_by_ode(w, u, R)
    assert film.rolling_force_per_length_N_m * u == pytest.approx(power, rel=2e-3)


NJ216 = CylindricalRollerBearing(18, 0.015, 0.020, 0.110, 40e-6, 0.00525, 0.06)


def test_radial_loads_follow_stribecks_integral_and_balance_the_load():
    """360 rollers without clearance: Q_max·Z/F_r = 1/J_r within 0.1 % (measured 1e-8); every case: Σ Q·cos ψ =
    F_r to 1e-9; clearance narrows the load zone (NJ 216 with 40 µm: fewer loaded rollers than without)."""
    many = CylindricalRollerBearing(360, 0.001, 0.01, 0.2)
    Q = radial_roller_loads(many, 1e5)
    J_r = math.gamma(14 / 9) / (2.0 * math.sqrt(math.pi) * math.gamma(37 / 18))
    assert Q.max() * 360 / 1e5 == pytest.approx(1.0 / J_r, rel=1e-3)
    assert 1.0 / J_r == pytest.approx(4.08, rel=2e-3)
    for bearing in (many, NJ216):
        Q = radial_roller_loads(bearing, 2e4)
        assert Q @ np.cos(bearing.roller_angles_rad()) == pytest.approx(2e4, rel=1e-9)
    tight = CylindricalRollerBearing(18, 0.015, 0.020, 0.110, 0.0, 0.00525, 0.06)
    assert (radial_roller_loads(NJ216, 2e4) > 0).sum() < (radial_roller_loads(tight, 2e4) > 0).sum()


def _rigid_body_rib_speeds(bearing, speed_rpm):
    """Tangential velocities at the rib contacts from the rigid-body motion of inner ring (ω), cage (ω_c)
    and a roller rolling on the inner raceway without slip; sliding = roller − ring, entraining = the
    mean of both relative to the contact point, which moves with the cage."""
    omega = speed_rpm * math.pi / 30.0
    D, rc, e = bearing.roller_diameter_m, bearing.pitch_diameter_m / 2, bearing.rib_contact_height_m
    omega_c = omega * (1.0 - D / (2 * rc)) / 2.0
    spin = (omega_c * rc - omega * (rc - D / 2)) * 2.0 / D  # absolute, about the roller's axis

    def roller(r):
        return omega_c * rc + spin * (r - rc)

    assert roller(rc + D / 2) == pytest.approx(0.0, abs=1e-12)  # it rolls on the held outer ring, too
    out = []
    for r, ring in ((rc - e, omega * (rc - e)), (rc + e, 0.0)):
        a, b = roller(r) - omega_c * r, ring - omega_c * r
        out.append((abs(a - b), abs(a + b) / 2))
    return out


@pytest.mark.parametrize("e_over_D", [0.0, 0.2, 0.35, 0.49])
def test_rib_speeds_are_the_rigid_body_ones(e_over_D):
    """Both ribs' sliding and entraining speeds equal the rigid-body ones to 1e-12 (relative)."""
    bearing = CylindricalRollerBearing(18, 0.015, 0.020, 0.110, 40e-6, e_over_D * 0.015, 0.06)
    for ours, ref in zip(rib_speeds_m_s(bearing, 1500.0), _rigid_body_rib_speeds(bearing, 1500.0)):
        np.testing.assert_allclose(ours, ref, rtol=1e-12, atol=1e-14)


def test_torque_is_the_lost_power_over_the_speed_and_grows_with_the_axial_load():
    """M·ω = Σ P exactly (energy balance); no axial load, no rib loss; the rib share grows with F_a."""
    oil = iso_vg_mineral_oil(100, 50.0)
    runs = [roller_bearing_friction(NJ216, oil, 50.0, 1500.0, 2e4, fa) for fa in (0.0, 1e3, 4e3)]
    for run in runs:
        total = run.rolling_power_W.sum() + run.rib_power_W.sum()
        assert run.torque_Nm * run.omega_rad_s == pytest.approx(total, rel=1e-12)
    assert runs[0].rib_torque_Nm == 0.0
    assert runs[0].torque_Nm < runs[1].torque_Nm < runs[2].torque_Nm
    np.testing.assert_allclose(runs[2].rib_load_N.sum(), 4e3, rtol=1e-12)
