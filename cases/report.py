"""Human-readable tables, result folders and plots of quasi-static load distributions."""

from __future__ import annotations

import csv
import json
import os
from pathlib import Path

import numpy as np

from mbd_core.quasistatic import LoadDistribution

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


def _plot(res: LoadDistribution, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.5), constrained_layout=True)
    for r in res.rows:
        psi = np.degrees(r.azimuth_rad) % 360.0
        order = np.argsort(psi)
        ax.plot(psi[order], r.load_N[order], marker="o", ms=3, lw=1, label=f"{r.name} ({r.kind})")
    ax.set_xlabel("element azimuth ψ (deg)")
    ax.set_ylabel("element load Q (N)")
    ax.set_xlim(0, 360)
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    ax.set_title(res.bearing_name)
    ax.legend(loc="best", fontsize=8)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def write_load_distribution(res: LoadDistribution, out_dir: str | os.PathLike, extra: dict | None = None) -> Path:
    """Write summary.json, element_loads.csv and element_loads.png to ``out_dir`` in the output
    units (:data:`cases.results.OUTPUT_UNITS`; elements numbered from 1 per row) (atomically,
    :func:`cases.outdir.atomic_folder`: an existing folder is replaced only if the project wrote it)."""
    with atomic_folder(out_dir, (extra or {}).get("case", res.bearing_name)) as tmp:
        with open(tmp / "element_loads.csv", "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["row", "element", "azimuth_deg", "load_N", "approach_mm", "contact_angle_deg", "unloaded"])
            for r in res.rows:
                for i in range(len(r.load_N)):
                    w.writerow([r.name, i + 1, f"{np.degrees(r.azimuth_rad[i]):.6f}", f"{r.load_N[i]:.6f}",
                                f"{r.approach_m[i] * 1e3:.9e}", f"{np.degrees(r.contact_angle_rad[i]):.6f}",
                                int(r.unloaded[i])])
        _plot(res, tmp / "element_loads.png")
        summary = res.to_dict()
        if extra:
            summary.update(extra)
        (tmp / "summary.json").write_text(json.dumps(output_units(summary), indent=1))
    return Path(out_dir)
