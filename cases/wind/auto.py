"""``bodies.rings = "auto"`` and ``bodies.cages = "auto"``: model the main bearing's rings and cages
only as finely as the scene requires, and say why.

Rings — a cheap pass, in the manner of the slewing ring's top structure (:mod:`cases.slewing.auto`):

1. **Rigid equilibrium** (milliseconds): the quasi-static roller loads with rigid rings under the
   load of the case's history that loads a roller most (as :func:`.dynamic.slice_error` picks it);
   the row of the largest roller load, its spread Q_max − Q_min and the line-contact approach δ of
   that roller.
2. **Coarse probe** (seconds): the inner ring reduced on a coarse mesh (:data:`PROBE_ELEMENT_SIZE_M`,
   :data:`PROBE_MODES` modes) with a probe on that row's raceway: its compliance c = nᵀCn to a
   roller force spread over half a roller length (inertia relief; the probe of
   :class:`cms_reduction.RacewaySpec`), n the row's contact normal (radial or axial). Under the rigid
   loads the raceway's deflection then differs between rollers by about Δr = c·(Q_max − Q_min);
   against the approach of the most loaded roller this is η = (10/9)·Δr/δ (the line contact
   Q ∝ δ^(10/9) of ISO/TS 16281: dQ/dδ = (10/9)·Q/δ), and η/(1 + η) bounds the change of its load.
   Below the tolerance: rigid.
3. **Modal**, with :data:`MODAL_N_MODES` modes: the wind ladder measured 20 → 40 modes moving the
   largest roller load by 0.3 % (cases/wind/README.md, "Speed against accuracy"). The mesh, bolts
   and raceway grids stay the case's.

Slices per roller: the case's ``rollers.n_slices`` while the slicing estimate of the largest roller
load (:func:`.dynamic.slice_error`: quasi-static with rigid rings at n, 2n and 4n slices,
Richardson; on the quick ladder within 1.2× of the slice sweep with rigid rings, and above the
static slicing error with modal rings, 0.93–1.31× of which the flexible estimate gives) meets the
tolerance; else doubled, at most :data:`MAX_SLICE_DOUBLINGS` times, and said so.

Cages: rigid, always, with the reason: a cage carries no raceway load (the wind ladder measured
modal cages moving the largest roller load by 0.2 %), and its pocket forces, which a modal cage
does change, change by 30–140 % between every pair of rungs of that ladder, so no cage model
converges them; ask for ``bodies.cages = "modal"`` where a cage's stress is the question.
"""

from __future__ import annotations

import math

import numpy as np

from cms_reduction.pipeline import RacewaySpec, ReductionSpec, reduced_body
from fem_rings import MeshSpec
from fem_rings.sections import three_row_inner_ring
from mbd_core.multibody.bearings import LINE_EXPONENT
from mbd_core.quasistatic import Bearing, solve_load_distribution

from ..parts import STEEL_42CRMO
from .case import WindCase
from .dynamic import slice_error
from .scene import inner_ring_load, load_history, rows

__all__ = ["AUTO_TOLERANCE", "MODAL_N_MODES", "resolve"]

#: relative error of the largest roller load the decisions aim at
AUTO_TOLERANCE = 0.01
#: the coarse probe's mesh and modes (those of the wind ladder's quick rungs)
PROBE_ELEMENT_SIZE_M = 0.18
PROBE_MODES = 8
#: modes of modal rings (module docstring)
MODAL_N_MODES = 20
#: the slices per roller are doubled at most this many times (module docstring)
MAX_SLICE_DOUBLINGS = 3
#: raceway of each row on the inner ring, and its contact normal in the (r, z) section
_RACEWAY = {"radial": ("radial_raceway", (1.0, 0.0)), "front thrust": ("front_thrust_raceway", (0.0, 1.0)),
            "rear thrust": ("rear_thrust_raceway", (0.0, 1.0))}


def _rigid_pass(case: WindCase):
    """(row of the largest roller load, its loads) under the history's most loading load, rigid rings."""
    bearing = Bearing("three-row roller", rows(case))
    _, loads = load_history(case)
    best = None
    for f in np.unique(loads, axis=0):
        res = solve_load_distribution(bearing, inner_ring_load(f))
        row = max(res.rows, key=lambda r: float(r.load_N.max()))
        if best is None or row.load_N.max() > best.load_N.max():
            best = row
    return best


def _probe_compliance_m_per_N(case: WindCase, row_name: str) -> float:
    """c = nᵀCn of the inner ring at a roller of ``row_name`` (step 2), on the coarse mesh."""
    segment, normal = _RACEWAY[row_name]
    spread = 0.5 * next(r for r in rows(case) if r.name == row_name).roller_length_m
    spec = ReductionSpec(n_modes=PROBE_MODES, raceways=(RacewaySpec(segment, case.bodies.n_theta, n_max=-1,
                                                                    probe_spread_m=spread),))
    body = reduced_body(three_row_inner_ring(), MeshSpec(PROBE_ELEMENT_SIZE_M, "hex27"), STEEL_42CRMO, spec,
                        name="inner ring (auto probe)")
    C = np.asarray(body.metadata["probe_compliance_m_per_N"])
    n = np.asarray(normal)
    return float(n @ C @ n)


def _ring_decision(case: WindCase, tolerance: float) -> tuple[str, dict]:
    row = _rigid_pass(case)
    q = np.asarray(row.load_N, float)
    k = int(np.argmax(q))
    delta = float(row.approach_m[k])
    c = _probe_compliance_m_per_N(case, row.name)
    dr = c * float(q.max() - q.min())
    eta = LINE_EXPONENT * dr / delta
    bound = eta / (1.0 + eta)
    figures = {"row": row.name, "rigid_max_roller_load_N": float(q.max()), "rigid_min_roller_load_N": float(q.min()),
               "hertz_approach_m": delta, "ring_compliance_m_per_N": c, "deflection_difference_m": dr,
               "stiffness_ratio": eta, "load_change_bound": bound, "tolerance": tolerance}
    where = (f"under rigid rings the {row.name} row's roller loads run from {q.min():.0f} to {q.max():.0f} N; the inner "
             f"ring's compliance at a roller is {c:.3g} m/N, so its raceway deflects by up to {1e6 * dr:.3g} µm more "
             f"under one roller than another, against the line-contact approach {1e6 * delta:.3g} µm of the most "
             f"loaded roller (η = {eta:.3g}, load change up to {100 * bound:.3g} %)")
    if bound < tolerance:
        return "rigid", {"body": "rings", "choice": "bodies.rings = rigid",
                         "reason": f"{where} (< {100 * tolerance:g} %): rigid", **figures}
    return "modal", {"body": "rings", "choice": f"bodies.rings = modal, bodies.n_modes = {MODAL_N_MODES}",
                     "reason": f"{where} (≥ {100 * tolerance:g} %): modal, with {MODAL_N_MODES} modes (the wind "
                               "ladder: 20 → 40 modes move the largest roller load by 0.3 %)", **figures}


_CAGE_REASON = ("a cage carries no raceway load: modal cages moved the largest roller load by 0.2 % on the wind "
                "ladder, and its pocket forces, which they do change, differ by 30–140 % between every pair of that "
                "ladder's rungs, so no cage model converges them; rigid (ask for bodies.cages = \"modal\" where a "
                "cage's stress is the question)")


def _slice_decision(case: WindCase, tolerance: float) -> tuple[int, dict]:
    """Slices per roller (module docstring): the case's, doubled up to :data:`MAX_SLICE_DOUBLINGS`
    times until the slicing estimate of the largest roller load meets the tolerance."""
    n = case.rollers.n_slices
    for doubling in range(MAX_SLICE_DOUBLINGS + 1):
        est = slice_error(case.with_(rollers={"n_slices": n}))
        if est is None or est["max_load"] < tolerance or doubling == MAX_SLICE_DOUBLINGS:
            break
        n *= 2
    figures = {"estimated_slice_error": None if est is None else est["max_load"], "tolerance": tolerance}
    if est is None:
        return n, {"body": "rollers", "choice": f"rollers.n_slices = {n}", **figures,
                   "reason": "the adams contact preset takes each roller contact whole; its slices only carry it"}
    met = est["max_load"] < tolerance
    kept = n == case.rollers.n_slices
    reason = (f"{n} slice{'s' if n > 1 else ''} per roller put the slicing error of the largest roller load at "
              f"{100 * est['max_load']:.2g} % ({'<' if met else '≥'} {100 * tolerance:g} %; quasi-static, rigid rings, "
              f"{n}/{2 * n}/{4 * n} slices, "
              f"Richardson): {'kept' if kept else 'raised from ' + str(case.rollers.n_slices)}"
              + ("" if met else f"; {n} is the most it takes (the case's × {2 ** MAX_SLICE_DOUBLINGS})"))
    return n, {"body": "rollers", "choice": f"rollers.n_slices = {n}", "reason": reason, **figures}


def resolve(case: WindCase, tolerance: float = AUTO_TOLERANCE) -> tuple[WindCase, list[dict]]:
    """``case`` with ``"auto"`` rings and cages replaced by the decisions, the slices per roller
    checked against the tolerance, and the decisions (``summary.json`` ``fidelity_decisions``:
    body, choice, reason and the figures it rests on)."""
    if not (math.isfinite(tolerance) and 0.0 < tolerance < 1.0):
        raise ValueError(f"auto tolerance must lie in (0, 1), got {tolerance!r}")
    bodies, decisions = {}, []
    if case.bodies.rings == "auto":
        kind, decision = _ring_decision(case, tolerance)
        bodies["rings"] = kind
        if kind == "modal":
            bodies["n_modes"] = MODAL_N_MODES
        decisions.append(decision)
    if case.bodies.cages == "auto":
        bodies["cages"] = "rigid"
        decisions.append({"body": "cages", "choice": "bodies.cages = rigid", "reason": _CAGE_REASON})
    n_slices, decision = _slice_decision(case, tolerance)
    decisions.append(decision)
    return case.with_(bodies=bodies, rollers={"n_slices": n_slices}), decisions
