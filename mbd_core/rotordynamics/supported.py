"""Modes of a solid FE model held at chosen DOFs (a rotor on rigid supports).

A ball bearing holds a shaft's seat in translation and lets it tilt: holding the lateral (x, y)
displacement of every node of a seat face models that pinned support; holding z at one node
removes the axial rigid motion. The modes of the held model span the rotor's motion on rigid
supports; they are mass-normalised over the whole model (held DOFs zero) so the invariants of
:mod:`cms_reduction.invariants` apply to them unchanged.
"""

from __future__ import annotations

import math

import numpy as np

from fem_rings.linalg import shift_invert_operator
from fem_rings.modal_basis import deflated_eigsh
from fem_rings.model import FEModel, vector_dofs

__all__ = ["held_dofs", "supported_modes"]

_AXES = {"x": 0, "y": 1, "z": 2}


def held_dofs(n_nodes: int, holds) -> np.ndarray:
    """Sorted DOF indices held by ``holds``: (node indices, components such as ``"xy"``) pairs."""
    out = []
    for nodes, comps in holds:
        nodes = np.asarray(nodes, dtype=np.int64).ravel()
        bad = sorted(set(comps) - set(_AXES))
        if bad or not comps:
            raise ValueError(f"held components must be letters of 'xyz', got {comps!r}")
        if len(nodes) == 0:
            raise ValueError("a hold names no nodes")
        if nodes.min() < 0 or nodes.max() >= n_nodes:
            raise ValueError(f"held node indices must lie in 0…{n_nodes - 1}")
        out.append(vector_dofs(nodes, tuple(_AXES[c] for c in comps)))
    return np.unique(np.concatenate(out)) if out else np.zeros(0, dtype=np.int64)


def supported_modes(model: FEModel, holds, n_modes: int) -> tuple[np.ndarray, np.ndarray]:
    """The lowest ``n_modes`` modes of ``model`` with the DOFs of ``holds`` held.

    Returns
    -------
    frequencies_Hz : (n_modes,) float64
    shapes : (3N, n_modes) float64, m/√kg
        Mass-normalised over the whole model, zero at the held DOFs.
    """
    n = model.n_dofs
    held = held_dofs(len(model.nodes_m), holds)
    free = np.setdiff1d(np.arange(n), held)
    K = model.K.tocsr()[free][:, free]
    M = model.M.tocsr()[free][:, free]
    sigma = -(2.0 * math.pi) ** 2  # below a rigid motion the holds may leave free
    op, _ = shift_invert_operator(K, M, sigma)
    lam, vec = deflated_eigsh(K, M, int(n_modes), sigma, op)
    shapes = np.zeros((n, vec.shape[1]))
    shapes[free] = vec
    return np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * math.pi), shapes
