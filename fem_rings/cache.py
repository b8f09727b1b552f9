"""On-disk cache of expensive products (meshes, FE matrices), keyed by a hash of their inputs.

The key is a SHA-256 of a canonical JSON description of the inputs (dataclasses are expanded field
by field) plus a format version, so any change of profile, mesh size, element or material gives a
new entry. Files are written atomically (temporary name, then rename): an interrupted run never
leaves an entry that looks complete.

The folder is ``$FLEXBEARING_CACHE`` if set, else ``~/.cache/flexbearing``.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import logging
import os
import uuid
from contextlib import contextmanager
from pathlib import Path

import numpy as np

__all__ = ["atomic_path", "cache_dir", "input_hash", "load_arrays", "save_arrays"]

log = logging.getLogger(__name__)

#: Bump when the stored layout changes: old entries are then simply not found.
FORMAT_VERSION = 1


def cache_dir() -> Path:
    """The cache folder (created on first use)."""
    root = os.environ.get("FLEXBEARING_CACHE") or Path.home() / ".cache" / "flexbearing"
    return Path(root)


def _canonical(obj):
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {"__type__": type(obj).__name__,
                **{f.name: _canonical(getattr(obj, f.name)) for f in dataclasses.fields(obj)}}
    if isinstance(obj, dict):
        return {str(k): _canonical(v) for k, v in sorted(obj.items(), key=lambda kv: str(kv[0]))}
    if isinstance(obj, (list, tuple)):
        return [_canonical(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return {"__array__": hashlib.sha256(np.ascontiguousarray(obj).tobytes()).hexdigest(),
                "shape": list(obj.shape), "dtype": str(obj.dtype)}
    if isinstance(obj, (float, np.floating)):
        return repr(float(obj))
    if isinstance(obj, (bool, int, str, type(None), np.integer)):
        return obj if not isinstance(obj, np.integer) else int(obj)
    raise TypeError(f"cannot hash input of type {type(obj).__name__}")


def input_hash(kind: str, *inputs) -> str:
    """Hex digest identifying a product of ``kind`` made from ``inputs``."""
    payload = json.dumps({"kind": kind, "version": FORMAT_VERSION, "inputs": _canonical(list(inputs))},
                         sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(payload.encode()).hexdigest()[:24]


def _path(kind: str, key: str) -> Path:
    return cache_dir() / kind / f"{key}.npz"


def load_arrays(kind: str, key: str) -> dict | None:
    """Stored arrays of an entry, or None when absent or unreadable."""
    p = _path(kind, key)
    if not p.exists():
        return None
    try:
        with np.load(p, allow_pickle=False) as f:
            return {k: f[k] for k in f.files}
    except (OSError, ValueError) as exc:
        log.warning("ignoring unreadable cache entry %s: %s", p, exc)
        return None


def save_arrays(kind: str, key: str, arrays: dict) -> Path:
    """Store arrays atomically; returns the file."""
    p = _path(kind, key)
    with atomic_path(p, ".npz") as tmp:
        np.savez(tmp, **arrays)
    return p


@contextmanager
def atomic_path(path: Path, suffix: str = ""):
    """Yield a temporary file name next to ``path``; rename it to ``path`` on success.

    The file appears under its final name only when complete (``os.replace`` within one folder
    is atomic on POSIX and Windows); on error the temporary file is removed.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    # a unique name that the writer creates itself, so the file gets the usual permissions
    # (tempfile.mkstemp would leave it readable by the owner only)
    tmp = path.with_name(f".{path.name}.{os.getpid()}-{uuid.uuid4().hex[:12]}.part{suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
