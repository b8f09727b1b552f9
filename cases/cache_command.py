"""``flexbearing cache info|clean``: where the model cache is, what it holds, and clearing it.

The cache (meshes, FE matrices, reduced bodies; :mod:`fem_rings.cache`) lives in
``$FLEXBEARING_CACHE`` or ``~/.cache/flexbearing``. A change of the stored format leaves older
entries unused on disk; ``clean --older-than-days N`` removes the entries not used for N days,
plain ``clean`` all of them. Only the cache's own entry files are removed (:mod:`fem_rings.cache_admin`).
"""

from __future__ import annotations

import time

from fem_rings.cache import cache_dir
from foundation.text import plural
from fem_rings.cache_admin import cache_entries, remove_entries, summarise

__all__ = ["add_cache_parser", "cache_help_line"]

_MB = 1024.0 * 1024.0


def cache_help_line() -> str:
    """One line for ``flexbearing --help``: the cache folder and its size."""
    try:
        s = summarise(cache_entries())
    except OSError:
        return f"model cache: {cache_dir()} (unreadable)"
    return (f"model cache: {cache_dir()} ({plural(s['entries'], 'entry', 'entries')}, {s['size_bytes'] / _MB:.0f} MB; "
            "$FLEXBEARING_CACHE moves it; see 'flexbearing cache info')")


def _print_kinds(summary: dict) -> None:
    for kind, k in sorted(summary["kinds"].items()):
        print(f"  {kind:10s} {k['entries']:5d} entries {k['size_bytes'] / _MB:10.1f} MB")


def cmd_cache_info(args) -> dict:
    entries = cache_entries()
    summary = {"folder": str(cache_dir()), **summarise(entries)}
    if entries:
        summary["least_recently_used_days"] = (time.time() - entries[0].last_used_s) / 86400.0
    if not args.json:
        print(f"model cache {summary['folder']}: {plural(summary['entries'], 'entry', 'entries')}, "
              f"{summary['size_bytes'] / _MB:.1f} MB")
        _print_kinds(summary)
        if entries:
            print(f"least recently used entry: {summary['least_recently_used_days']:.1f} days ago")
    return summary


def cmd_cache_clean(args) -> dict:
    removed = remove_entries(args.older_than_days)
    summary = {"folder": str(cache_dir()), "removed": summarise(removed),
               "left": summarise(cache_entries())}
    if not args.json:
        age = "" if args.older_than_days is None else f" not used for {args.older_than_days:g} days"
        print(f"removed {plural(len(removed), 'entry', 'entries')}{age} ({summary['removed']['size_bytes'] / _MB:.1f} MB) "
              f"from {summary['folder']}; {plural(summary['left']['entries'], 'entry', 'entries')} "
              f"({summary['left']['size_bytes'] / _MB:.1f} MB) left")
    return summary


def add_cache_parser(sub) -> None:
    """The ``cache`` command with its ``info`` and ``clean`` sub-commands."""
    c = sub.add_parser("cache", help="where the model cache is, its size, and cleaning it")
    cs = c.add_subparsers(dest="action", required=True)
    info = cs.add_parser("info", help="the cache folder, its entries and size per kind")
    info.set_defaults(func=cmd_cache_info)
    clean = cs.add_parser("clean", help="remove cached models (all, or those not used for some days)")
    clean.add_argument("--older-than-days", type=float, default=None, metavar="DAYS",
                       help="remove only entries not used for this many days")
    clean.set_defaults(func=cmd_cache_clean)
    for p in (info, clean):
        p.add_argument("--json", action="store_true", help="print the figures as JSON")
