"""A long explicit run of a case's model in pieces, for the progress bar and for resuming (shared by the cases).

Each piece is an independent :func:`mbd_core.multibody.explicit.simulate` from the state at the
end of the previous one. Inside :func:`checkpoints` (``flexbearing run --resume``), every finished
piece is stored (its record and end state, written atomically) in a slot of the checkpoint folder,
one slot per :func:`integrate` call in call order; a resumed run loads the stored pieces and goes
on from the first missing one, so it gives bit for bit the record of an uninterrupted run. A slot
remembers the model's fingerprint (:func:`mbd_core.multibody.model.model_fingerprint`) and the run
settings: a resume against another model or other settings is refused, naming what differs.
"""

from __future__ import annotations

import json
import logging
import math
import shutil
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path

import numpy as np

from fem_rings.cache import atomic_path
from mbd_core.multibody.explicit import simulate
from mbd_core.multibody.model import State, fingerprint_differences, model_fingerprint
from foundation.npzfile import NPZ_ERRORS, read_npz

from .config import CaseError

__all__ = ["integrate", "integrate_implicit", "checkpoints", "checkpoint_folder", "ResumeError", "IMPLICIT_STEP_FACTOR"]

log = logging.getLogger(__name__)

_MANIFEST = "run.json"
_STATE = ("t", "q", "v", "eta", "eta_dot")


class ResumeError(CaseError):
    """A stored run cannot be continued with this model or these settings (names what differs)."""


class _Store:
    """Slots of one case run's explicit runs in ``folder`` (``resume``: reuse stored pieces)."""

    def __init__(self, folder: Path, resume: bool):
        self.folder, self.resume, self.count = Path(folder), resume, 0

    def next_slot(self) -> Path:
        slot = self.folder / f"run_{self.count:02d}"
        self.count += 1
        return slot


_STORE: ContextVar[_Store | None] = ContextVar("cases_integrate_store", default=None)


def checkpoint_folder() -> tuple[Path, bool] | None:
    """(folder, resume) of the case run going on: its checkpoint folder and whether it resumes an
    interrupted run; None outside :func:`checkpoints`."""
    store = _STORE.get()
    return None if store is None else (store.folder, store.resume)


@contextmanager
def checkpoints(folder, resume: bool = False):
    """Store the pieces of every :func:`integrate` in the block under ``folder`` (``resume``: reuse them)."""
    token = _STORE.set(_Store(folder, resume))
    try:
        yield
    finally:
        _STORE.reset(token)


def _settings(state: State, duration_s: float, record_every: int, chunks: int, adaptive: bool,
              timestep_s: float | None) -> dict:
    start = {k: np.asarray(getattr(state, k), float).tolist() for k in _STATE}
    out = {"duration_s": float(duration_s), "record_every": int(record_every), "chunks": int(chunks),
           "adaptive": bool(adaptive), "start_state": start}
    if timestep_s is not None:  # (absent: the automatic step, as in slots stored before the key existed)
        out["timestep_s"] = float(timestep_s)
    return out


def _open_slot(slot: Path, resume: bool, manifest: dict) -> bool:
    """Prepare ``slot``; True when its stored pieces may be reused (raises when they belong elsewhere)."""
    path = slot / _MANIFEST
    if resume and path.exists():
        try:
            old = json.loads(path.read_text(encoding="utf-8"))
            old["model_sha256"], old["settings"]
        except (OSError, UnicodeDecodeError, ValueError, KeyError, TypeError) as exc:
            raise ResumeError(f"{path}: stored run unreadable ({exc}); run again without --resume") from None
        differ = fingerprint_differences(old["model_sha256"], manifest["model_sha256"])
        if differ:
            raise ResumeError(f"cannot resume from {slot}: the model differs from the interrupted run's "
                              f"({', '.join(differ)}); run again without --resume")
        for key, value in manifest["settings"].items():
            if old["settings"].get(key) != value:
                what = "start state" if key == "start_state" else key
                raise ResumeError(f"cannot resume from {slot}: the run's {what} differs from the interrupted "
                                  f"run's; run again without --resume")
        return True
    if slot.exists():
        shutil.rmtree(slot)
    slot.mkdir(parents=True)
    with atomic_path(path, ".json") as tmp:
        tmp.write_text(json.dumps(manifest), encoding="utf-8")
    return False


def _save_piece(path: Path, out: dict, state: State) -> None:
    arrays = {f"rec:{k}": v for k, v in out.items() if isinstance(v, np.ndarray)}
    meta = {k: v for k, v in out.items() if not isinstance(v, np.ndarray)}
    arrays.update({f"state:{k}": np.asarray(getattr(state, k), float) for k in _STATE})
    with atomic_path(path, ".npz") as tmp:
        np.savez(tmp, meta=np.array(json.dumps(meta)), **arrays)


def _load_piece(path: Path, state: State) -> dict | None:
    """A stored piece (its end state copied into ``state``), or None when absent or unreadable."""
    if not path.exists():
        return None
    try:
        d = read_npz(path)
        out = json.loads(str(d["meta"]))
        end = {k: d[f"state:{k}"] for k in _STATE}
    except NPZ_ERRORS as exc:
        log.warning("recomputing from %s: stored piece unreadable (%s)", path, exc)
        return None
    if "rec:point" not in d:  # every piece of that run lacks them: the run is recomputed from its start
        log.warning("recomputing from %s: stored piece written before contact points were recorded", path)
        return None
    out.update({k[4:]: v for k, v in d.items() if k.startswith("rec:")})
    state.t = float(end["t"])
    state.q[:], state.v[:] = end["q"], end["v"]
    state.eta, state.eta_dot = end["eta"].copy(), end["eta_dot"].copy()
    return out


def integrate(model, state, duration_s: float, record_every: int, progress=None, chunks: int = 40,
              adaptive: bool = False, timestep_s: float | None = None) -> dict:
    """Explicit integration of ``model`` for ``duration_s`` from ``state`` in ``chunks`` pieces.

    The first piece's automatic step is kept for all, or (``adaptive``) each piece takes the
    automatic step of its own start, for scenes whose loads grow far beyond the start's (the
    step of a contact law stiffening with its load shrinks); ``timestep_s`` of the result is then
    the smallest. ``timestep_s`` given: every piece takes that step (a step above the explicit
    stability limit raises :class:`mbd_core.multibody.StepTooLargeError`, which names the limit).
    ``progress(iterable, label)`` wraps the pieces (a progress bar) when given.
    Inside :func:`checkpoints` the pieces are stored and, on a resume, reused (module docstring).

    Raises
    ------
    ResumeError
        Resuming, and the stored run has another model or other settings.
    """
    t0 = state.t
    ends = t0 + duration_s * np.arange(1, chunks + 1) / chunks
    store = _STORE.get()
    slot, reuse = None, False
    if store is not None:
        slot = store.next_slot()
        manifest = {"model_sha256": model_fingerprint(model),
                    "settings": _settings(state, duration_s, record_every, chunks, adaptive, timestep_s)}
        reuse = _open_slot(slot, store.resume, manifest)
    if timestep_s is not None and adaptive:
        raise ValueError("integrate: give either timestep_s or adaptive, not both")
    parts, h, h_min = [], timestep_s, math.inf
    for i, t_end in enumerate(progress(ends, "simulated") if progress else ends):
        piece = slot / f"piece_{i:03d}.npz" if slot is not None else None
        out = _load_piece(piece, state) if reuse else None
        if out is None:
            reuse = False  # every later piece starts from this one's end
            out = simulate(model, state, float(t_end), timestep_s=None if adaptive else h,
                           record_every=record_every)
            if piece is not None:
                _save_piece(piece, out, state)
        h = out["timestep_s"]
        h_min = min(h_min, h)
        parts.append(out if not parts else {k: (v[1:] if isinstance(v, np.ndarray) else v) for k, v in out.items()})
    run = {k: (np.concatenate([p[k] for p in parts]) if isinstance(parts[0][k], np.ndarray) else parts[0][k])
           for k in parts[0]}
    run["timestep_s"] = h_min
    return run


#: the implicit run's default step over the automatic explicit one: on the 1 m slewing ring
#: (rotation quick, 0.4 s) every ball load then lies within 2.8e-7 of the mean load of the explicit run
IMPLICIT_STEP_FACTOR = 20.0


def integrate_implicit(model, state, duration_s: float, record_every: int, rho_inf: float,
                       timestep_s: float | None = None, key: str = "analysis.timestep_s",
                       step_factor: float = IMPLICIT_STEP_FACTOR) -> dict:
    """The run with the implicit generalized-α integrator (:func:`mbd_core.multibody.implicit.simulate_implicit`),
    in one piece (no checkpoints: a resumed run starts again), at ``timestep_s`` or ``step_factor``
    × the automatic explicit step. A run that diverges, or whose Newton iteration fails, stops with
    a :class:`CaseError` naming ``key`` (the case key that sets the step)."""
    from mbd_core.multibody import DivergenceError, stable_timestep
    from mbd_core.multibody.implicit import simulate_implicit

    h = timestep_s or step_factor * stable_timestep(model, state).timestep_s
    try:
        return simulate_implicit(model, state, state.t + duration_s, h, rho_inf=rho_inf, record_every=record_every)
    except DivergenceError as exc:
        raise CaseError(f"{key}: the implicit run at the step {h:.3g} s failed: {exc}") from None
