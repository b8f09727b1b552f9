"""Ball-row clearance through the unloaded groove geometry (ISO/TS 16281; Harris & Kotzalas,
*Rolling Bearing Analysis*, 5th ed., ch. 2 and 7), against an independent implementation here.

Reference model (Harris, rigid rings, the moving ring held aligned: θ = 0): with the diametral
clearance P_d the curvature centres of a ball sit s0 = (A cos α0 − P_d/2, A sin α0) apart
(radial, axial) in the concentric rings, A = (f_i + f_o − 1)·D; a ring displacement (δ_r, δ_a)
adds (δ_r cos ψ, δ_a); δ = |s| − A, Q = K δ^1.5, α = atan2(s_a, s_r), and
Σ Q cos α cos ψ = F_r, Σ Q sin α = F_a. Solved by nested brentq (axial balance inside, radial
outside). The moment this aligned ring needs is applied to the solver's ring, whose tilt must then
vanish.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from mbd_core.quasistatic import BallRow, Bearing, RingLoad, solve_load_distribution

D, DM, F_GROOVE, Z = 12.7e-3, 65e-3, 0.52, 9  # a 6209-size deep-groove bearing (Harris ch. 7)


def row(pd_m: float, alpha0_deg: float = 0.0) -> BallRow:
    return BallRow("balls", Z, D, DM, math.radians(alpha0_deg), F_GROOVE, F_GROOVE, "inner", 1,
                   diametral_clearance_m=pd_m)


def harris_reference(r: BallRow, Fr: float, Fa: float):
    """(δ_r, δ_a, Q (Z,), α (Z,), M_y) of the aligned ring (module docstring); M_y the moment of the
    ball forces on the moving ring about y, from their points of action on its groove centres."""
    A, a0, K = r.curvature_centre_distance_m, r.contact_angle_rad, r.contact_stiffness()
    psi = 2 * np.pi * np.arange(Z) / Z
    s_r0, s_a0 = A * math.cos(a0) - r.diametral_clearance_m / 2, A * math.sin(a0)

    def balls(dr, da):
        sr = s_r0 + dr * np.cos(psi)
        sa = np.full(Z, s_a0 + da)
        Q = K * np.maximum(np.hypot(sr, sa) - A, 0.0) ** 1.5
        return Q, np.arctan2(sa, sr)

    def axial_balance(dr, da):
        Q, a = balls(dr, da)
        return np.sum(Q * np.sin(a)) - Fa

    def da_of(dr):
        lo, hi = -A, A
        return brentq(lambda da: axial_balance(dr, da), lo, hi, xtol=1e-300, rtol=1e-15)

    def radial_balance(dr):
        Q, a = balls(dr, da_of(dr))
        return np.sum(Q * np.cos(a) * np.cos(psi)) - Fr

    if Fr == 0.0:
        dr = 0.0
    else:
        hi = 1e-6
        while radial_balance(hi) < 0:
            hi *= 2
        dr = brentq(radial_balance, 0.0, hi, xtol=1e-300, rtol=1e-15)
    da = da_of(dr)
    Q, a = balls(dr, da)
    # moving groove centres at ball centre + (f − 1/2)·D·(cos α0 e_r + sin α0 e_z); force −Q·(cos α e_r + sin α e_z)
    p_x = (DM / 2 + (F_GROOVE - 0.5) * D * math.cos(a0)) * np.cos(psi)
    p_z = (F_GROOVE - 0.5) * D * math.sin(a0)
    f_x, f_z = -Q * np.cos(a) * np.cos(psi), -Q * np.sin(a)
    My = float(np.sum(p_z * f_x - p_x * f_z))
    return dr, da, Q, a, My


CASES = [  # (P_d, α0 deg, F_r, F_a)
    (20e-6, 0.0, 0.0, 2000.0),
    (20e-6, 0.0, 3000.0, 0.0),
    (20e-6, 0.0, 3000.0, 2000.0),
    (40e-6, 0.0, 1000.0, 4450.0),
    (10e-6, 25.0, 3000.0, 2000.0),
    (-5e-6, 0.0, 3000.0, 2000.0),  # preload
]


@pytest.mark.parametrize("pd, alpha0_deg, Fr, Fa", CASES)
def test_clearance_through_geometry_matches_harris(pd, alpha0_deg, Fr, Fa):
    """Ball loads, contact angles and ring displacement equal the curvature-centre reference to
    1e-6 relative (angles 1e-8 rad, tilt below 1e-9 rad) under axial, radial and combined loads."""
    r = row(pd, alpha0_deg)
    dr, da, Q, a, My = harris_reference(r, Fr, Fa)
    res = solve_load_distribution(Bearing("dg", (r,)), RingLoad(Fx_N=Fr, Fz_N=Fa, My_Nm=-My))
    loads = res.rows[0]
    np.testing.assert_allclose(loads.load_N, Q, rtol=1e-6, atol=1e-6 * Q.max())
    loaded = Q > 0
    np.testing.assert_allclose(loads.contact_angle_rad[loaded], a[loaded], atol=1e-8)
    np.testing.assert_allclose(res.displacement[[0, 2]], [dr, da], rtol=1e-6, atol=1e-6 * max(abs(dr), abs(da)))
    assert abs(res.displacement[3]) < 1e-9 and abs(res.displacement[4]) < 1e-9


def test_free_contact_angle_from_clearance():
    """cos α_f = 1 − P_d/(2A) (Harris & Kotzalas ch. 2), and the smallest axial load turns the
    balls to that angle: α within 1e-7 rad of α_f at 1 nN (the approach, ~1e-13 m, turns it by ~1e-9 rad)."""
    r = row(20e-6)
    A = r.curvature_centre_distance_m
    alpha_f = math.acos(1 - 20e-6 / (2 * A))
    assert r.free_contact_angle_rad == pytest.approx(alpha_f, rel=1e-12)
    res = solve_load_distribution(Bearing("dg", (r,)), RingLoad(Fz_N=1e-9))
    np.testing.assert_allclose(res.rows[0].contact_angle_rad, alpha_f, atol=1e-7)


def test_radial_and_diametral_clearance_by_name():
    """radial_clearance_m = P_d/2: the two spellings give the same row; disagreeing ones are refused."""
    a = row(30e-6)
    b = BallRow("balls", Z, D, DM, 0.0, F_GROOVE, F_GROOVE, "inner", 1, radial_clearance_m=15e-6)
    assert (a.diametral_clearance_m, a.radial_clearance_m) == (b.diametral_clearance_m, b.radial_clearance_m)
    with pytest.raises(ValueError, match="disagree"):
        BallRow("balls", Z, D, DM, 0.0, F_GROOVE, F_GROOVE, "inner", 1, radial_clearance_m=15e-6,
                diametral_clearance_m=20e-6)
    with pytest.raises(ValueError, match="radial_clearance_m"):  # more play than the groove holds
        BallRow("balls", Z, D, DM, 0.0, F_GROOVE, F_GROOVE, "inner", 1, radial_clearance_m=1e-3)
