"""``bearing.rings = "auto"``: model each ring of a bearing file's ``[rings.X]`` tables only as finely
as its load distribution requires, and say why (the slewing ring's races decide the same way,
:mod:`cases.slewing.auto`).

For each ring, in three steps:

1. **Rigid equilibrium** (milliseconds) of every load case of the file with rigid rings; the load
   case of the largest element load is the scene, and of the rows the ring carries the one with
   that load.
2. **Probe** (a reduction with :data:`PROBE_MODES` modes on the file's mesh and support): the ring's
   compliance to radial and axial forces at every element of that row, spread over the raceway
   patch element load shapes use (:func:`cases.bearing_ring_reduction.probe_compliance_m_per_N`).
   With it, the raceway's static deflection along each element's contact normal under all the
   rigid element forces (held at its support, so bolts and clamps are in it), and from the
   difference between elements against the approach of the most loaded one the bound η/(1 + η) on
   the change of the loads (:func:`mbd_core.quasistatic.estimates.deflection_bound`; e = 1.5 for
   balls, 10/9 for rollers, ISO/TS 16281). Below the ring's share of the tolerance: rigid. (A ring of revolution under
   equal element loads is not enough: the bolts alone spread a thrust-loaded ring's loads.) A
   four-point or crossed roller row has its contacts on the two flanks of its groove and its
   raceway sample at the apex, where no probe patch fits: its ring is not probed and stays modal
   as the file makes it, and the decision says so.
3. **Modal**: with the static shapes of the element forces at their places
   (``element_load_shapes``) and :data:`MODAL_CHOICE`'s modes, which make the equilibrium the
   finite-element solution of the ring under the element forces (the ladder's ``shapes-cheap`` rung,
   cases/bearings/README.md); where a four-point or crossed row rules the shapes out, the file's own
   modes and raceway load shapes, and the decision says so.

When two rings decide, each takes half the tolerance (their deflections add). The mesh stays the
file's. The decisions are for the quasi-static load distribution: ``auto`` is refused by the
other studies (the limiting curve compares rigid with modal rings itself; a rotation moves the
elements off the places their shapes hold).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from mbd_core.multibody.bearings import LINE_EXPONENT
from mbd_core.quasistatic import solve_load_distribution
from mbd_core.quasistatic.estimates import deflection_bound
from mbd_core.quasistatic.rows import RollerRow

from ..bearing_ring_reduction import contact_normals_rz, element_patch_m, probe_compliance_m_per_N, two_sided
from ..bearing_rings import ring_mesh_spec
from .case import DescribedCase

__all__ = ["AUTO_TOLERANCE", "MODAL_CHOICE", "PROBE_MODES", "resolve", "most_loaded_case", "refused_reason"]

#: relative error of the largest element load the decisions aim at
AUTO_TOLERANCE = 0.01
#: modes of the probe's reduction
PROBE_MODES = 5
#: the modal choice (step 3)
MODAL_CHOICE = {"n_modes": 10, "raceway_harmonics": 0, "element_load_shapes": True}


def most_loaded_case(desc):
    """(index, rigid-ring solution) of the load case with the largest element load."""
    best = None
    for k, load in enumerate(desc.load_cases):
        res = solve_load_distribution(desc.bearing, load)
        worst = max(float(np.max(r.load_N)) for r in res.rows)
        if best is None or worst > best[0]:
            best = (worst, k, res)
    return best[1], best[2]


def _decide(desc, name: str, m, res, tolerance: float) -> tuple[dict | None, dict]:
    """(ring keys to set, or None for rigid; the decision record) of ring ``name``."""
    rows = {r.name: r for r in desc.bearing.rows}
    loaded = max((r for r in res.rows if r.name in m.places), key=lambda r: float(np.max(r.load_N)))
    row = rows[loaded.name]
    q = np.asarray(loaded.load_N, float)
    k = int(np.argmax(q))
    delta = float(loaded.approach_m[k])
    record = {"body": f"rings.{name}"}
    if two_sided(row):
        choice = (f"modal, the file's {m.keys.n_modes} modes and raceway load shapes to harmonic "
                  f"{m.keys.raceway_harmonics}")
        reason = (f"the {row.name} row's contacts lie on the two flanks of its groove, away from the raceway "
                  "sample at its apex, where no probe patch fits: the ring's deflection at the elements is not "
                  "measured, so it stays as the file makes it (element load shapes are not offered there either, "
                  "cases/bearings/README.md)")
        return {}, {**record, "choice": choice, "reason": reason, "row": row.name,
                    "rigid_max_element_load_N": float(q.max()), "tolerance": tolerance}
    C = probe_compliance_m_per_N(m, desc.bearing, row.name, PROBE_MODES)
    n = contact_normals_rz(m, row, loaded.contact_angle_rad)
    test = deflection_bound(C, n, q, loaded.approach_m, LINE_EXPONENT if isinstance(row, RollerRow) else 1.5)
    dr, eta, bound = test["deflection_difference_m"], test["stiffness_ratio"], test["load_change_bound"]
    figures = {"row": row.name, "rigid_max_element_load_N": float(q.max()), "rigid_min_element_load_N": float(q.min()),
               "hertz_approach_m": delta, **test, "tolerance": tolerance}
    where = (f"under rigid rings the {row.name} row's element loads run from {q.min():.4g} to {q.max():.4g} N; "
             f"under them the {name} ring's raceway deflects by up to {1e6 * dr:.3g} µm more at one loaded element "
             f"than at another (its static response, held at its support), against the approach "
             f"{1e6 * delta:.3g} µm of the most loaded (η = {eta:.3g}, load change up to {100 * bound:.3g} %)")
    if bound < tolerance:
        return None, {**record, "choice": "rigid", "reason": f"{where} (< {100 * tolerance:g} %): rigid", **figures}
    if any(two_sided(r) for r in desc.bearing.rows):
        keys = {}
        choice = (f"modal, the file's {m.keys.n_modes} modes and raceway load shapes to harmonic "
                  f"{m.keys.raceway_harmonics}")
        why = ("element load shapes are not offered with a four-point or crossed roller row in the bearing "
               "(cases/bearings/README.md), so the file's own modes and raceway load shapes")
    else:
        keys = dict(MODAL_CHOICE)
        patch, size = element_patch_m(m, row), ring_mesh_spec(m).size_m
        choice = f"modal, element load shapes on a {1e3 * patch:.3g} mm raceway patch, {keys['n_modes']} modes, harmonic 0"
        why = ("the static shapes of the element forces at their places make the equilibrium the finite-element "
               f"solution of the ring under them; {keys['n_modes']} normal modes add little to it (the ladder's "
               "shapes-cheap rung)")
        if patch < size:
            figures["warning"] = (f"rings.{name}: the element patch ({1e3 * patch:.3g} mm) is narrower than the ring's "
                                  f"elements ({1e3 * size:.3g} mm), so the finite-element solution on this mesh carries "
                                  "the mesh's error (1.4 % on the test bearing of cases/bearings/README.md); refine "
                                  "rings.element_size_factor with bearing.rings = \"file\" to see it")
    return keys, {**record, "choice": choice, "reason": f"{where} (≥ {100 * tolerance:g} %): {why}", **figures}


def resolve(case: DescribedCase, desc, tolerance: float = AUTO_TOLERANCE):
    """``desc`` (the case's bearing description) with each ``[rings.X]`` ring decided (module
    docstring): rigid rings left out of its ``rings``, modal ones at the chosen keys; and the
    decisions (``summary.json`` ``fidelity_decisions``)."""
    from ..bearing_rings import with_fidelity

    if not (math.isfinite(tolerance) and 0.0 < tolerance < 1.0):
        raise ValueError(f"auto tolerance must lie in (0, 1), got {tolerance!r}")
    if not desc.rings:
        return desc, [{"body": "rings", "choice": "rigid",
                       "reason": "the bearing file gives no [rings.X] tables: its rings are rigid"}]
    index, res = most_loaded_case(desc)
    share = tolerance / len(desc.rings)
    rings, decisions = {}, []
    for name, m in desc.rings.items():
        keys, decision = _decide(desc, name, m, res, share)
        decision["load_case"] = index + 1
        decisions.append(decision)
        if keys is not None:
            rings[name] = with_fidelity({name: m}, keys, f"rings.{name}")[name] if keys else m
    return dataclasses.replace(desc, rings=rings), decisions


def refused_reason(case: DescribedCase) -> str | None:
    """Why ``bearing.rings = "auto"`` does not apply to the case's study, or None."""
    if case.study.kind == "load-distribution":
        return None
    if case.study.kind == "limiting-curve":
        return ("the limiting-curve study compares rigid with modal rings itself; set bearing.rings = \"file\" (or "
                "run the load-distribution study with auto)")
    return ("a rotation moves the elements off the places element load shapes hold; set bearing.rings = \"file\" and "
            "choose the [rings] keys")

