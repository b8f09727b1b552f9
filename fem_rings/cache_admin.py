"""Housekeeping of the model cache: what it holds, and removing entries not used for a while.

An entry is the file group ``<kind>/<key>.*`` with a 24-hex-digit ``key`` (:func:`fem_rings.cache.
input_hash`): an ``.npz`` and, for reduced bodies, its ``.json`` sidecar. Only such files and the
stale temporary files of killed writes (:func:`fem_rings.cache.clean_stale_parts`) are ever removed;
anything else in the folder is left alone. An entry's last use is the latest access or change time
of its files (access times on Linux's default ``relatime`` mounts are exact to within a day).
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass
from pathlib import Path

from .cache import cache_dir, clean_stale_parts

__all__ = ["CacheEntry", "cache_entries", "remove_entries", "summarise"]

_ENTRY_FILE = re.compile(r"^(?P<key>[0-9a-f]{24})\.(npz|json)$")
DAY_S = 86400.0


@dataclass(frozen=True)
class CacheEntry:
    """One cached product: its kind folder, key, files, size (bytes) and last use (epoch s)."""

    kind: str
    key: str
    files: tuple[Path, ...]
    size_bytes: int
    last_used_s: float


def cache_entries(root: Path | None = None) -> list[CacheEntry]:
    """Entries under ``root`` (default :func:`cache_dir`), oldest use first; [] when there is no cache."""
    root = cache_dir() if root is None else Path(root)
    groups: dict[tuple[str, str], list[Path]] = {}
    if not root.is_dir():
        return []
    for kind_dir in sorted(p for p in root.iterdir() if p.is_dir() and not p.is_symlink()):
        for f in kind_dir.iterdir():
            m = _ENTRY_FILE.match(f.name)
            if m and f.is_file() and not f.is_symlink():
                groups.setdefault((kind_dir.name, m["key"]), []).append(f)
    entries = []
    for (kind, key), files in groups.items():
        stats = [f.stat() for f in files]
        entries.append(CacheEntry(kind, key, tuple(sorted(files)), sum(s.st_size for s in stats),
                                  max(max(s.st_atime, s.st_mtime) for s in stats)))
    return sorted(entries, key=lambda e: e.last_used_s)


def summarise(entries: list[CacheEntry]) -> dict:
    """Per kind and in total: number of entries and bytes."""
    kinds: dict[str, dict] = {}
    for e in entries:
        k = kinds.setdefault(e.kind, {"entries": 0, "size_bytes": 0})
        k["entries"] += 1
        k["size_bytes"] += e.size_bytes
    return {"kinds": kinds, "entries": len(entries), "size_bytes": sum(e.size_bytes for e in entries)}


def remove_entries(older_than_days: float | None = None, root: Path | None = None,
                   now_s: float | None = None) -> list[CacheEntry]:
    """Delete the entries not used for ``older_than_days`` (all when None) and stale temporary files.

    Returns the removed entries. Raises ValueError for a negative or non-finite age.
    """
    if older_than_days is not None and not (0.0 <= older_than_days < float("inf")):
        raise ValueError(f"--older-than-days must be a finite number ≥ 0, got {older_than_days}")
    root = cache_dir() if root is None else Path(root)
    now_s = time.time() if now_s is None else now_s
    removed = []
    for e in cache_entries(root):
        if older_than_days is not None and now_s - e.last_used_s < older_than_days * DAY_S:
            continue
        for f in e.files:
            f.unlink(missing_ok=True)
        removed.append(e)
    if root.is_dir():
        for kind_dir in (p for p in root.iterdir() if p.is_dir() and not p.is_symlink()):
            clean_stale_parts(kind_dir)
    return removed
