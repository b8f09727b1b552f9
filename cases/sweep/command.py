"""``flexbearing sweep``: a case run at every combination (or pairing) of some keys' values.

    flexbearing sweep wind-static --quick --vary loads.scale=0.8,1.0,1.2 --out results/scale
    flexbearing sweep sweep.toml --workers 2
    flexbearing sweep wind-speeds --vary analysis.speed_rpm=20:30:3 --scheduler tcp://10.0.0.5:8786
"""

from __future__ import annotations

from pathlib import Path

from ..config import CaseError

__all__ = ["add_sweep_parser", "cmd_sweep", "add_cluster_options", "cluster_options"]


def add_cluster_options(parser, workers_help: str, scheduler_help: str) -> None:
    """``--workers N`` (a local Dask cluster) and ``--scheduler ADDRESS`` (a running one)."""
    parser.add_argument("--workers", type=int, default=None, help=workers_help)
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS", help=scheduler_help)


def cluster_options(args, default: str | None) -> tuple[str | None, int | None]:
    """(scheduler, workers) from ``--scheduler``/``--workers``: "local" when only ``--workers``
    is given, ``default`` when neither; CaseError naming the option for a bad combination."""
    if args.workers is not None and args.workers < 1:
        raise CaseError(f"--workers must be at least 1, got {args.workers}")
    if args.workers is not None and args.scheduler not in (None, "local"):
        raise CaseError("--workers sizes the local cluster; an existing cluster (--scheduler ADDRESS) has its own")
    if args.scheduler is not None and not args.scheduler.strip():
        raise CaseError("--scheduler must be 'local' or a scheduler's address, got an empty string")
    return args.scheduler or ("local" if args.workers is not None else default), args.workers


def add_sweep_parser(sub, func) -> None:
    sw = sub.add_parser("sweep", help="run a case over varied keys, in parallel on Dask (local cores or a cluster)")
    sw.add_argument("case", help="case name (see run --list), a case .toml file, or a sweep .toml file (with a [vary] table)")
    sw.add_argument("--vary", action="append", default=[], metavar="KEY=V1,V2,…|KEY=START:STOP:N",
                    help="a key and its values (TOML values split at top-level commas) or n evenly spaced values")
    mode = sw.add_mutually_exclusive_group()
    mode.add_argument("--grid", dest="mode", action="store_const", const="grid",
                      help="every combination of the values (default)")
    mode.add_argument("--zip", dest="mode", action="store_const", const="zip",
                      help="the i-th values of every key together (equal lengths)")
    sw.add_argument("--quick", action="store_true", help="the case's reduced variant at every point")
    sw.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="change one case entry at every point")
    add_cluster_options(sw, "worker processes of the local cluster (default: one per core, at most one per point)",
                        "'local' (a LocalCluster on this machine, default) or the address of a running Dask "
                        "scheduler, e.g. tcp://host:8786")
    sw.add_argument("--resume", action="store_true",
                    help="also continue points whose explicit run was interrupted, from their checkpoints "
                    "(completed points are always reused)")
    sw.add_argument("--recompute", action="store_true", help="run every point again, even those already computed")
    sw.add_argument("--plot", action="append", default=None, metavar="FIGURE",
                    help="a column of sweep.csv to plot against the first varied key (default: up to 6 that vary)")
    sw.add_argument("--out", default=None, help="sweep folder (default results/sweep-<case name>)")
    sw.add_argument("--json", action="store_true", help="print sweep.json to stdout at the end")
    sw.set_defaults(func=func, mode=None)


def _spec(args):
    from .spec import SweepSpec, is_sweep_file, parse_vary, read_sweep_file

    axes = tuple(parse_vary(v) for v in args.vary)
    if is_sweep_file(args.case):
        f = read_sweep_file(args.case)
        return SweepSpec(f.case, f.axes + axes, args.mode or f.mode, f.quick or args.quick, f.sets + tuple(args.set))
    return SweepSpec(args.case, axes, args.mode or "grid", args.quick, tuple(args.set))


def cmd_sweep(args) -> dict:
    from ..outdir import check_output_target
    from ..run import resolve_case
    from .runner import run_sweep

    scheduler, workers = cluster_options(args, "local")
    if args.out is not None and not args.out.strip():
        raise CaseError("--out must name a folder, got an empty string")
    spec = _spec(args)
    out_dir = args.out
    if out_dir is None:
        out_dir = str(Path("results") / f"sweep-{resolve_case(spec.case, spec.quick, spec.sets).name}")
    check_output_target(out_dir)
    n = len(spec.points())
    print(f"sweep of {spec.case}{' --quick' if spec.quick else ''}: {n} points ({spec.mode} over "
          f"{', '.join(a.key for a in spec.axes)}) into {out_dir}/")
    result = run_sweep(spec, out_dir, scheduler, workers, args.resume, args.recompute, args.plot)
    counts = {s: sum(1 for r in result["points"] if r.get("status") == s) for s in ("computed", "reused")}
    print(f"{counts['computed']} computed, {counts['reused']} reused; results in {out_dir}/ (sweep.csv, "
          "sweep.parquet, sweep.json, sweep_*.png, one folder per point)")
    return result
