"""A modal body prestressed by its own spin: the stress stiffening of a rotor at its running speed.

A body spinning at Ω about its z axis carries the centrifugal prestress of Ω² ρ (x, y, 0), whose
geometric stiffness adds Ω² S to the modal stiffness, S = Φᵀ K_σ Φ at 1 rad/s
(:func:`fem_rings.spinning.centrifugal_geometric_stiffness`, stored by :func:`.pipeline.reduced_body`
with ``ReductionSpec(spin_stiffening=True)`` as ``extras["spin_stiffening"]``). The floating frame's
inertia terms carry the spin softening of a body that turns (the −ωᵀ G_k ω of
:mod:`.invariants`) but not this stiffening, which comes from the stress state, not from the motion;
without it a disc's tilt softens with speed although a rigid disc's tilt does not (1–2 % of a
whirl frequency at 1 000 rad/s in ``tests/test_rotordynamics.py``, growing with Ω²).

:func:`prestressed` folds Ω² S into the basis: the symmetric eigenproblem

    (diag(ω²) + Ω² S) Ψ = Ψ diag(ω'²),     Ψᵀ Ψ = I,

gives mass-normalised shapes Φ' = Φ Ψ whose modal stiffness diag(ω'²) holds the stiffening at Ω, so
the multibody kernels take the body unchanged (K.-J. Bathe, *Finite Element Procedures*, 2nd ed.
2014, §6.3.2 for the initial-stress stiffness; the same change of basis as a prestressed modal
analysis). Every extra that is linear in the modes turns with Ψ (invariants I3, I4, I8 once, I5, I6,
I9 twice; raceway samples; stress modes; S itself). The stiffening is that of one speed: it fits a
run at (or near) that speed; it grows with Ω², so at 0.9 Ω it is 23 % too high.

Modal damping diag(2ζω) does not stay diagonal under Ψ; each new mode takes the ζ of the old modes
weighted by its share Ψ_kj² of each (exact for a uniform ζ in the ratio, not in 2ζω).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from .body import ReducedBody
from .invariants import Invariants

__all__ = ["SPIN_STIFFENING", "prestressed"]

SPIN_STIFFENING = "spin_stiffening"


def _turn_invariants(inv: Invariants, psi: np.ndarray) -> Invariants:
    once = lambda a: a @ psi  # noqa: E731  (last axis is the mode)
    twice = lambda a: np.einsum("...kl,kp,lq->...pq", a, psi, psi)  # noqa: E731
    return replace(inv, I3_translational_sqrtkg_m=once(inv.I3), I4_rotational_sqrtkg_m2=once(inv.I4),
                   I5_modal_cross_m2=twice(inv.I5), I6_modal_mass=twice(inv.I6),
                   I8_inertia_linear_sqrtkg_m2=once(inv.I8), I9_inertia_quadratic_m2=twice(inv.I9))


def prestressed(body: ReducedBody, speed_rad_s: float) -> ReducedBody:
    """``body`` with the centrifugal stress stiffening of spinning at ``speed_rad_s`` about its z axis
    folded into its modes (module docstring)."""
    if SPIN_STIFFENING not in body.extras:
        raise ValueError(f"body {body.name!r}: no stress stiffening stored; reduce it with "
                         "ReductionSpec(spin_stiffening=True)")
    w = float(speed_rad_s)
    if not math.isfinite(w):
        raise ValueError(f"body {body.name!r}: speed_rad_s must be finite, got {speed_rad_s!r}")
    S = np.asarray(body.extras[SPIN_STIFFENING], dtype=float)
    lam, psi = np.linalg.eigh(np.diag(body.omega_rad_s ** 2) + w * w * 0.5 * (S + S.T))
    scale = max(float(np.max(np.abs(lam))), 1.0)
    if lam[0] < -1e-9 * scale:
        raise ValueError(f"body {body.name!r}: the prestress at {w:g} rad/s leaves a mode with negative "
                         f"stiffness ({lam[0]:.3g} 1/s²)")
    psi = psi * np.where(psi[np.argmax(np.abs(psi), axis=0), np.arange(psi.shape[1])] < 0.0, -1.0, 1.0)
    extras = {}
    inv = Invariants.from_arrays(body.extras)
    for key, value in body.extras.items():
        a = np.asarray(value)
        if key.startswith("sample:") and (key.endswith(":displacement") or key.endswith(":rotation")):
            extras[key] = a @ psi
        elif key in ("stress_modes",):
            extras[key] = a @ psi
        elif key == SPIN_STIFFENING:
            extras[key] = psi.T @ S @ psi
        else:
            extras[key] = value
    extras.update(_turn_invariants(inv, psi).to_arrays())
    zeta = (psi ** 2).T @ np.asarray(body.damping_ratio, dtype=float)
    return replace(body, shapes=body.shapes @ psi, frequencies_Hz=np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * math.pi),
                   damping_ratio=zeta, extras=extras,
                   metadata={**body.metadata, "prestress_speed_rad_s": w})
