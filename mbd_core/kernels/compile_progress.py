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

import logging

from numba.core import event

from foundation.progress import phase

__all__ = ["COMPILING_LABEL", "CompileListener", "install"]

log = logging.getLogger(__name__)

COMPILING_LABEL = "compiling kernels (first run only, cached afterwards)"


class CompileListener(event.Listener):
    """Turns the outermost ``numba:compile`` event into a progress phase.

    A listener that raised would abort the compilation it watches, so a failure to show the phase
    is logged (DEBUG) and otherwise ignored.
    """

    def __init__(self) -> None:
        self._depth = 0
        self._open = None            # (context manager, phase) of the outermost compilation
        self.compiled: list[str] = []

    def on_start(self, ev) -> None:
        self._depth += 1
        if self._depth == 1:
            try:
                name = getattr(ev.data.get("dispatcher"), "__name__", "kernel") if isinstance(ev.data, dict) else "kernel"
                self.compiled.append(name)
                ctx = phase(COMPILING_LABEL, once=True)
                shown = ctx.__enter__()
                self._open = (ctx, shown)
                shown.note(name)
            except Exception:  # noqa: BLE001 — display only, never stop the compilation
                log.debug("could not show the compilation phase", exc_info=True)

    def on_end(self, ev) -> None:
        self._depth -= 1
        if self._depth == 0 and self._open is not None:
            (ctx, shown), self._open = self._open, None
            try:
                # the error itself reaches the kernel's caller; numba 0.68's Event.is_failed returns the
                # opposite of its docstring, so the exception details are read directly
                shown.failed = getattr(ev, "_exc_details", None) is not None
                ctx.__exit__(None, None, None)
            except Exception:  # noqa: BLE001 — display only, never stop the compilation
                log.debug("could not close the compilation phase", exc_info=True)


_listener: CompileListener | None = None


def install() -> CompileListener:
    """Register the listener once per process (idempotent); returns it."""
    global _listener
    if _listener is None:
        _listener = CompileListener()
        event.register("numba:compile", _listener)
    return _listener
