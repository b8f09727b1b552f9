"""``flexbearing tradeoff``: run a case's fidelity ladder and measure what each rung's accuracy costs.

Each rung runs in a fresh interpreter (one rung per process) with an empty temporary
model cache, so its wall time, CPU time and peak memory are those of a first run of that model on
this machine (meshing and reduction included); the same worker then repeats the solve with its
bodies cached (``warm_wall_s``: what a second run of that model costs). Errors are measured against
the ladder's reference rung (:func:`cases.fidelity.rung_errors`).

A finished ladder is kept in the cache (``tradeoff/`` under ``$FLEXBEARING_CACHE``), keyed by the
case's scene with its knobs at the ladder's base values, the ladder and this module's version, so
``flexbearing run … --tolerance`` and a second ``tradeoff`` reuse it. While a ladder runs, each
measured rung is kept there too, so an interrupted ladder measures only the rungs missing.

``flexbearing tradeoff --workers N`` (a local Dask cluster) or ``--scheduler ADDRESS`` sends the
rungs to Dask workers, each measuring its rung in a fresh process of its own; rungs measured side
by side on one machine share it, so their times are those of a loaded machine (one worker per
machine keeps them clean).
"""

from __future__ import annotations

import dataclasses
import json
import logging
import os
import resource
import shutil
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from fem_rings.cache import atomic_path, cache_dir, input_hash

from .config import CaseError, dumps_case
from .described import fidelity as described_fidelity
from .described.case import DescribedCase
from .dma import fidelity as dma_fidelity
from .dma.case import DmaCase
from .fidelity import (ERROR_NAMES, Ladder, Outcome, Rung, choose_rung, observed_order, rung_errors, rungs,
                       sweep_members)
from .outdir import atomic_folder
from .results import RunOutput, output_units
from .slewing import fidelity as slewing_fidelity
from .slewing.case import SlewingCase
from .tradeoff_plots import plot_convergence, plot_pareto
from .wind import fidelity as wind_fidelity
from .wind.case import WindCase

__all__ = ["LADDERS", "LadderResult", "family_ladder", "run_ladder", "write_tradeoff", "pareto_front", "choose_fidelity",
           "measure_cold"]

log = logging.getLogger(__name__)

#: case class → the module that declares its ladder (``ladder``, ``scene``, ``rung_case``,
#: ``measure``, ``describe``, ``rung_overrides``, ``element_columns``; optional ``WARM_REPEAT``,
#: False when a second, warm measurement of each rung is not worth its time)
LADDERS = {SlewingCase: slewing_fidelity, WindCase: wind_fidelity, DescribedCase: described_fidelity,
           DmaCase: dma_fidelity}
#: family → why it declares no ladder (its model has no discretisation to trade)
WITHOUT_LADDER = {
    "crb": "the crb family's friction model is closed form contact by contact (roller loads from one root solve, "
           "films and losses from fitted formulas): it has no mesh, modes, slices or step to trade, and a whole "
           "speed–axial map takes about a second",
    "turbocharger": "the turbocharger family has no fidelity ladder yet: its rotor's modes, mesh and step are set "
                    "in the case (rotor.n_modes, rotor.mesh_size_m; the step by the stable-step guard)",
}
#: part of the ladder cache key: bump when what a rung measures changes
TRADEOFF_VERSION = 4


def family_ladder(case):
    """The module declaring ``case``'s ladder; CaseError naming the families that have one."""
    module = LADDERS.get(type(case))
    if module is None and type(case).FAMILY in WITHOUT_LADDER:
        raise CaseError(f"tradeoff and --tolerance: {WITHOUT_LADDER[type(case).FAMILY]}")
    if module is None:
        have = ", ".join(sorted(c.FAMILY for c in LADDERS))
        raise CaseError(f"no fidelity ladder is declared for {type(case).FAMILY} cases yet; tradeoff and "
                        f"--tolerance take {have} cases")
    return module


def _peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _measure_rung(module_name: str, case, settings: dict) -> dict:
    """In a fresh worker: the rung cold (empty cache), then warm (unless the family's
    ``WARM_REPEAT`` is False); times, peak memory, outcome."""
    import importlib

    module = importlib.import_module(module_name)
    rung_case = module.rung_case(case, settings)
    with tempfile.TemporaryDirectory(prefix="fb-rung-") as cache:
        os.environ["FLEXBEARING_CACHE"] = cache
        w0, c0 = time.perf_counter(), time.process_time()
        outcome = module.measure(rung_case)
        wall, cpu = time.perf_counter() - w0, time.process_time() - c0
        warm = None
        if getattr(module, "WARM_REPEAT", True):
            w1 = time.perf_counter()
            module.measure(rung_case)
            warm = time.perf_counter() - w1
    return {"outcome": outcome, "wall_s": wall, "cpu_s": cpu, "warm_wall_s": warm, "peak_rss_mb": _peak_rss_mb()}


def _measure_files(task_file: str, result_file: str) -> None:
    """The body of :func:`measure_cold`'s fresh interpreter: the pickled arguments in,
    the pickled measurement (or the exception) out."""
    import pickle

    with open(task_file, "rb") as f:
        args = pickle.load(f)
    try:
        result = ("ok", _measure_rung(*args))
    except Exception as exc:  # noqa: BLE001 — handed back to the caller, which raises it
        result = ("error", exc)
    with open(result_file, "wb") as f:
        pickle.dump(result, f)


def measure_cold(module_name: str, case, settings: dict) -> dict:
    """``case`` at ``settings`` measured by ``module_name`` in a fresh interpreter, cold then warm
    (:func:`_measure_rung`): outcome, wall and CPU time, warm wall time, peak memory. The
    interpreter is started with :mod:`subprocess`, which also works inside a Dask worker (a
    daemonic process, which :mod:`multiprocessing` may not give children)."""
    import pickle
    import subprocess
    import sys

    with tempfile.TemporaryDirectory(prefix="fb-rung-task-") as tmp:
        task, result = Path(tmp) / "task.pkl", Path(tmp) / "result.pkl"
        task.write_bytes(pickle.dumps((module_name, case, settings)))
        code = f"from cases.tradeoff import _measure_files; _measure_files({str(task)!r}, {str(result)!r})"
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        if not result.is_file():
            tail = " ".join(done.stderr.split()[-40:])
            raise RuntimeError(f"the rung's process ended with status {done.returncode} without a result: {tail}")
        status, value = pickle.loads(result.read_bytes())
    if status == "error":
        raise value
    return value


@dataclass
class LadderResult:
    """The rungs of a ladder, their measurements (``rows``, one dict per rung) and outcomes."""

    ladder: Ladder
    rungs: list[Rung]
    rows: list[dict]
    outcomes: dict[str, Outcome]
    cached: bool = False

    def row(self, name: str) -> dict:
        return next(r for r in self.rows if r["rung"] == name)


def _cache_key(case, module, ladder: Ladder, quick: bool) -> str:
    """The ladder's key: the case's scene at the base rung, the ladder, and the contents of the files
    the case reads (a bearing file and the sections, solids and loads it names: the family's
    ``cache_inputs``)."""
    base = module.rung_case(case, dict(ladder.base))
    text = dumps_case(dataclasses.replace(base, name="tradeoff", description=""))
    files = list(getattr(module, "cache_inputs", lambda c: ())(case))
    return input_hash("tradeoff", TRADEOFF_VERSION, text, [(k.key, k.values) for k in ladder.knobs], sorted(ladder.reference.items()),
                      sorted((k, sorted(v.items())) for k, v in ladder.combined.items()), quick, *([files] if files else []))


def _cache_file(key: str) -> Path:
    return cache_dir() / "tradeoff" / f"{key}.json"


def _to_json(result: LadderResult) -> dict:
    return {"rows": result.rows, "outcomes": {k: o.to_json() for k, o in result.outcomes.items()}}


def _load_cached(path: Path, ladder: Ladder, all_rungs: list[Rung]) -> LadderResult | None:
    try:
        data = json.loads(path.read_text())
        outcomes = {k: Outcome.from_json(v) for k, v in data["outcomes"].items()}
        rows = data["rows"]
    except (OSError, ValueError, KeyError, TypeError):
        return None
    if {r["rung"] for r in rows} != {r.name for r in all_rungs}:
        return None
    return LadderResult(ladder, all_rungs, rows, outcomes, cached=True)


def _save_rung(path: Path, m: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp:
        Path(tmp).write_text(json.dumps({**{k: v for k, v in m.items() if k != "outcome"},
                                         "outcome": m["outcome"].to_json()}))


def _load_rung(path: Path) -> dict | None:
    try:
        data = json.loads(path.read_text())
        return {**data, "outcome": Outcome.from_json(data["outcome"])}
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _measure_rungs(module, case, all_rungs, folder: Path | None, progress, scheduler, workers) -> dict:
    """rung name → measurement (:func:`measure_cold`) of every rung. With ``folder`` (the ladder's
    cache entry), each measured rung is kept there as it finishes and an interrupted ladder
    measures only the rungs missing. ``scheduler``: None measures them one after the other here;
    "local" (``workers`` processes) or a Dask scheduler's address sends each rung to a worker,
    which measures it in a fresh process of its own (rungs measured side by side share their
    machine: their times are those of a loaded machine unless each worker has one to itself)."""
    measured = {r.name: m for r in all_rungs if folder is not None and (m := _load_rung(folder / f"{r.name}.json"))}
    todo = [r for r in all_rungs if r.name not in measured]
    if measured:
        log.info("rungs reused from an interrupted ladder: %s", ", ".join(measured))

    def keep(name: str, m: dict) -> None:
        measured[name] = m
        if folder is not None:
            _save_rung(folder / f"{name}.json", m)

    if scheduler is None:
        for r in (progress(todo, "rungs") if progress else todo):
            log.info("rung %s: %s", r.name, module.describe(dict(r.settings)))
            keep(r.name, measure_cold(module.__name__, case, dict(r.settings)))
    elif todo:
        from distributed import as_completed

        from foundation.progress import phase

        from .sweep.engine import open_client

        with open_client(scheduler, workers, len(todo)) as (client, _), phase("rungs", len(todo)) as bar:
            futures = {client.submit(measure_cold, module.__name__, case, dict(r.settings), pure=False): r.name
                       for r in todo}
            for fut in as_completed(futures):
                keep(futures[fut], fut.result())
                bar.advance()
    return measured


def run_ladder(case, quick: bool = False, progress=None, use_cache: bool = True, scheduler: str | None = None,
               workers: int | None = None) -> LadderResult:
    """Every rung of ``case``'s ladder, measured (or read from the ladder cache); ``scheduler``
    and ``workers``: where the rungs run (:func:`_measure_rungs`)."""
    module = family_ladder(case)
    try:
        ladder = module.ladder(case, quick)
        all_rungs = rungs(ladder)
        for r in all_rungs:  # every rung is a valid case before any work
            module.rung_case(case, dict(r.settings))
    except ValueError as exc:
        raise CaseError(str(exc)) from None
    path = _cache_file(_cache_key(case, module, ladder, quick))
    if use_cache and path.is_file():
        cached = _load_cached(path, ladder, all_rungs)
        if cached is not None:
            return cached
    measured = _measure_rungs(module, case, all_rungs, path.with_suffix("") if use_cache else None, progress,
                              scheduler, workers)
    ref = measured["reference"]["outcome"]
    rows = []
    for r in all_rungs:
        m = measured[r.name]
        o = m["outcome"]
        rows.append({"rung": r.name, "knob": r.knob or "", "model": module.describe(dict(r.settings)),
                     **{k: v for k, v in r.settings.items()},
                     "wall_s": m["wall_s"], "cpu_s": m["cpu_s"], "warm_wall_s": m["warm_wall_s"],
                     "peak_rss_mb": m["peak_rss_mb"], "max_load_N": float(o.load_N.max()), "unloaded_elements": o.unloaded,
                     **rung_errors(o, ref), **{name: o.estimates.get(name) for name in ladder.estimates}})
    result = LadderResult(ladder, all_rungs, rows, {k: v["outcome"] for k, v in measured.items()})
    if use_cache:
        path.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(path) as tmp:
            Path(tmp).write_text(json.dumps(_to_json(result)))
    shutil.rmtree(path.with_suffix(""), ignore_errors=True)  # the rungs kept while it ran
    return result


def pareto_front(rows: list[dict], primary: str) -> list[str]:
    """Rungs (not the reference) that no other rung beats in both wall time and ``primary`` error."""
    rs = [r for r in rows if r["rung"] != "reference"]
    front = []
    for r in rs:
        dominated = any(o is not r and o["wall_s"] <= r["wall_s"] and o[primary] <= r[primary]
                        and (o["wall_s"] < r["wall_s"] or o[primary] < r[primary]) for o in rs)
        if not dominated:
            front.append(r["rung"])
    return sorted(front, key=lambda n: next(r["wall_s"] for r in rs if r["rung"] == n))


def convergence(result: LadderResult) -> dict[str, dict]:
    """Per knob with a resolution: its rungs, values, the primary quantity and its observed order."""
    out = {}
    for knob in result.ladder.knobs:
        if knob.resolution is None:
            continue
        members = sweep_members(result.ladder, result.rungs, knob)
        if len(members) < 2:
            continue
        values = [m.settings[knob.key] for m in members]
        res = [float(knob.resolution(v)) for v in values]
        q = [result.ladder.primary_value(result.outcomes[m.name]) for m in members]
        errors = [result.row(m.name)[result.ladder.primary] for m in members]
        out[knob.key] = {"label": knob.label, "resolution_label": knob.resolution_label, "values": values, "resolution": res, "rungs": [m.name for m in members],
                         "primary_value": q, "error": errors, "observed_order": observed_order(res, q)}
    return out


def _cell(row: dict, name: str, front: list[str]):
    if name == "pareto":
        return row["rung"] in front
    value = row.get(name)
    return "" if value is None else value


def _true_errors(result: LadderResult, knob_key: str | None) -> dict[str, float]:
    """The true errors an estimate of ``knob_key`` estimates (:attr:`cases.fidelity.Ladder.estimates`),
    per rung: the ``primary`` error against the reference (None), or against the finest rung of
    that knob's sweep (the other rungs of that sweep only)."""
    ladder, primary = result.ladder, result.ladder.primary
    if knob_key is None:
        return {r["rung"]: float(r[primary]) for r in result.rows if r["rung"] != "reference"}
    knob = next(k for k in ladder.knobs if k.key == knob_key)
    members = sweep_members(ladder, result.rungs, knob)
    finest = result.outcomes[members[-1].name] if members else None
    return {m.name: float(rung_errors(result.outcomes[m.name], finest)[primary]) for m in members[:-1]}


def estimate_tracking(result: LadderResult) -> dict:
    """How the runs' own error estimates track the true errors they estimate (:func:`_true_errors`):
    per estimate and rung with both (true error > 0), the ratio estimate / true, and its range."""
    out = {}
    for name, knob_key in result.ladder.estimates.items():
        true = _true_errors(result, knob_key)
        est = {r["rung"]: r.get(name) for r in result.rows}
        ratios = {k: est[k] / v for k, v in true.items() if v > 0.0 and est.get(k) is not None}
        against = ("its error against the reference" if knob_key is None else
                   f"its error against the finest rung of the {knob_key} sweep")
        track = {"estimates": against, "true_error": {k: v for k, v in true.items() if est.get(k) is not None},
                 "ratio_estimated_to_true": ratios}
        if ratios:
            track.update(min_ratio=min(ratios.values()), max_ratio=max(ratios.values()),
                         within_factor_3=sorted(k for k, v in ratios.items() if 1 / 3 <= v <= 3))
        out[name] = track
    return out


def write_tradeoff(case, out_dir, quick: bool = False, progress=None, source: str | None = None,
                   scheduler: str | None = None, workers: int | None = None):
    """Run (or reuse) the ladder and write tradeoff.csv, the element loads of every rung (the family's
    ``LOADS_FILE``), summary.json and the plots;
    returns (summary, ladder result)."""
    t0 = time.perf_counter()
    result = run_ladder(case, quick, progress, scheduler=scheduler, workers=workers)
    ladder = result.ladder
    front = pareto_front(result.rows, ladder.primary)
    conv = convergence(result)
    with atomic_folder(out_dir, f"tradeoff-{case.name}", source) as tmp:
        out = RunOutput(tmp)
        knob_keys = [k.key for k in ladder.knobs]
        header = ["rung", "knob", "model", *knob_keys, "wall_s", "cpu_s", "warm_wall_s", "peak_rss_mb", "max_load_N",
                  "unloaded_elements", *ladder.errors, *ladder.estimates, "pareto"]
        out.write_csv("tradeoff.csv", [h.replace(".", "_") for h in header],
                      [[_cell(r, h, front) for h in header] for r in result.rows])
        names = [r.name for r in result.rungs]
        module = family_ladder(case)
        label_header, labels = module.element_columns(case, len(result.outcomes["reference"].load_N))
        out.write_csv(module.LOADS_FILE, [*label_header, *[f"{n}_N" for n in names]],
                      [(*labels[i], *(result.outcomes[n].load_N[i] for n in names)) for i in range(len(labels))])
        out.save_figure(plot_pareto(result.rows, front, ladder.primary, ladder.primary_label, case.name), "tradeoff_pareto.png")
        for key, c in conv.items():
            out.save_figure(plot_convergence(key, c, ladder.primary_label), f"convergence_{key.replace('.', '_')}.png")
        ref = result.row("reference")
        out.summary = output_units({
            "case": case.name, "scene": ladder.scene, "quick": quick, "primary": ladder.primary,
            "primary_quantity": ladder.primary_label, "errors": {k: ERROR_NAMES[k] for k in ladder.errors},
            "reference": {"model": ref["model"], "wall_s": ref["wall_s"], "max_load_N": ref["max_load_N"]},
            "rungs": result.rows, "pareto_front": front, "estimate_tracking": estimate_tracking(result),
            "convergence": {k: {kk: v for kk, v in c.items() if "label" not in kk} for k, c in conv.items()},
            "ladder_from_cache": result.cached, "wall_time_s": time.perf_counter() - t0,
            "ladder_wall_s": float(sum(r["wall_s"] + (r["warm_wall_s"] or 0.0) for r in result.rows)),
        })
        out.write_summary()
    return out.summary, result


def choose_fidelity(case, tolerance: float, progress=None, say=print):
    """``case`` at the cheapest rung of its ladder meeting ``tolerance`` on the family's primary
    quantity, and the choice (rung, model, expected error, why, which ladder) for ``summary.json``.

    The ladder comes from the cache (the full one when it exists, else the quick one); without
    either, the quick ladder runs first and ``say`` tells the user. Raises
    :class:`cases.fidelity.ToleranceError` when no rung the case's study can run meets it.
    """
    module = family_ladder(case)
    result = None
    for quick in (False, True):
        ladder = module.ladder(case, quick)
        path = _cache_file(_cache_key(case, module, ladder, quick))
        if path.is_file():
            result = _load_cached(path, ladder, rungs(ladder))
            if result is not None:
                which = "quick" if quick else "full"
                break
    if result is None:
        n = len(rungs(module.ladder(case, True)))
        say(f"no fidelity ladder of this case is cached: running the quick ladder first ({n} rungs, each a "
            f"first run from an empty cache; about a minute per rung on a laptop)")
        result, which = run_ladder(case, quick=True, progress=progress), "quick"
    overrides = {r.name: module.rung_overrides(case, dict(r.settings)) for r in result.rungs}
    rows = [r for r in result.rows if overrides[r["rung"]] is not None]
    chosen, why = choose_rung(rows, tolerance, result.ladder.primary)
    run = case.with_(**overrides[chosen["rung"]])
    said = f"fidelity for a tolerance of {100 * tolerance:g} %: {chosen['model']}"
    run = dataclasses.replace(run, description="; ".join(x for x in (case.description, said) if x))
    choice = {"tolerance": tolerance, "rung": chosen["rung"], "model": chosen["model"],
              "expected_error": float(chosen[result.ladder.primary]), "primary": result.ladder.primary,
              "primary_quantity": result.ladder.primary_label, "why": why, "ladder": which,
              "ladder_scene": result.ladder.scene, "ladder_wall_s_of_rung": float(chosen["wall_s"])}
    return run, choice
