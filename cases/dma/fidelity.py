"""The DMA bearing's fidelity ladder, beside its case schema: the keys that trade speed for accuracy
in the friction torque of a dynamic run, the scene the ladder measures and what a rung computes.

Knobs (cheap → expensive):

- ``traction.strips``: strips across each contact ellipse, 0 (the centre-point law: no spin, no
  points of pure rolling) … 40;
- ``traction.blend_m_s``: the slip below which the constant and falling laws fade to zero, 1e-3 …
  3e-5 m/s (the report's laws have none: the smaller, the closer to them, and the shorter the
  step the friction slope allows); not a knob of the linear law, which reads none;
- ``analysis.step_factor``: the explicit step as a share of the automatic stable step, 1 … 1/4;
- ``analysis.duration_s``: the simulated time, 0.02 … 0.1 s; the means are taken over its part after
  ``analysis.settle_fraction``, so a longer run averages the start-up out.

Scene: one ``torque`` run at the case's operating point. The ``traction-models`` study is measured
with κ = 0.030, the report's set whose torque depends most on the strips and the blend; the
``speed`` study at its highest speed and thrust. Reference: 40 strips, a blend of 0.01 mm/s (a third
of the sweep's smallest), half the stable step (the step sweep measures what a quarter adds) and
0.1 s; the quick ladder's: 20 strips, 0.03 mm/s, half the step, 0.02 s.

What a rung computes (:func:`measure`): the mean friction torque per ball on the inner and the outer
race (the family's primary quantity: the larger of the two relative errors), each ball's mean
outer-race contact load, and the run's own estimate of its time-step error in the race torques
(:func:`.torque.run_torque`), which the ladder compares with the step sweep.
"""

from __future__ import annotations

import numpy as np

from ..fidelity import Knob, Ladder, Outcome, case_tables, fixed_knob
from .case import DmaCase
from .studies import TRACTION_MODELS
from .torque import run_torque

__all__ = ["ladder", "scene", "measure", "rung_case", "describe", "rung_overrides", "element_columns", "LOADS_FILE",
           "WARM_REPEAT"]

#: the traction set the traction-models study is measured with (module docstring)
MODELS_SCENE = "κ = 0.03"
#: the reference's blend speed, m/s (full ladder, quick ladder): below the sweep's smallest
REFERENCE_BLEND_M_S = {False: 1e-5, True: 3e-5}
#: a ball counts as unloaded below this share of the mean ball load
UNLOADED_SHARE = 0.01
#: nothing is meshed or reduced: a second, warm run would measure the same time again
WARM_REPEAT = False
LOADS_FILE = "ball_loads.csv"
_ERRORS = ("race_torque", "max_load", "load_max", "load_rms", "unloaded")


def ladder(case: DmaCase, quick: bool = False) -> Ladder:
    """The ladder of ``case`` (module docstring; ``quick``: 0 or 10 strips, two blends, the stable
    step or half of it, 0.02 s)."""
    blended = scene(case).traction.model != "linear"
    strips = Knob("traction.strips", (0, 10) if quick else (0, 5, 10, 20, 40), "strips across the contact ellipse",
                  lambda n: n + 1.0, "strips + 1")
    blends = (1e-3, 1e-4) if quick else (1e-3, 1e-4, 3e-5)
    blend = Knob("traction.blend_m_s", blends, "traction blend speed (m/s)", lambda v: 1.0 / v,
                 "1 / blend speed (s/m)")
    step = Knob("analysis.step_factor", (1.0, 0.5) if quick else (1.0, 0.5, 0.25), "share of the stable step",
                lambda f: 1.0 / f, "1 / step factor")
    duration = (fixed_knob("analysis.duration_s", 0.02, "simulated time (s)") if quick else
                Knob("analysis.duration_s", (0.02, 0.05, 0.1), "simulated time (s)", float, "simulated time (s)"))
    knobs = [strips, *([blend] if blended else []), step, duration]
    base = {"traction.strips": 10 if quick else 20, "analysis.step_factor": 1.0,
            "analysis.duration_s": 0.02 if quick else 0.05, **({"traction.blend_m_s": 1e-4} if blended else {})}
    reference = {"traction.strips": 20 if quick else 40, "analysis.step_factor": 0.5,
                 "analysis.duration_s": 0.02 if quick else 0.1,
                 **({"traction.blend_m_s": REFERENCE_BLEND_M_S[quick]} if blended else {})}
    combined = {} if quick else {"centre-point": {"traction.strips": 0, "analysis.duration_s": 0.02},
                                 "fine": {"traction.strips": 40, "analysis.duration_s": 0.1,
                                          **({"traction.blend_m_s": 3e-5} if blended else {})}}
    return Ladder(tuple(knobs), base, reference, combined, primary="race_torque",
                  primary_label="mean race friction torque", scene="one torque run: " + describe_scene(case),
                  errors=_ERRORS, estimates={"estimated_step_error": "analysis.step_factor"},
                  primary_figure=("race_torque", "inner"))


def _scene_values(case: DmaCase) -> dict:
    values = {"study": {"kind": "torque"}}
    if case.study.kind == "traction-models":
        values["traction"] = dict(TRACTION_MODELS[MODELS_SCENE])
    if case.study.kind == "speed":
        values["operation"] = {"thrust_N": max(case.study.loads_N), "outer_speed_rpm": max(case.study.speeds_rpm)}
    return values


def scene(case: DmaCase) -> DmaCase:
    """The single torque run the ladder measures (module docstring), before the rung's knobs."""
    return case.with_(**_scene_values(case))


def describe_scene(case: DmaCase) -> str:
    c = scene(case)
    return (f"{c.operation.thrust_N:g} N thrust, {c.operation.outer_speed_rpm:g} rev/min of the outer race, "
            f"traction {c.traction.label}")


def rung_case(case: DmaCase, settings: dict) -> DmaCase:
    """``case``'s scene with the rung's knob values (dotted keys → values)."""
    return scene(case).with_(**case_tables(settings))


def measure(case: DmaCase) -> Outcome:
    """Mean race torques per ball and the balls' mean contact loads of one run of ``case``."""
    run = run_torque(case)
    figures = {"race_torque": {"inner": run.mean_per_ball("inner"), "outer": run.mean_per_ball("outer")}}
    return Outcome(np.asarray(run.ball_load_N, float), unloaded_share=UNLOADED_SHARE, figures=figures,
                   estimates={"estimated_step_error": run.step_error["race_torque"]})


def element_columns(case: DmaCase, n: int) -> tuple[list[str], list[tuple]]:
    """The column that names the ``n`` balls in :data:`LOADS_FILE`."""
    if n != case.bearing.n_balls:
        raise ValueError(f"the DMA bearing has {case.bearing.n_balls} balls, the ladder measured {n}")
    return ["ball"], [(k + 1,) for k in range(n)]


def describe(settings: dict) -> str:
    """A rung in words, as a user would set it."""
    strips = settings["traction.strips"]
    text = "centre-point traction" if strips == 0 else f"traction over {strips} strips"
    if "traction.blend_m_s" in settings:
        text += f", blend {1e3 * settings['traction.blend_m_s']:g} mm/s"
    return f"{text}, step ×{settings['analysis.step_factor']:g}, {settings['analysis.duration_s']:g} s"


def rung_overrides(case: DmaCase, settings: dict) -> dict:
    """The table overrides that run ``case`` (its own study, loads and speeds) at a rung's fidelity."""
    return case_tables(settings)
