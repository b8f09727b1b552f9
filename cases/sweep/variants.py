"""The variants of a multi-run study (``wind-friction``, ``wind-driving-speed``) as sweep points.

A study that compares several runs of one case (each friction set, each driving speed) hands
them to :func:`run_variants`: every variant is an ordinary run of a single-run study into its own
folder ``<results>/<variant>/``, and the study builds its comparison from the variants'
``summary.json``. The variants run

- one after the other in this process (the default);
- as Dask tasks when the run is given ``--workers N`` (a LocalCluster) or ``--scheduler
  ADDRESS`` (:func:`executing`), exactly as the points of ``flexbearing sweep``.

While the case runs, the finished variants wait in the run's checkpoint folder
(:func:`cases.integrate.checkpoint_folder`): after an interruption ``flexbearing run --resume``
reuses each one whose folder holds the identical case (content hash) and runs only the others;
without ``--resume`` every variant runs.
"""

from __future__ import annotations

import contextlib
import json
import shutil
import time
from contextvars import ContextVar
from pathlib import Path

from ..config import CaseError
from .collect import read_point
from .engine import PointTask, compute
from .spec import case_hash

__all__ = ["executing", "inside_study", "as_variant", "run_variants", "VariantFailed"]

#: (scheduler, workers) of the case run going on; (None, None): variants in this process
_EXECUTION: ContextVar[tuple[str | None, int | None]] = ContextVar("cases_variant_execution", default=(None, None))
#: True while a run goes on as a variant of a study
_INSIDE: ContextVar[bool] = ContextVar("cases_variant_inside", default=False)


class VariantFailed(CaseError):
    """A variant of a study failed on a worker (the message names it and the cause)."""


@contextlib.contextmanager
def executing(scheduler: str | None, workers: int | None):
    """Run the variants of the studies in the block on Dask: ``scheduler`` "local" (``workers``
    processes) or an address; ``(None, None)`` keeps them in this process."""
    token = _EXECUTION.set((scheduler, workers))
    try:
        yield
    finally:
        _EXECUTION.reset(token)


def inside_study() -> bool:
    """True while the run going on is a variant of a study, whose study draws the figures that
    compare the variants (a variant may then leave out a figure of its own that costs more than
    its computation)."""
    return _INSIDE.get()


@contextlib.contextmanager
def as_variant():
    """Run the block as a variant of a study (:func:`inside_study`)."""
    token = _INSIDE.set(True)
    try:
        yield
    finally:
        _INSIDE.reset(token)


def run_variants(variants, out, progress=None) -> dict[str, dict]:
    """Run every ``(name, case)`` of ``variants`` into ``out.folder/<name>/``; returns name → its
    ``summary.json`` (output units). Raises what a variant raised (in this process), or
    :class:`VariantFailed` naming the variant that failed on a worker."""
    from ..integrate import checkpoint_folder
    from ..run import run_case

    variants = list(variants)
    keep, resume = checkpoint_folder() or (None, False)
    where = (keep / "points") if keep is not None else Path(out.folder)
    scheduler, workers = _EXECUTION.get()
    hashes = {name: case_hash(c) for name, c in variants}
    todo = [(name, c) for name, c in variants if not resume or read_point(where / name, hashes[name]) is None]
    for name in sorted(set(hashes) - {name for name, _ in todo}):
        out.note(f"{name}: reused from the interrupted run")
    t0, done = time.perf_counter(), {}
    if scheduler is None:
        for name, c in (progress(todo, "runs") if progress is not None and len(todo) > 1 else todo):
            extra = {"sweep_point": {"name": name, "values": {}, "case_hash": hashes[name]}}
            with as_variant():
                run = run_case(c, where / name, progress=progress, summary_extra=extra)
            done[name] = {"worker": "this process", "wall_time_s": run.summary["wall_time_s"],
                          "peak_rss_mb": run.summary["peak_rss_mb"], "finished_after_s": time.perf_counter() - t0}
    elif todo:
        tasks = [PointTask(name, c, str(where / name), "variant", hashes[name], (), False) for name, c in todo]
        info: dict = {}
        for rec in compute(tasks, scheduler, workers, info):
            if rec["status"] != "computed":
                raise VariantFailed(f"variant {rec['name']}: {rec['error']}")
            done[rec["name"]] = {**{k: rec[k] for k in ("worker", "wall_time_s", "peak_rss_mb")},
                                 "finished_after_s": time.perf_counter() - t0}
        out.summary["cluster"] = info
    # when each variant finished (from the start of the variants), its wall time and its process's peak memory
    out.summary["variants"] = {name: done.get(name, {"worker": "reused"}) for name, _ in variants}
    summaries = {}
    for name, _ in variants:
        if where != Path(out.folder):
            shutil.copytree(where / name, Path(out.folder) / name)
        summaries[name] = json.loads((Path(out.folder) / name / "summary.json").read_text(encoding="utf-8"))
    return summaries
