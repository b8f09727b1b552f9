"""Stress modes: the nodal stress tensor of every mode, so σ(x, t) = Σ_j η_j(t) σ_j(x).

Linear elasticity makes stress linear in the displacement, hence in the modal coordinates: the
stress of each mass-normalised mode (Pa/√kg per unit η) is recovered once with
:func:`fem_rings.stress.nodal_stress_Pa` and combined at any instant. Von Mises is not linear and is
formed after the combination.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from fem_rings.model import FEModel
from fem_rings.stress import nodal_stress_Pa, von_mises_Pa
from foundation.progress import phase

from .body import ReducedBody

__all__ = ["add_stress_modes", "modal_stress_Pa", "render_modal_state"]


def add_stress_modes(body: ReducedBody, model: FEModel) -> ReducedBody:
    """A copy of ``body`` with ``extras["stress_modes"]`` (N, 6, m), Pa per unit η (Voigt order)."""
    if model.ring.n_nodes != len(body.nodes_m) or not np.array_equal(model.nodes_m, body.nodes_m):
        raise ValueError(f"body {body.name!r} was not reduced from this FE model (nodes differ)")
    modes = np.empty((len(body.nodes_m), 6, body.n_modes))
    with phase("stress modes", total=body.n_modes) as p:
        for j in range(body.n_modes):
            modes[:, :, j] = nodal_stress_Pa(model, body.shapes[:, j])
            p.advance()
    return replace(body, extras={**body.extras, "stress_modes": modes})


def modal_stress_Pa(body: ReducedBody, eta: np.ndarray) -> np.ndarray:
    """Nodal stress tensors (N, 6) Pa of modal coordinates η (m,)."""
    if "stress_modes" not in body.extras:
        raise ValueError(f"body {body.name!r} has no stress modes; build them with add_stress_modes")
    return body.extras["stress_modes"] @ np.asarray(eta, dtype=float)


def render_modal_state(body: ReducedBody, eta: np.ndarray, path: str | Path, title: str | None = None) -> Path:
    """Off-screen PNG of the deformed body coloured by von Mises stress (MPa) for modal coordinates η."""
    from fem_rings.render import render_png

    vm = von_mises_Pa(modal_stress_Pa(body, eta))
    return render_png(path, body.mesh(), vm, label="von Mises", unit="MPa", scale=1e-6,
                      displacement_m=body.displacement_m(eta), title=title or body.name)
