"""Progress of long phases: library code announces them, a front end decides how to show them.

Library code wraps a long step in :func:`phase` and, when it knows how many equal pieces of work
the step has, advances it piece by piece::

    with phase("constraint modes", total=n_blocks) as p:
        for block in blocks:
            ...
            p.advance()

Phases nest (a phase opened inside another, on the same thread, is its child). What happens to
them is up to the installed :class:`Reporter`: by default each finished phase is one logging INFO
line with its elapsed time (logger ``foundation.progress``), so a library user sees nothing unless
logging shows INFO; the command line installs a reporter that draws on stderr
(:mod:`cases.progress_display`). Announcing costs a few microseconds per call, so phases mark
steps and blocks of work, never single elements in a hot loop.

The time left of a phase with a total is the work left at the average rate so far,
(n − k) · t / k after k of n pieces in t seconds (:func:`remaining_time_s`). One-off work inside a
piece (``phase(..., once=True)``, e.g. compiling kernels on a first run) is not counted in t: the
pieces still to come will not repeat it.
"""

from __future__ import annotations

import logging
import threading
import time
from contextlib import contextmanager
from typing import Callable, Iterable, Iterator

__all__ = ["Phase", "Reporter", "LoggingReporter", "phase", "track", "reporting", "remaining_time_s",
           "format_seconds"]

log = logging.getLogger(__name__)


def remaining_time_s(done: float, total: float | None, elapsed_s: float) -> float | None:
    """Time left at the average rate so far: (n − k) · t / k, s; None before the first piece.

    Parameters
    ----------
    done : float
        Pieces finished, k.
    total : float or None
        Pieces in all, n (None: unknown, no estimate).
    elapsed_s : float
        Time the k pieces took, t, s.
    """
    if total is None or done <= 0:
        return None
    return max(float(total) - float(done), 0.0) * float(elapsed_s) / float(done)


def format_seconds(seconds: float) -> str:
    """``42 s``, ``3 min 05 s``, ``1 h 02 min``: a duration for people, to the second."""
    s = int(round(max(seconds, 0.0)))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {(s % 3600) // 60:02d} min"


class Phase:
    """One announced step of work: its label, optional total and what is done of it.

    Attributes
    ----------
    label : str
        What is being done, e.g. ``"factorising (41322 DOF, 6182553 nonzeros, cholmod)"``.
    total : int or None
        Number of pieces of work, when known.
    done : int
        Pieces finished (:meth:`advance`).
    parent : Phase or None
        The phase this one runs inside.
    detail : str
        Free text a reporter may show after the label (set with :meth:`note`).
    once : bool
        One-off work (not repeated by the pieces of the phases around it).
    one_off_s : float
        Time of finished one-off phases inside this one, s (left out of its rate).
    failed : bool
        The phase ended by an exception (reporters say nothing more of it: the error speaks).
    """

    def __init__(self, label: str, total: int | None = None, parent: "Phase | None" = None,
                 clock: Callable[[], float] = time.perf_counter, once: bool = False) -> None:
        self.label = str(label)
        self.total = None if total is None else int(total)
        self.done = 0
        self.parent = parent
        self.detail = ""
        self.once = bool(once)
        self.one_off_s = 0.0
        self.failed = False
        self._clock = clock
        self.started_s = clock()
        self.ended_s: float | None = None
        self.depth = 0 if parent is None else parent.depth + 1

    def advance(self, n: int = 1) -> None:
        """Mark ``n`` more pieces done and let the reporter redraw."""
        self.done += int(n)
        _shared.reporter.update(self)

    def note(self, detail: str) -> None:
        """Set the detail text (e.g. the kernel being compiled) and let the reporter redraw."""
        self.detail = str(detail)
        _shared.reporter.update(self)

    def elapsed_s(self) -> float:
        """Seconds since the phase started (until it ended, once it has)."""
        return (self.clock() if self.ended_s is None else self.ended_s) - self.started_s

    def clock(self) -> float:
        return self._clock()

    def remaining_s(self) -> float | None:
        """Estimated seconds left (:func:`remaining_time_s`) from the time of the pieces done, one-off
        work inside them left out; None without a total or progress."""
        return remaining_time_s(self.done, self.total, self.elapsed_s() - self.one_off_s)

    def path(self) -> list[str]:
        """Labels from the outermost phase down to this one."""
        return ([] if self.parent is None else self.parent.path()) + [self.label]


class Reporter:
    """Receives phases as they start, advance and finish; the base class ignores them."""

    def start(self, phase: Phase) -> None:
        """A phase began."""

    def update(self, phase: Phase) -> None:
        """A phase advanced or changed its detail."""

    def finish(self, phase: Phase) -> None:
        """A phase ended (``phase.ended_s`` set)."""


class LoggingReporter(Reporter):
    """The default: one INFO line per finished phase, with its elapsed time."""

    def finish(self, phase: Phase) -> None:
        if log.isEnabledFor(logging.INFO) and not phase.failed:
            counted = f" ({phase.done}/{phase.total})" if phase.total is not None else ""
            log.info("%s%s: %.2f s", " > ".join(phase.path()), counted, phase.elapsed_s())


class _ThreadPhases(threading.local):
    """Per thread: the open phases (innermost last). The reporter is shared by all threads."""

    def __init__(self) -> None:
        self.stack: list[Phase] = []


_threads = _ThreadPhases()


class _Shared:
    reporter: Reporter = LoggingReporter()


_shared = _Shared()


@contextmanager
def phase(label: str, total: int | None = None, *, once: bool = False,
          clock: Callable[[], float] = time.perf_counter) -> Iterator[Phase]:
    """Announce a phase of work for the ``with`` block.

    Parameters
    ----------
    label : str
        What the block does, for people.
    total : int, optional
        Pieces of work in the block, when known; call ``advance`` once per piece.
    once : bool
        One-off work (compiling, a first-time setup): its time is left out of the time-left
        estimates of the phases around it.
    clock : callable, optional
        Source of seconds (tests pass a fake one).

    Yields
    ------
    Phase
    """
    stack = _threads.stack
    p = Phase(label, total, stack[-1] if stack else None, clock, once)
    stack.append(p)
    _shared.reporter.start(p)
    try:
        yield p
    except BaseException:
        p.failed = True
        raise
    finally:
        p.ended_s = p.clock()
        if p in stack:          # a generator left open may close out of order: remove it wherever it is
            stack.remove(p)
        if p.once:
            outer = p.parent
            while outer is not None:
                outer.one_off_s += p.elapsed_s()
                outer = outer.parent
        _shared.reporter.finish(p)


def track(iterable: Iterable, label: str) -> Iterator:
    """Iterate ``iterable`` as a phase with one piece per item (total from ``len`` when it has one)."""
    try:
        total = len(iterable)  # type: ignore[arg-type]
    except TypeError:
        total = None
    with phase(label, total) as p:
        for item in iterable:
            yield item
            p.advance()


@contextmanager
def reporting(reporter: Reporter) -> Iterator[Reporter]:
    """Install ``reporter`` for the ``with`` block (the previous one comes back afterwards)."""
    previous = _shared.reporter
    _shared.reporter = reporter
    try:
        yield reporter
    finally:
        _shared.reporter = previous
