"""On-disk cache of expensive products (meshes, FE matrices), keyed by a hash of their inputs.

The key is a SHA-256 of a canonical JSON description of the inputs (dataclasses are expanded field
by field) plus a format version, so any change of profile, mesh size, element or material gives a
new entry. Files are written atomically (temporary name, then rename): an interrupted run never
leaves an entry that looks complete; the temporary files of killed runs (``.NAME.<pid>-<hex>.part*``)
are removed at the next use of their folder once their process is gone.

Every entry holds the SHA-256 of its arrays (:func:`content_hash`), checked on load: an entry that
is unreadable (truncated, bad CRC, missing member) or whose arrays do not match the hash is
reported (a warning naming the file), treated as absent and rebuilt. A cache that cannot be written
(disk full, read-only, the cache path is a file) costs a warning and the rebuild next time, not
the run.

The folder is ``$FLEXBEARING_CACHE`` if set, else ``~/.cache/flexbearing``.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import logging
import os
import re
import time
from pathlib import Path

import numpy as np

from foundation.files import atomic_path  # (here too, where its callers have always found it)
from foundation.npzfile import NPZ_ERRORS, read_npz

__all__ = ["atomic_path", "cache_dir", "clean_stale_parts", "content_hash", "file_digest", "input_hash", "load_arrays",
           "process_alive", "save_arrays"]

log = logging.getLogger(__name__)

#: Bump when the stored layout changes: old entries are then simply not found.
#: 2: entries carry the content hash ``HASH_KEY``.
FORMAT_VERSION = 2

#: name of the content hash inside an entry
HASH_KEY = "__content_sha256__"
#: temporary files older than this are stale even if their process id is in use again, s
STALE_PART_AGE_S = 24 * 3600.0
_PART = re.compile(r"^\..+\.(?P<pid>\d+)-[0-9a-f]{12}\.part(\.\w+)?$")
_cleaned: set = set()


def cache_dir() -> Path:
    """The cache folder (created on first use)."""
    root = os.environ.get("FLEXBEARING_CACHE") or Path.home() / ".cache" / "flexbearing"
    return Path(root)


def _hashed(f: dataclasses.Field, obj) -> bool:
    """Whether a dataclass field enters the hash: ``metadata={"hash": False}`` leaves it out (a file's
    path beside its digest); ``"if-set"`` leaves it out while it is None (an optional field added
    later, so that the keys of products made without it do not change)."""
    how = f.metadata.get("hash", True)
    return how is True or (how == "if-set" and getattr(obj, f.name) is not None)


def _canonical(obj):
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {"__type__": type(obj).__name__,
                **{f.name: _canonical(getattr(obj, f.name)) for f in dataclasses.fields(obj) if _hashed(f, obj)}}
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


def file_digest(path) -> str:
    """SHA-256 (hex) of a file's bytes (OSError when it cannot be read): what a cache key holds for
    an input file, so that an edited file is seen and a moved one is not."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def content_hash(arrays: dict) -> str:
    """SHA-256 (hex) of named arrays: names, dtypes, shapes and bytes, in name order."""
    h = hashlib.sha256()
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}\x00{a.dtype.str}\x00{a.shape}\x00".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def _discard(p: Path, why: str) -> None:
    log.warning("cache entry %s is unusable (%s): rebuilding it", p, why)
    try:
        p.unlink()
    except OSError:
        pass


def load_arrays(kind: str, key: str) -> dict | None:
    """Stored arrays of an entry, or None when absent, unreadable or not matching its hash."""
    p = _path(kind, key)
    clean_stale_parts(p.parent)
    if not p.is_file():
        return None
    try:
        arrays = read_npz(p)
        recorded = str(arrays.pop(HASH_KEY))
    except NPZ_ERRORS as exc:
        _discard(p, f"{type(exc).__name__}: {exc}")
        return None
    if content_hash(arrays) != recorded:
        _discard(p, "content does not match its SHA-256: corrupt or modified")
        return None
    return arrays


def save_arrays(kind: str, key: str, arrays: dict) -> Path | None:
    """Store arrays atomically with their content hash; returns the file, or None (with a
    warning) when the cache cannot be written."""
    p = _path(kind, key)
    try:
        clean_stale_parts(p.parent)
        with atomic_path(p, ".npz") as tmp:
            np.savez(tmp, **arrays, **{HASH_KEY: np.array(content_hash(arrays))})
    except OSError as exc:
        log.warning("could not write cache entry %s (%s): going on without it", p, exc)
        return None
    return p


def process_alive(pid: int) -> bool:
    """True when a process ``pid`` exists on this machine (this process included); the owner
    test of the temporary files and folders of killed runs."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # exists, owned by another user
        return True
    return True


def clean_stale_parts(folder: Path) -> None:
    """Remove the temporary files of killed writers in ``folder`` (once per process and folder).

    A file ``.NAME.<pid>-<hex>.part*`` (:func:`atomic_path`) is stale when process ``pid`` no
    longer exists or the file is older than :data:`STALE_PART_AGE_S`; writers still running keep
    theirs."""
    folder = Path(folder)
    if folder in _cleaned:
        return
    _cleaned.add(folder)
    try:
        entries = list(folder.iterdir())
    except OSError:
        return
    now = time.time()
    for p in entries:
        m = _PART.match(p.name)
        if not m:
            continue
        try:
            if not process_alive(int(m["pid"])) or now - p.stat().st_mtime > STALE_PART_AGE_S:
                p.unlink()
                log.info("removed %s left by a killed run", p)
        except OSError:
            pass


