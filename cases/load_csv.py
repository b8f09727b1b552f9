"""Load CSV files of bearing description files: a load spectrum, or a load time history.

A spectrum (``[load] spectrum_csv``) has the columns ``Fx_N, Fy_N, Fz_N, Mx_Nm, My_Nm`` and
optionally ``time_share``, one load case a line. A time history (``[load] time_history_csv``) has
``time_s`` and the five load columns, one line per instant, time strictly increasing; each instant
becomes a load case whose time share is its trapezoid-rule weight over the history's duration
T = t_n − t_0 (the composite trapezoid rule of ∫ f(t) dt, e.g. Press et al., *Numerical Recipes*,
3rd ed., 2007, eq. 4.1.11)::

    w_0 = (t_1 − t_0)/2,   w_i = (t_{i+1} − t_{i−1})/2 (0 < i < n),   w_n = (t_n − t_{n−1})/2,
    time_share_i = w_i / T   (Σ w_i = T)

so the Palmgren–Miner sum Σ share_i/L_i of the life is the trapezoid rule of the damage rate
(1/T)∫ dt/L(t) over the history. Every error is a :class:`cases.config.CaseError` naming the key,
the file and, where it lies in a line, the row (numbered as in a spreadsheet, header = 1) and column.
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

from mbd_core.quasistatic import RingLoad
from mbd_core.quasistatic.results import LOAD_NAMES

from .config import CaseError

__all__ = ["read_spectrum_csv", "read_time_history_csv", "trapezoid_time_shares", "MAX_LOAD_CASES", "TIME_SHARE",
           "TIME"]

#: Most load cases a spectrum (or instants a time history) may hold.
MAX_LOAD_CASES = 10_000
TIME_SHARE = "time_share"
TIME = "time_s"

Table = list[tuple[int, dict[str, float]]]  # (row number, values by column) per line below the header


def _number(text: str, at: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise CaseError(f"{at}: not a number: {text.strip()!r:.40}") from None
    if not math.isfinite(value):
        raise CaseError(f"{at}: not a finite number: {text.strip()!r:.40}")
    return value


def _header(header: list[str], at: str, required: tuple[str, ...], optional: tuple[str, ...], hint: str) -> list[str]:
    names = [h.strip() for h in header]
    known = (*required, *optional)
    for name in names:
        if name not in known:
            raise CaseError(f"{at}: unknown column {name!r:.40}; the columns are {', '.join(known)}{hint}")
    missing = [n for n in required if n not in names]
    if missing:
        raise CaseError(f"{at}: column {missing[0]} missing; the columns are {', '.join(known)}{hint}")
    if len(set(names)) != len(names):
        raise CaseError(f"{at}: a column appears twice in {', '.join(names)}")
    return names


def _read_table(path: Path, at: str, required: tuple[str, ...], optional: tuple[str, ...] = ()) -> Table:
    """The numbers of a CSV file with a header of ``required`` (and ``optional``) columns."""
    hint = f" ({', '.join(optional)} optional)" if optional else ""
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except OSError as exc:
        raise CaseError(f"{at}: cannot read: {exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        raise CaseError(f"{at}: not UTF-8 text (byte {exc.start})") from None
    try:
        lines = [r for r in csv.reader(io.StringIO(text)) if any(c.strip() for c in r)]
    except csv.Error as exc:
        raise CaseError(f"{at}: not a CSV file: {exc}") from None
    if not lines:
        extra = "".join(f"[, {n}]" for n in optional)
        raise CaseError(f"{at}: empty (expected a header {', '.join(required)}{extra} and one line per case)")
    names = _header(lines[0], f"{at}, header", required, optional, hint)
    if len(lines) == 1:
        raise CaseError(f"{at}: no load cases below the header")
    if len(lines) - 1 > MAX_LOAD_CASES:
        raise CaseError(f"{at}: {len(lines) - 1} load cases, at most {MAX_LOAD_CASES}")
    table = []
    for n, line in enumerate(lines[1:], start=2):
        if len(line) != len(names):
            raise CaseError(f"{at}: row {n}: {len(line)} values for {len(names)} columns")
        table.append((n, {name: _number(cell, f"{at}: row {n}, column {name}") for name, cell in zip(names, line)}))
    return table


def _loads(table: Table) -> tuple[RingLoad, ...]:
    return tuple(RingLoad(**{k: values[k] for k in LOAD_NAMES}) for _, values in table)


def read_spectrum_csv(path: Path, key: str = "load.spectrum_csv"
                      ) -> tuple[tuple[RingLoad, ...], tuple[float, ...] | None]:
    """Load cases (and time shares, or None) of a spectrum CSV; CaseError naming ``key``, the file, row and column."""
    at = f"{key}: {path}"
    table = _read_table(path, at, LOAD_NAMES, (TIME_SHARE,))
    shares = []
    for n, values in table:
        if TIME_SHARE in values:
            if values[TIME_SHARE] < 0.0:
                raise CaseError(f"{at}: row {n}, column {TIME_SHARE}: must be >= 0, got {values[TIME_SHARE]!r}")
            shares.append(values[TIME_SHARE])
    if shares and not sum(shares) > 0.0:
        raise CaseError(f"{at}: column {TIME_SHARE}: the shares sum to 0")
    return _loads(table), (tuple(shares) if shares else None)


def trapezoid_time_shares(time_s) -> np.ndarray:
    """Trapezoid-rule weights of the instants over the duration, summing to 1 (module docstring).

    Parameters
    ----------
    time_s : (n,) float array, s, strictly increasing, n ≥ 2
    """
    t = np.asarray(time_s, dtype=float)
    if t.ndim != 1 or t.size < 2 or not np.all(np.diff(t) > 0.0):
        raise ValueError(f"time_s must hold at least two strictly increasing instants, got {t!r:.80}")
    dt = np.diff(t)
    w = np.zeros_like(t)
    w[:-1] += 0.5 * dt
    w[1:] += 0.5 * dt
    return w / (t[-1] - t[0])


def read_time_history_csv(path: Path, key: str = "load.time_history_csv"
                          ) -> tuple[tuple[RingLoad, ...], tuple[float, ...]]:
    """Load cases and their trapezoid time shares of a load time history CSV (module docstring);
    CaseError naming ``key``, the file and the row (a time not after the previous row's)."""
    at = f"{key}: {path}"
    table = _read_table(path, at, (TIME, *LOAD_NAMES))
    if len(table) < 2:
        raise CaseError(f"{at}: one instant; a time history needs at least two (the time shares are the "
                        "trapezoid weights of the intervals between them)")
    for (_, before), (n, values) in zip(table, table[1:]):
        if not values[TIME] > before[TIME]:
            raise CaseError(f"{at}: row {n}, column {TIME}: time must increase strictly, got {values[TIME]!r} "
                            f"after {before[TIME]!r}")
    first, last = table[0][1][TIME], table[-1][1][TIME]
    if not math.isfinite(last - first):
        raise CaseError(f"{at}: column {TIME}: the duration {last!r} − {first!r} s is not a finite number")
    shares = trapezoid_time_shares([values[TIME] for _, values in table])
    return _loads(table), tuple(float(s) for s in shares)
