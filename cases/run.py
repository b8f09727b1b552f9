"""``flexbearing run``: from a case name or TOML file to a complete results folder.

Resolution order: the named sub-case (or the TOML file), then ``--quick``, then every ``--set
key=value``; the resolved case is validated before any meshing starts and saved as ``case.toml``
beside the results, so a folder always says exactly what produced it.
"""

from __future__ import annotations

import logging
import platform
import resource
import time
from pathlib import Path

from .config import CaseError, dumps_case, read_case, with_overrides
from .report import atomic_folder
from .results import RunOutput
from .slewing.case import SlewingCase
from .slewing.presets import PRESETS, preset, quick
from .slewing.studies import run_study

__all__ = ["CASES", "resolve_case", "run_case"]

log = logging.getLogger(__name__)

#: named cases: name → one-line description
CASES = {name: c.description for name, c in PRESETS.items()}


def resolve_case(name_or_path: str, quick_run: bool = False, overrides=()) -> SlewingCase:
    """The case a command line describes (raises :class:`CaseError` naming the bad key)."""
    if name_or_path in PRESETS:
        case = preset(name_or_path)
    elif name_or_path.endswith(".toml"):
        path = Path(name_or_path)
        if not path.is_file():
            raise CaseError(f"case file {name_or_path!r} does not exist")
        case = read_case(SlewingCase, path)
    else:
        raise CaseError(f"unknown case {name_or_path!r}: give a TOML file or one of {', '.join(sorted(PRESETS))}")
    if quick_run:
        case = quick(case)
    return with_overrides(case, list(overrides)) if overrides else case


def _peak_rss_mb() -> float:
    kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return kb / (1024.0 * 1024.0) if platform.system() == "Darwin" else kb / 1024.0


def run_case(case: SlewingCase, out_dir, progress=None) -> RunOutput:
    """Run ``case`` into ``out_dir`` (replaced only when the run completes); returns the output."""
    t0 = time.perf_counter()
    with atomic_folder(out_dir) as tmp:
        out = RunOutput(tmp)
        out.path("case.toml").write_text(dumps_case(case))
        run_study(case, out, progress)
        out.summary = {"case": case.name, "study": case.study.kind, "description": case.description,
                       **out.summary, "wall_time_s": time.perf_counter() - t0, "peak_rss_mb": _peak_rss_mb()}
        out.write_summary()
    out.folder = Path(out_dir)
    return out
