"""Human-readable tables, result folders and plots of quasi-static load distributions."""

from __future__ import annotations

import csv
import json
import os
from pathlib import Path

import numpy as np

from mbd_core.quasistatic import LoadDistribution

from .loaddist_plots import has_ball_rows, plot_contact_angles, plot_element_loads
from .outdir import atomic_folder
from .results import output_units

__all__ = ["atomic_folder", "format_table", "load_distribution_table", "write_load_distribution"]


def format_table(rows: list[tuple], headers: tuple[str, ...]) -> str:
    """Plain-text table with right-aligned columns."""
    cells = [headers] + [tuple(str(c) for c in r) for r in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(headers))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def load_distribution_table(res: LoadDistribution) -> str:
    """Summary of a load distribution: ring displacement, per-row extremes and validity warnings."""
    q = res.displacement
    out = [
        f"bearing: {res.bearing_name}",
        "load:    Fx {:.4g} N, Fy {:.4g} N, Fz {:.4g} N, Mx {:.4g} N·m, My {:.4g} N·m".format(*res.load),
        "moving ring: x {:.4f} mm, y {:.4f} mm, z {:.4f} mm, rot_x {:.4f} mrad, rot_y {:.4f} mrad".format(
            q[0] * 1e3, q[1] * 1e3, q[2] * 1e3, q[3] * 1e3, q[4] * 1e3
        ),
        f"equilibrium error {res.equilibrium_error:.1e} after {res.iterations} Newton iterations"
        + (f"; held at zero (no stiffness): {', '.join(res.held_dofs)}" if res.held_dofs else ""),
        "",
    ]
    rows = []
    for r in res.rows:
        i = int(np.argmax(r.load_N))
        loaded = r.load_N[~r.unloaded]
        rows.append((
            r.name,
            r.kind,
            len(r.load_N),
            f"{r.max_load_N:.0f}",
            f"{np.degrees(r.azimuth_rad[i]):.1f}",
            f"{(loaded.min() if loaded.size else 0.0):.0f}",
            r.n_unloaded,
            f"{np.degrees(r.contact_angle_rad[i]):.3f}",
            f"{r.approach_m[i] * 1e3:.4f}",
        ))
    out.append(format_table(rows, ("row", "kind", "Z", "Q_max N", "at deg", "Q_min>0 N", "unloaded",
                                   "angle deg", "approach mm")))
    out += [f"WARNING: {w}" for w in res.warnings]
    return "\n".join(out)


#: columns of element_loads.csv; the four-point ones are empty for other rows
CSV_COLUMNS = ("row", "element", "azimuth_deg", "load_N", "approach_mm", "contact_angle_deg", "unloaded",
               "load_plus_N", "load_minus_N", "contact_angle_plus_deg", "contact_angle_minus_deg", "n_contact_points")


def _four_point_cells(r, i: int) -> list:
    if r.contact_load_N is None:
        return [""] * 5
    Q, a = r.contact_load_N[i], np.degrees(r.contact_angles_rad[i])
    return [f"{Q[0]:.6f}", f"{Q[1]:.6f}", f"{a[0]:.6f}", f"{a[1]:.6f}", int(r.n_contact_points[i])]


def _write_csv(results: list[LoadDistribution], path: Path) -> None:
    """Per element (and load case, numbered from 1, when there are several): the output units."""
    many = len(results) > 1
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow((("case",) if many else ()) + CSV_COLUMNS)
        for k, res in enumerate(results):
            for r in res.rows:
                for i in range(len(r.load_N)):
                    w.writerow(([k + 1] if many else []) + [
                        r.name, i + 1, f"{np.degrees(r.azimuth_rad[i]):.6f}", f"{r.load_N[i]:.6f}",
                        f"{r.approach_m[i] * 1e3:.9e}", f"{np.degrees(r.contact_angle_rad[i]):.6f}",
                        int(r.unloaded[i])] + _four_point_cells(r, i))


def _case_dict(res: LoadDistribution, extra: dict | None) -> dict:
    """A result's summary with ``extra`` (e.g. static safety) added; its warnings join the result's."""
    d = res.to_dict()
    if extra:
        d.update({k: v for k, v in extra.items() if k != "warnings"})
        d["warnings"] = list(d.get("warnings", [])) + list(extra.get("warnings", []))
    return d


def _cases_summary(results: list[LoadDistribution], time_share, case_extra) -> dict:
    """Summary of several load cases: each case's result, numbered from 1, and each row's largest load."""
    cases = [{"case": k + 1, **({} if time_share is None else {"time_share": time_share[k]}), **_case_dict(res, x)}
             for k, (res, x) in enumerate(zip(results, case_extra))]
    worst = []
    for i, r in enumerate(results[0].rows):
        loads = [res.rows[i].max_load_N for res in results]
        worst.append({"name": r.name, "max_load_N": max(loads), "case": int(np.argmax(loads)) + 1})
    return {"bearing": results[0].bearing_name, "n_load_cases": len(results), "rows_max": worst,
            "warnings": sorted({f"case {k + 1}: {w}" for k, c in enumerate(cases) for w in c["warnings"]}),
            "load_cases": cases}


def write_load_distribution(res: LoadDistribution | list[LoadDistribution], out_dir: str | os.PathLike,
                            extra: dict | None = None, time_share=None, case_extra: list[dict] | None = None,
                            more=None) -> Path:
    """Write summary.json, element_loads.csv, element_loads.png and (ball rows) contact_angles.png to
    ``out_dir`` in the output units (:data:`cases.results.OUTPUT_UNITS`; elements and load cases
    numbered from 1) (atomically, :func:`cases.outdir.atomic_folder`: an existing folder is replaced
    only if the project wrote it). ``res``: one result, or one per load case (``time_share`` their
    shares, or None). ``case_extra``: per load case, entries added to its summary (its
    ``warnings`` joined to the result's); ``more``: a function writing further files into the new
    folder (given its path) before it replaces the old one."""
    results = res if isinstance(res, list) else [res]
    with atomic_folder(out_dir, (extra or {}).get("case", results[0].bearing_name)) as tmp:
        _write_csv(results, tmp / "element_loads.csv")
        plot_element_loads(results, tmp / "element_loads.png")
        if has_ball_rows(results[0]):
            plot_contact_angles(results, tmp / "contact_angles.png")
        case_extra = case_extra or [None] * len(results)
        if more is not None:
            more(tmp)
        summary = _case_dict(results[0], case_extra[0]) if len(results) == 1 else \
            _cases_summary(results, time_share, case_extra)
        if extra:
            summary.update(extra)
        (tmp / "summary.json").write_text(json.dumps(output_units(summary), indent=1))
    return Path(out_dir)
