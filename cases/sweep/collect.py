"""The collected results of a sweep, rebuilt from its point folders.

One row per point (in the sweep's order): the point's folder name, one column per varied key,
its status, and one column per figure of the point's ``summary.json`` (nested entries flattened
to dotted names, lists to ``name[i]``; text, the case's description and the warnings left out;
lists longer than :data:`MAX_LIST` left out too: they are per-element data, which the point's
own CSV files hold). A row's figures come from its folder only when the folder's
``summary.json`` records the point's case hash, so the table cannot disagree with the folders.

Written: ``sweep.csv`` and ``sweep.parquet`` (the same table), ``sweep.json`` (the sweep, where
it ran, and per point its status, error, wall time and worker) and ``sweep_<figure>.png`` plots
(figure against the first numeric varied key, one line per value of the others).
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

from foundation.files import atomic_path

from .spec import Point, SweepSpec, value_of

__all__ = ["point_figures", "collect_rows", "write_table", "write_sweep_json", "plot_figures", "MAX_LIST"]

#: lists up to this length become columns; longer ones are per-element data
MAX_LIST = 12
#: summary entries that are not figures of the point (``variants``, ``cluster``: where and when a
#: study's own runs went)
_NOT_FIGURES = {"case", "study", "description", "warnings", "sweep_point", "fidelity_choice", "fidelity_decisions",
                "variants", "cluster"}
#: figures plotted by default: at most this many of those that vary over the points
MAX_PLOTS = 6
_BOOKKEEPING = {"wall_time_s", "peak_rss_mb"}


def _flatten(value, name: str, out: dict) -> None:
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(v, f"{name}.{k}" if name else str(k), out)
    elif isinstance(value, list):
        if len(value) <= MAX_LIST:
            for i, v in enumerate(value):
                _flatten(v, f"{name}[{i}]", out)
    elif isinstance(value, bool):
        out[name] = int(value)
    elif isinstance(value, (int, float)) or value is None:
        out[name] = value


def point_figures(summary: dict) -> dict:
    """The figures of a point's ``summary.json``, flattened (module docstring)."""
    out: dict = {}
    for k, v in summary.items():
        if k not in _NOT_FIGURES:
            _flatten(v, k, out)
    return out


def read_point(folder: Path, case_hash: str) -> dict | None:
    """The summary of a point's folder when it holds the run of the case with ``case_hash``."""
    try:
        summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError):
        return None
    stored = summary.get("sweep_point", {}) if isinstance(summary, dict) else {}
    return summary if isinstance(stored, dict) and stored.get("case_hash") == case_hash else None


def collect_rows(spec: SweepSpec, points: list[Point], folder: Path, hashes: dict, records: dict) -> list[dict]:
    """The table's rows, rebuilt from the point folders (``records``: this run's status and errors)."""
    rows = []
    for p in points:
        row = {"point": p.name, **{k: value_of(v) for k, v in p.values}}
        summary = read_point(folder / p.name, hashes[p.name]) if p.name in hashes else None
        rec = records.get(p.name, {})
        if summary is not None:
            row["status"] = "ok"
            row.update(point_figures(summary))
        else:
            row["status"] = rec.get("status") if rec.get("status") in ("failed", "invalid") else "missing"
            row["error"] = rec.get("error", "")
        rows.append(row)
    return rows


def _columns(rows: list[dict]) -> list[str]:
    cols: list[str] = []
    for r in rows:
        cols += [c for c in r if c not in cols]
    if "error" in cols:  # after the status
        cols.remove("error")
        cols.insert(cols.index("status") + 1, "error")
    return cols


def _arrow_column(values: list):
    import pyarrow as pa

    present = [v for v in values if v is not None]
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in present):
        kind = pa.int64() if all(isinstance(v, int) for v in present) and present else pa.float64()
        return pa.array(values, type=kind)
    return pa.array([None if v is None else str(v) for v in values], type=pa.string())


def write_table(rows: list[dict], folder: Path) -> list[str]:
    """``sweep.csv`` and ``sweep.parquet`` of the rows; returns the columns."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    cols = _columns(rows)

    def write_csv(path: Path) -> None:
        with open(path, "w", newline="", encoding="utf-8") as f:
            w = csv.writer(f)
            w.writerow(cols)
            for r in rows:
                w.writerow(["" if r.get(c) is None else r.get(c) for c in cols])

    table = pa.table({c: _arrow_column([r.get(c) for r in rows]) for c in cols})
    with atomic_path(folder / "sweep.csv") as tmp:
        write_csv(tmp)
    with atomic_path(folder / "sweep.parquet") as tmp:
        pq.write_table(table, tmp)
    return cols


def write_sweep_json(folder: Path, data: dict) -> Path:
    path = folder / "sweep.json"
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(data, indent=1, allow_nan=False, default=str) + "\n", encoding="utf-8")
    return path


def _number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def default_figures(rows: list[dict], varied: list[str]) -> list[str]:
    """The figures that change over the points (at most :data:`MAX_PLOTS`, in summary order)."""
    ok = [r for r in rows if r["status"] == "ok"]
    out = []
    for c in _columns(ok):
        if c in varied or c in ("point", "status", "error") or c in _BOOKKEEPING:
            continue
        vals = [r.get(c) for r in ok]
        if all(_number(v) for v in vals) and len(set(vals)) > 1:
            out.append(c)
    return out[:MAX_PLOTS]


def plot_figures(rows: list[dict], spec: SweepSpec, folder: Path, figures: list[str] | None = None) -> list[Path]:
    """``sweep_<figure>.png``: each figure against the first numeric varied key, one line per
    combination of the other keys' values (the points that did not complete are left out)."""
    from ..results import plt

    keys = [a.key for a in spec.axes]
    ok = [r for r in rows if r["status"] == "ok"]
    if not ok:
        return []
    x_key = next((k for k in keys if all(_number(r[k]) for r in ok)), keys[0])
    others = [k for k in keys if k != x_key]
    figures = default_figures(rows, keys) if figures is None else figures
    paths = []
    for fig_name in figures:
        fig, ax = plt().subplots(figsize=(6.4, 4.2))
        groups: dict = {}
        for r in ok:
            if _number(r.get(fig_name)):
                groups.setdefault(tuple(r[k] for k in others), []).append((r[x_key], r[fig_name]))
        for label, pts in groups.items():
            numeric = all(_number(x) for x, _ in pts)
            pts = sorted(pts) if numeric else pts
            xs = [x if numeric else str(x) for x, _ in pts]
            ax.plot(xs, [y for _, y in pts], "o-", label=", ".join(f"{k} = {v}" for k, v in zip(others, label)) or None)
        ax.set_xlabel(x_key)
        ax.set_ylabel(fig_name)
        ax.grid(True, alpha=0.3)
        if others:
            ax.legend(fontsize=8)
        fig.tight_layout()
        safe = "".join(ch if ch.isalnum() or ch in "._-" else "_" for ch in fig_name)
        path = folder / f"sweep_{safe}.png"
        fig.savefig(path, dpi=110)
        plt().close(fig)
        paths.append(path)
    return paths
