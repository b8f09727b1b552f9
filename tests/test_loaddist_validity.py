"""Results outside the load-distribution model's validity carry warnings (ISO 76 pressure limits,
ring displacement, groove edge), in the result, its summary dict and the printed table.

The contact pressures of the references are computed here independently: point contacts with the
Hamrock–Brewe closed forms (Hamrock & Brewe, J. Lubr. Technol. 105 (1983) 171–177; within ~3 % of
the exact elliptic integrals), line contacts with Johnson's p0 = (P·E*/(π·R))^½ (*Contact
Mechanics*, 1985, eq. 4.45). Loads are chosen ≥ 20 % away from the limits in p0.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cases.catalog import slewing_ring, three_row_roller
from cases.cli import main
from cases.report import load_distribution_table
from mbd_core.contact.limits import groove_edge_warning
from mbd_core.quasistatic import Bearing, RingLoad, RollerRow, solve_load_distribution

E_STEEL, NU_STEEL = 207e9, 0.29  # BEARING_STEEL
E_STAR = E_STEEL / (2 * (1 - NU_STEEL**2))  # Johnson's E*, two equal steels


def p0_ball_hamrock_brewe(Q: float, D: float, f: float, dm: float, alpha: float) -> float:
    """p0 of a ball on an inner groove (convex in rolling), Hamrock–Brewe: k = 1.0339 (Ry/Rx)^0.636,
    E ≈ 1.0003 + 0.5968 Rx/Ry, a, b from 6 k² E Q R/(π E'), p0 = 3Q/(2π a b)."""
    g = D * math.cos(alpha) / dm
    rx = 2 / D + 2 / D * g / (1 - g)  # rolling direction
    ry = 2 / D - 1 / (f * D)  # across the groove
    Rx, Ry = 1 / rx, 1 / ry
    R = 1 / (rx + ry)
    k = 1.0339 * (Ry / Rx) ** 0.636
    E = 1.0003 + 0.5968 * Rx / Ry
    Ep = 2 * E_STAR
    a = (6 * k * k * E * Q * R / (math.pi * Ep)) ** (1 / 3)
    b = (6 * E * Q * R / (math.pi * k * Ep)) ** (1 / 3)
    return 1.5 * Q / (math.pi * a * b)


def p0_roller_johnson(Q_slice: float, slice_length: float, D: float, raceway_d: float) -> float:
    R = 1 / (2 / D + 2 / raceway_d)
    return math.sqrt(Q_slice / slice_length * E_STAR / (math.pi * R))


def _ball_p0(case, res) -> float:
    row, r = case.bearing.rows[0], res.rows[0]
    i = int(np.argmax(r.load_N))
    return p0_ball_hamrock_brewe(r.load_N[i], row.ball_diameter_m, row.conformity_moving, row.pitch_diameter_m,
                                 row.contact_angle_rad)


def test_slewing_ring_pressure_warning_iff_above_iso76():
    """The dead load (p0 well below 4.2 GPa) has no warning; a load scaled to p0 ≈ 5 GPa names the
    ISO 76 limit, in the result, its summary dict and the printed table."""
    case = slewing_ring("full")
    res = solve_load_distribution(case.bearing, case.default_load)
    p0 = _ball_p0(case, res)
    assert p0 < 0.8 * 4.2e9 and res.warnings == ()
    heavy = RingLoad(Fz_N=case.default_load.Fz_N * (5.0e9 / p0) ** 3)
    res2 = solve_load_distribution(case.bearing, heavy)
    assert _ball_p0(case, res2) > 1.15 * 4.2e9
    assert any("ISO 76" in w and "4.2 GPa" in w for w in res2.warnings)
    assert res2.to_dict()["warnings"] == list(res2.warnings)
    assert "WARNING" in load_distribution_table(res2) and "ISO 76" in load_distribution_table(res2)


def test_roller_pressure_warning_iff_above_iso76():
    """Three-row roller under a thrust per roller giving p0 ≈ 3 GPa (none) and ≈ 5 GPa (warning)."""
    case = three_row_roller()
    row = case.bearing.rows[1]
    ls = row.roller_length_m / row.n_slices
    for p0_target, warned in ((3.0e9, False), (5.0e9, True)):
        q_slice = (p0_target / math.sqrt(E_STAR / (math.pi * row.roller_diameter_m / 2) / ls)) ** 2
        res = solve_load_distribution(case.bearing, RingLoad(Fz_N=q_slice * row.n_slices * row.n_rollers))
        p0 = p0_roller_johnson(res.row("front thrust").slice_load_N.max(), ls, row.roller_diameter_m, math.inf)
        assert p0 == pytest.approx(p0_target, rel=1e-6)
        assert any("ISO 76" in w and "4 GPa" in w for w in res.warnings) == warned


@pytest.mark.parametrize("gap_m, warned", [(1e-3, False), (3e-3, True)])
def test_displacement_warning(gap_m, warned):
    """A ring displacement beyond a quarter of the roller diameter (2.5 mm here) is flagged."""
    b = Bearing("r", (RollerRow("rollers", 20, 10e-3, 10e-3, 0.25, "radial", 1, gap_m=gap_m, n_slices=5),))
    res = solve_load_distribution(b, RingLoad(Fx_N=1e3))
    assert (res.displacement[0] > 2.5e-3) == warned
    assert any("displacement" in w for w in res.warnings) == warned


def test_groove_edge_warning_geometry():
    """The ellipse spans ±a/(f·D) on the groove (arc length over groove radius): at α = 80° with
    a = 2 mm on a 10 mm groove it spans ±11.46° and passes 90°; at α = 60° it does not."""
    assert groove_edge_warning(2e-3, 10e-3, math.radians(80), 0.0, math.pi / 2) is not None
    assert groove_edge_warning(2e-3, 10e-3, math.radians(60), 0.0, math.pi / 2) is None
    assert "11.5°" in groove_edge_warning(2e-3, 10e-3, math.radians(80), 0.0, math.pi / 2)


def test_hertz_report_warns_above_the_limit(capsys):
    """`hertz ball … --load-N 1e300` printed absurd numbers silently: now such a load is refused
    naming the option, and a load inside the accepted range but far beyond the model (1e9 N) gives
    a report with the pressure warning (p0 ∝ Q^(1/3) far above 4.2 GPa) and the groove-edge warning."""
    args = ["hertz", "ball", "--ball-diameter-mm", "95.25", "--conformity", "0.525", "--pitch-diameter-mm", "6690",
            "--contact-angle-deg", "60", "--load-N"]
    assert main(args + ["1e300"]) == 2
    assert "--load-N" in capsys.readouterr().err
    assert main(args + ["1e9"]) == 0
    out = capsys.readouterr().out
    assert "ISO 76" in out and "groove edge" in out
    assert main(args + ["1e4"]) == 0  # p0 ≈ 1.6 GPa (thesis Table 8 order): no warning
    assert "WARNING" not in capsys.readouterr().out
