"""Chunked on-disk record of a run, its checkpoint, and the reader.

Layout of a run folder (described here only)::

    layout.json         names, shapes, units, time step, decimation, status ("running",
                        "complete" or "failed: <reason>"), number of chunks
    chunk_000000.npz    one chunk of samples, each array with the sample axis first:
                        t (k,) s; q (k, n_b, 7) positions m + quaternions (w, x, y, z);
                        v (k, n_b, 6) velocity m/s (world) + angular velocity rad/s (body);
                        eta, eta_dot (k, n_η) modal coordinates √kg and rates √kg/s (the modal
                        bodies' ranges in ``modal_ranges`` of layout.json);
                        fn, delta, slip, ft, angle, theta (k, n_c): normal force N, penetration m,
                        slip speed m/s, friction force N, contact angle rad, ball angle on its
                        groove rad (0 for other contacts); point, normal (k, n_c, 3) float32:
                        contact point m and unit normal of the force on the element, world
    checkpoint.npz      the integrator state after the last chunk: t_origin, step, q, v, eta,
                        eta_dot, body_f, body_t, modal_f, fric_c, fric_v, the contact outputs and n_chunks, from
                        which a run resumes bit for bit

Chunks and the checkpoint are written atomically (temporary file, then rename), so an interrupted
run leaves complete chunks only; ``layout.json`` says whether the run finished.

``layout.json`` also holds ``model_sha256``, the fingerprint of the model that wrote the record
(:func:`.model.model_fingerprint`, one hash per model array): a resume with another model (another
load, stiffness, mass…) is refused with the arrays that differ, as is one with another time step or
decimation. An unreadable layout or checkpoint raises :class:`RecordError` naming the file.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from foundation.npzfile import NPZ_ERRORS, read_npz
from .model import RECORDED_CONTACT_FIELDS, Model, fingerprint_differences, model_fingerprint

__all__ = ["RunRecord", "RecordError", "read_run", "FORMAT_VERSION"]


class RecordError(ValueError):
    """A run record or its checkpoint is unreadable or belongs to another run (names the file)."""

#: 2: contact points and normals recorded (a version 1 record is read without them, not resumed)
FORMAT_VERSION = 2
READABLE_VERSIONS = (1, 2)
UNITS = {"t": "s", "q": "m | quaternion", "v": "m/s | rad/s (body)", "eta": "√kg", "eta_dot": "√kg/s", "fn": "N", "delta": "m", "slip": "m/s",
         "ft": "N", "angle": "rad", "theta": "rad", "point": "m (world)", "normal": "1 (world)"}


def _atomic_save(path: Path, **arrays) -> None:
    tmp = path.with_name(path.name + ".tmp.npz")
    np.savez(tmp, **arrays)
    os.replace(tmp, path)


def _atomic_json(path: Path, data: dict) -> None:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(data, indent=1))
    os.replace(tmp, path)


class RunRecord:
    """Writer of one run folder (see the module docstring)."""

    def __init__(self, folder, model: Model, timestep_s: float, every: int, t_end_s: float, resume: bool = False):
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self.layout_path = self.folder / "layout.json"
        fingerprint = model_fingerprint(model)
        if resume:
            layout = _read_layout(self.folder)
            if layout.get("format_version") != FORMAT_VERSION:
                raise RecordError(f"{self.layout_path}: the record has format {layout.get('format_version')!r}, this "
                                  f"version writes {FORMAT_VERSION}; run again from the start")
            if "model_sha256" not in layout:
                raise RecordError(f"{self.layout_path}: the record holds no model fingerprint (written by an "
                                  f"older version), so a resume cannot be checked; run again from the start")
            differ = fingerprint_differences(layout["model_sha256"], fingerprint)
            if differ:
                raise RecordError(f"{self.layout_path}: the record was written by a different model: "
                                  f"{', '.join(differ)} differ; run again from the start")
            for key, value in (("timestep_s", timestep_s), ("every", every)):
                if layout[key] != value:
                    raise RecordError(f"{self.layout_path}: resume needs the record's {key} = {layout[key]!r}, "
                                      f"got {value!r}")
            self.layout = layout
        else:
            for old in self.folder.glob("chunk_*.npz"):
                old.unlink()
            (self.folder / "checkpoint.npz").unlink(missing_ok=True)
            self.layout = {
                "format_version": FORMAT_VERSION, "body_names": list(model.body_names),
                "pair_names": list(model.pair_names), "pair_kinds": list(model.pair_kinds),
                "timestep_s": timestep_s, "every": every, "t_end_s": t_end_s, "n_chunks": 0,
                "status": "running", "units": UNITS,
                "modal_ranges": {name: [int(a), int(b)] for name, a, b in _modal_ranges(model)},
                "model_sha256": fingerprint,
            }
        self.layout["t_end_s"] = t_end_s
        self.layout["status"] = "running"
        if not resume:  # a resume's layout is rewritten with its first checkpoint (a refused one leaves it)
            _atomic_json(self.layout_path, self.layout)

    def write_chunk(self, rec, k: int) -> None:
        """Store the first k samples of the buffers as the next chunk."""
        if k > 0:
            n = self.layout["n_chunks"]
            _atomic_save(self.folder / f"chunk_{n:06d}.npz", **{f: getattr(rec, f)[:k] for f in rec._fields})
            self.layout["n_chunks"] = n + 1

    def write_checkpoint(self, t_origin: float, step: int, state, work, energy_limit_J: float) -> None:
        _atomic_save(self.folder / "checkpoint.npz", t_origin=t_origin, step=step, q=state.q, v=state.v,
                     energy_limit_J=energy_limit_J,
                     eta=state.eta, eta_dot=state.eta_dot, n_chunks=self.layout["n_chunks"],
                     body_f=work.body_f, body_t=work.body_t, modal_f=work.modal_f, fric_c=work.fric_c,
                     fric_v=work.fric_v,
                     **{f: getattr(work, f"contact_{f}") for f in RECORDED_CONTACT_FIELDS})
        _atomic_json(self.layout_path, self.layout)

    def finish(self, status: str) -> None:
        self.layout["status"] = status
        _atomic_json(self.layout_path, self.layout)

    def load_checkpoint(self):
        path = self.folder / "checkpoint.npz"
        if not path.exists():
            raise FileNotFoundError(f"{self.folder}: no checkpoint to resume from")
        try:
            ck = read_npz(path)
            n_chunks = int(ck["n_chunks"])
        except NPZ_ERRORS as exc:
            raise RecordError(f"{path}: checkpoint unreadable ({type(exc).__name__}: {exc}); "
                              f"run again from the start") from None
        if n_chunks > self.layout["n_chunks"]:
            raise RecordError(f"{path}: checkpoint refers to {n_chunks} chunks, the layout lists "
                              f"{self.layout['n_chunks']}; run again from the start")
        self.layout["n_chunks"] = int(ck["n_chunks"])  # chunks written after the checkpoint are dropped
        return ck


def _modal_ranges(model: Model):
    """(body name, first, stop) of every modal body's coordinates within η."""
    a = model.arrays
    return [(model.body_names[int(i)], a.modal_off[j], a.modal_off[j + 1]) for j, i in enumerate(a.modal_body)]


def _read_layout(folder: Path) -> dict:
    path = Path(folder) / "layout.json"
    if not path.exists():
        raise FileNotFoundError(f"{folder}: not a run record (no layout.json)")
    try:
        layout = json.loads(path.read_text(encoding="utf-8"))
        for key in ("timestep_s", "every", "n_chunks"):
            layout[key]
    except (UnicodeDecodeError, ValueError, KeyError, TypeError) as exc:
        raise RecordError(f"{path}: run layout unreadable ({type(exc).__name__}: {exc})") from None
    return layout


def recorded_timestep_s(folder) -> float:
    """The time step of the run recorded in ``folder``, s."""
    return float(_read_layout(Path(folder))["timestep_s"])


def read_run(folder) -> dict:
    """Read a run folder: a dict of the concatenated arrays (see the module docstring) plus
    ``body_names``, ``pair_names``, ``pair_kinds``, ``status``, ``timestep_s`` and ``every``."""
    folder = Path(folder)
    layout = _read_layout(folder)
    if layout.get("format_version") not in READABLE_VERSIONS:
        raise ValueError(f"{folder}: record format {layout.get('format_version')} is not one of {READABLE_VERSIONS}")
    parts: dict[str, list] = {}
    for n in range(layout["n_chunks"]):
        path = folder / f"chunk_{n:06d}.npz"
        try:
            chunk = read_npz(path)
        except NPZ_ERRORS as exc:
            raise RecordError(f"{path}: record chunk unreadable ({type(exc).__name__}: {exc})") from None
        for k, a in chunk.items():
            parts.setdefault(k, []).append(a)
    out = {k: np.concatenate(v) for k, v in parts.items()}
    for key in ("body_names", "pair_names", "pair_kinds", "status", "timestep_s", "every"):
        out[key] = layout[key]
    out["modal_ranges"] = layout.get("modal_ranges", {})
    return out
