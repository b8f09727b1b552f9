"""``flexbearing loaddist --rotating-ring --speed-rpm``: the L10 it reports against the library called directly."""

from __future__ import annotations

import json
import math

import pytest

from cases.cli import main
from cases.loaddist_command import bearing_description
from mbd_core.bearing.distribution_life import rating_life
from mbd_core.quasistatic import RingLoad, solve_load_distribution


def test_cli_life_equals_rating_life_and_hours(capsys):
    # reference: rating_life called directly on an independently solved distribution (rel. 1e-9,
    # same solver, so only rounding); hours from ISO 281 L10h = 10^6·L10/(60·n)
    assert main(["loaddist", "slewing-ring", "--Fz-N", "-2e5", "--rotating-ring", "moving", "--speed-rpm", "5",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    _, desc = bearing_description("slewing-ring")
    life = rating_life(desc.bearing, solve_load_distribution(desc.bearing, RingLoad(Fz_N=-2e5)), "moving")
    got = out["rating_life"]
    assert got["life_Mrev"] == pytest.approx(life.life_Mrev, rel=1e-9)
    assert got["life_h"] == pytest.approx(life.life_Mrev * 1e6 / (60 * 5), rel=1e-9)


def test_without_speed_life_is_not_computed_and_says_why(capsys):
    assert main(["loaddist", "slewing-ring", "--Fz-N", "-2e5", "--json"]) == 0
    life = json.loads(capsys.readouterr().out)["rating_life"]
    assert life["computed"] is False and "--speed-rpm" in life["reason"]


def test_rotating_ring_without_speed_is_one_line(capsys):
    assert main(["loaddist", "--rotating-ring", "moving"]) == 2
    assert "--speed-rpm" in capsys.readouterr().err


THRUST = """[bearing]
name = "thrust test"
[[rows]]
type = "thrust_ball"
name = "balls"
count = 20
ball_diameter_m = 0.02
pitch_diameter_m = 0.2
conformity_inner = 0.53
conformity_outer = 0.53
[load]
spectrum_csv = "spectrum.csv"
"""


def test_cli_spectrum_life_is_palmgren_miner_of_the_equal_ball_loads(tmp_path, capsys):
    """Thrust ball row under centric axial loads: every ball carries Q_i = F_i/Z (α = 90°), so each
    washer's equivalent load is Q_i whatever its exponent; per washer L = 1/Σ t_i·(Q_c/Q_i)^(−3)
    (Palmgren–Miner, ISO 281:2007 9.5) and the bearing (Σ L_w^(−10/9))^(−9/10) (Lundberg–Palmgren,
    e = 10/9). Q_c of each washer from the contact rating (Harris & Kotzalas, Advanced Concepts,
    ch. 8). Tolerance 1e-6: the element loads carry the solver's equilibrium error (≤ 1e-10)."""
    (tmp_path / "spectrum.csv").write_text("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,time_share\n0,0,2e4,0,0,0.25\n0,0,5e4,0,0,0.75\n")
    path = tmp_path / "thrust.toml"
    path.write_text(THRUST)
    assert main(["loaddist", str(path), "--rotating-ring", "moving", "--speed-rpm", "100", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    from mbd_core.bearing.distribution_life import ball_contact_rating_N

    t, Q = [0.25, 0.75], [2e4 / 20, 5e4 / 20]
    lives = []
    for raceway in ("inner", "outer"):
        qc = ball_contact_rating_N(0.02, 0.53, 0.2, math.pi / 2, 20, raceway, 1.3)
        lives.append(1.0 / sum(ti * (qc / qi) ** -3 for ti, qi in zip(t, Q)))
    expected = sum(L ** (-10 / 9) for L in lives) ** (-9 / 10)
    assert got["rating_life"]["life_Mrev"] == pytest.approx(expected, rel=1e-6)
