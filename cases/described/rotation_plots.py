"""Figure of a described bearing's ``rotation`` study (matplotlib, off-screen): per row, the ball
loads over time against the quasi-static largest load, and the cage (or ball orbit) speed against
the no-slip speed."""

from __future__ import annotations

import math

from mbd_core.multibody.bearings import row_speed_rad_s

from ..results import plt

__all__ = ["plot_rotation"]


def plot_rotation(sc, desc, run: dict, figures: dict):
    """Ball loads (top) and cage speeds (bottom) of every row over the run; the left-out start dimmed."""
    t = run["t"]
    fig, (ax, bx) = plt().subplots(2, 1, figsize=(9, 6.5), sharex=True, constrained_layout=True)
    for k, (row, rb, fr) in enumerate(zip(sc.rows, sc.row_bodies, figures["rows"])):
        colour = f"C{k}"
        fn = run["fn"][:, list(rb.moving_pairs)]
        ax.plot(t, fn, color=colour, lw=0.6, alpha=0.5)
        ax.plot([], [], color=colour, lw=1, label=f"{row.name}: balls")
        ax.axhline(fr["quasistatic_largest_load_N"], color=colour, ls="--", lw=1,
                   label=f"{row.name}: quasi-static largest load {fr['quasistatic_largest_load_N']:.0f} N")
        w = row_speed_rad_s(rb, run["q"], run["v"])
        what = "cage" if rb.cage is not None else "ball orbit"
        bx.plot(t, w * 30 / math.pi, color=colour, lw=1, label=f"{row.name}: {what}")
        bx.axhline(fr["kinematic_cage_speed_rpm"], color=colour, ls="--", lw=1, label=f"{row.name}: no slip")
    for a in (ax, bx):
        a.axvspan(t[0], figures["settled_from_s"], color="0.9", zorder=0)
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7, loc="best")
    ax.set_ylabel("ball load at the moving ring (N)")
    bx.set_ylabel("speed about the axis (r/min)")
    bx.set_xlabel("time (s)")
    ax.set_title(f"{desc.name}: rotation, largest deviation from the quasi-static loads "
                 f"{100 * figures['max_deviation_from_quasistatic']:.2f} % (shaded: start, left out)")
    return fig
