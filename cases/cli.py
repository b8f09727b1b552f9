"""The ``flexbearing`` command line.

Inputs on the command line are in engineering units (mm, N, N·m, deg, GPa) and converted once
to SI. ``--json`` prints machine-readable results instead of tables: SI for ``hertz``, for the
commands that write a results folder the summary as ``summary.json`` holds it, in the output units
of :data:`cases.results.OUTPUT_UNITS` (strict JSON: a value
that is not finite is written as null, with a warning on stderr). Exit status: 0 done, 2 a failure
the input caused (one line on stderr naming the cause and the option or key), 1 an internal error
(one line and a hint; ``--debug`` shows the traceback), 130 interrupted.
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import os
import re
import sys
import traceback
from importlib.metadata import PackageNotFoundError, version

import numpy as np

from foundation.progress import phase, track
from mbd_core.multibody import SimulationError

from . import signals
from .cache_command import add_cache_parser, cache_help_line
from .cli_input import USER_FAILURES, UserError, require_finite, require_positive
from .hertz_command import add_hertz_parser
from .sweep.command import add_cluster_options, add_sweep_parser, cluster_options, cmd_sweep
from .bearing_solver import bearing_solver
from .edge_stress_report import check_edge_stress
from .loaddist_command import (LOAD_NAMES, add_loaddist_parser, bearing_description, check_loaddist_options,
                               chosen_loads, loaddist_outputs)
from .outdir import check_output_target
from .parts import RING_PARTS, ring_part
from .progress_display import terminal_progress
from .report import format_table
from .fidelity import parse_tolerance
from .results import output_units

__all__ = ["main"]



def _check_out(args) -> None:
    """Refuse an unusable ``--out`` before any work (an empty name, a folder the project did not write)."""
    if args.out is None:
        return
    if not args.out.strip():
        raise UserError("--out must name a folder, got an empty string")
    check_output_target(args.out)


def cmd_loaddist(args) -> dict:
    _check_out(args)
    check_loaddist_options(args)
    name, desc = bearing_description(args.bearing)
    if args.edge_stress:
        check_edge_stress(desc.bearing)
    loads, time_share = chosen_loads(desc, {k: getattr(args, k) for k in LOAD_NAMES})
    solver = bearing_solver(desc, rigid=args.rigid_rings)
    with phase(f"load distribution of {name}"):
        results = [solver.solve(load) for load in track(loads, "load cases")] \
            if len(loads) > 1 else [solver.solve(loads[0])]
    return loaddist_outputs(args, name, desc, results, time_share, solver)


def _modes_part(args):
    """The part of ``flexbearing modes``: a built-in part, or a ring of a bearing description file."""
    from .bearing_rings import ring_part_of

    if args.part in RING_PARTS:
        if args.ring is not None:
            raise UserError(f"--ring picks a ring of a bearing description file; {args.part!r} is a built-in part")
        return ring_part(args.part)
    if args.part.endswith(".toml") or os.path.exists(args.part):
        if args.ring is None:
            raise UserError("--ring inner|outer: which ring of the bearing description file")
        _, desc = bearing_description(args.part)
        return ring_part_of(desc, args.ring)
    return ring_part(args.part)


def cmd_modes(args) -> dict:
    from .fem_report import modes_table, part_modes, write_modes

    _check_out(args)
    part = _modes_part(args)
    if args.size_mm is not None:
        require_positive(size_mm=args.size_mm)
    if args.modes < 7:
        raise UserError(f"--modes must be at least 7 (six rigid-body modes + one elastic), got {args.modes}")
    model, modes, summary = part_modes(part, args.modes, None if args.size_mm is None else args.size_mm * 1e-3,
                                       args.element, use_cache=not args.no_cache, keys=("--size-mm", "--modes"))
    if args.out:
        with phase(f"writing {args.out}"):
            write_modes(model, modes, summary, args.out)
    if not args.json:
        print(modes_table(summary))
        if args.out:
            print(f"\nresults: {args.out}/summary.json, modes.vtu (ParaView), mode_*.png")
    return output_units(summary)


def _variant_execution(args, case):
    """The context that sends the study's variants to Dask (``--workers``/``--scheduler``), or
    a null context; refuses the options for a study that makes one run."""
    import contextlib

    from .run import runs_variants
    from .sweep.variants import executing

    scheduler, workers = cluster_options(args, None)
    if scheduler is None:
        return contextlib.nullcontext()
    if not runs_variants(case):
        option = "--workers" if args.workers is not None else "--scheduler"
        raise UserError(f"{option}: the {case.study.kind} study of {case.name} makes one run, nothing to share "
                        "out; flexbearing sweep runs a case over varied keys in parallel")
    return executing(scheduler, workers)


def cmd_run(args) -> dict:
    from .run import CASES, case_source, default_out_dir, resolve_case, run_case

    if args.list or args.case is None:
        print(format_table([(n, d) for n, d in CASES.items()], ("case", "what it runs")))
        return {}
    tolerance = parse_tolerance(args.tolerance) if args.tolerance is not None else None
    _check_out(args)
    case = resolve_case(args.case, args.quick, args.set)
    execution = _variant_execution(args, case)
    source = case_source(args.case)
    out_dir = args.out if args.out is not None else default_out_dir(case, source)
    choice = None
    if tolerance is not None:
        from .tradeoff import choose_fidelity

        check_output_target(out_dir)
        case, choice = choose_fidelity(case, tolerance, progress=track)
        print(f"fidelity: {choice['model']} (rung {choice['rung']} of the {choice['ladder']} ladder), expected "
              f"error of the {choice['primary_quantity']} {100 * choice['expected_error']:.3g} %: {choice['why']}")
    print(f"{case.name}: {case.description}" if case.description else case.name)
    extra = {"summary_extra": {"fidelity_choice": choice}} if choice else {}
    with execution:
        out = run_case(case, out_dir, progress=track, resume=args.resume, source=source, **extra)
    for line in out.report:
        print(f"  {line}")
    entries = sorted({f"*{p.suffix}" for p in out.folder.iterdir() if p.is_file() and not p.name.startswith(".")})
    folders = sorted(f"{p.name}/" for p in out.folder.iterdir() if p.is_dir())
    entries += folders if len(folders) <= 8 else [f"{len(folders)} folders {folders[0]} … {folders[-1]}"]
    print(f"wall time {out.summary['wall_time_s']:.1f} s, peak memory {out.summary['peak_rss_mb']:.0f} MB; "
          f"results in {out.folder}/ ({', '.join(entries)})")
    return out.summary


def cmd_tradeoff(args) -> dict:
    from pathlib import Path

    from .run import case_source, resolve_case
    from .tradeoff import family_ladder, write_tradeoff
    from .tradeoff_plots import order_text

    _check_out(args)
    case = resolve_case(args.case, False, args.set)
    family_ladder(case)  # a family without a ladder stops here, before any work
    out_dir = args.out if args.out is not None else str(Path("results") / f"tradeoff-{case.name}")
    check_output_target(out_dir)
    scheduler, workers = cluster_options(args, None)
    summary, result = write_tradeoff(case, out_dir, args.quick, progress=track, source=case_source(args.case),
                                     scheduler=scheduler, workers=workers)
    print(f"{case.name}: {summary['scene']}; errors of the {summary['primary_quantity']} against the reference "
          f"({summary['reference']['model']})" + (" — ladder from the cache" if result.cached else ""))
    estimates = list(result.ladder.estimates)
    rows = [(r["rung"], r["model"], f"{r['wall_s']:.1f}", f"{r['peak_rss_mb']:.0f}",
             f"{100 * r[result.ladder.primary]:.3g}",
             *("" if r.get(e) is None else f"{100 * r[e]:.3g}" for e in estimates),
             "*" if r["rung"] in summary["pareto_front"] else "")
            for r in result.rows]
    print(format_table(rows, ("rung", "model", "wall s", "peak MB", "error %",
                              *(e.replace("estimated_", "est. ").replace("_", " ") + " %" for e in estimates), "Pareto")))
    for key, c in summary["convergence"].items():
        print(f"  {key}: {order_text(c['observed_order'])}")
    print(f"results in {out_dir}/ (tradeoff.csv, {family_ladder(case).LOADS_FILE}, summary.json, tradeoff_pareto.png, "
          "convergence_*.png)")
    return summary


def build_parser() -> argparse.ArgumentParser:
    try:
        ver = version("flexbearing")
    except PackageNotFoundError:  # running from a source tree
        ver = "unknown"
    parser = argparse.ArgumentParser(prog="flexbearing", description="Dynamics and load distribution of large rolling bearings.",
                                     epilog=cache_help_line())
    parser.add_argument("--version", action="version", version=f"flexbearing {ver}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")
    sub = parser.add_subparsers(dest="command", required=True)
    add_hertz_parser(sub)

    add_loaddist_parser(sub, cmd_loaddist)

    rn = sub.add_parser("run", help="run a case (named study or TOML file) into a results folder")
    rn.add_argument("case", nargs="?", default=None, help="case name (see --list) or a case .toml file")
    rn.add_argument("--quick", action="store_true", help="the reduced variant (coarser meshes, fewer positions)")
    rn.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="change one case entry, e.g. --set undulation.scale=1.5 --set top.n_modes=30")
    rn.add_argument("--out", default=None, help="results folder (default results/<case name>, "
                    "which is not replaced when it holds the results of another named case or case file)")
    rn.add_argument("--list", action="store_true", help="list the named cases")
    rn.add_argument("--json", action="store_true", help="print summary.json to stdout at the end")
    rn.add_argument("--tolerance", default=None, metavar="ERR",
                    help="relative error allowed on the case's primary quantity (e.g. 1%% or 0.01): the case runs "
                    "at the cheapest rung of its fidelity ladder that meets it (flexbearing tradeoff)")
    rn.add_argument("--resume", action="store_true",
                    help="continue an interrupted run of the same case into the same folder from its last checkpoint")
    add_cluster_options(rn, "studies that compare several runs (wind-friction, wind-static, slewing-thermal, …): run them on a "
                        "local Dask cluster of this many worker processes",
                        "as --workers, on a running Dask cluster (tcp://host:8786)")
    rn.set_defaults(func=cmd_run)

    to = sub.add_parser("tradeoff", help="speed against accuracy: run a case's fidelity ladder against its reference")
    to.add_argument("case", help="case name (see run --list) or a case .toml file")
    to.add_argument("--quick", action="store_true", help="the short ladder (a few rungs on a coarse mesh)")
    to.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="change one case entry first")
    to.add_argument("--out", default=None, help="results folder (default results/tradeoff-<case name>)")
    to.add_argument("--json", action="store_true", help="print summary.json to stdout at the end")
    add_cluster_options(to, "measure the rungs on a local Dask cluster of this many workers (side by side: their "
                        "times are then those of a loaded machine)",
                        "measure the rungs on a running Dask cluster (tcp://host:8786), each in a fresh process")
    to.set_defaults(func=cmd_tradeoff)

    md = sub.add_parser("modes", help="free–free natural modes of a ring or cage (solid finite elements)")
    md.add_argument("part", help=f"built-in ring or cage ({', '.join(sorted(RING_PARTS))}), or a bearing "
                    "description file .toml whose [rings.X] table gives the ring (with --ring)")
    md.add_argument("--ring", choices=("inner", "outer"), default=None,
                    help="the ring of a bearing description file")
    md.add_argument("--modes", type=int, default=16, help="modes to compute, rigid-body modes included")
    md.add_argument("--size-mm", type=float, default=None, help="element size (mm); default per part")
    md.add_argument("--element", choices=("hex27", "tet10"), default=None, help="default per part")
    md.add_argument("--no-cache", action="store_true", help="do not read or write the model cache")
    md.add_argument("--out", default=None, help="write summary.json, modes.vtu and PNGs here")
    md.add_argument("--json", action="store_true", help="print SI results as JSON")
    md.set_defaults(func=cmd_modes)
    add_sweep_parser(sub, cmd_sweep)
    add_cache_parser(sub)
    return parser


_NEGATIVE_NUMBER = re.compile(r"^-((\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|inf|infinity|nan)$", re.IGNORECASE)


def _attach_negative_values(argv: list[str]) -> list[str]:
    """Join ``--opt -1e5`` into ``--opt=-1e5``: argparse takes "-1e5" for an option otherwise."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        tok = argv[i]
        if tok.startswith("--") and "=" not in tok and i + 1 < len(argv) and _NEGATIVE_NUMBER.match(argv[i + 1]):
            out.append(f"{tok}={argv[i + 1]}")
            i += 2
        else:
            out.append(tok)
            i += 1
    return out


def _json_safe(value, where: str, bad: list[str]):
    """``value`` with arrays as lists and non-finite floats as None (their paths go to ``bad``)."""
    if isinstance(value, dict):
        return {str(k): _json_safe(v, f"{where}.{k}" if where else str(k), bad) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_json_safe(v, f"{where}[{i}]", bad) for i, v in enumerate(value)]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        bad.append(where)
        return None
    return value if value is None or isinstance(value, (str, int, float)) else str(value)


def _print_json(result: dict) -> None:
    bad: list[str] = []
    text = json.dumps(_json_safe(result, "", bad), indent=1, allow_nan=False)
    if bad:
        print(f"flexbearing: warning: not finite, written as null: {', '.join(bad[:5])}"
              f"{f' and {len(bad) - 5} more' if len(bad) > 5 else ''}", file=sys.stderr)
    print(text)


def _one_line(exc: BaseException) -> str:
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    return "; ".join(lines) or type(exc).__name__


def _os_error_text(exc: OSError, args: argparse.Namespace) -> str:
    """``cannot write PATH: reason``, naming the option or setting the path came from."""
    path = exc.filename if exc.filename is not None else ""
    verb = "cannot read" if isinstance(exc, (FileNotFoundError, IsADirectoryError)) else "cannot write"
    text = f"{verb} {path}: {exc.strerror or exc}" if path else f"{verb}: {exc.strerror or exc}"
    out = getattr(args, "out", None)
    cache = os.environ.get("FLEXBEARING_CACHE")
    if out and str(path).startswith(str(out).rstrip("/")):
        text += " (--out)"
    elif cache and str(path).startswith(cache.rstrip("/")):
        text += " (the cache folder, $FLEXBEARING_CACHE)"
    return text


def _stdout_gone() -> None:
    """After a broken pipe (``flexbearing … | head``): send what is left to devnull, quietly."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # stdout without a file descriptor (captured)
        pass


def _run(args: argparse.Namespace) -> int:
    """Run the chosen command; the exit status by what ended it (module docstring)."""
    try:
        require_finite(args)
        result = args.func(args)
        if args.json:
            _print_json(result)
        sys.stdout.flush()
        return 0
    except signals.Terminated:
        raise                         # ends by its own signal (cases.signals), after the cleanups ran
    except KeyboardInterrupt:
        print("flexbearing: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        _stdout_gone()
        return 1
    except USER_FAILURES as e:
        if args.debug:
            traceback.print_exc()
        stopped = "the simulation stopped: " if isinstance(e, SimulationError) else ""
        print(f"flexbearing: error: {stopped}{_one_line(e)}", file=sys.stderr)
        return 2
    except OSError as e:
        if args.debug:
            traceback.print_exc()
        print(f"flexbearing: error: {_one_line(_os_error_text(e, args))}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001 — an internal error: one line and the way to more
        if args.debug:
            traceback.print_exc()
        print(f"flexbearing: internal error: {type(e).__name__}: {_one_line(e)} "
              f"(run again with --debug for the traceback, and please report it)", file=sys.stderr)
        return 1


def main(argv: list[str] | None = None) -> int:
    signals.install()
    parser = build_parser()
    args = parser.parse_args(_attach_negative_values(sys.argv[1:] if argv is None else list(argv)))
    logging.basicConfig(level=logging.INFO if args.verbose else logging.WARNING, format="%(message)s")
    with terminal_progress(sys.stderr):     # long phases on stderr: stdout stays clean for --json
        return _run(args)


if __name__ == "__main__":
    sys.exit(main())
