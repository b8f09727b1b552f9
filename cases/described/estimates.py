"""``error_estimates`` of a bearing file's load distribution with modal rings: each ring's modal
truncation at the most loaded element of its most loaded row, without a reference.

Every modal ring's reduction measures its compliance C to radial and axial element forces on the
element patch at the first element of each of its rows, and the part R of it its basis misses
(:func:`cases.bearing_ring_reduction.probe_block`). At the most loaded element of the ring's most
loaded row, :func:`mbd_core.quasistatic.estimates.truncation_estimate` turns them into the
estimated relative error of its load, η/(1 + κ). The rings' missing deflections add, so the
estimate of the largest load is the sum over the rings. A four-point or crossed row has no probe
(its raceway sample lies at the groove's apex): its ring gives no estimate, and the run says why.
"""

from __future__ import annotations

import numpy as np

from mbd_core.multibody.bearings import LINE_EXPONENT
from mbd_core.quasistatic.estimates import truncation_estimate
from mbd_core.quasistatic.rows import RollerRow

from ..bearing_ring_reduction import contact_normals_rz, probe_block, two_sided

__all__ = ["truncation_estimates"]


def truncation_estimates(desc, solver, result) -> dict:
    """``error_estimates`` of ``result`` (a load distribution of ``desc`` solved by ``solver``)."""
    if not solver.flexible:
        return {"modal_truncation": None, "why_none": "rigid rings (no modes to truncate)"}
    rows = {r.name: r for r in desc.bearing.rows}
    per_ring, why = {}, {}
    for ring in solver.rings:
        m = desc.rings[ring.name]
        loaded = max((r for r in result.rows if r.name in m.places), key=lambda r: float(np.max(r.load_N)))
        row = rows[loaded.name]
        if two_sided(row):
            why[ring.name] = f"the {row.name} row's raceway sample lies at its groove's apex: no probe"
            continue
        C, R = (probe_block(m, desc.bearing, row.name, ring.body.metadata[k])
                for k in ("probe_compliance_m_per_N", "residual_compliance_m_per_N"))
        n = contact_normals_rz(m, row, loaded.contact_angle_rad)
        exponent = LINE_EXPONENT if isinstance(row, RollerRow) else 1.5
        est = truncation_estimate(C, R, n, loaded.load_N, loaded.approach_m, exponent)
        est["element"] += 1
        per_ring[ring.name] = {"row": row.name, **est}
    out = {"modal_truncation": ({"max_load": float(sum(e["max_load"] for e in per_ring.values())), "rings": per_ring}
                                if per_ring else None),
           "what": "estimated relative error of the largest element load from each modal ring's residual "
                   "flexibility at its most loaded element: η/(1 + κ), η = e·r/δ the deflection r its basis misses "
                   "against the Hertz approach δ (e = 1.5 balls, 10/9 rollers), κ the same for the ring's whole deflection, "
                   "summed over the rings "
                   "(mbd_core.quasistatic.estimates; its tracking of the true error: flexbearing tradeoff)"}
    if why:
        out["why_none"] = why
    return out
