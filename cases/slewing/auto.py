"""``top.kind = "auto"`` and ``bottom.kind = "auto"``: model the top structure and the bottom race
only as finely as the scene requires, and say why.

A cheap pass decides, for the case's quasi-static equilibrium (study ``single`` without travel, or
each equilibrium of the undulation study), for each race left to it, in three steps:

1. **Rigid equilibrium** (milliseconds), every race left to ``auto`` rigid. For the top structure,
   which floats: when its ball loads vary by less than the tolerance around the ring, a floating
   ring of revolution deforms alike under every ball, which leaves the loads equal, W / (Z sin α):
   rigid, as the analytic check of the static case has it (thesis §3.2.1). Not for the bottom
   race: its bolts alone spread equal loads (+13 % on the largest of the 2 m ring's flat dead-load
   equilibrium with 12 bolts).
2. **Probe** (a reduction with 5 modes and no load shapes, seconds: the top structure on a mesh
   twice as coarse as the default, the bottom race on its own, whose bolt patches need elements
   narrower than they are): the race's compliance to radial and axial ball forces on its groove
   patch at every ball — the floating top structure with inertia relief, the bottom race held at
   its bolt patches (the probe of :class:`cms_reduction.RacewaySpec`). With it, the race's static
   deflection along each ball's contact normal under all the rigid ball forces, and from the
   difference between balls against the Hertz approach of the most loaded one the bound η/(1 + η)
   on the change of the loads (:func:`mbd_core.quasistatic.estimates.deflection_bound`). Below the
   tolerance: rigid. When both races decide, each takes half the tolerance (their deflections
   add).
3. **Modal**, with the static shapes of the ball forces at the balls' places on the groove patch
   s = 0.3·D (``ball_load_shapes``): the quasi-static equilibrium is then the finite-element solution
   of the ring under the ball forces (Ritz: their static response lies in the basis, up to what
   the groove-centre sampling adds beyond the patch average), so normal modes and harmonic load
   shapes add almost nothing to it — 5 modes, no harmonics (against 40 modes and harmonic 16:
   0.06 % on the 2 m ring's largest load). What remains is the mesh's error (0.30 % on the 70 mm
   default elements against the ladder's reference).

The element size stays the case's (the mesh is the user's budget); the modes, load shapes and
patch are chosen. Travels and dynamics move the balls off the places their shapes hold, so
``auto`` is refused there (when the case is built, naming the race's ``kind``).
"""

from __future__ import annotations

import math

import numpy as np

from mbd_core.quasistatic.estimates import deflection_bound

from . import scene as scene_mod
from .case import SlewingCase
from .quasistatic import equilibrium

__all__ = ["AUTO_TOLERANCE", "CHOSEN_KEYS", "resolve"]

#: relative error of the largest ball load the decisions aim at
AUTO_TOLERANCE = 0.01
#: the races ``auto`` decides for
RACES = ("top", "bottom")
#: a race's keys ``auto`` chooses (a value set by the user is refused)
CHOSEN_KEYS = ("n_modes", "groove_harmonics", "raceway_spread_m", "ball_load_shapes")
#: the coarse probe's mesh, as a factor of the default element size, and its modes
PROBE_MESH_FACTOR = 2.0
PROBE_MODES = 5
#: the modal choice (step 3)
MODAL_CHOICE = {"n_modes": 5, "groove_harmonics": -1, "ball_load_shapes": True}


def _rigid_pass(case: SlewingCase):
    """The row of the equilibrium with every race ``auto`` decides kept rigid."""
    c = case.with_(**{race: {"kind": "rigid"} for race in RACES if getattr(case, race).kind == "auto"})
    res = equilibrium(c, scene_mod.Bodies(scene_mod.top_body(c), scene_mod.bottom_body(c)))
    return res.rows[0]


def _probe_compliance_m_per_N(case: SlewingCase, race: str) -> np.ndarray:
    """(2Z, 2Z) compliance of ``race`` to radial and axial ball forces at every ball (step 2): the
    floating top structure with inertia relief on the coarse mesh, the bottom race held at its bolts
    on its own mesh (a bolt patch needs elements narrower than it)."""
    h = round(PROBE_MESH_FACTOR * scene_mod.DEFAULT_ELEMENT_SIZE_M[case.geometry.variant], 4) if race == "top" \
        else case.bottom.element_size_m
    probe = case.with_(**{race: {"kind": "modal", "n_modes": PROBE_MODES, "groove_harmonics": -1, "element_size_m": h,
                                 "raceway_spread_m": 0.0, "ball_load_shapes": False}})
    build = scene_mod.top_body if race == "top" else scene_mod.bottom_body
    return np.asarray(build(probe, probe_all_balls=True).metadata["probe_compliance_m_per_N"], float)


def _contact_normals(case: SlewingCase, race: str, row) -> np.ndarray:
    """(Z, 2) each ball's contact normal on ``race`` at its loaded angle."""
    groove = case.geometry.section().groove(race, case.geometry.pitch_diameter_m)
    return np.array([groove.direction(math.degrees(a)) for a in np.asarray(row.contact_angle_rad, float)])


def _settings_text(race: str, fidelity: dict) -> str:
    return ", ".join(f"{race}.{k} = {v}" for k, v in fidelity.items())


def _decide(case: SlewingCase, race: str, row, tolerance: float) -> tuple[dict, dict]:
    """The fidelity of one race (module docstring) and its decision record."""
    name = "top structure" if race == "top" else "bottom race"
    q = np.asarray(row.load_N, float)
    k = int(np.argmax(q))
    spread = float((q.max() - q.min()) / q.max())
    figures = {"rigid_max_ball_load_N": float(q.max()), "rigid_min_ball_load_N": float(q.min()),
               "rigid_load_spread": spread, "hertz_approach_m": float(row.approach_m[k]), "tolerance": tolerance}
    if race == "top" and spread < tolerance:
        choice = {"kind": "rigid"}
        reason = (f"under rigid races the ball loads vary by {100 * spread:.2g} % (< {100 * tolerance:g} %): a "
                  "floating ring of revolution deforms alike under every ball, which leaves the loads equal "
                  "(W / (Z sin α)); rigid")
    else:
        test = deflection_bound(_probe_compliance_m_per_N(case, race), _contact_normals(case, race, row), q,
                                row.approach_m)
        dr, eta, bound = test["deflection_difference_m"], test["stiffness_ratio"], test["load_change_bound"]
        figures.update(test)
        held = "" if race == "top" else ", held at its bolts,"
        where = (f"the ball loads under rigid races vary by {100 * spread:.3g} %; under them the {name}{held} "
                 f"deflects by up to {1e6 * dr:.3g} µm more at one loaded ball than at another (its static "
                 f"response), against the Hertz approach {1e6 * float(row.approach_m[k]):.3g} µm of the most loaded "
                 f"ball (η = {eta:.3g}, load change up to {100 * bound:.3g} %)")
        if bound < tolerance:
            choice = {"kind": "rigid"}
            reason = f"{where} (< {100 * tolerance:g} %): rigid"
        else:
            choice = {"kind": "modal", **MODAL_CHOICE, "raceway_spread_m": scene_mod.groove_patch_m(case)}
            reason = (f"{where} (≥ {100 * tolerance:g} %): modal, with the static shapes of the ball forces at "
                      f"their places on a {1e3 * choice['raceway_spread_m']:g} mm groove patch, which make the "
                      f"equilibrium the finite-element solution of the {name} under them; normal modes and "
                      "harmonic load shapes add almost nothing to it (5 modes, none); the mesh's error remains")
    return choice, {"body": race, "choice": _settings_text(race, choice), "reason": reason, **figures}


def resolve(case: SlewingCase, tolerance: float = AUTO_TOLERANCE) -> tuple[SlewingCase, list[dict]]:
    """``case`` with every ``kind = "auto"`` (top structure, bottom race) replaced by its decision,
    and the decisions (``summary.json`` ``fidelity_decisions``): body, choice, reason, the figures
    it rests on. When both races decide, each takes half the tolerance."""
    races = [race for race in RACES if getattr(case, race).kind == "auto"]
    row = _rigid_pass(case)
    share = tolerance / len(races) if races else tolerance
    choices, decisions = {}, []
    for race in races:
        choices[race], decision = _decide(case, race, row, share)
        decisions.append(decision)
    return case.with_(**choices), decisions
