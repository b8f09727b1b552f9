"""``flexbearing loaddist``: which bearing the argument names, and the table of a load spectrum's results."""

from __future__ import annotations

import os

from mbd_core.quasistatic import RingLoad
from mbd_core.quasistatic.results import LOAD_NAMES

from .bearing_file import BUILTIN_DIR, BearingDescription, read_bearing_file
from .catalog import BUILTIN_BEARINGS
from .report import format_table

__all__ = ["LOAD_NAMES", "bearing_description", "cases_table", "chosen_loads"]


def chosen_loads(desc: BearingDescription, given: dict) -> tuple[tuple[RingLoad, ...], tuple[float, ...] | None]:
    """(load cases, time shares) to solve: the file's, or one case of the ``given`` components
    (None: not given, 0) when any is given."""
    if all(v is None for v in given.values()):
        return desc.load_cases, desc.time_share
    return (RingLoad(**{k: (0.0 if v is None else v) for k, v in given.items()}),), None


def bearing_description(name: str) -> tuple[str, BearingDescription]:
    """(name, description) of a built-in bearing by name, or of a description file by path
    (:mod:`cases.bearing_file`; the built-ins are files too, read alike). ValueError naming the
    argument when it is neither."""
    if name in BUILTIN_BEARINGS:
        return name, read_bearing_file(BUILTIN_DIR / f"{name}.toml")
    if name.endswith(".toml") or os.sep in name or "/" in name or os.path.exists(name):
        return os.path.splitext(os.path.basename(name.rstrip("/" + os.sep)))[0] or name, read_bearing_file(name)
    raise ValueError(f"bearing: unknown built-in bearing {name!r}; one of {', '.join(sorted(BUILTIN_BEARINGS))}, "
                    "or a bearing description file (.toml)")


def cases_table(results, time_share) -> str:
    """One line per load case: the load and each row's largest element load."""
    names = [r.name for r in results[0].rows]
    lines = []
    for k, res in enumerate(results):
        share = [] if time_share is None else [f"{time_share[k]:.4g}"]
        lines.append((k + 1, *share, *(f"{v:.4g}" for v in res.load), *(f"{r.max_load_N:.0f}" for r in res.rows)))
    head = ("case", *(["time_share"] if time_share is not None else []), "Fx N", "Fy N", "Fz N", "Mx N·m",
            "My N·m", *(f"Q_max {n} N" for n in names))
    warnings = [f"WARNING: case {k + 1}: {w}" for k, res in enumerate(results) for w in res.warnings]
    return "\n".join([f"bearing: {results[0].bearing_name}", format_table(lines, head), *warnings])
