"""Figures of the wind main bearing studies (matplotlib, Agg)."""

from __future__ import annotations

import math

import numpy as np

from cases.results import RPM_PER_RAD_S, label_lines, plt, share_ylim

from .dynamic import roller_spin_rad_s, watched_roller
from .scene import rolling_speeds
from .spectrum import plot_spectrum

__all__ = ["spectrum_figure", "max_loads_figure", "load_cases_figure", "roller_speed_figure", "roller_speed_figures", "sweep_figure"]


def spectrum_figure(times_s, loads, share, path):
    return plot_spectrum(times_s, loads, share, path)


def max_loads_figure(per_row: dict, share):
    p = plt()
    fig, ax = p.subplots(figsize=(8, 4.5))
    k = np.arange(1, len(share) + 1)  # numbered from 1, as in max_roller_loads.csv
    for name, vals in per_row.items():
        ax.plot(k, [v[0] for v in vals], marker="o", ms=3, label=name)
    ax.set_xlabel("load case")
    ax.set_ylabel("largest roller load, N")
    ax.set_title(f"Quasi-static roller loads (rigid rings) under the {len(share)} load cases")
    ax.grid(alpha=0.3)
    ax.legend()
    return fig


def load_cases_figure(per_case: list[dict]):
    """The load of every roller against its azimuth, one panel per row and one line per load case
    (coloured by its number from 1): ``per_case[k]`` row name → (azimuth deg, load N)."""
    p = plt()
    names = list(per_case[0])
    fig, axes = p.subplots(len(names), 1, figsize=(9, 1.0 + 2.4 * len(names)), sharex=True, squeeze=False,
                           constrained_layout=True)
    for ax, name in zip(axes[:, 0], names):
        lines = []
        for rows in per_case:
            psi, q = (np.asarray(v, float) for v in rows[name])
            order = np.argsort(psi)
            lines += ax.plot(psi[order], q[order], lw=0.9)
        label_lines(ax, lines, range(1, len(per_case) + 1), "load case")
        ax.set_ylabel("roller load, N")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
        ax.set_title(f"{name} row", fontsize=9)
    axes[-1, 0].set_xlabel("roller azimuth ψ (deg)")
    axes[-1, 0].set_xlim(0, 360)
    axes[-1, 0].set_xticks(np.arange(0, 361, 45))
    fig.suptitle(f"Quasi-static roller loads (rigid rings) under the {len(per_case)} load cases")
    return fig


def roller_speed_figure(case, sc, rec):
    """Spin of the most loaded roller of each row at the start (numbered from 1), relative to the
    cage, with the no-slip value; the settling window that the summary's averages leave out is shaded."""
    p = plt()
    fig, axes = p.subplots(3, 1, figsize=(8, 8), sharex=True)
    w_i = case.analysis.speed_rpm * 2.0 * math.pi / 60.0
    for k, ax in enumerate(axes):
        row = sc.row_defs[k]
        _, w_s = rolling_speeds(row, w_i)
        j = watched_roller(sc, rec, k)
        spin = np.abs(roller_spin_rad_s(sc, rec, k)[:, j]) * RPM_PER_RAD_S
        settle = case.analysis.settle_s
        if settle > rec["t"][0]:
            ax.axvspan(rec["t"][0], settle, color="0.88", label="settling, not in summary.json's averages")
        ax.plot(rec["t"], spin, lw=0.8, label=f"roller {j + 1} (relative to the cage)")
        ax.axhline(abs(w_s) * RPM_PER_RAD_S, color="k", ls="--", lw=1, label=f"no slip {abs(w_s) * RPM_PER_RAD_S:.1f} r/min")
        ax.set_ylabel("r/min")
        ax.set_title(f"{row.name} row", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="best")
    axes[-1].set_xlabel("time, s")
    b = case.bodies
    fig.suptitle(f"Roller spin at {case.analysis.speed_rpm:g} r/min ({b.rings} rings, {b.cages} cages)")
    fig.tight_layout()
    return fig


def roller_speed_figures(runs: dict) -> dict:
    """:func:`roller_speed_figure` of each run, ``runs`` label → (case, scene, record); the
    figures of one comparison share the y range of each row (the larger of them)."""
    figs = {label: roller_speed_figure(*run) for label, run in runs.items()}
    for k in range(3):
        share_ylim(f.axes[k] for f in figs.values())
    return figs


def sweep_figure(results: dict, xlabel: str):
    """Mean and peak roller–cage force per row, and the rings' friction torque (mean ± ripple), over
    the swept values."""
    p = plt()
    fig, (a, b, c) = p.subplots(1, 3, figsize=(14, 4))
    keys = list(results)
    x = np.arange(len(keys))
    for name in ("radial", "front thrust", "rear thrust"):
        a.plot(x, [results[k]["cage_forces"][name]["mean_N"] for k in keys], marker="o", label=name)
        b.plot(x, [results[k]["cage_forces"][name]["peak_N"] for k in keys], marker="o", label=name)
    for ring in ("inner", "outer"):
        c.errorbar(x, [results[k]["ring_torque"][f"{ring}_ring_Nm"] for k in keys],
                   yerr=[results[k]["ring_torque"][f"{ring}_ring_ripple_Nm"] for k in keys], marker="o", capsize=3,
                   label=f"{ring} ring (± ripple)")
    for ax, what in ((a, "mean roller–cage force, N"), (b, "peak roller–cage force, N"),
                     (c, "friction torque about the axis, N·m")):
        ax.set_xticks(x, [str(k) for k in keys])
        ax.set_xlabel(xlabel)
        ax.set_ylabel(what)
        ax.grid(alpha=0.3)
        ax.legend()
    fig.tight_layout()
    return fig
