"""Kernel compilation as a progress phase: shown when numba compiles, not when it loads its cache.

numba's dispatcher looks a signature up in the on-disk cache first and raises its
``numba:compile`` event only on a miss, around the actual compilation. A listener on that event
opens one :func:`foundation.progress.phase` for the outermost compilation (kernels called from a
kernel compile inside it, as nested events) with the name of the kernel being compiled, and closes it
when that compilation ends, so the phase's time is the measured compile time (one-off work: left
out of the time-left estimate of a time loop it interrupts). Loading compiled code
from the cache raises no event and shows nothing.
"""

from __future__ import annotations

from numba.core import event

from foundation.progress import phase

__all__ = ["COMPILING_LABEL", "CompileListener", "install"]

COMPILING_LABEL = "compiling kernels (first run only, cached afterwards)"


class CompileListener(event.Listener):
    """Turns the outermost ``numba:compile`` event into a progress phase."""

    def __init__(self) -> None:
        self._depth = 0
        self._phase = None
        self.compiled: list[str] = []

    def on_start(self, ev) -> None:
        name = getattr(ev.data.get("dispatcher"), "__name__", "kernel") if isinstance(ev.data, dict) else "kernel"
        self.compiled.append(name)
        self._depth += 1
        if self._depth == 1:
            self._phase = phase(COMPILING_LABEL, once=True)
            self._phase.__enter__().note(name)

    def on_end(self, ev) -> None:
        self._depth -= 1
        if self._depth == 0 and self._phase is not None:
            ctx, self._phase = self._phase, None
            ctx.__exit__(None, None, None)


_listener: CompileListener | None = None


def install() -> CompileListener:
    """Register the listener once per process (idempotent); returns it."""
    global _listener
    if _listener is None:
        _listener = CompileListener()
        event.register("numba:compile", _listener)
    return _listener
