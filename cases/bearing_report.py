"""What ``flexbearing loaddist`` adds to a load distribution for a bearing engineer.

Per load case: the static safety factor s0 of every row and of the bearing (ISO 76, from the most
loaded contact: :mod:`mbd_core.bearing.static_safety`), every contact's load, angle, Hertz
pressure p0, ellipse semi-axes and groove-edge truncation (:mod:`mbd_core.quasistatic.contacts`),
and the bearing's 5×5 tangent stiffness matrix (:func:`mbd_core.quasistatic.solver.stiffness_matrix`).
On request, the limiting load curve of axial force against tilting moment
(:mod:`mbd_core.bearing.limiting_load`); with modal rings, beside the rigid-ring curve.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from mbd_core.bearing.limiting_load import LimitingLoadCurve, limiting_load_curve, ray_ratios
from mbd_core.bearing.static_safety import static_safety
from mbd_core.quasistatic import Bearing, LoadDistribution
from mbd_core.quasistatic.contacts import contact_sets

from .bearing_plots import plot_limiting_load_curve
from .report import format_table

__all__ = ["CONTACT_COLUMNS", "bearing_checks", "bearing_checks_lines", "stiffness_lines", "write_contacts_csv",
           "write_limiting_curve", "curve_comparison"]

#: columns of contacts.csv (output units: N, deg, MPa, mm)
CONTACT_COLUMNS = ("row", "element", "contact", "load_N", "contact_angle_deg", "p0_MPa", "a_mm", "b_mm",
                   "truncated")


def _truncation_warnings(sets) -> list[str]:
    """How many contacts of each set are truncated (the validity warnings name the most loaded one)."""
    return [f"row {s.row!r}, {s.label}: {int(s.truncated.sum())} of {len(s.truncated)} contact ellipses truncated "
            "at the groove edge (contacts.csv, column truncated)" for s in sets if s.truncated.any()]


def bearing_checks(bearing: Bearing, dist: LoadDistribution) -> dict:
    """s0 per row and of the bearing, and their warnings (s0 < 1, truncated contact ellipses).

    Returns a dict with ``static_safety`` (``s0`` of the bearing, ``rows``: per row s0, the deciding
    contact, element (numbered from 1) and p0) and ``warnings`` (list of str)."""
    rows = static_safety(bearing, dist)
    s0 = min((r.s0 for r in rows), default=math.inf)
    row_dicts = []
    for r in rows:
        d = r.to_dict()
        d["element"] = r.element + 1 if r.element >= 0 else None
        d["s0"] = None if math.isinf(r.s0) else r.s0
        row_dicts.append(d)
    warnings = [f"row {r.row!r}: static safety s0 = {r.s0:.3g} < 1 (ISO 76): p0 = {r.max_pressure_Pa / 1e6:.0f} MPa "
                f"at {r.contact}, element {r.element + 1}, above the {r.static_limit_Pa / 1e6:.0f} MPa limit"
                for r in rows if r.s0 < 1.0]
    warnings += _truncation_warnings(contact_sets(bearing, dist))
    return {"static_safety": {"s0": None if math.isinf(s0) else s0, "rows": row_dicts}, "warnings": warnings}


def bearing_checks_lines(checks: dict) -> list[str]:
    """Screen lines of :func:`bearing_checks`: a table of s0 per row and the warnings."""
    table = []
    for r in checks["static_safety"]["rows"]:
        s0 = "unloaded" if r["s0"] is None else f"{r['s0']:.3g}"
        table.append((r["row"], s0, r["contact"] or "-", r["element"] or "-", f"{r['max_pressure_Pa'] / 1e6:.0f}"))
    s0 = checks["static_safety"]["s0"]
    head = f"static safety (ISO 76): s0 = {'unloaded' if s0 is None else f'{s0:.3g}'}"
    return ["", head, format_table(table, ("row", "s0", "contact", "element", "p0 MPa")),
            *(f"WARNING: {w}" for w in checks["warnings"])]


def stiffness_lines(dist: LoadDistribution) -> list[str]:
    """The 5×5 stiffness matrix as a table, rows and columns (x, y, z, θx, θy)."""
    if dist.stiffness is None:
        return []
    names = ("x", "y", "z", "rot_x", "rot_y")
    K = np.asarray(dist.stiffness, dtype=float)
    K = np.where(np.abs(K) > 1e-12 * np.abs(K).max(initial=0.0), K, 0.0)  # round-off of exact zeros shown as 0
    rows = [(n, *(f"{v:.4g}" for v in K[i])) for i, n in enumerate(("Fx", "Fy", "Fz", "Mx", "My"))]
    return ["", "stiffness matrix dF/dq at the operating point (force rows N/m, N/rad; moment rows N·m/m, N·m/rad)",
            format_table(rows, ("", *names))]


def write_contacts_csv(bearing: Bearing, results: list[LoadDistribution], path: Path) -> None:
    """contacts.csv: one line per element and contact (per load case when there are several)."""
    many = len(results) > 1
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow((("case",) if many else ()) + CONTACT_COLUMNS)
        for k, dist in enumerate(results):
            for s in contact_sets(bearing, dist):
                for i in range(len(s.load_N)):
                    w.writerow(([k + 1] if many else []) + [
                        s.row, i + 1, s.label, f"{s.load_N[i]:.6f}", f"{math.degrees(s.contact_angle_rad[i]):.6f}",
                        f"{s.max_pressure_Pa[i] / 1e6:.6f}", f"{s.semi_major_m[i] * 1e3:.6f}",
                        f"{s.semi_minor_m[i] * 1e3:.6f}", int(s.truncated[i])])


def _write_curve_csv(curve: LimitingLoadCurve, path: Path) -> None:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(("ray", "axial_force_N", "tilting_moment_Nm", "row", "contact", "element", "carried",
                    "equilibrium_limited"))
        for i in range(len(curve.axial_N)):
            w.writerow((i + 1, f"{curve.axial_N[i]:.6g}", f"{curve.moment_Nm[i]:.6g}", curve.row[i], curve.contact[i],
                        int(curve.element[i]) + 1 if curve.element[i] >= 0 else "", int(curve.carried[i]),
                        int(curve.equilibrium_limited[i])))


def write_limiting_curve(bearing: Bearing, folder: Path, results: list[LoadDistribution], s0: float = 1.0,
                         pressure_limit_Pa: float | None = None, n_rays: int = 36, solve=None):
    """limiting_load_curve.csv and .png in ``folder``, at the largest radial force of the load cases
    (conservative for the others), the load cases' (M, Fz) marked on the plot.

    With ``solve`` (a flexible-ring model's load → distribution) the curve is that model's, on the
    rays of the rigid-ring curve, which is written beside it (limiting_load_curve_rigid.csv) and drawn
    dashed. Returns (curve, rigid curve or None).
    """
    radial_N = max(math.hypot(r.load[0], r.load[1]) for r in results)
    rigid = limiting_load_curve(bearing, n_rays=n_rays, s0=s0, pressure_limit_Pa=pressure_limit_Pa, radial_N=radial_N)
    curve = rigid
    if solve is not None:
        curve = limiting_load_curve(bearing, n_rays=n_rays, s0=s0, pressure_limit_Pa=pressure_limit_Pa,
                                    radial_N=radial_N, axial_ref_N=rigid.axial_ref_N,
                                    moment_ref_Nm=rigid.moment_ref_Nm, solve=solve)
        _write_curve_csv(rigid, folder / "limiting_load_curve_rigid.csv")
    _write_curve_csv(curve, folder / "limiting_load_curve.csv")
    # the curve is the same for a moment about any diametral axis: each case at its moment's size
    points = [(math.copysign(math.hypot(r.load[3], r.load[4]), r.load[4] or r.load[3] or 1.0), float(r.load[2]))
              for r in results]
    labels = ("modal rings", "rigid rings") if solve is not None else ("limiting load", "")
    plot_limiting_load_curve(curve, folder / "limiting_load_curve.png", bearing.name, operating_points=points,
                             reference=rigid if solve is not None else None, labels=labels)
    return curve, (rigid if solve is not None else None)


def curve_comparison(curve: LimitingLoadCurve, rigid: LimitingLoadCurve) -> dict:
    """How far the modal-ring curve lies inside the rigid one: load scale ratios along the rays."""
    ratio = ray_ratios(curve, rigid)
    ok = np.isfinite(ratio)
    if not ok.any():
        return {"rays_compared": 0}
    k = int(np.nanargmin(ratio))
    return {"rays_compared": int(ok.sum()), "min_ratio": float(ratio[k]), "mean_ratio": float(np.nanmean(ratio)),
            "max_ratio": float(np.nanmax(ratio)),
            "min_ratio_at": {"axial_force_N": float(rigid.axial_N[k]), "tilting_moment_Nm": float(rigid.moment_Nm[k])},
            "equilibrium_limited_rays": {"modal": int(curve.equilibrium_limited.sum()),
                                         "rigid": int(rigid.equilibrium_limited.sum())},
            "ratio_per_ray": [None if not np.isfinite(v) else float(v) for v in ratio]}
