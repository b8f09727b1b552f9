"""Stop signals end a run like Ctrl-C: the stack unwinds, so half-written results are removed.

By default SIGTERM (``kill``, a batch system's time limit) and SIGHUP (closed terminal) end the
process at once, leaving temporary folders behind. :func:`install` makes them raise
:class:`Terminated`, a :class:`KeyboardInterrupt`, so every ``finally`` and ``except BaseException``
cleanup runs (:func:`cases.outdir.atomic_folder`, :func:`fem_rings.cache.atomic_path`). When
nothing catches it, the process prints one line and ends by the same signal, so its exit status
(128 + signal number in a shell) still says how it was stopped.

A signal that arrives while Python runs a finaliser or weakref callback (an import's module-lock
clean-up, a garbage-collected object's ``__del__``) raises :class:`Terminated` where Python cannot
let it propagate: it would print "Exception ignored … Traceback" and lose the stop. The hook on
such exceptions raises it again from a short timer (SIGALRM), once the finaliser is done.

A stop that lands between two steps of a cleanup's set-up (a temporary folder made, the block that
removes it not yet entered) would skip that cleanup. Code that makes such things registers a
function with :func:`at_stop`; it runs once the stop has unwound the stack, before the process
ends (and at any normal exit).
"""

from __future__ import annotations

import atexit
import os
import signal
import sys
import threading
from contextlib import contextmanager

__all__ = ["Terminated", "at_stop", "held", "install"]

#: functions run when a stop has unwound the stack, or at exit (:func:`at_stop`)
_AT_STOP: list = []

_STOP = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n))


class Terminated(KeyboardInterrupt):
    """The process received a stop signal (``signum``)."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum

    def __str__(self) -> str:
        return f"stopped by {signal.Signals(self.signum).name}"


def _raise(signum, frame):
    raise Terminated(signum)


def at_stop(fn) -> None:
    """Run ``fn()`` (no arguments) when a stop signal ends the process, after the stack has unwound,
    and at a normal exit: the last chance to remove what a run left unfinished. Exceptions of
    ``fn`` (other than a further stop) are ignored."""
    if fn not in _AT_STOP:
        _AT_STOP.append(fn)


def _run_at_stop() -> None:
    with held():
        for fn in _AT_STOP:
            try:
                fn()
            except Exception:  # noqa: BLE001 — a cleanup that fails must not hide the stop
                pass


atexit.register(_run_at_stop)


def _excepthook(kind, value, tb, _previous=sys.excepthook):
    if not isinstance(value, Terminated):
        return _previous(kind, value, tb)
    _run_at_stop()
    print(f"flexbearing: {value}; unfinished results removed", file=sys.stderr)
    sys.stderr.flush()
    sys.stdout.flush()
    signal.signal(value.signum, signal.SIG_DFL)
    os.kill(os.getpid(), value.signum)


def _unraisable(info, _previous=sys.unraisablehook):
    if isinstance(info.exc_value, Terminated) and hasattr(signal, "setitimer"):
        # raised again by a timer 5 ms on, once the finaliser is done (a signal sent from here would
        # be handled inside this hook, again where it cannot propagate)
        signum = info.exc_value.signum
        signal.signal(signal.SIGALRM, lambda _s, _f: _raise(signum, None))
        signal.setitimer(signal.ITIMER_REAL, 0.005)
        return
    _previous(info)


@contextmanager
def held():
    """Hold back SIGINT, SIGTERM and SIGHUP in the block; one that arrived is acted on at its end.

    The handlers are swapped for ones that only note the signal (a mask would not do: another
    thread of the process may receive it), then restored; the first noted signal is then passed to
    its restored handler (a Python handler is called, the default action is taken by re-sending
    it). Outside the main thread signals cannot be handled, and the block runs as is.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    noted: list[int] = []
    previous = {s: signal.signal(s, lambda signum, frame: noted.append(signum)) for s in _STOP}
    try:
        yield
    finally:
        for s, h in previous.items():
            signal.signal(s, signal.SIG_DFL if h is None else h)  # None: a handler not set from Python
        if noted:
            _deliver(noted[0], previous[noted[0]])


def _deliver(signum: int, handler) -> None:
    if callable(handler):
        handler(signum, None)
    elif handler == signal.SIG_DFL:
        os.kill(os.getpid(), signum)


def install() -> None:
    """Turn SIGTERM and SIGHUP into :class:`Terminated` (only from the main thread; elsewhere a no-op)."""
    if threading.current_thread() is not threading.main_thread():
        return
    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), _raise)
    sys.excepthook = _excepthook
    sys.unraisablehook = _unraisable
