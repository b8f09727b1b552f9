"""The results folder of a run: what a study writes into it, and the short report it prints.

A run writes into a temporary folder that replaces the target only when the run completes
(:func:`cases.outdir.atomic_folder`), so a folder that exists is complete (and carries the
project's marker ``.flexbearing-results.json``): ``case.toml`` (the
resolved case), ``summary.json`` (key figures, SI units in the key names), CSV time/angle series,
``.vtu`` files for ParaView and PNG plots.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np

__all__ = ["RunOutput", "plt"]


def plt():
    """matplotlib.pyplot on the off-screen Agg backend (no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot

    return pyplot


def _json_ready(x):
    if isinstance(x, dict):
        return {str(k): _json_ready(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_ready(v) for v in x]
    if isinstance(x, np.ndarray):
        return _json_ready(x.tolist())
    if isinstance(x, (np.floating, float)):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, np.bool_):
        return bool(x)
    return x


#: validity warnings printed in the report; all of them go to summary.json
PRINTED_WARNINGS = 5


class RunOutput:
    """Collects the files, key figures and report lines of one run in ``folder``."""

    def __init__(self, folder: Path):
        self.folder = Path(folder)
        self.summary: dict = {}
        self.report: list[str] = []

    def path(self, name: str) -> Path:
        p = self.folder / name
        p.parent.mkdir(parents=True, exist_ok=True)
        return p

    def write_csv(self, name: str, header, rows) -> Path:
        p = self.path(name)
        with open(p, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            for r in rows:
                w.writerow([f"{v:.9g}" if isinstance(v, (float, np.floating)) else v for v in r])
        return p

    def save_figure(self, fig, name: str) -> Path:
        p = self.path(name)
        fig.savefig(p, dpi=120)
        plt().close(fig)
        return p

    def note(self, line: str) -> None:
        self.report.append(line)

    def warn(self, messages, context: str = "") -> None:
        """Record validity warnings (once each) in ``summary["warnings"]`` and the printed report.

        ``messages`` is an iterable of strings, e.g. ``LoadDistribution.warnings``; ``context``
        says which load case or position they belong to.
        """
        seen = self.summary.setdefault("warnings", [])
        for m in messages:
            line = f"{context}: {m}" if context else str(m)
            if line in seen:
                continue
            seen.append(line)
            if len(seen) <= PRINTED_WARNINGS:
                self.report.append(f"WARNING: {line}")
            elif len(seen) == PRINTED_WARNINGS + 1:
                self.report.append("WARNING: more warnings in summary.json (key 'warnings')")

    def write_summary(self) -> Path:
        p = self.path("summary.json")
        p.write_text(json.dumps(_json_ready(self.summary), indent=1))
        return p
