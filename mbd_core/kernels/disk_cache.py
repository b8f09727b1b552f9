"""What numba's disk cache holds for a kernel (``@njit(cache=True)``).

Reads numba's own index file of the kernel; any failure to read it counts as "nothing cached", so
that a change of numba's internals costs a compilation, never a wrong answer.
"""

from __future__ import annotations

__all__ = ["has_cached_overloads"]


def has_cached_overloads(kernel) -> bool:
    """True when the disk cache holds at least one current (source unchanged) compilation of ``kernel``."""
    try:
        return bool(kernel._cache._cache_file._load_index())
    except Exception:  # noqa: BLE001 (numba internals; see the module docstring)
        return False
