"""``top.kind = "auto"``: model the top structure only as finely as the scene requires, and say why.

A cheap pass decides, for the case's quasi-static equilibrium (study ``single`` without travel),
in three steps:

1. **Rigid equilibrium** (milliseconds). When its ball loads vary by less than the tolerance
   around the ring, the top structure — a ring of revolution — deforms alike under every ball,
   which leaves the loads equal, W / (Z sin α) (a shared change of α moves them together): rigid,
   as the analytic check of the static case has it (thesis §3.2.1).
2. **Coarse probe** (a reduction on a mesh twice as coarse as the default, 5 modes, no load
   shapes, seconds): the ring's compliance c = nᵀCn to a ball force on its groove patch, with
   inertia relief (:func:`cms_reduction.craig_bampton.residual_compliance`; the probe of
   :class:`cms_reduction.RacewaySpec`). Under the rigid loads the deflection differs between balls
   by at most Δr = c·(Q_max − Q_min); against the Hertz approach δ of the most loaded ball this is
   η = 1.5·Δr/δ (Hertz: dQ/dδ = 1.5 Q/δ), and η/(1 + η) bounds the load change it can cause when
   the approaches are imposed. Below the tolerance: rigid.
3. **Modal**, with the static shapes of the ball forces at the balls' places on the groove patch
   s = 0.3·D (``ball_load_shapes``): the quasi-static equilibrium is then the finite-element solution
   of the ring under the ball forces (Ritz: their static response lies in the basis, up to what
   the groove-centre sampling adds beyond the patch average), so normal modes and harmonic load
   shapes add almost nothing to it — 5 modes, no harmonics (against 40 modes and harmonic 16:
   0.06 % on the 2 m ring's largest load). What remains is the mesh's error (0.30 % on the 70 mm
   default elements against the ladder's reference).

The element size stays the case's (the mesh is the user's budget); the modes, load shapes and
patch are chosen. Travels and dynamics move the balls off the places their shapes hold, so
``auto`` is refused there (when the case is built, naming ``top.kind``).
"""

from __future__ import annotations

import math

import numpy as np

from . import scene as scene_mod
from .case import SlewingCase
from .quasistatic import equilibrium

__all__ = ["AUTO_TOLERANCE", "CHOSEN_KEYS", "resolve"]

#: relative error of the largest ball load the decisions aim at
AUTO_TOLERANCE = 0.01
#: the top structure's keys ``auto`` chooses (a value set by the user is refused)
CHOSEN_KEYS = ("n_modes", "groove_harmonics", "raceway_spread_m", "ball_load_shapes")
#: the coarse probe's mesh, as a factor of the default element size, and its modes
PROBE_MESH_FACTOR = 2.0
PROBE_MODES = 5
#: the modal choice (step 3)
MODAL_CHOICE = {"n_modes": 5, "groove_harmonics": -1, "ball_load_shapes": True}


def _rigid_pass(case: SlewingCase):
    c = case.with_(top={"kind": "rigid"})
    res = equilibrium(c, scene_mod.Bodies(None, scene_mod.bottom_body(c)))
    return res.rows[0]


def _probe_compliance_m_per_N(case: SlewingCase, alpha_rad: float) -> float:
    """c = nᵀCn of the top structure at a ball (step 2), on the coarse mesh."""
    h = round(PROBE_MESH_FACTOR * scene_mod.DEFAULT_ELEMENT_SIZE_M[case.geometry.variant], 4)
    probe = case.with_(top={"kind": "modal", "n_modes": PROBE_MODES, "groove_harmonics": -1, "element_size_m": h,
                            "raceway_spread_m": 0.0, "ball_load_shapes": False})
    C = np.asarray(scene_mod.top_body(probe).metadata["probe_compliance_m_per_N"])
    n = case.geometry.section().groove("top", case.geometry.pitch_diameter_m).direction(math.degrees(alpha_rad))
    return float(n @ C @ n)


def _settings_text(top: dict) -> str:
    return ", ".join(f"top.{k} = {v}" for k, v in top.items())


def resolve(case: SlewingCase, tolerance: float = AUTO_TOLERANCE) -> tuple[SlewingCase, dict]:
    """``case`` with ``top.kind = "auto"`` replaced by the decision, and the decision
    (``summary.json`` ``fidelity_decisions``): body, choice, reason, the figures it rests on."""
    row = _rigid_pass(case)
    q = np.asarray(row.load_N, float)
    k = int(np.argmax(q))
    spread = float((q.max() - q.min()) / q.max())
    figures = {"rigid_max_ball_load_N": float(q.max()), "rigid_min_ball_load_N": float(q.min()),
               "rigid_load_spread": spread, "hertz_approach_m": float(row.approach_m[k]), "tolerance": tolerance}
    if spread < tolerance:
        top = {"kind": "rigid"}
        reason = (f"under a rigid top structure the ball loads vary by {100 * spread:.2g} % "
                  f"(< {100 * tolerance:g} %): a ring of revolution deforms alike under every ball, which leaves "
                  "the loads equal (W / (Z sin α)); rigid")
    else:
        c = _probe_compliance_m_per_N(case, float(row.contact_angle_rad[k]))
        dr = c * float(q.max() - q.min())
        eta = 1.5 * dr / float(row.approach_m[k])
        bound = eta / (1.0 + eta)
        figures.update(ring_compliance_m_per_N=c, deflection_difference_m=dr, stiffness_ratio=eta, load_change_bound=bound)
        where = (f"the ball loads under a rigid top structure vary by {100 * spread:.3g} %; the ring's compliance "
                 f"at a ball is {c:.3g} m/N, so its deflection differs between balls by up to "
                 f"{1e6 * dr:.3g} µm against the Hertz approach {1e6 * float(row.approach_m[k]):.3g} µm of the "
                 f"most loaded ball (η = {eta:.3g}, load change up to {100 * bound:.3g} %)")
        if bound < tolerance:
            top = {"kind": "rigid"}
            reason = f"{where} (< {100 * tolerance:g} %): rigid"
        else:
            top = {"kind": "modal", **MODAL_CHOICE, "raceway_spread_m": scene_mod.groove_patch_m(case)}
            reason = (f"{where} (≥ {100 * tolerance:g} %): modal, with the static shapes of the ball forces at "
                      f"their places on a {1e3 * top['raceway_spread_m']:g} mm groove patch, which make the "
                      "equilibrium the finite-element solution of the ring under them; normal modes and "
                      "harmonic load shapes add almost nothing to it (5 modes, none); the mesh's error remains")
    decision = {"body": "top", "choice": _settings_text(top), "reason": reason, **figures}
    return case.with_(top=top), decision
