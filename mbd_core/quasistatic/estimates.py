"""A-posteriori estimate of a modal ring's truncation error in a load distribution, without a reference.

A reduced ring holds only part of its static response to the element forces; the rest is the
residual flexibility of its basis (:func:`cms_reduction.craig_bampton.residual_compliance`, measured
at one element place when the ring is reduced: 2 × 2 compliances to radial and axial forces spread
over the element's raceway patch, m/N — R, the part the basis misses, and C, the ring's whole
compliance there with inertia relief). Along an element's contact direction n = (n_r, n_z) they
are g = nᵀRn and c = nᵀCn.

Linearise the element's load about the computed equilibrium, Q_i = k_i (δ_geom,i − w_i) with
k_i = dQ/dδ = 1.5 Q_i/δ_i (Hertz, Q ∝ δ^{3/2}) and w_i the ring's deflection there. The missing
compliance adds g·Q_i to w_i, and the load change ΔQ_i adds (C_modal,ii + g)·ΔQ_i = c·ΔQ_i plus
the neighbours' share Σ_{j≠i} C_ij ΔQ_j. Keeping the element's own term (one Jacobi step):

    ΔQ_i / Q_i ≈ − η / (1 + κ),   η = k_i g,   κ = k_i c,

η the missing deflection r = g·Q_i against the approach (η = 1.5 r/δ) and κ the ring's whole
deflection under that load against it: a ring much softer than the contact (κ ≫ 1) spreads the
missing deflection over the neighbours and the load changes little. The neighbours' terms (the
truncated harmonics of the whole distribution) are left out. On the 2 m undulated slewing ring the
estimate lay within a factor 3 of the true error on every truncated basis (0.42 … 2.9). It was
lowest, below half, where a basis lacks most harmonic load shapes (``flexbearing tradeoff``
prints the comparison).
"""

from __future__ import annotations

import numpy as np

__all__ = ["truncation_estimate", "deflection_bound"]


def truncation_estimate(compliance_rz_m_per_N, residual_rz_m_per_N, direction_rz, load_N, approach_m,
                        exponent: float = 1.5) -> dict:
    """The truncation estimate at the most loaded element (module docstring).

    Parameters
    ----------
    compliance_rz_m_per_N : (2, 2)
        Whole compliance C of the ring to (radial, axial) unit forces at an element, m/N.
    residual_rz_m_per_N : (2, 2)
        Its part R that the ring's basis does not hold, m/N.
    direction_rz : (Z, 2)
        Unit direction of each element's force on the ring in its section (radial, axial).
    load_N, approach_m : (Z,)
        Element loads and Hertz approaches (as in :class:`.results.RowLoads`).
    exponent : float
        e of the load–approach law Q ∝ δ^e: 1.5 for balls (the 1.5 above), 10/9 for rollers
        (ISO/TS 16281).

    Returns
    -------
    dict
        ``element`` (index of the most loaded), ``residual_deflection_m`` r there,
        ``hertz_approach_m`` δ there, ``stiffness_ratio`` η = 1.5 r/δ, ``ring_stiffness_ratio``
        κ = 1.5 c Q/δ, and ``max_load`` η/(1 + κ): the estimated relative error of the largest load.
    """
    C = np.asarray(compliance_rz_m_per_N, float).reshape(2, 2)
    R = np.asarray(residual_rz_m_per_N, float).reshape(2, 2)
    n = np.asarray(direction_rz, float).reshape(-1, 2)
    q = np.asarray(load_N, float)
    d = np.asarray(approach_m, float)
    k = int(np.argmax(q))
    r = float(max(n[k] @ R @ n[k], 0.0)) * float(q[k])  # R is positive semi-definite up to round-off
    w = float(n[k] @ C @ n[k]) * float(q[k])
    eta, kappa = (exponent * x / float(d[k]) if d[k] > 0.0 else 0.0 for x in (r, w))
    return {"element": k, "residual_deflection_m": r, "hertz_approach_m": float(d[k]), "stiffness_ratio": eta,
            "ring_stiffness_ratio": kappa, "max_load": eta / (1.0 + kappa)}


def deflection_bound(compliance_m_per_N, direction_rz, load_N, approach_m, exponent: float = 1.5) -> dict:
    """How much a ring's deflection under the elements' loads can change them (``auto``'s test).

    The ring's static deflection along each element's contact direction under all the element
    forces, d = Nᵀ C N Q (C the (2Z, 2Z) compliance to radial and axial forces at the Z elements, N
    the directions, Q the loads of a rigid-ring solution), changes the elements' approaches by up to
    Δr = max d − min d over the loaded ones (a part shared by all moves the ring and leaves the
    loads). Against the approach δ of the most loaded element, η = e·Δr/δ (Q ∝ δ^e: dQ/dδ = e·Q/δ;
    Q/δ grows with the load, so no element's load changes by more than η·Q_max to first order), and
    η/(1 + η) bounds the change relative to the largest load once the approaches are imposed.

    Returns ``deflection_difference_m`` Δr, ``stiffness_ratio`` η and ``load_change_bound``.
    """
    n = np.asarray(direction_rz, float).reshape(-1, 2)
    q = np.asarray(load_N, float)
    d = np.sum((np.asarray(compliance_m_per_N, float) @ (n * q[:, None]).ravel()).reshape(-1, 2) * n, axis=1)
    on = q > 0.0
    dr = float(d[on].max() - d[on].min()) if on.any() else 0.0
    delta = float(np.asarray(approach_m, float)[int(np.argmax(q))])
    eta = exponent * dr / delta if delta > 0.0 else 0.0
    return {"deflection_difference_m": dr, "stiffness_ratio": eta, "load_change_bound": eta / (1.0 + eta)}
