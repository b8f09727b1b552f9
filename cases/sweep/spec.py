"""What a sweep runs: the case, the varied keys and their values, and the points they make.

A sweep varies case keys (the ones ``--set`` takes) over lists of values. ``grid`` runs every
combination (the Cartesian product, the first key varying slowest); ``zip`` pairs the i-th values
of every key (equal lengths). A value list is given

- on the command line: ``--vary key=v1,v2,…`` (each value a TOML value, split at the commas
  outside brackets and quotes) or ``--vary key=start:stop:n`` (``n`` evenly spaced values, ends
  included; integers when both ends are written as integers and every value is one);
- in a sweep file (TOML, told from a case file by its ``vary`` table)::

      case = "wind-static"            # a named case, or a case file (relative to this file)
      quick = true                    # optional: the case's --quick variant
      mode = "grid"                   # optional: "grid" (default) or "zip"
      set = ["loads.scale=1.2"]       # optional: entries changed at every point
      [vary]
      "loads.scale" = [0.8, 1.0, 1.2]
      "analysis.speed_rpm" = { start = 20, stop = 30, n = 3 }

Every point is an ordinary run of the case with its values applied as ``--set`` entries after
the sweep's own ``set`` entries, so it is validated exactly as ``flexbearing run`` validates.
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import tomli_w

from fem_rings.cache import input_hash

from ..config import CaseError, _parse_value, read_toml

__all__ = ["Axis", "Point", "SweepSpec", "case_hash", "value_of", "parse_vary", "read_sweep_file", "is_sweep_file", "MAX_POINTS"]

#: more points than this is almost surely a typo in a range (and a very long sweep)
MAX_POINTS = 10_000
#: longest point folder name before it is shortened with a hash (file systems allow 255 bytes)
MAX_NAME_CHARS = 120

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
_RANGE = re.compile(rf"^\s*(?P<start>{_NUMBER})\s*:\s*(?P<stop>{_NUMBER})\s*:\s*(?P<n>\d+)\s*$")
_FILE_KEYS = {"case", "quick", "mode", "set", "vary"}


@dataclass(frozen=True)
class Axis:
    """One varied key and its values, each as the TOML text ``--set`` takes."""

    key: str
    values: tuple[str, ...]


@dataclass(frozen=True)
class Point:
    """One run of a sweep: its folder name and (key, value text) pairs."""

    name: str
    values: tuple[tuple[str, str], ...]

    @property
    def assignments(self) -> tuple[str, ...]:
        return tuple(f"{k}={v}" for k, v in self.values)


@dataclass(frozen=True)
class SweepSpec:
    """A sweep: ``case`` (named case or case file), its ``axes``, ``grid`` or ``zip``, ``quick``
    and the ``sets`` applied at every point."""

    case: str
    axes: tuple[Axis, ...]
    mode: str = "grid"
    quick: bool = False
    sets: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.mode not in ("grid", "zip"):
            raise CaseError(f"mode: must be 'grid' or 'zip', got {self.mode!r:.40}")
        if not self.axes:
            raise CaseError("--vary: a sweep needs at least one varied key (--vary key=v1,v2,…)")
        keys = [a.key for a in self.axes]
        for k in keys:
            if keys.count(k) > 1:
                raise CaseError(f"--vary {k}: given twice; put all its values in one list")
            if any(s.partition("=")[0].strip() == k for s in self.sets):
                raise CaseError(f"--vary {k}: also given with --set; a key is either fixed or varied")
        if self.mode == "zip" and len({len(a.values) for a in self.axes}) > 1:
            shown = ", ".join(f"{a.key} {len(a.values)}" for a in self.axes)
            raise CaseError(f"--zip pairs the i-th values of every key, which needs as many values for each ({shown})")
        n = math.prod(len(a.values) for a in self.axes) if self.mode == "grid" else len(self.axes[0].values)
        if n > MAX_POINTS:
            raise CaseError(f"--vary: {n} points is more than {MAX_POINTS}; check the ranges")

    def points(self) -> list[Point]:
        """The points in order (grid: the first key varies slowest)."""
        combos = itertools.product(*(a.values for a in self.axes)) if self.mode == "grid" \
            else zip(*(a.values for a in self.axes))
        keys = [a.key for a in self.axes]
        labels = _labels(keys)
        points, seen = [], set()
        for combo in combos:
            name = "_".join(f"{lab}={_safe(v)}" for lab, v in zip(labels, combo))
            if len(name) > MAX_NAME_CHARS:
                digest = hashlib.sha256(name.encode()).hexdigest()[:10]
                name = f"{name[:MAX_NAME_CHARS - 11]}~{digest}"
            base, i = name, 2
            while name in seen:  # two values that read the same in a folder name ("1.0" and 1.0)
                name, i = f"{base}~{i}", i + 1
            seen.add(name)
            points.append(Point(name, tuple(zip(keys, combo))))
        return points

    def describe(self) -> dict:
        """The sweep as plain data (``sweep.json``)."""
        return {"case": self.case, "quick": self.quick, "mode": self.mode, "set": list(self.sets),
                "vary": {a.key: [value_of(v) for v in a.values] for a in self.axes}}


def _labels(keys: list[str]) -> list[str]:
    """The last part of each key, or the whole key where two keys share their last part."""
    tails = [k.rsplit(".", 1)[-1] for k in keys]
    return [t if tails.count(t) == 1 else k for k, t in zip(keys, tails)]


def _safe(text: str) -> str:
    """A value as it can stand in a folder name: enclosing brackets and quotes dropped, letters,
    digits and ``.+-`` kept, every other run of characters ``-``."""
    return re.sub(r"[^A-Za-z0-9.+\-]+", "-", text.strip("[]{}\"' \n\t")) or "-"


def value_of(text: str):
    """The value a point's TOML text stands for, as ``--set`` reads it (the text itself where it
    is not one value: the point is then refused by the case, and listed with its text)."""
    try:
        return _parse_value(text, "value")
    except CaseError:
        return text


def _toml_text(value, where: str) -> str:
    """TOML text of a value from a sweep file (a list inline, as ``--set`` takes it)."""
    if isinstance(value, list):
        return "[" + ", ".join(_toml_text(v, f"{where}[{i}]") for i, v in enumerate(value)) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(str(k))} = {_toml_text(v, f'{where}.{k}')}" for k, v in value.items()) + "}"
    try:
        return tomli_w.dumps({"v": value})[4:].strip()
    except TypeError:
        raise CaseError(f"{where}: not a value a case key takes: {value!r:.60}") from None


def _split_top_level(text: str) -> list[str]:
    """``text`` split at the commas that are not inside brackets, braces or quotes."""
    parts, depth, quote, current = [], 0, "", []
    for ch in text:
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append("".join(current).strip())
            current = []
            continue
        current.append(ch)
    parts.append("".join(current).strip())
    return parts


def _range_values(start: str, stop: str, n: int, where: str) -> tuple[str, ...]:
    if n < 2:
        raise CaseError(f"{where}: a range start:stop:n needs n ≥ 2, got {n}")
    if n > MAX_POINTS:
        raise CaseError(f"{where}: n = {n} is more than {MAX_POINTS}")
    a, b = float(start), float(stop)
    if not (math.isfinite(a) and math.isfinite(b)):
        raise CaseError(f"{where}: the range ends must be finite numbers")
    values = np.linspace(a, b, n)
    integers = all(re.fullmatch(r"[+-]?\d+", s) for s in (start, stop)) and np.all(values == np.round(values))
    return tuple(str(int(v)) if integers else format(float(v), ".12g") for v in values)


def parse_vary(item: str) -> Axis:
    """``key=v1,v2,…`` or ``key=start:stop:n`` (the module docstring) as an :class:`Axis`."""
    key, sep, rhs = item.partition("=")
    key = key.strip()
    if not sep or not key:
        raise CaseError(f"--vary {item!r:.60}: expected key=v1,v2,… or key=start:stop:n")
    where = f"--vary {key}"
    m = _RANGE.match(rhs)
    if m:
        return Axis(key, _range_values(m["start"], m["stop"], int(m["n"]), where))
    values = tuple(_split_top_level(rhs))
    if any(v == "" for v in values):
        raise CaseError(f"{where}: an empty value in {rhs!r:.60}")
    return Axis(key, values)


def _file_axis(key, values, source: str) -> Axis:
    where = f"{source}: vary.{key}"
    if isinstance(values, dict):
        if set(values) != {"start", "stop", "n"}:
            raise CaseError(f"{where}: a range is {{ start = …, stop = …, n = … }}, got keys {sorted(values)}")
        start, stop, n = values["start"], values["stop"], values["n"]
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (start, stop)) \
                or not isinstance(n, int) or isinstance(n, bool):
            raise CaseError(f"{where}: start and stop must be numbers and n an integer")
        return Axis(key, _range_values(repr(start), repr(stop), n, where))
    if not isinstance(values, list) or not values:
        raise CaseError(f"{where}: expected a list of values or a range table, got {values!r:.60}")
    return Axis(key, tuple(_toml_text(v, f"{where}[{i}]") for i, v in enumerate(values)))


def is_sweep_file(path: str) -> bool:
    """True for a TOML file with a ``vary`` table (a sweep file rather than a case file); a
    TOML file that cannot be read raises :class:`CaseError` naming the file and the line."""
    if not path.endswith(".toml") or not Path(path).is_file():
        return False
    return "vary" in read_toml(path)


def read_sweep_file(path: str) -> SweepSpec:
    """The sweep a sweep file describes (its case file, if any, found relative to the file)."""
    data = read_toml(path)
    unknown = sorted(set(data) - _FILE_KEYS)
    if unknown:
        raise CaseError(f"{path}: {unknown[0]}: unknown key (a sweep file has {', '.join(sorted(_FILE_KEYS))})")
    case = data.get("case")
    if not isinstance(case, str) or not case:
        raise CaseError(f"{path}: case: missing; give a named case or a case file")
    if case.endswith(".toml") and not Path(case).is_absolute():
        case = str(Path(path).parent / case)
    vary = data["vary"]
    if not isinstance(vary, dict):
        raise CaseError(f"{path}: vary: expected a table of key = [values]")
    sets = data.get("set", [])
    if not isinstance(sets, list) or not all(isinstance(s, str) for s in sets):
        raise CaseError(f"{path}: set: expected a list of \"key=value\" strings")
    quick, mode = data.get("quick", False), data.get("mode", "grid")
    if not isinstance(quick, bool):
        raise CaseError(f"{path}: quick: expected true or false, got {quick!r:.40}")
    axes = tuple(_file_axis(k, v, path) for k, v in _flatten_keys(vary))
    return SweepSpec(case, axes, mode if isinstance(mode, str) else repr(mode), quick, tuple(sets))


def _flatten_keys(table: dict, prefix: str = ""):
    """``vary`` entries as (dotted key, values); ``[vary.contact] mu_dynamic = […]`` reads as
    ``contact.mu_dynamic`` (a range table is a value, not a sub-table)."""
    for k, v in table.items():
        if isinstance(v, dict) and not {"start", "stop", "n"} & set(v):
            yield from _flatten_keys(v, f"{prefix}{k}.")
        else:
            yield f"{prefix}{k}", v


def case_hash(case) -> str:
    """Content hash of a resolved case (:func:`fem_rings.cache.input_hash`): every entry but its
    name and description, which say where it came from, not what it computes."""
    return input_hash("case", dataclasses.replace(case, name="case", description=""))
