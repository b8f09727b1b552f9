"""A sweep from its description to its folder: validate every point, reuse what is done, run the
rest on Dask, collect.

The sweep's folder (``--out``) holds one sub-folder per point (an ordinary results folder, named
by the point's values), ``sweep.json``, ``sweep.csv``/``sweep.parquet`` and the plots
(:mod:`.collect`). A point whose folder already holds the run of the identical resolved case
(same content hash, :func:`.spec.case_hash`) is reused, so an interrupted sweep or a widened range
costs only the new points; ``recompute=True`` runs every point again. ``resume=True`` also lets a
point continue an interrupted explicit run from its checkpoints (``flexbearing run --resume``).
"""

from __future__ import annotations

import logging
import time
from pathlib import Path

from ..config import CaseError
from ..outdir import open_collection
from .collect import collect_rows, plot_figures, read_point, write_sweep_json, write_table
from .engine import PointTask, compute
from .spec import SweepSpec, case_hash

__all__ = ["run_sweep", "SweepFailed", "SWEEP_FORMAT"]

log = logging.getLogger(__name__)

SWEEP_FORMAT = "flexbearing-sweep/1"


class SweepFailed(CaseError):
    """Some points of a sweep failed (the others completed): the message names them."""


def _resolve_points(spec: SweepSpec, points):
    """(cases, records): the resolved case of each valid point, and an ``invalid`` record with
    the one-line reason for each point whose values the case refuses."""
    from ..run import resolve_case

    base = resolve_case(spec.case, spec.quick, spec.sets)  # a bad case or --set stops the sweep here
    cases, records = {}, {}
    for p in points:
        try:
            cases[p.name] = resolve_case(spec.case, spec.quick, (*spec.sets, *p.assignments))
        except CaseError as exc:
            records[p.name] = {"name": p.name, "status": "invalid", "error": " ".join(str(exc).split())}
    if not cases:  # every point refused: the keys themselves are wrong, not one value
        raise CaseError(next(iter(records.values()))["error"])
    return base, cases, records


def _point_line(rec: dict) -> str:
    if rec["status"] in ("failed", "invalid"):
        return f"{rec['name']}: {rec['status'].upper()}: {rec['error']}"
    if rec["status"] == "reused":
        return f"{rec['name']}: reused (computed before with the identical case)"
    return f"{rec['name']}: done in {rec['wall_time_s']:.1f} s on {rec['worker']}"


def run_sweep(spec: SweepSpec, out_dir, scheduler: str = "local", workers: int | None = None, resume: bool = False,
              recompute: bool = False, figures=None, echo=print) -> dict:
    """Run the sweep into ``out_dir``; returns what ``sweep.json`` holds.

    ``echo``: where a line per point goes (a progress bar over the points goes to the
    reporter of :mod:`foundation.progress`). Raises :class:`SweepFailed` at the end when a point
    failed or was refused (after everything else is written), :class:`CaseError` before any work
    when the case, a ``--set`` or every point is refused.
    """
    from ..run import case_source

    t0 = time.perf_counter()
    points = spec.points()
    base, cases, records = _resolve_points(spec, points)
    source = case_source(spec.case)
    out = open_collection(out_dir, f"sweep-{base.name}", source, kind="sweep")
    hashes = {name: case_hash(c) for name, c in cases.items()}
    for rec in records.values():
        echo(_point_line(rec))
    todo = []
    for p in points:
        if p.name not in cases:
            continue
        if not recompute and read_point(out / p.name, hashes[p.name]) is not None:
            records[p.name] = {"name": p.name, "status": "reused"}
            echo(_point_line(records[p.name]))
        else:
            todo.append(p)
    data = {"format": SWEEP_FORMAT, **spec.describe(), "case_name": base.name, "source": source, "n_points": len(points)}
    where: dict = {}

    def save(final: bool = False) -> None:
        listed = []
        for p in points:
            rec = records.get(p.name, {"status": "pending" if not final else "not run"})
            listed.append({"name": p.name, "folder": p.name, "values": {k: v for k, v in p.values},
                           "case_hash": hashes.get(p.name), **{k: v for k, v in rec.items() if k != "name"}})
        counts = {s: sum(1 for x in listed if x["status"] == s) for s in ("computed", "reused", "failed", "invalid")}
        write_sweep_json(out, {**data, **where, **counts, "wall_time_s": time.perf_counter() - t0, "points": listed})

    save()
    try:
        if todo:
            _compute(todo, cases, hashes, out, source, resume, scheduler, workers, records, where, save, echo)
    except BaseException:
        for p in todo:
            records.setdefault(p.name, {"name": p.name, "status": "interrupted"})
        save(final=True)
        raise
    rows = collect_rows(spec, points, out, hashes, records)
    write_table(rows, out)
    plot_figures(rows, spec, out, figures)
    save(final=True)
    bad = [r for r in records.values() if r["status"] in ("failed", "invalid")]
    result = {**data, **where, "points": [records.get(p.name, {}) for p in points]}
    if bad:
        shown = "; ".join(f"{r['name']}: {r['error']}" for r in bad[:3])
        raise SweepFailed(f"{len(bad)} of {len(points)} points failed ({shown}{'; …' if len(bad) > 3 else ''}); "
                          f"the others are in {out_dir}, sweep.json lists every error")
    return result


def _compute(todo, cases, hashes, out: Path, source, resume, scheduler, workers, records, where, save, echo):
    """Submit the points to the cluster and record each as it completes."""
    tasks = [PointTask(p.name, cases[p.name], str(out / p.name), source, hashes[p.name], p.values, resume) for p in todo]
    where["cluster"] = {}
    for rec in compute(tasks, scheduler, workers, where["cluster"], echo):
        records[rec["name"]] = rec
        echo(_point_line(rec))
        save()
