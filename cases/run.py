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
from .slewing import presets as slewing_presets
from .slewing import studies as slewing_studies
from .slewing.case import SlewingCase
from .wind import presets as wind_presets
from .wind import studies as wind_studies
from .wind.case import WindCase

__all__ = ["CASES", "resolve_case", "run_case"]

log = logging.getLogger(__name__)

#: the bearings with cases: case class → (presets module, studies module)
_FAMILIES = {SlewingCase: (slewing_presets, slewing_studies), WindCase: (wind_presets, wind_studies)}
PRESETS = {name: c for presets, _ in _FAMILIES.values() for name, c in presets.PRESETS.items()}
#: named cases: name → one-line description
CASES = {name: c.description for name, c in PRESETS.items()}


def _case_class(path: Path) -> type:
    """A case file names its bearing through its tables: ``rollers`` for the wind main bearing."""
    import tomllib

    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"case file {str(path)!r} is not valid TOML: {exc}") from None
    return WindCase if "rollers" in data else SlewingCase


def resolve_case(name_or_path: str, quick_run: bool = False, overrides=()):
    """The case a command line describes (raises :class:`CaseError` naming the bad key)."""
    if name_or_path in PRESETS:
        case = PRESETS[name_or_path]
    elif name_or_path.endswith(".toml"):
        path = Path(name_or_path)
        if not path.is_file():
            raise CaseError(f"case file {name_or_path!r} does not exist")
        case = read_case(_case_class(path), path)
    else:
        raise CaseError(f"unknown case {name_or_path!r}: give a TOML file or one of {', '.join(sorted(PRESETS))}")
    if quick_run:
        case = _FAMILIES[type(case)][0].quick(case)
    return with_overrides(case, list(overrides)) if overrides else case


def _peak_rss_mb() -> float:
    kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return kb / (1024.0 * 1024.0) if platform.system() == "Darwin" else kb / 1024.0


def run_case(case, out_dir, progress=None) -> RunOutput:
    """Run ``case`` into ``out_dir`` (replaced only when the run completes); returns the output."""
    t0 = time.perf_counter()
    with atomic_folder(out_dir) as tmp:
        out = RunOutput(tmp)
        out.path("case.toml").write_text(dumps_case(case))
        _FAMILIES[type(case)][1].run_study(case, out, progress)
        out.summary = {"case": case.name, "study": case.study.kind, "description": case.description,
                       **out.summary, "wall_time_s": time.perf_counter() - t0, "peak_rss_mb": _peak_rss_mb()}
        out.write_summary()
    out.folder = Path(out_dir)
    return out
