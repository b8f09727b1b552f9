"""Crossed cylindrical roller rows (rigid rings) against an independent implementation written here.

The reference below loops over rollers and slices in plain Python with its own geometry: roller k
at ψ_k on diagonal σ_k has the contact normal n = s_r·cos α0·e_r + σ_k·sin α0·e_z and its axis
±n × e_t in the meridian plane (pointing to +z: slices numbered from the −z end); slice j at p = c + x_j·axis approaches by n·(d + θ × p) − g − drop(x_j)
and carries (c_L/n_s)·δ^(10/9) (ISO/TS 16281:2008 slices, rigid rings: Harris & Kotzalas, *Rolling
Bearing Analysis*, 5th ed., ch. 7). The 5-DOF equilibrium is solved by scipy.optimize.fsolve.
c_L is the row's ISO/TS 16281 constant (checked against the standard in test_line_contact.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import fsolve, least_squares

from cases.bearing_file import loads_bearing
from mbd_core.bearing.distribution_life import rating_life
from mbd_core.bearing.static_safety import (
    classical_static_safety,
    roller_row_static_rating_N,
    row_forces_N,
    static_safety,
)
from mbd_core.quasistatic import Bearing, RingLoad, RollerRow, solve_load_distribution, stiffness_matrix
from mbd_core.quasistatic.contacts import contact_sets

Z, D, L, DM, NS = 40, 0.020, 0.018, 0.40, 8
ALPHA = math.radians(45.0)

#: (name, diametral clearance m, profile kwargs, pattern, moving ring carries the inner raceway)
DESIGNS = {
    "zero clearance, logarithmic": (0.0, dict(profile="logarithmic"), "alternate", True),
    "preload, crowned": (-20e-6, dict(crown_drop_m=4e-6), "alternate", True),
    "clearance, straight, outer ring moving, ++-": (30e-6, dict(), "++-", False),
}
LOADS = {
    "radial": RingLoad(Fx_N=5.0e4),
    "axial": RingLoad(Fz_N=8.0e4),
    "tilt": RingLoad(My_Nm=2.0e4),
    "combined": RingLoad(Fx_N=2.0e4, Fy_N=-1.0e4, Fz_N=-5.0e4, Mx_Nm=1.0e4, My_Nm=-5.0e3),
}


def _row(clearance_m: float, profile: dict, pattern: str, inner_moving: bool, alpha: float = ALPHA) -> RollerRow:
    return RollerRow("crossed", Z, D, L, DM, "crossed", load_sign=1 if inner_moving else -1,
                     gap_m=0.5 * clearance_m * math.cos(alpha), n_slices=NS, contact_angle_rad=alpha,
                     pattern=pattern, **profile)


class Reference:
    """The crossed row of ``DESIGNS`` evaluated roller by roller, slice by slice."""

    def __init__(self, clearance_m, profile, pattern, inner_moving, K_roller, alpha=ALPHA):
        self.gap = 0.5 * clearance_m * math.cos(alpha)  # diametral clearance → gap along the normal
        self.s_r = 1.0 if inner_moving else -1.0
        seq = "+-" if pattern == "alternate" else pattern
        self.sigma = [1.0 if seq[k % len(seq)] == "+" else -1.0 for k in range(Z)]
        self.alpha, self.k_slice = alpha, K_roller / NS
        self.profile = profile

    def drop(self, x: float) -> float:
        u = 2.0 * x / L
        if self.profile.get("profile") == "logarithmic":
            return 0.00035 * D * math.log(1.0 / (1.0 - u * u))  # ISO/TS 16281 default relief
        return self.profile.get("crown_drop_m", 0.0) * u * u

    def slices(self, q):
        """Per roller the list of slice loads, and the force (Fx, Fy, Fz, Mx, My) of all on the moving ring."""
        x, y, z, tx, ty = q
        total = [0.0] * 5
        loads = []
        for k in range(Z):
            psi = 2.0 * math.pi * k / Z
            e_r = (math.cos(psi), math.sin(psi), 0.0)
            e_t = (-math.sin(psi), math.cos(psi), 0.0)
            n = (self.s_r * math.cos(self.alpha) * e_r[0], self.s_r * math.cos(self.alpha) * e_r[1],
                 self.sigma[k] * math.sin(self.alpha))
            axis = (n[1] * e_t[2] - n[2] * e_t[1], n[2] * e_t[0] - n[0] * e_t[2], n[0] * e_t[1] - n[1] * e_t[0])
            if axis[2] < 0.0:  # slices numbered from the roller's −z end
                axis = tuple(-a for a in axis)
            per = []
            for j in range(NS):
                xj = -0.5 * L + (j + 0.5) * L / NS
                p = [0.5 * DM * e_r[i] + xj * axis[i] for i in range(3)]
                u = (x + ty * p[2], y - tx * p[2], z + tx * p[1] - ty * p[0])  # d + θ × p, θ = (θx, θy, 0)
                delta = sum(u[i] * n[i] for i in range(3)) - self.gap - self.drop(xj)
                qj = self.k_slice * max(delta, 0.0) ** (10.0 / 9.0)
                per.append(qj)
                f = [-qj * n[i] for i in range(3)]  # the roller pushes the moving ring back along −n
                total[0] += f[0]
                total[1] += f[1]
                total[2] += f[2]
                total[3] += p[1] * f[2] - p[2] * f[1]
                total[4] += p[2] * f[0] - p[0] * f[2]
            loads.append(per)
        return loads, total

    def solve(self, load: RingLoad) -> np.ndarray:
        """Equilibrium q of the moving ring under ``load`` (unknowns in µm, moments over the pitch radius)."""
        f_ext = load.as_array()
        scale = np.array([1e-6, 1e-6, 1e-6, 2e-6 / DM, 2e-6 / DM])
        w = np.array([1.0, 1.0, 1.0, 2.0 / DM, 2.0 / DM]) / max(np.linalg.norm(f_ext), 1.0)

        def residual(y):
            return (np.array(self.slices(y * scale)[1]) + f_ext) * w

        # a start pushed 20 µm along the load, then least squares (robust where rollers lift off),
        # then fsolve to the rounding level
        y0 = 20.0 * f_ext * w / np.linalg.norm(f_ext * w)
        y = least_squares(residual, y0, xtol=1e-15, ftol=1e-15, gtol=1e-15).x
        y, _, ok, msg = fsolve(residual, y, xtol=1e-14, full_output=True)
        assert ok == 1 or np.linalg.norm(residual(y)) < 1e-12, msg
        return y * scale


def _solve_both(design: str, load_name: str):
    clearance, profile, pattern, inner = DESIGNS[design]
    row = _row(clearance, profile, pattern, inner)
    ref = Reference(clearance, profile, pattern, inner, row.contact_stiffness())
    return row, ref, solve_load_distribution(Bearing("x", (row,)), LOADS[load_name]), ref.solve(LOADS[load_name])


@pytest.mark.parametrize("design", list(DESIGNS))
@pytest.mark.parametrize("load_name", list(LOADS))
def test_roller_loads_match_the_independent_solution(design, load_name):
    """Roller and slice loads of the library against the reference's own equilibrium, ≤ 1e-6 of the
    largest roller load (both solve to ~1e-10 of the load); the library's equilibrium error ≤ 1e-9,
    also recomputed by the reference's force sum at the library's displacement."""
    row, ref, res, q_ref = _solve_both(design, load_name)
    slices_ref, _ = ref.slices(q_ref)
    roller_ref = np.array([sum(s) for s in slices_ref])
    r = res.rows[0]
    assert r.load_N == pytest.approx(roller_ref, abs=1e-6 * roller_ref.max())
    assert r.slice_load_N == pytest.approx(np.array(slices_ref), abs=1e-6 * roller_ref.max())
    assert res.equilibrium_error <= 1e-9
    _, force = ref.slices(res.displacement)
    unbalanced = (np.array(force) + LOADS[load_name].as_array()) * [1, 1, 1, 2 / DM, 2 / DM]
    scale = max(np.linalg.norm(LOADS[load_name].as_array() * [1, 1, 1, 2 / DM, 2 / DM]), r.load_N.sum())
    assert np.linalg.norm(unbalanced) <= 1e-9 * scale
    # the signed nominal contact angle names each roller's diagonal
    assert r.contact_angle_rad == pytest.approx(np.array(ref.sigma) * ALPHA, rel=1e-15)


@pytest.mark.parametrize("design", list(DESIGNS))
def test_stiffness_matrix_is_the_central_difference_and_symmetric(design):
    """K = dF/dq of the library against a central difference of the reference's forces (step 1 nm,
    1 nrad·(d_m/2)), 1e-5 of the largest entry with rotations and moments over the pitch radius."""
    row, ref, res, _ = _solve_both(design, "combined")
    K = stiffness_matrix(Bearing("x", (row,)), res)
    h = np.array([1e-9, 1e-9, 1e-9, 2e-9 / DM, 2e-9 / DM])
    K_fd = np.zeros((5, 5))
    for j in range(5):
        dq = np.zeros(5)
        dq[j] = h[j]
        plus, minus = (np.array(ref.slices(res.displacement + s * dq)[1]) for s in (1.0, -1.0))
        K_fd[:, j] = -(plus - minus) / (2.0 * h[j])  # F = −(element forces) holds the ring at q
    S = np.diag([1.0, 1.0, 1.0, 2.0 / DM, 2.0 / DM])
    Ks, Kfs = S @ K @ S, S @ K_fd @ S
    assert np.abs(Ks - Kfs).max() <= 1e-5 * np.abs(Ks).max()
    assert np.abs(Ks - Ks.T).max() <= 1e-12 * np.abs(Ks).max()


def test_pure_axial_load_each_loaded_roller_carries_fa_over_half_z_sin_alpha():
    """Zero clearance, alternating rollers, F_a towards +z: the −α0 rollers lift off and each +α0
    roller carries F_a/((Z/2)·sin α0) (equilibrium of the axial components; by symmetry the radial
    components of the equally loaded rollers cancel), 1e-9 relative."""
    for alpha_deg in (45.0, 30.0, 60.0):
        a = math.radians(alpha_deg)
        row = _row(0.0, dict(profile="logarithmic"), "alternate", True, a)
        F = 8.0e4
        res = solve_load_distribution(Bearing("x", (row,)), RingLoad(Fz_N=F))
        Q = res.rows[0].load_N
        assert Q[0::2] == pytest.approx(np.full(Z // 2, F / (Z / 2 * math.sin(a))), rel=1e-9)
        assert Q[1::2].max() == 0.0
        # and the other way: the −α0 rollers alone
        Q = solve_load_distribution(Bearing("x", (row,)), RingLoad(Fz_N=-F)).rows[0].load_N
        assert Q[1::2] == pytest.approx(np.full(Z // 2, F / (Z / 2 * math.sin(a))), rel=1e-9)
        assert Q[0::2].max() == 0.0


@pytest.mark.parametrize("moving", ["inner", "outer"])
@pytest.mark.parametrize("alpha_deg", [45.0, 30.0])
def test_diametral_clearance_is_the_free_radial_play(moving, alpha_deg):
    """A description file's P_d is the rings' free radial play: moved radially (no tilt, no axial
    shift) the moving ring touches the first roller at ±P_d/2 (no roller loaded at (1 − 1e-6)·P_d/2,
    one at (1 + 1e-6)·P_d/2); the free axial play is P_d·cot α0 (g/sin α0 each way with
    g = (P_d/2)·cos α0), met under a pure axial load of 1 N, which the +α0 rollers share alike
    (z = g/sin α0 + δ, δ ≈ (Q/c_L)^0.9 ≈ 1e-10 m: 1e-4 relative)."""
    from mbd_core.quasistatic.solver import _Problem

    P_d = 40e-6
    d = loads_bearing(f"""[bearing]
name = "x"
moving_ring = "{moving}"
[[rows]]
type = "crossed_roller"
name = "x"
count = {Z}
roller_diameter_m = {D}
roller_length_m = {L}
pitch_diameter_m = {DM}
contact_angle_deg = {alpha_deg}
diametral_clearance_m = {P_d}
""")
    prob = _Problem(d.bearing)
    for direction in (1.0, -1.0):
        for factor, touches in ((1.0 - 1e-6, False), (1.0 + 1e-6, True)):
            q = np.array([direction * factor * P_d / 2, 0.0, 0.0, 0.0, 0.0])
            reaction, _ = prob.reaction(q, jacobian=False)
            assert (np.abs(reaction).max() > 0.0) == touches, (direction, factor)
    z = solve_load_distribution(d.bearing, RingLoad(Fz_N=1.0)).displacement[2]
    assert z == pytest.approx(0.5 * P_d / math.tan(math.radians(alpha_deg)), rel=1e-4)


def _line_p0_Pa(q_N: np.ndarray, row: RollerRow, inner: bool) -> np.ndarray:
    """Hertz line contact p0 = (q/ℓ·E*/(π·R))^(1/2) (Johnson, Contact Mechanics, 1985, eq. 4.45) of a
    slice of length ℓ = L/n_s, R the reduced radius of the roller (D/2) and the conical raceway at α0
    touched at radius (d_m ∓ D·cos α0)/2, whose curvature across the roller axis is cos α0 over that
    radius (Meusnier): 1/R = 2/D ± 2·cos α0/(d_m ∓ D·cos α0)."""
    c = math.cos(row.contact_angle_rad)
    sign = 1.0 if inner else -1.0
    inv_R = 2.0 / D + sign * 2.0 * c / (DM - sign * D * c)
    m = row.roller_material
    E_star = 1.0 / (2.0 * (1.0 - m.nu**2) / m.E_Pa)
    return np.sqrt(q_N / (L / NS) * E_star * inv_R / math.pi)


def test_contact_sets_static_safety_and_iso76_rating():
    """Four contact sets (inner and outer raceway of each diagonal), p0 of each roller's most loaded
    slice as the line-contact closed form (1e-12), s0 = (4.0 GPa/p0_max)² (ISO 76), and C0r against
    ISO 76's printed 44·(1 − D·cos α/d_m)·Z·L·D·cos α (N, mm; i·Z = Z for the two diagonals), whose
    constant is rounded (1.5 %, as for the radial roller rows in test_static_safety.py)."""
    row = _row(0.0, dict(profile="logarithmic"), "alternate", True)
    bearing = Bearing("x", (row,))
    res = solve_load_distribution(bearing, LOADS["combined"])
    sets = contact_sets(bearing, res)
    assert [s.label for s in sets] == ["inner raceway, diagonal +α", "outer raceway, diagonal +α",
                                       "inner raceway, diagonal −α", "outer raceway, diagonal −α"]
    q_max = res.rows[0].slice_load_N.max(axis=1)
    sig = np.where(np.arange(Z) % 2 == 0, 1.0, -1.0)
    for s in sets:
        on = sig == (1.0 if "+α" in s.label else -1.0)
        expected = np.where(on, _line_p0_Pa(q_max, row, s.raceway == "inner"), 0.0)
        assert s.max_pressure_Pa == pytest.approx(expected, rel=1e-12, abs=0.0)
    p0_max = max(s.max_pressure_Pa.max() for s in sets)
    assert static_safety(bearing, res)[0].s0 == pytest.approx((4.0e9 / p0_max) ** 2, rel=1e-12)
    gamma = D * math.cos(ALPHA) / DM
    C0r = 44.0 * (1.0 - gamma) * Z * (L * 1e3) * (D * 1e3) * math.cos(ALPHA)
    assert roller_row_static_rating_N(row) == pytest.approx(C0r, rel=1.5e-2)
    # ISO 76 6.2, double row α ≠ 0: P0r = F_r + 0.44·cot α·F_a
    F_r, F_a = row_forces_N(res, "crossed")
    assert classical_static_safety(row, F_r, abs(F_a)) == pytest.approx(
        roller_row_static_rating_N(row) / (F_r + 0.44 / math.tan(ALPHA) * abs(F_a)), rel=1e-12)


def test_iso76_rating_of_a_steep_crossed_row_is_the_thrust_rating_of_one_diagonal():
    """α0 = 60° (> 45°: a thrust bearing for ISO 76): C0a against ISO 76 8.1's printed
    220·(1 − D·cos α/d_m)·Z·L·D·sin α (N, mm) with Z the rollers loaded in one direction (Z/2, and the
    fewer of the two diagonals for pattern "++-": Z/3 rounded down), 1.5 % (rounded constant); P0a =
    F_a + 2.3·F_r·tan α (ISO 76 8.2)."""
    a = math.radians(60.0)
    gamma = D * math.cos(a) / DM
    for pattern, Z_d in (("alternate", Z // 2), ("++-", Z // 3)):
        row = _row(0.0, {}, pattern, True, a)
        C0a = 220.0 * (1.0 - gamma) * Z_d * (L * 1e3) * (D * 1e3) * math.sin(a)
        assert roller_row_static_rating_N(row) == pytest.approx(C0a, rel=1.5e-2)
        assert classical_static_safety(row, 1.0e4, 5.0e4) == pytest.approx(
            roller_row_static_rating_N(row) / (5.0e4 + 2.3 * 1.0e4 * math.tan(a)), rel=1e-12)


def test_rating_life_of_a_pure_axial_load_per_diagonal():
    """Pure axial load, zero clearance: the +α0 rollers alone carry it, all alike, so each lamina's
    equivalent load over the Z/2 rollers of its diagonal is its own load q_k, and ISO/TS 16281 gives
    L_k = (q_c/q_k)^4, q_c = Q_c·n_s^(−7/9) with Q_c = 552·b_m·(1 ∓ γ)^(29/27)/(1 ± γ)^(1/4)·(D/d_m)^(2/9)
    ·D^(29/27)·L^(7/9)·(Z/2)^(−1/4) (N, mm; γ = D·cos α0/d_m, b_m = 1.1); the row: all laminae of the
    two loaded raceways in series with e = 9/8. Evaluated here, 1e-12 relative."""
    row = _row(0.0, dict(profile="logarithmic"), "alternate", True)
    bearing = Bearing("x", (row,))
    res = solve_load_distribution(bearing, RingLoad(Fz_N=8.0e4))
    q = res.rows[0].slice_load_N[0]  # roller 0 is on +α0
    gamma = D * math.cos(ALPHA) / DM
    inv = 0.0
    for s in (1.0, -1.0):  # inner, outer
        Qc = (552.0 * 1.1 * (1 - s * gamma) ** (29 / 27) / (1 + s * gamma) ** 0.25 * (D / DM) ** (2 / 9)
              * (D * 1e3) ** (29 / 27) * (L * 1e3) ** (7 / 9) * (Z / 2) ** -0.25)
        inv += np.sum(((Qc * NS ** (-7 / 9)) / q) ** (-4 * 9 / 8))
    life = rating_life(bearing, res, "moving")
    assert life.life_Mrev == pytest.approx(inv ** (-8 / 9), rel=1e-12)
    assert life.rows[0].set_labels == ("inner raceway, diagonal +α", "outer raceway, diagonal +α",
                                       "inner raceway, diagonal −α", "outer raceway, diagonal −α")
    assert math.isinf(life.rows[0].set_life_Mrev[2]) and math.isinf(life.rows[0].set_life_Mrev[3])


@pytest.mark.parametrize("kwargs, message", [
    (dict(orientation="crossed", contact_angle_rad=math.pi / 2), "contact_angle must lie in (0, 90) deg"),
    (dict(orientation="crossed", pattern="+*"), "pattern must be 'alternate' or a string"),
    (dict(orientation="radial", contact_angle_rad=0.5), "contact_angle is only used by crossed rows"),
    (dict(orientation="thrust", pattern="+-"), "pattern is only used by crossed rows"),
])
def test_row_checks_name_the_field(kwargs, message):
    with pytest.raises(ValueError, match=re_escape(message)):
        RollerRow("r", Z, D, L, DM, **kwargs)


def re_escape(text: str) -> str:
    import re

    return re.escape(text)


def test_multibody_rows_refuse_crossed_rollers():
    from mbd_core.multibody import ModelBuilder
    from mbd_core.multibody.bearings import add_roller_row

    row = _row(0.0, {}, "alternate", True)
    with pytest.raises(ValueError, match="crossed roller rows are modelled by the quasi-static solver only"):
        add_roller_row(ModelBuilder(), row, None, None)


def test_flexible_model_takes_crossed_rows_sampled_at_the_v_apex():
    """Without flexible rings the flexible-ring solver's slices are the rigid solver's: the same roller
    loads (to the solvers' tolerance, 1e-7 of the largest). A flexible ring's raceway of a crossed
    row is sampled at the apex of its V-groove, (D/2)/cos α0 radially beyond the roller axis (both
    flanks half a roller diameter from it along n± = (cos α0, ±sin α0)); a sample elsewhere — here
    half a roller diameter out, where a radial row's would be — is refused by name."""
    from mbd_core.quasistatic import FlexibleRing, build_flexible_model, solve_flexible_load_distribution
    from tests.test_quasistatic_flexible import circle, random_fields, sampled_body

    row = _row(-10e-6, dict(profile="logarithmic"), "alternate", True)
    bearing = Bearing("x", (row,))
    a = solve_load_distribution(bearing, LOADS["combined"])
    b = solve_flexible_load_distribution(build_flexible_model(bearing), LOADS["combined"])
    assert b.rows[0].load_N == pytest.approx(a.rows[0].load_N, abs=1e-7 * a.rows[0].load_N.max())

    def outer(r_m):
        th, pts = circle((r_m, 0.0), 36)
        body = sampled_body("o", [100.0], {"raceway": (th, pts, *random_fields(np.random.default_rng(1), 36, 1), True)})
        return (FlexibleRing("o", body, "fixed", {"crossed": "raceway"}),)

    with pytest.raises(ValueError, match="row .crossed.: the raceway samples lie .* from the roller axis"):
        build_flexible_model(bearing, outer(0.5 * DM + 0.5 * D))
    model = build_flexible_model(bearing, outer(0.5 * DM + 0.5 * D / math.cos(ALPHA)))
    assert solve_flexible_load_distribution(model, LOADS["combined"]).equilibrium_error <= 1e-9
