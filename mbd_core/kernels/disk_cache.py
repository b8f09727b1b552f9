"""What numba's disk cache holds for a kernel (``@njit(cache=True, …)``), and keeping it current.

numba keys a kernel's cached machine code on the modification stamp of the kernel's own source
file only. A kernel that calls kernels of other files (the force stage calls the contact families,
which inline the point-contact and frame helpers) embeds their code, so a change in a helper's file
leaves the caller's cached code stale: a silent wrong answer after an update of a source checkout.
:func:`invalidate_on_source_change` closes that gap: it hashes the sources of every kernel module
(and the numba version) and, when the hash differs from the one stored beside the cache, empties the
cache index of every kernel of the package (numba's own ``flush``), so that each compiles afresh once.

Reading numba's index counts any failure as "nothing cached", so that a change of numba's internals
costs a compilation, never a wrong answer.
"""

from __future__ import annotations

import hashlib
import importlib
import logging
from pathlib import Path

import numba
from numba.core.registry import CPUDispatcher

from foundation.files import atomic_path

__all__ = ["has_cached_overloads", "invalidate_on_source_change", "sources_hash"]

log = logging.getLogger(__name__)

_STAMP = "flexbearing-kernels.sha256"


def has_cached_overloads(kernel) -> bool:
    """True when the disk cache holds at least one current (source unchanged) compilation of ``kernel``."""
    try:
        return bool(kernel._cache._cache_file._load_index())
    except Exception:  # noqa: BLE001 (numba internals; see the module docstring)
        return False


def sources_hash(folder: Path) -> str:
    """SHA-256 of the numba version and of every ``*.py`` file of ``folder`` (names and contents)."""
    h = hashlib.sha256(numba.__version__.encode())
    for path in sorted(Path(folder).glob("*.py")):
        h.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


def _kernels(package: str, folder: Path):
    """The cached kernels (dispatchers with a disk cache) defined in the modules of ``package``."""
    for path in sorted(Path(folder).glob("*.py")):
        if path.stem == "__init__":
            continue
        module = importlib.import_module(f"{package}.{path.stem}")
        for obj in vars(module).values():
            if isinstance(obj, CPUDispatcher) and obj.__module__ == module.__name__ and obj._cache is not None:
                yield obj


def invalidate_on_source_change(package: str, folder) -> bool:
    """Empty the disk-cache index of every kernel of ``package`` (source folder ``folder``) when the
    package's sources changed since the cache was written; returns True when it did."""
    folder = Path(folder)
    digest = sources_hash(folder)
    try:
        kernels = list(_kernels(package, folder))
        cache_dirs = {Path(k._cache._cache_path) for k in kernels}
    except Exception:  # noqa: BLE001 (numba internals: no cache to keep current)
        log.debug("numba cache locations unknown", exc_info=True)
        return False
    stale = [d for d in cache_dirs if not _stamp_matches(d / _STAMP, digest)]
    if not stale:
        return False
    for kernel in kernels:
        if Path(kernel._cache._cache_path) in stale:
            try:
                kernel._cache.flush()
            except OSError as exc:  # a read-only cache: numba then compiles without saving
                log.debug("could not empty the cache index of %s: %s", kernel.__name__, exc)
    for d in stale:
        try:
            with atomic_path(d / _STAMP) as tmp:
                tmp.write_text(digest, encoding="ascii")
        except OSError as exc:
            log.debug("could not write %s: %s", d / _STAMP, exc)
    log.info("kernel sources changed since their compilation was cached: they compile afresh")
    return True


def _stamp_matches(path: Path, digest: str) -> bool:
    try:
        return path.read_text(encoding="ascii").strip() == digest
    except (OSError, UnicodeDecodeError):
        return False
