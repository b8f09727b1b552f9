"""The wind main bearing's fidelity ladder, beside its case schema: which keys trade speed for
accuracy in a dynamic run, the short window the ladder measures, and what a rung computes.

Knobs (cheap → expensive):

- ``bodies.rings``, ``bodies.cages``: rigid, modal;
- ``bodies.n_modes``: free–free (inner ring, cages) or bolted (outer ring) modes per body, 8 … 40;
- ``rollers.n_slices``: slices per roller, 5 … 20;
- ``analysis.step_factor``: the explicit step as a share of the automatic stable step, 1 … 1/4;
- ``contact.v_static_m_s``: the friction law's transition speed (μ_static reached at v_static,
  μ_dynamic from 2·v_static on), 0.3 … 0.03 m/s: the smaller, the closer to Coulomb friction;
- ``contact.implicit_friction``: on (the friction of rollers and rigid cages integrated
  implicitly, a 5–6× longer step), off (explicit friction at the step its slope allows).

The full ladder's sweeps vary around modal rings (20 modes) and rigid cages, since rigid rings
are the one knob that changes the largest roller load by tens of per cent; the quick ladder's
around rigid rings (its modal rungs are the slow ones).

Scene: the case's run with its load case ``loads.case_index`` held constant (a study that sweeps
speeds takes its highest, one that sweeps friction its highest pair), over a short window: the
first ``settle`` seconds (the modes swinging up from the rigid start) are left out of the figures.
The mesh sizes, bolts and the modal damping are the case's (the quick ladder: the coarse meshes of
the ``wind-rigid-flexible`` quick preset). Reference: modal rings and cages with 40 modes, 20
slices, a quarter of the automatic step and the lowest transition speed, implicit friction: the
finest model whose window the machine runs in minutes. Explicit friction is a knob of its own,
measured at the base (its step is set by the friction law's slope, 5–6× below the implicit one).

What a rung computes (:func:`measure`): per roller (radial row, then front and rear thrust rows)
its raceway load averaged over the window after settling; per row the mean spin of the loaded
rollers, the mean cage speed, the mean and the peak roller–pocket force; per modal ring its peak
von Mises stress; and its own estimates of the time-step and slicing errors of the largest roller
load (:func:`.dynamic.step_error`, :func:`.dynamic.slice_error`), which the ladder compares with the
errors along the step and slice sweeps.
"""

from __future__ import annotations

import numpy as np

from ..fidelity import Knob, Ladder, Outcome, case_tables, fixed_knob
from . import dynamic
from .bodies import peak_stresses
from .case import WindCase

__all__ = ["ladder", "scene", "measure", "rung_case", "describe", "rung_overrides", "element_columns", "LOADS_FILE",
           "WARM_REPEAT"]

#: simulated window and the settling left out of it, s (full ladder, quick ladder)
WINDOW_S = {False: (0.2, 0.1), True: (0.06, 0.03)}
#: coarse meshes, modes and bolts of the quick ladder (those of the wind-rigid-flexible quick preset)
QUICK_BODIES = {"bodies.n_modes": 8, "bodies.bolts": 24, "bodies.ring_element_size_m": 0.18,
                "bodies.cage_element_size_m": 0.05}
#: samples of the record: one every this many steps at step_factor 1 (more at smaller steps, so
#: that every rung samples the same instants)
RECORD_EVERY = 20
#: a roller counts as unloaded below this share of the mean roller load
UNLOADED_SHARE = 0.01
#: the dynamic rungs are not measured a second time warm: a rung's cold wall time holds its
#: meshing and reduction, which ``warm`` would only subtract
WARM_REPEAT = False
LOADS_FILE = "roller_loads.csv"

_ERRORS = ("max_load", "load_max", "load_rms", "unloaded", "roller_speed", "cage_speed", "cage_force_mean",
           "cage_force_peak", "ring_von_mises")


def ladder(case: WindCase, quick: bool = False) -> Ladder:
    """The ladder of ``case`` (``quick``: rigid or modal rings at 8 modes on coarse meshes, 5 or 10
    slices, two steps, two transition speeds, implicit or explicit friction, over 0.06 s)."""
    duration, settle = WINDOW_S[quick]
    adams = case.contact.preset == "adams"
    if quick:
        modal = {"bodies.rings": "modal"}
        knobs = [Knob("bodies.rings", ("rigid", "modal"), "rings"),
                 fixed_knob("bodies.cages", "rigid", "cages"),
                 *(fixed_knob(k, v, k.split(".")[1]) for k, v in QUICK_BODIES.items()),
                 Knob("rollers.n_slices", (5, 10), "slices per roller", float, "slices per roller"),
                 Knob("analysis.step_factor", (1.0,) if adams else (1.0, 0.5), "share of the stable step",
                      lambda f: 1.0 / f, "1 / step factor"),
                 Knob("contact.v_static_m_s", (0.3, 0.1), "friction transition speed (m/s)", lambda v: 1.0 / v,
                      "1 / transition speed (s/m)", implies={v: {"contact.v_dynamic_m_s": 2 * v} for v in (0.3, 0.1)}),
                 fixed_knob("contact.v_dynamic_m_s", 0.6, "friction: μ_dynamic from (m/s)"),
                 Knob("contact.implicit_friction", (True, False), "implicit friction")]
        base = {"bodies.rings": "rigid", **{k.key: k.values[0] for k in knobs if k.key != "bodies.rings"}}
        reference = {**modal, "rollers.n_slices": 10, "analysis.step_factor": 1.0 if adams else 0.5,
                     "contact.v_static_m_s": 0.1, "contact.v_dynamic_m_s": 0.2}
        combined = {}
    else:
        b = case.bodies
        modal = {"bodies.rings": "modal", "bodies.cages": "modal"}
        speeds = (0.3, 0.1, 0.03)
        knobs = [Knob("bodies.rings", ("rigid", "modal"), "rings"),
                 Knob("bodies.cages", ("rigid", "modal"), "cages"),
                 Knob("bodies.n_modes", (8, 20, 40), "modes per body", float, "modes n"),
                 fixed_knob("bodies.bolts", b.bolts, "bolts"),
                 fixed_knob("bodies.ring_element_size_m", b.ring_element_size_m, "ring element size (m)"),
                 fixed_knob("bodies.cage_element_size_m", b.cage_element_size_m, "cage element size (m)"),
                 Knob("rollers.n_slices", (5, 10, 20), "slices per roller", float, "slices per roller"),
                 Knob("analysis.step_factor", (1.0,) if adams else (1.0, 0.5, 0.25), "share of the stable step",
                      lambda f: 1.0 / f, "1 / step factor"),
                 Knob("contact.v_static_m_s", speeds, "friction transition speed (m/s)", lambda v: 1.0 / v,
                      "1 / transition speed (s/m)", implies={v: {"contact.v_dynamic_m_s": 2 * v} for v in speeds}),
                 fixed_knob("contact.v_dynamic_m_s", 0.6, "friction: μ_dynamic from (m/s)"),
                 Knob("contact.implicit_friction", (True, False), "implicit friction")]
        # the sweeps vary around modal rings: the rigid rings' error dwarfs every other knob's
        base = {"bodies.rings": "modal", "bodies.cages": "rigid", "bodies.n_modes": 20,
                **{k.key: k.values[0] for k in knobs if len(k.values) == 1},
                "rollers.n_slices": 10, "analysis.step_factor": 1.0, "contact.v_static_m_s": 0.3,
                "contact.implicit_friction": True}
        combined = {"rigid-fine-step": {"bodies.rings": "rigid", "analysis.step_factor": 0.25},
                    "flexible-fine": {**modal, "bodies.n_modes": 40, "rollers.n_slices": 20}}
        reference = {**modal, "bodies.n_modes": 40, "rollers.n_slices": 20,
                     "analysis.step_factor": 1.0 if adams else 0.25, "contact.v_static_m_s": 0.03,
                     "contact.v_dynamic_m_s": 0.06}
    knobs = [*knobs, fixed_knob("analysis.duration_s", duration, "simulated window (s)"),
             fixed_knob("analysis.settle_s", settle, "settling left out (s)")]
    base.update({"analysis.duration_s": duration, "analysis.settle_s": settle})
    return Ladder(tuple(knobs), base, reference, combined, primary="max_load",
                  primary_label="largest roller load (mean over the window)",
                  scene="a dynamic window: " + describe_scene(case), errors=_ERRORS,
                  estimates={"estimated_step_error": "analysis.step_factor", "estimated_slice_error": "rollers.n_slices"})


def _scene_values(case: WindCase) -> dict:
    """The case tables that make the ladder's single run."""
    kind = case.study.kind
    if kind in ("static", "load-case"):
        raise ValueError(f"tradeoff: the wind {kind} study is quasi-static with rigid rings and has no fidelity "
                         "knobs; the ladder measures the dynamic studies (speeds, rigid-flexible, driving-speed, "
                         "friction)")
    if case.loads.source == "csv":
        raise ValueError("loads.source: the wind ladder holds one load case of the synthetic spectrum "
                         "(loads.case_index) constant; a CSV load history has none (use source = \"constant\")")
    values = {"study": {"kind": "speeds"}, "loads": {"source": "constant"}}
    if kind == "driving-speed":
        values["analysis"] = {"speed_rpm": max(case.study.speeds_rpm)}
    if kind == "friction":
        mu_d, mu_s = max(case.study.friction_sets)
        values["contact"] = {"mu_dynamic": mu_d, "mu_static": mu_s}
    return values


def scene(case: WindCase) -> WindCase:
    """The single dynamic run the ladder measures (module docstring), before the rung's knobs."""
    return case.with_(**_scene_values(case))


def describe_scene(case: WindCase) -> str:
    c = scene(case)
    return (f"load case {c.loads.case_index + 1} of the synthetic spectrum ×{c.loads.scale:g} held constant, "
            f"{c.analysis.speed_rpm:g} r/min, μ = {c.contact.mu_dynamic:g}/{c.contact.mu_static:g}, "
            f"{c.contact.preset} contacts")


def rung_case(case: WindCase, settings: dict) -> WindCase:
    """``case``'s scene with the rung's knob values (dotted keys → values); the record samples
    the same instants at every step factor."""
    tables = case_tables(settings)
    factor = settings.get("analysis.step_factor", 1.0)
    tables.setdefault("analysis", {})["record_every"] = max(1, round(RECORD_EVERY / factor))
    return scene(case).with_(**tables)


def measure(case: WindCase) -> Outcome:
    """The figures of the module docstring from one run of ``case`` (a rung's case)."""
    sc, rec = dynamic.run(case)
    ok = dynamic.settled(case, rec)
    loads = np.concatenate([rec["fn"][ok][:, list(rb.moving_pairs)].mean(axis=0) for rb in sc.rows])
    speeds = dynamic.roller_speeds(case, sc, rec)
    cages = dynamic.cage_speeds(case, sc, rec)
    forces = dynamic.cage_forces(case, sc, rec)
    figures = {"roller_speed": {n: v["loaded_mean_rpm"] for n, v in speeds.items()},
               "cage_speed": {n: v["mean_rad_s"] for n, v in cages.items()},
               "cage_force_mean": {n: v["mean_N"] for n, v in forces.items()},
               "cage_force_peak": {n: v["peak_N"] for n, v in forces.items()}}
    if case.bodies.rings == "modal":
        rings = peak_stresses(sc, rec, case.analysis.settle_s, names=("inner ring", "outer ring"))
        figures["ring_von_mises"] = {name: w.von_mises_Pa for name, (_, _, w) in rings.items()}
    slices = dynamic.slice_error(case, sc.modal)
    estimates = {"estimated_step_error": dynamic.step_error(sc, rec["timestep_s"])["max_load"],
                 "estimated_slice_error": None if slices is None else slices["max_load"]}
    return Outcome(loads, unloaded_share=UNLOADED_SHARE, estimates=estimates, figures=figures)


def element_columns(case: WindCase, n: int) -> tuple[list[str], list[tuple]]:
    """The columns that name the ``n`` rollers in :data:`LOADS_FILE`: row and roller number in it."""
    from .scene import rows

    out = [(row.name, i + 1) for row in rows(case) for i in range(row.n_rollers)]
    if len(out) != n:
        raise ValueError(f"the wind bearing has {len(out)} rollers, the ladder measured {n}")
    return ["row", "roller"], out


def describe(settings: dict) -> str:
    """A rung in words, as a user would set it."""
    rings, cages = settings["bodies.rings"], settings["bodies.cages"]
    bodies = f"{rings} rings, {cages} cages"
    if "modal" in (rings, cages):
        bodies += f" ({settings['bodies.n_modes']} modes)"
    friction = "implicit" if settings["contact.implicit_friction"] else "explicit"
    return (f"{bodies}, {settings['rollers.n_slices']} slices, step ×{settings['analysis.step_factor']:g}, "
            f"{friction} friction from {1e3 * settings['contact.v_static_m_s']:g} mm/s")


#: the knob keys :func:`rung_overrides` carries over to a run (the window stays the case's); the
#: meshes and bolts only with modal bodies (rigid ones do not read them)
_RUN_KEYS = ("bodies.rings", "bodies.cages", "bodies.n_modes", "rollers.n_slices", "analysis.step_factor",
             "contact.v_static_m_s", "contact.v_dynamic_m_s", "contact.implicit_friction")
_MESH_KEYS = ("bodies.bolts", "bodies.ring_element_size_m", "bodies.cage_element_size_m")


def rung_overrides(case: WindCase, settings: dict) -> dict | None:
    """The table overrides that run ``case`` at a rung's fidelity, on the meshes the ladder measured
    (its own study, loads and window kept), or None when the rung does not apply: the
    rigid-flexible study runs both rigid and modal bodies, so only its rungs with modal rings and
    cages set its modes, slices and step."""
    keys = list(_RUN_KEYS)
    modal = "modal" in (settings["bodies.rings"], settings["bodies.cages"])
    if case.study.kind == "rigid-flexible":
        if (settings["bodies.rings"], settings["bodies.cages"]) != ("modal", "modal"):
            return None
        keys = [k for k in keys if k not in ("bodies.rings", "bodies.cages")]
    if modal:
        keys += _MESH_KEYS
    else:
        keys.remove("bodies.n_modes")
    return case_tables({key: settings[key] for key in keys})
