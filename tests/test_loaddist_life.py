"""``flexbearing loaddist --rotating-ring --speed-rpm``: the L10 it reports against the library called directly."""

from __future__ import annotations

import json

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
