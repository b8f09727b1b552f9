"""The results folder of a run: what a study writes into it, and the short report it prints.

A run writes into a temporary folder that replaces the target only when the run completes
(:func:`cases.outdir.atomic_folder`), so a folder that exists is complete (and carries the
project's marker ``.flexbearing-results.json``): ``case.toml`` (the
resolved case), ``summary.json`` (key figures, units in the key names: :data:`OUTPUT_UNITS`), CSV
time/angle series (the same units),
``.vtu`` files for ParaView and PNG plots.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np

from foundation.text import plural

__all__ = ["RunOutput", "plt", "output_units", "output_name", "OUTPUT_UNITS", "RPM_PER_RAD_S", "plural", "newtons",
           "label_lines", "share_ylim"]

#: r/min per rad/s: speeds leave the model in rad/s and are written in r/min (README, output units)
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)
#: most lines a legend names one by one; more are coloured by their number with a colour bar
LEGEND_MAX_LINES = 16


def plt():
    """matplotlib.pyplot on the off-screen Agg backend (no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot

    return pyplot


#: the unit of each quantity kind in every output file and plot (README, "Output units"):
#: SI-suffixed names and values from the model → (suffix, factor) in the outputs, the first
#: matching ending applies (an elastic modulus ``E_Pa`` in GPa, other stresses in MPa). Forces
#: stay in N, moments in N·m, times in s, frequencies in Hz.
OUTPUT_UNITS = {"_m": ("_mm", 1e3), "E_Pa": ("E_GPa", 1e-9), "_Pa": ("_MPa", 1e-6), "_rad_s": ("_rpm", RPM_PER_RAD_S),
                "_rad": ("_deg", 180.0 / math.pi)}
#: name endings that look like an SI suffix but are not one (a curvature in 1/m)
_NOT_A_UNIT = ("_per_m",)


def output_name(name: str) -> tuple[str, float]:
    """(name in the output units, factor on its value) of an SI-suffixed name, e.g.
    ``("offset_m") → ("offset_mm", 1000.0)``; other names are returned with factor 1."""
    if not name.endswith(_NOT_A_UNIT):
        for suffix, (new, factor) in OUTPUT_UNITS.items():
            if name.endswith(suffix):
                return name[: -len(suffix)] + new, factor
    return name, 1.0


def _scaled(x, factor: float):
    if factor == 1.0 or isinstance(x, (bool, np.bool_, str)) or x is None:
        return x
    if isinstance(x, (list, tuple, np.ndarray)):
        return [_scaled(v, factor) for v in x]
    if isinstance(x, (int, float, np.integer, np.floating)):
        return float(x) * factor
    return x


def output_units(x):
    """``x`` (nested dicts and lists, e.g. a summary) with every SI-suffixed key and its value in
    the output units (:data:`OUTPUT_UNITS`). Idempotent: converted names no longer match."""
    if isinstance(x, dict):
        out = {}
        for k, v in x.items():
            name, factor = output_name(str(k))
            out[name] = _scaled(output_units(v), factor) if factor != 1.0 else output_units(v)
        return out
    if isinstance(x, (list, tuple)):
        return [output_units(v) for v in x]
    return x


def newtons(force_N: float) -> str:
    """A force for titles and reports, in N with thin spaces between thousands: ``"675 909 N"``."""
    return f"{force_N:,.0f}".replace(",", "\u2009") + " N"


def label_lines(ax, lines, names, what: str) -> None:
    """Say which line is which: a legend for up to ``LEGEND_MAX_LINES`` lines, otherwise the lines
    take the colours of a colour bar numbered by ``names`` (``what`` titles it, e.g. "ball")."""
    lines = list(lines)
    if len(lines) <= LEGEND_MAX_LINES:
        for line, name in zip(lines, names):
            line.set_label(f"{what} {name}")
        ax.legend(fontsize=7, ncol=max(1, (len(lines) + 9) // 10), loc="upper left", bbox_to_anchor=(1.01, 1.0))
        return
    import matplotlib as mpl

    numbers = np.asarray([float(n) for n in names])
    norm = mpl.colors.Normalize(numbers.min(), numbers.max())
    cmap = mpl.colormaps["viridis"]
    for line, n in zip(lines, numbers):
        line.set_color(cmap(norm(n)))
    ax.figure.colorbar(mpl.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, label=f"{what} number")
    if ax.get_legend_handles_labels()[0]:  # the other labelled lines and spans keep their legend
        ax.legend(fontsize=7, loc="best")


def share_ylim(axes) -> tuple[float, float]:
    """Give every axis of ``axes`` the union of their y ranges (comparison plots share their
    scale); returns the shared (low, high)."""
    axes = list(axes)
    lo = min(ax.get_ylim()[0] for ax in axes)
    hi = max(ax.get_ylim()[1] for ax in axes)
    for ax in axes:
        ax.set_ylim(lo, hi)
    return lo, hi


def _csv_cell(v, factor: float):
    """A CSV cell: floats with 9 significant digits, numbers of a unit column in the output unit."""
    if isinstance(v, (float, np.floating)) or (factor != 1.0 and isinstance(v, (int, np.integer))
                                               and not isinstance(v, (bool, np.bool_))):
        return f"{v * factor:.9g}"
    return v


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
        """A CSV table; SI-suffixed columns (``approach_m``) are written in the output units
        (``approach_mm``, :func:`output_name`) like the summary's keys."""
        names, factors = zip(*(output_name(h) for h in header))
        p = self.path(name)
        with open(p, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(names)
            for r in rows:
                w.writerow([_csv_cell(v, f) for v, f in zip(r, factors)])
        return p

    def save_figure(self, fig, name: str) -> Path:
        p = self.path(name)
        fig.savefig(p, dpi=120)
        plt().close(fig)
        return p

    def write_timeseries(self, model, run: dict, name: str = "timeseries.nc", **attrs) -> Path:
        """The raw time series of a dynamic run (:mod:`mbd_core.multibody.timeseries`: NetCDF-4, readable
        by xarray or ParaView without flexbearing); ``attrs`` become global attributes (case, study)."""
        from mbd_core.multibody.timeseries import write_timeseries

        p = write_timeseries(self.path(name), model, run, attrs)
        self.summary.setdefault("timeseries_files", []).append(name)
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
        """summary.json: the key figures in the output units (:func:`output_units`)."""
        p = self.path("summary.json")
        p.write_text(json.dumps(_json_ready(output_units(self.summary)), indent=1))
        return p
