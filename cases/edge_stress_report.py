"""``flexbearing loaddist --edge-stress``: the raceway pressures along the most loaded roller of each
roller row, slices coupled through the half-space (edge stresses) beside the ISO/TS 16281 slices
(:mod:`mbd_core.bearing.edge_stress`)."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from mbd_core.bearing.edge_stress import RollerEdgeStress, roller_edge_stress
from mbd_core.quasistatic import Bearing, LoadDistribution, RollerRow

from .report import format_table
from .results import plt

__all__ = ["EDGE_STRESS_FILES", "check_edge_stress", "edge_stresses", "edge_stress_lines", "write_edge_stress"]

EDGE_STRESS_FILES = ("roller_edge_stress.csv", "roller_edge_stress.png")


def check_edge_stress(bearing: Bearing) -> None:
    """ValueError naming the option when the bearing has no roller row (before any work)."""
    if not any(isinstance(r, RollerRow) for r in bearing.rows):
        raise ValueError(f"--edge-stress: bearing {bearing.name!r} has no roller rows (edge stresses are "
                         "those of line contacts)")


def edge_stresses(bearing: Bearing, results: list[LoadDistribution]) -> list[tuple[int, RollerEdgeStress]]:
    """(load case index, pressures) of both raceways of each roller row's most loaded roller over
    all load cases; rows without load are left out."""
    out = []
    for i, row in enumerate(bearing.rows):
        if not isinstance(row, RollerRow):
            continue
        loads = np.array([r.rows[i].load_N for r in results])
        case, roller = np.unravel_index(int(np.argmax(loads)), loads.shape)
        if not loads[case, roller] > 0.0:
            continue
        slices = results[case].rows[i].slice_load_N[roller]
        out += [(int(case), e) for e in roller_edge_stress(row, slices, int(roller))]
    return out


def edge_stress_lines(entries: list[tuple[int, RollerEdgeStress]], many_cases: bool) -> list[str]:
    """Screen table: peak pressure with coupled slices against the ISO slices, per row and raceway."""
    if not entries:
        return ["edge stress: no loaded roller"]
    rows = [(e.row, *([case + 1] if many_cases else []), e.roller + 1, e.raceway, f"{e.load_N:.0f}",
             f"{e.peak_pressure_Pa / 1e6:.0f}", f"{e.iso_peak_pressure_Pa / 1e6:.0f}",
             f"{e.peak_pressure_Pa / e.iso_peak_pressure_Pa:.3f}") for case, e in entries]
    head = ("row", *(["case"] if many_cases else []), "roller", "raceway", "Q N", "p_max coupled MPa",
            "p_max ISO MPa", "ratio")
    warnings = [f"WARNING: {e.warning}" for _, e in entries if e.warning]
    return ["", "edge stress of the most loaded roller (slices coupled through the half-space vs ISO/TS 16281):",
            format_table(rows, head), *warnings]


def write_edge_stress(entries: list[tuple[int, RollerEdgeStress]], folder: Path, many_cases: bool) -> None:
    """roller_edge_stress.csv (one line per slice) and roller_edge_stress.png (one panel per row)."""
    folder = Path(folder)
    with open(folder / EDGE_STRESS_FILES[0], "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow((("case",) if many_cases else ()) + ("row", "roller", "raceway", "slice", "x_mm",
                                                         "p_coupled_MPa", "p_iso_MPa"))
        for case, e in entries:
            for k, x in enumerate(e.x_m):
                w.writerow(([case + 1] if many_cases else []) + [
                    e.row, e.roller + 1, e.raceway, k + 1, f"{x * 1e3:.6f}", f"{e.pressure_Pa[k] / 1e6:.6f}",
                    f"{e.iso_pressure_Pa[k] / 1e6:.6f}"])
    names = list(dict.fromkeys(e.row for _, e in entries))
    pyplot = plt()
    fig, axes = pyplot.subplots(1, max(len(names), 1), figsize=(5.0 * max(len(names), 1), 4.2),
                                constrained_layout=True, squeeze=False)
    for ax, name in zip(axes[0], names):
        for j, (case, e) in enumerate(x for x in entries if x[1].row == name):
            ax.plot(e.x_m * 1e3, e.pressure_Pa / 1e6, "o-", ms=3, color=f"C{j}", label=f"{e.raceway}, coupled")
            ax.plot(e.x_m * 1e3, e.iso_pressure_Pa / 1e6, "--", color=f"C{j}", label=f"{e.raceway}, ISO slices")
        ax.set_title(f"{name}: roller {e.roller + 1}" + (f", case {case + 1}" if many_cases else "")
                     + f"\nQ = {e.load_N / 1e3:.4g} kN, raceway tilt {e.tilt_rad * 1e3:.3g} mrad")
        ax.set_xlabel("position along the roller (mm)")
        ax.set_ylabel("peak contact pressure p0 (MPa)")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize=8)
    fig.savefig(folder / EDGE_STRESS_FILES[1], dpi=120)
    pyplot.close(fig)
