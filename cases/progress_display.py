"""The command line's view of long phases (:mod:`foundation.progress`) on stderr.

On a terminal every open phase is one line, nested phases under their parent: a bar with the
pieces done, the elapsed time and the time left when the phase has a total, otherwise its label
and the elapsed seconds, kept ticking by a small refresh thread. A finished outermost phase leaves
one line with its time. When stderr is not a terminal (a log file, CI) nothing is redrawn: each
finished phase is one line, ``outer > inner: 3.2 s``. A phase ended by an error leaves no line
(the error is told in one line by the command line). Nothing goes to stdout, so ``--json``
output stays clean.
"""

from __future__ import annotations

import math
import threading
import time
from contextlib import contextmanager, nullcontext
from typing import IO, Iterator

from foundation.progress import Phase, Reporter, format_seconds, reporting

__all__ = ["TerminalReporter", "terminal_progress", "phase_line", "finished_line"]

#: seconds between redraws of the ticking lines
REFRESH_S = 0.5

#: at most one redraw per phase within this many seconds when it advances quickly (the ticking
#: thread draws the latest state), so many small pieces cost a clock read each, not a redraw
MIN_REDRAW_S = 0.1

_BAR = "{desc} {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt}{postfix}"


def phase_line(p: Phase) -> str:
    """The text of an open phase without a total: label, detail, elapsed time (and time left)."""
    detail = f": {p.detail}" if p.detail else ""
    return f"{p.label}{detail}  {format_seconds(p.elapsed_s())}"


def _bar_postfix(p: Phase) -> str:
    left = p.remaining_s()
    return format_seconds(p.elapsed_s()) + ("" if left is None else f", {format_seconds(left)} left")


def finished_line(p: Phase) -> str:
    """One line for a finished phase: its path, pieces done of its total and its time."""
    counted = f" ({p.done}/{p.total})" if p.total is not None else ""
    detail = f": {p.detail}" if p.detail else ""
    return f"{' > '.join(p.path())}{detail}{counted}: {p.elapsed_s():.1f} s"


class TerminalReporter(Reporter):
    """Draws phases on ``stream`` (redrawn lines on a terminal, one line per finished phase otherwise).

    Parameters
    ----------
    stream : file
        Where to draw (stderr on the command line).
    interactive : bool, optional
        Redraw lines in place; default ``stream.isatty()``.
    """

    def __init__(self, stream: IO[str], interactive: bool | None = None) -> None:
        self.stream = stream
        self.interactive = bool(stream.isatty()) if interactive is None else bool(interactive)
        self._bars: dict[Phase, object] = {}
        self._drawn_s: dict[Phase, float] = {}
        self._lock = threading.RLock()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._gone = False

    # -- reporter protocol -------------------------------------------------------------------
    def start(self, phase: Phase) -> None:
        if not self.interactive:
            return
        from tqdm import tqdm

        with self._lock:
            known = phase.total is not None
            bar = tqdm(total=phase.total if known else None, desc=phase.label if known else phase_line(phase),
                       bar_format=_BAR if known else "{desc}", position=phase.depth, leave=False,
                       file=self.stream, dynamic_ncols=True)
            self._bars[phase] = bar
            self._ensure_ticking()

    def update(self, phase: Phase) -> None:
        if not self.interactive:
            return
        now = time.monotonic()
        if now - self._drawn_s.get(phase, -math.inf) < MIN_REDRAW_S and phase.done != phase.total:
            return
        self._drawn_s[phase] = now
        with self._lock:
            self._draw(phase)

    def finish(self, phase: Phase) -> None:
        if not self.interactive:
            if not phase.failed and not self._gone:      # a failure is told by its one error line
                try:
                    print(finished_line(phase), file=self.stream, flush=True)
                except (OSError, ValueError):             # stderr closed (a pipe reader quit): stop showing
                    self._gone = True
            return
        with self._lock:
            bar = self._bars.pop(phase, None)
            self._drawn_s.pop(phase, None)
            if bar is not None:
                bar.close()
            if phase.depth == 0 and not phase.failed:
                from tqdm import tqdm

                tqdm.write(finished_line(phase), file=self.stream)

    # -- drawing -----------------------------------------------------------------------------
    def _draw(self, phase: Phase) -> None:
        bar = self._bars.get(phase)
        if bar is None:
            return
        if phase.total is None:
            bar.set_description_str(phase_line(phase), refresh=False)
        else:
            bar.n = min(phase.done, phase.total)
            bar.postfix = _bar_postfix(phase)
        bar.refresh()

    def _ensure_ticking(self) -> None:
        if self._thread is None or not self._thread.is_alive():
            self._stop.clear()
            self._thread = threading.Thread(target=self._tick, name="flexbearing-progress", daemon=True)
            self._thread.start()

    def _tick(self) -> None:
        while not self._stop.wait(REFRESH_S):
            with self._lock:
                for p in list(self._bars):
                    self._draw(p)

    def close(self) -> None:
        """Stop the refresh thread and clear any lines still drawn."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        with self._lock:
            for bar in self._bars.values():
                bar.close()
            self._bars.clear()


@contextmanager
def terminal_progress(stream: IO[str], interactive: bool | None = None) -> Iterator[TerminalReporter]:
    """Show the phases of the ``with`` block on ``stream`` (:class:`TerminalReporter`); on a terminal,
    console log lines are written above the drawn lines instead of through them."""
    reporter = TerminalReporter(stream, interactive)
    try:
        with reporting(reporter), (_logging_above_bars() if reporter.interactive else nullcontext()):
            yield reporter
    finally:
        reporter.close()


def _logging_above_bars():
    from tqdm.contrib.logging import logging_redirect_tqdm

    return logging_redirect_tqdm()
