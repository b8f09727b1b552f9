"""A long explicit run of a case's model in pieces, for the progress bar (shared by the cases)."""

from __future__ import annotations

import math

import numpy as np

from mbd_core.multibody.explicit import simulate

__all__ = ["integrate"]


def integrate(model, state, duration_s: float, record_every: int, progress=None, chunks: int = 40,
              adaptive: bool = False) -> dict:
    """Explicit integration of ``model`` for ``duration_s`` from ``state`` in ``chunks`` pieces.

    The first piece's automatic step is kept for all, or (``adaptive``) each piece takes the
    automatic step of its own start, for scenes whose loads grow far beyond the start's (the
    step of a contact law stiffening with its load shrinks); ``timestep_s`` of the result is then
    the smallest. ``progress(iterable, label)`` wraps the pieces (a progress bar) when given."""
    t0 = state.t
    ends = t0 + duration_s * np.arange(1, chunks + 1) / chunks
    parts, h, h_min = [], None, math.inf
    for t_end in (progress(ends, "simulated") if progress else ends):
        out = simulate(model, state, float(t_end), timestep_s=None if adaptive else h, record_every=record_every)
        h = out["timestep_s"]
        h_min = min(h_min, h)
        parts.append(out if not parts else {k: (v[1:] if isinstance(v, np.ndarray) else v) for k, v in out.items()})
    run = {k: (np.concatenate([p[k] for p in parts]) if isinstance(parts[0][k], np.ndarray) else parts[0][k])
           for k in parts[0]}
    run["timestep_s"] = h_min
    return run
