"""A-posteriori estimate of a modal ring's truncation error in a load distribution, without a reference.

A reduced ring holds only part of its static response to the element forces; the rest is the
residual flexibility of its basis (:func:`cms_reduction.craig_bampton.residual_compliance`, measured
at one element place when the ring is reduced: a 2 × 2 compliance to radial and axial forces spread
over the element's raceway patch, m/N). For an element of load Q along the contact direction
n = (n_r, n_z) it is a deflection the model misses,

    r = nᵀ R n · Q,

to compare with the element's Hertz approach δ. In series with the contact (Hertz: Q ∝ δ^{3/2},
so dQ/dδ = 1.5 Q/δ), the missing compliance nᵀRn lowers the element's stiffness by the factor
1/(1 + η), η = 1.5 r/δ: the relative change of its load when its approach is imposed,
η/(1 + η). That is the scale of the load error of the most loaded element when the rings are stiff
compared with the contacts; a soft ring spreads part of it to the neighbours, so the actual error
lies below it there (measured against the fidelity ladder's reference: ``flexbearing tradeoff``).
The estimate takes the local residual of one element and not the cross terms between elements,
which carry the truncated harmonics of the whole distribution.
"""

from __future__ import annotations

import numpy as np

__all__ = ["truncation_estimate"]


def truncation_estimate(compliance_rz_m_per_N, direction_rz, load_N, approach_m) -> dict:
    """The truncation estimate at the most loaded element (module docstring).

    Parameters
    ----------
    compliance_rz_m_per_N : (2, 2)
        Residual compliance R of the ring to (radial, axial) unit forces at an element, m/N.
    direction_rz : (Z, 2)
        Unit direction of each element's force on the ring in its section (radial, axial).
    load_N, approach_m : (Z,)
        Element loads and Hertz approaches (as in :class:`.results.RowLoads`).

    Returns
    -------
    dict
        ``element`` (index of the most loaded), ``residual_deflection_m`` r there,
        ``hertz_approach_m`` δ there, ``stiffness_ratio`` η = 1.5 r/δ, and ``max_load`` η/(1 + η):
        the estimated relative error of the largest load.
    """
    R = np.asarray(compliance_rz_m_per_N, float).reshape(2, 2)
    n = np.asarray(direction_rz, float).reshape(-1, 2)
    q = np.asarray(load_N, float)
    d = np.asarray(approach_m, float)
    k = int(np.argmax(q))
    r = float(max(n[k] @ R @ n[k], 0.0)) * float(q[k])  # R is positive semi-definite up to round-off
    eta = 1.5 * r / float(d[k]) if d[k] > 0.0 else 0.0
    return {"element": k, "residual_deflection_m": r, "hertz_approach_m": float(d[k]), "stiffness_ratio": eta,
            "max_load": eta / (1.0 + eta)}
