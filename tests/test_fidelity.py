"""Fidelity ladders (cases.fidelity): rungs, errors, order of convergence, the choice for a tolerance.

Each expected value is computed by hand in the test from the definitions of ERROR_NAMES (the
reference here is that arithmetic), or is an exact power law whose order is known.
"""

import math

import numpy as np
import pytest

from cases.fidelity import (Knob, Ladder, Outcome, ToleranceError, choose_rung, observed_order, parse_tolerance,
                            rung_errors, rungs, sweep_members)
from cases.slewing import fidelity as slewing_fidelity
from cases.slewing.case import SlewingCase
from cases.slewing.presets import PRESETS
from cases.tradeoff import pareto_front


def _ladder():
    return Ladder((Knob("top.kind", ("rigid", "modal"), "kind"), Knob("top.n_modes", (5, 20, 80), "modes", float)),
                  {"top.kind": "modal", "top.n_modes": 20}, {"top.n_modes": 80},
                  {"cheap": {"top.n_modes": 5}})


def test_rungs_are_base_sweeps_combined_and_a_distinct_reference():
    names = [r.name for r in rungs(_ladder())]
    # base; kind=rigid (kind=modal is the base); n_modes=5 (n_modes=20 is the base); n_modes=80 is the
    # reference's setting, so it is the reference only; "cheap" equals n_modes=5 and is not repeated
    assert names == ["base", "top.kind=rigid", "top.n_modes=5", "reference"]
    ref = rungs(_ladder())[-1]
    assert dict(ref.settings) == {"top.kind": "modal", "top.n_modes": 80}


def test_sweep_members_follow_the_knob_values():
    lad = _ladder()
    members = sweep_members(lad, rungs(lad), lad.knobs[1])
    assert [m.name for m in members] == ["top.n_modes=5", "base"]


def test_ladder_rejects_a_setting_that_is_no_knob():
    with pytest.raises(ValueError, match="no knobs"):
        Ladder((Knob("top.n_modes", (5, 20), "modes"),), {"top.n_modes": 20}, {"top.E_Pa": 1.0})


def test_rung_errors_by_their_definitions():
    ref = Outcome(np.array([100.0, 50.0, 0.0, 20.0]), np.radians([61.0, 60.5, 60.0, 60.2]), 2.0e9)
    rung = Outcome(np.array([110.0, 45.0, 5.0, 0.0]), np.radians([61.5, 60.0, 60.1, 60.0]), 2.1e9)
    e = rung_errors(rung, ref)
    assert e["max_load"] == pytest.approx(0.10, rel=1e-12)           # |110 − 100| / 100
    assert e["load_max"] == pytest.approx(0.20, rel=1e-12)           # |0 − 20| / 100
    assert e["load_rms"] == pytest.approx(math.sqrt((100 + 25 + 25 + 400) / 4) / 100, rel=1e-12)
    assert e["unloaded"] == 0.0                                      # one unloaded in each
    assert e["contact_angle_deg"] == pytest.approx(0.5, abs=1e-9)    # balls loaded in either
    assert e["tau_max"] == pytest.approx(0.05, rel=1e-12)


def test_observed_order_of_an_exact_power_law():
    n = [5.0, 10.0, 20.0, 40.0, 80.0]
    # v = 1 + 3 n^-2 with a constant refinement ratio: successive differences fall as n^-2 exactly
    v = [1.0 + 3.0 * x ** -2 for x in n]
    assert observed_order(n, v) == pytest.approx(2.0, abs=1e-9)
    assert observed_order(n[:2], v[:2]) is None


@pytest.mark.parametrize("text,value", [("1%", 0.01), (" 5 % ".replace(" ", ""), 0.05), ("0.02", 0.02)])
def test_tolerance_parsing(text, value):
    assert parse_tolerance(text) == pytest.approx(value)


@pytest.mark.parametrize("text", ["0", "0%", "100%", "1", "-1%", "nan", "inf", "abc", "%"])
def test_impossible_tolerances_are_refused(text):
    with pytest.raises(ToleranceError, match="--tolerance"):
        parse_tolerance(text)


ROWS = [
    {"rung": "rigid", "wall_s": 0.01, "max_load": 1.9},
    {"rung": "n5", "wall_s": 16.0, "max_load": 0.012},
    {"rung": "base", "wall_s": 21.0, "max_load": 0.008},
    {"rung": "fine", "wall_s": 60.0, "max_load": 0.0004},
    {"rung": "slow-and-poor", "wall_s": 70.0, "max_load": 0.02},
    {"rung": "reference", "wall_s": 90.0, "max_load": 0.0},
]


def test_choice_is_the_fastest_rung_meeting_the_tolerance():
    assert choose_rung(ROWS, 0.01, "max_load")[0]["rung"] == "base"
    assert choose_rung(ROWS, 0.05, "max_load")[0]["rung"] == "n5"
    assert choose_rung(ROWS, 0.001, "max_load")[0]["rung"] == "fine"


def test_a_tolerance_no_rung_meets_names_the_best_one():
    with pytest.raises(ToleranceError, match=r"best is fine with 0\.04 %"):
        choose_rung(ROWS, 1e-4, "max_load")


def test_pareto_front():
    assert pareto_front(ROWS, "max_load") == ["rigid", "n5", "base", "fine"]


@pytest.mark.parametrize("variant", ["1m", "2m", "full"])
@pytest.mark.parametrize("quick", [False, True])
def test_every_slewing_rung_is_a_valid_case_with_its_knob_values(variant, quick):
    """The knobs are keys of the case schema: each rung's case carries exactly the rung's values."""
    case = SlewingCase(geometry=SlewingCase().geometry.__class__(variant=variant))
    lad = slewing_fidelity.ladder(case, quick)
    for r in rungs(lad):
        c = slewing_fidelity.rung_case(case, dict(r.settings))
        for key, value in r.settings.items():
            table, name = key.split(".")
            assert getattr(getattr(c, table), name) == value, (r.name, key)


def test_a_study_that_makes_the_top_modal_cannot_take_a_rigid_rung():
    modal = {"top.kind": "modal", "top.n_modes": 5, "top.groove_harmonics": -1, "top.element_size_m": 0.1}
    case = PRESETS["slewing-combined"]  # sets top.kind itself
    assert slewing_fidelity.rung_overrides(case, {"top.kind": "rigid"}) is None
    assert slewing_fidelity.rung_overrides(case, modal) == {"top": {"n_modes": 5, "groove_harmonics": -1,
                                                                   "element_size_m": 0.1}}
    case = PRESETS["slewing-undulation"]  # auto by default; modal or auto, never rigid
    assert slewing_fidelity.rung_overrides(case, {"top.kind": "rigid"}) is None
    o = slewing_fidelity.rung_overrides(case, modal)
    assert o == {"top": {"kind": "modal", "n_modes": 5, "groove_harmonics": -1, "element_size_m": 0.1}}
    assert case.with_(**o).top.kind == "modal"


def test_the_scene_of_the_undulation_study():
    c = slewing_fidelity.scene(PRESETS["slewing-undulation"])
    assert (c.study.kind, c.undulation.scale, c.top.E_Pa) == ("single", 1.0, 1.5975e9)
