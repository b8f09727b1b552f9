"""DG03 case-depth life factor in ``flexbearing loaddist`` (``case_depth_m`` and a core strength per row).

The reference factor is computed in the test independently of :mod:`mbd_core.contact.subsurface`
(Thomas & Hoersch's closed form): the stresses on the contact axis are integrated numerically from
Boussinesq's point-load solution over the Hertz pressure p0·sqrt(1 − x²/a² − y²/b²) (Johnson,
*Contact Mechanics*, 1985, eq. 3.20), then τ_max = half the spread of the principal stresses
σ_xx, σ_yy, σ_zz at z = 1.1·h, τ_f = 0.6·0.425·UTS and A_cd = min(τ_f/τ_max, 1) (Harris,
Rumbarger & Butterfield, NREL DG03, 2009).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from cases.bearing_file import loads_bearing
from cases.cli import main
from cases.config import CaseError
from mbd_core.bearing.distribution_life import rating_life
from mbd_core.quasistatic import solve_load_distribution
from mbd_core.quasistatic.contacts import contact_sets

UTS_PA, CASE_DEPTH_M = 9.0e8, 2.0e-3

BALLS = """[bearing]
name = "case depth test"
[[rows]]
type = "four_point"
name = "balls"
count = 80
ball_diameter_m = 0.05
pitch_diameter_m = 2.5
conformity_inner = 0.53
conformity_outer = 0.53
{extra}
[load]
Fz_N = -3.0e5
My_Nm = 1.2e6
"""


def _boussinesq_axis_stresses(p0, a, b, z, nu, n_u=96, n_t=256):
    """(σ_xx, σ_yy, σ_zz) at depth z below the centre of an elliptical Hertz pressure, Pa.

    Boussinesq's point load P at horizontal distance r (Johnson, eq. 3.20; R² = r² + z²):
    σ_r = P/2π·[(1 − 2ν)/(R(R + z)) − 3z r²/R⁵], σ_θ = −P/2π·(1 − 2ν)·[1/(R(R + z)) − z/R³],
    σ_z = −3P z³/(2π R⁵), with (1 − z/R)/r² written as 1/(R(R + z)); σ_xx = σ_r cos²φ + σ_θ sin²φ.
    Over the ellipse x = a·sin u·cos t, y = b·sin u·sin t the load p·dA = p0·a·b·sin u·cos²u du dt
    is smooth: Gauss–Legendre in u, the trapezoid rule in the periodic t. Doubling both point
    counts changes the result by < 1e-13 (checked when the test was written)."""
    xg, wg = np.polynomial.legendre.leggauss(n_u)
    u, wu = 0.25 * math.pi * (xg + 1.0), 0.25 * math.pi * wg
    t = 2.0 * math.pi * np.arange(n_t) / n_t
    U, T = np.meshgrid(u, t, indexing="ij")
    dP = p0 * a * b * np.sin(U) * np.cos(U) ** 2 * wu[:, None] * (2.0 * math.pi / n_t)
    x, y = a * np.sin(U) * np.cos(T), b * np.sin(U) * np.sin(T)
    r2 = x * x + y * y
    R = np.sqrt(r2 + z * z)
    g = 1.0 / (R * (R + z))
    s_r = dP / (2 * math.pi) * ((1 - 2 * nu) * g - 3 * z * r2 / R**5)
    s_t = -dP / (2 * math.pi) * (1 - 2 * nu) * (g - z / R**3)
    s_z = -3 * dP * z**3 / (2 * math.pi * R**5)
    c2, s2 = x * x / r2, y * y / r2
    return float((s_r * c2 + s_t * s2).sum()), float((s_r * s2 + s_t * c2).sum()), float(s_z.sum())


def _tresca(stresses) -> float:
    return 0.5 * (max(stresses) - min(stresses))


def test_boussinesq_integration_reproduces_the_axisymmetric_closed_form():
    # the test's own integrator against Johnson eq. 3.45 (circular contact), 1e-10
    p0, a, nu = 2.0e9, 2.0e-3, 0.3
    for z in (0.5e-3, 1.0e-3, 3.0e-3):
        c = z / a
        s_r = -p0 * ((1 + nu) * (1 - c * math.atan(1 / c)) - 0.5 / (1 + c * c))
        s_z = -p0 / (1 + c * c)
        got = _boussinesq_axis_stresses(p0, a, a, z, nu)
        assert got == pytest.approx((s_r, s_r, s_z), rel=1e-10)


def _life(tmp_path, capsys, text: str, *extra) -> dict:
    path = tmp_path / "b.toml"
    path.write_text(text)
    assert main(["loaddist", str(path), "--rotating-ring", "moving", "--speed-rpm", "5", "--json", *extra]) == 0
    return json.loads(capsys.readouterr().out)["rating_life"]


def _most_loaded(bearing, dists):
    """(p0, a, b, set label, element, case) of the highest p0 of all contact sets and cases."""
    return max(((float(s.max_pressure_Pa[i]), float(s.semi_major_m[i]), float(s.semi_minor_m[i]), s.label, i, k)
                for k, d in enumerate(dists) for s in contact_sets(bearing, d) for i in range(len(s.load_N))),
               key=lambda c: c[0])


@pytest.mark.parametrize("case_depth_m", [CASE_DEPTH_M, 0.02])
def test_ball_row_factor_against_boussinesq_and_corrected_life(tmp_path, capsys, case_depth_m):
    # reference: the most loaded contact of the independently solved distribution, τ_max(1.1 h)
    # from the Boussinesq integration above, τ_f = 0.6·0.425·UTS (DG03). Tolerance 1e-9: the two
    # stress computations agree to ~1e-13 (integration converged) and the distribution is the
    # same solver's. At h = 2 mm A_cd < 1; at 20 mm the cap at 1 applies.
    text = BALLS.format(extra=f"case_depth_m = {case_depth_m}\ncore_uts_Pa = {UTS_PA}")
    life = _life(tmp_path, capsys, text)
    desc = loads_bearing(text)
    dist = solve_load_distribution(desc.bearing, desc.default_load)
    p0, a, b, label, element, _ = _most_loaded(desc.bearing, [dist])
    tau_c = _tresca(_boussinesq_axis_stresses(p0, a, b, 1.1 * case_depth_m, desc.bearing.rows[0].race_material.nu))
    tau_f = 0.6 * 0.425 * UTS_PA
    expected = min(tau_f / tau_c, 1.0)
    row = life["rows"][0]
    cd = row["case_depth"]
    assert (cd["contact"], cd["element"]) == (label, element + 1)
    assert cd["p0_MPa"] == pytest.approx(p0 / 1e6, rel=1e-12)
    assert cd["shear_at_check_depth_MPa"] == pytest.approx(tau_c / 1e6, rel=1e-9)
    assert cd["core_shear_fatigue_MPa"] == pytest.approx(tau_f / 1e6, rel=1e-12)
    assert cd["factor"] == pytest.approx(expected, rel=1e-9)
    assert (expected < 0.9) == (case_depth_m == CASE_DEPTH_M)
    # L10 from the library on the same distribution (1e-9); the corrected life is A_cd·L10 (1e-12),
    # for a one-row bearing also the bearing's
    assert row["life_Mrev"] == pytest.approx(rating_life(desc.bearing, dist, "moving").life_Mrev, rel=1e-9)
    assert row["life_cd_Mrev"] == pytest.approx(cd["factor"] * row["life_Mrev"], rel=1e-12)
    assert life["life_cd_Mrev"] == pytest.approx(cd["factor"] * life["life_Mrev"], rel=1e-12)
    assert row["life_cd_h"] == pytest.approx(row["life_cd_Mrev"] * 1e6 / (60 * 5), rel=1e-12)


def test_without_case_depth_the_life_has_no_case_depth_fields(tmp_path, capsys):
    life = _life(tmp_path, capsys, BALLS.format(extra=""))
    assert "life_cd_Mrev" not in life and "life_cd_h" not in life
    assert all(set(r) == {"row", "life_Mrev", "deciding", "contact_sets", "life_h"} for r in life["rows"])


def test_printed_lines_give_the_factor_and_the_corrected_life(tmp_path, capsys):
    life = _life(tmp_path, capsys, BALLS.format(extra=f"case_depth_m = {CASE_DEPTH_M}\ncore_yield_Pa = 7e8"))
    path = tmp_path / "b.toml"
    assert main(["loaddist", str(path), "--rotating-ring", "moving", "--speed-rpm", "5"]) == 0
    out = capsys.readouterr().out
    row = life["rows"][0]
    assert f"A_cd = {row['case_depth']['factor']:.3g}" in out
    assert f"L10·A_cd = {row['life_cd_Mrev']:.4g} Mrev" in out
    assert f"bearing: L10·A_cd = {life['life_cd_Mrev']:.4g} Mrev" in out


def test_spectrum_takes_the_most_loaded_contact_of_all_cases(tmp_path, capsys):
    # the case of the highest p0 decides; its factor is the one-load factor of that case (1e-12)
    (tmp_path / "s.csv").write_text("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,time_share\n0,0,-3e5,0,1.2e6,0.7\n"
                                    "0,0,-3e5,0,2.0e6,0.3\n")
    extra = f"case_depth_m = {CASE_DEPTH_M}\ncore_shear_yield_Pa = 4e8"
    spectrum = BALLS.format(extra=extra).replace("Fz_N = -3.0e5\nMy_Nm = 1.2e6", 'spectrum_csv = "s.csv"')
    cd = _life(tmp_path, capsys, spectrum)["rows"][0]["case_depth"]
    assert cd["load_case"] == 2
    one = _life(tmp_path, capsys, BALLS.format(extra=extra).replace("1.2e6", "2.0e6"))["rows"][0]["case_depth"]
    assert cd["factor"] == pytest.approx(one["factor"], rel=1e-12) and one["factor"] < 1.0


ROLLERS = """[bearing]
name = "thrust rollers"
[[rows]]
type = "thrust_roller"
name = "rollers"
count = 40
roller_diameter_m = 0.03
roller_length_m = 0.04
pitch_diameter_m = 0.6
case_depth_m = 1.0e-3
core_uts_Pa = 9e8
[load]
Fz_N = 4.0e6
"""


def _flamant_axis_stresses(p0, b, z, n=200):
    """(σ_x, σ_z) at depth z below the centre of a Hertz line pressure p0·sqrt(1 − x²/b²), Pa.

    Flamant's line load P per length at horizontal distance x (Johnson, eq. 2.15, in Cartesian form;
    r² = x² + z²): σ_x = −2P x² z/(π r⁴), σ_z = −2P z³/(π r⁴); x = b·sin u makes p·dx =
    p0·b·cos²u du smooth, integrated by Gauss–Legendre (200 points: converged to < 1e-13)."""
    xg, wg = np.polynomial.legendre.leggauss(n)
    u, wu = 0.5 * math.pi * xg, 0.5 * math.pi * wg
    x = b * np.sin(u)
    dP = p0 * b * np.cos(u) ** 2 * wu
    r4 = (x * x + z * z) ** 2
    return float((-2 * dP * x * x * z / (math.pi * r4)).sum()), float((-2 * dP * z**3 / (math.pi * r4)).sum())


def test_roller_row_factor_against_the_line_contact(tmp_path, capsys):
    # Reference: the plane-strain line contact's stresses integrated from Flamant's solution in the
    # test, σ_y = ν(σ_x + σ_z) (plane strain), at 1.1·h below the most loaded slice (p0, b).
    # Tolerance 1e-9: McEwen's closed form the library uses and the integration agree to ~1e-13.
    life = _life(tmp_path, capsys, ROLLERS)
    desc = loads_bearing(ROLLERS)
    dist = solve_load_distribution(desc.bearing, desc.default_load)
    p0, _, b, label, element, _ = _most_loaded(desc.bearing, [dist])
    nu = desc.bearing.rows[0].race_material.nu
    s_x, s_z = _flamant_axis_stresses(p0, b, 1.1e-3)
    tau_c = _tresca((s_x, nu * (s_x + s_z), s_z))
    expected = min(0.6 * 0.425 * 9e8 / tau_c, 1.0)
    row = life["rows"][0]
    cd = row["case_depth"]
    assert 0.5 * b < 1.1e-3 < 5 * b and expected < 1.0
    assert cd["shear_at_check_depth_MPa"] == pytest.approx(tau_c / 1e6, rel=1e-9)
    assert cd["factor"] == pytest.approx(expected, rel=1e-9)
    assert cd["a_mm"] is None and cd["b_mm"] == pytest.approx(b * 1e3, rel=1e-12)
    assert row["life_cd_Mrev"] == pytest.approx(cd["factor"] * row["life_Mrev"], rel=1e-12)


@pytest.mark.parametrize("extra, prefix", [
    ("core_uts_Pa = 9e8", "rows[0].core_uts_Pa: "),
    ("core_yield_Pa = 7e8", "rows[0].core_yield_Pa: "),
    ("case_depth_m = 0.002", "rows[0].case_depth_m: "),
    ("case_depth_m = 0.002\ncore_uts_Pa = 9e8\ncore_yield_Pa = 7e8", "rows[0].core_yield_Pa: "),
    ("case_depth_m = -0.002\ncore_uts_Pa = 9e8", "rows[0].case_depth_m: "),
    ("case_depth_m = 0.002\ncore_shear_yield_Pa = 0", "rows[0].core_shear_yield_Pa: "),
    ("case_depth_m = 0.002\ncore_uts_Pa = 5e-324", "rows[0].core_uts_Pa: too small"),
    ("case_depth_m = 0.05\ncore_uts_Pa = 9e8", "rows[0].case_depth_m: must be smaller than ball_diameter_m"),
])
def test_case_depth_key_errors_name_the_key(extra, prefix):
    with pytest.raises(CaseError) as exc:
        loads_bearing(BALLS.format(extra=extra))
    assert str(exc.value).startswith(prefix) and "\n" not in str(exc.value)


def test_roller_rows_take_the_keys_and_double_rows_give_both_rows():
    assert set(loads_bearing(ROLLERS).case_depths) == {"rollers"}
    double = BALLS.format(extra="case_depth_m = 0.002\ncore_uts_Pa = 9e8\nrow_spacing_m = 0.1").replace(
        '"four_point"', '"double_four_point"')
    cds = loads_bearing(double).case_depths
    assert set(cds) == {"balls (1)", "balls (2)"}
    assert cds["balls (1)"].core_shear_fatigue_Pa == pytest.approx(0.6 * 0.425 * 9e8, rel=1e-12)


def test_line_contact_shear_peak_is_johnsons():
    # published: below a line contact τ_max peaks at 0.300·p0 at z = 0.786·b (Johnson, Contact
    # Mechanics, §4.2, Fig. 4.6); printed to 3 digits, tolerance 2e-3
    from mbd_core.contact.subsurface import line_max_shear_profile_Pa

    z = np.linspace(0.5, 1.1, 6001)
    tau = line_max_shear_profile_Pa(1.0, 1.0, z, 0.3)
    assert tau.max() == pytest.approx(0.300, abs=2e-3)
    assert z[np.argmax(tau)] == pytest.approx(0.786, abs=2e-3)
