"""Plots of quasi-static load distributions: element loads around the circumference per row, and
the contact angles of the ball rows (both diagonals of four-point rows). Output units of
:data:`cases.results.OUTPUT_UNITS` (N, degrees); elements and load cases numbered from 1."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mbd_core.quasistatic import LoadDistribution

from .results import label_lines, plt

__all__ = ["plot_element_loads", "plot_contact_angles", "has_ball_rows"]


def _by_azimuth(r):
    psi = np.degrees(r.azimuth_rad) % 360.0
    return psi, np.argsort(psi)


def _panels(n: int, title: str):
    pyplot = plt()
    fig, axes = pyplot.subplots(n, 1, figsize=(9, 1.0 + 2.4 * n), sharex=True, squeeze=False,
                                constrained_layout=True)
    fig.suptitle(title)
    axes = axes[:, 0]
    axes[-1].set_xlabel("element azimuth ψ (deg)")
    axes[-1].set_xlim(0, 360)
    axes[-1].set_xticks(np.arange(0, 361, 45))
    return pyplot, fig, axes


def plot_element_loads(results: list[LoadDistribution], path: Path) -> None:
    """One panel per row: the load of each element against its azimuth, one line per load case."""
    first = results[0]
    pyplot, fig, axes = _panels(len(first.rows), f"{first.bearing_name}: element loads")
    for i, ax in enumerate(axes):
        lines = []
        crossed = _diagonals(first.rows[i])
        for res in results:
            r = res.rows[i]
            psi, order = _by_azimuth(r)
            if crossed is None:
                lines += ax.plot(psi[order], r.load_N[order], marker="o", ms=2.5, lw=1)
                continue
            for k, on in enumerate(crossed):  # one line per diagonal, the second dashed in the same colour
                o = order[on[order]]
                line, = ax.plot(psi[o], r.load_N[o], marker="o", ms=2.5, lw=1, ls="-" if k == 0 else "--",
                                color=None if k == 0 else lines[-1].get_color())
                if k == 0:
                    lines.append(line)
        ax.set_ylabel("Q (N)")
        ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
        note = "; solid: rollers on +α, dashed: on −α" if crossed is not None else ""
        ax.set_title(f"{first.rows[i].name} ({first.rows[i].kind}, {len(first.rows[i].load_N)} elements{note})",
                     fontsize=9)
        if len(results) > 1:
            label_lines(ax, lines, range(1, len(results) + 1), "load case")
    fig.savefig(path, dpi=110)
    pyplot.close(fig)


def _diagonals(r):
    """Masks of the rollers on +α and on −α of a crossed roller row (contact angles of both signs), else None."""
    if r.kind != "roller":
        return None
    plus, minus = r.contact_angle_rad > 0.0, r.contact_angle_rad < 0.0
    return (plus, minus) if plus.any() and minus.any() else None


def has_ball_rows(res: LoadDistribution) -> bool:
    return any(r.kind == "ball" for r in res.rows)


def plot_contact_angles(results: list[LoadDistribution], path: Path) -> None:
    """One panel per ball row: the loaded contact angle of each ball against its azimuth (four-point
    rows: each diagonal, +α solid and −α dashed, where it carries load), one colour per load case."""
    first = results[0]
    index = [i for i, r in enumerate(first.rows) if r.kind == "ball"]
    pyplot, fig, axes = _panels(len(index), f"{first.bearing_name}: contact angles of the loaded balls")
    for ax, i in zip(axes, index):
        lines = []
        for k, res in enumerate(results):
            r = res.rows[i]
            psi, order = _by_azimuth(r)
            colour = f"C{k % 10}"
            if r.contact_load_N is None:
                angle = np.where(r.unloaded, np.nan, np.degrees(r.contact_angle_rad))
                lines += ax.plot(psi[order], angle[order], marker="o", ms=2.5, lw=1, color=colour)
                continue
            for j, style in enumerate(("-", "--")):
                loaded = r.contact_load_N[:, j] > 0.0
                angle = np.where(loaded, np.degrees(r.contact_angles_rad[:, j]), np.nan)
                line = ax.plot(psi[order], angle[order], style, marker="o", ms=2.5, lw=1, color=colour,
                               label=("+α diagonal" if j == 0 else "−α diagonal") if k == 0 else None)
                if j == 0:
                    lines += line
        ax.set_ylabel("α (deg)")
        ax.grid(True, alpha=0.3)
        four_point = first.rows[i].contact_load_N is not None
        ax.set_title(first.rows[i].name + (" (diagonals: +α solid, −α dashed)" if four_point else ""), fontsize=9)
        if len(results) > 1:
            label_lines(ax, lines, range(1, len(results) + 1), "load case")
        elif ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="best")
    fig.savefig(path, dpi=110)
    pyplot.close(fig)
