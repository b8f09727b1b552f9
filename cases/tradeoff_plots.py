"""Plots of a fidelity ladder: error against wall time with the Pareto front, and one convergence
plot per knob with its observed order."""

from __future__ import annotations

import numpy as np

from .results import plt

__all__ = ["plot_pareto", "plot_convergence", "order_text", "ERROR_FLOOR"]

#: errors below this are drawn at it (log axes; a rung identical to the reference has error 0)
ERROR_FLOOR = 1e-7
#: wall times below this are drawn at it (a rigid ring's equilibrium takes milliseconds)
TIME_FLOOR_S = 1e-3


def order_text(p: float | None) -> str:
    """The observed order in words: a negative or missing one means the knob does not converge."""
    if p is None:
        return "observed order: not measurable (fewer than three values, or no change)"
    if p <= 0.0:
        return f"not converging (observed order p ≈ {p:.2f})"
    return f"observed order p ≈ {p:.2f}"


def plot_pareto(rows: list[dict], front: list[str], primary: str, primary_label: str, title: str):
    """Relative error of the primary quantity vs wall time (log–log), every rung labelled, the
    Pareto front joined, the reference's wall time a dashed line."""
    pyplot = plt()
    fig, ax = pyplot.subplots(figsize=(8.0, 5.5))
    rs = [r for r in rows if r["rung"] != "reference"]
    t = np.maximum([r["wall_s"] for r in rs], TIME_FLOOR_S)
    e = np.maximum([r[primary] for r in rs], ERROR_FLOOR)
    on = np.array([r["rung"] in front for r in rs])
    ax.loglog(t[~on], e[~on], "o", color="0.55", label="rung")
    ax.loglog(t[on], e[on], "o", color="C3", label="Pareto front")
    order = np.argsort(t[on])
    ax.loglog(t[on][order], e[on][order], "-", color="C3", lw=1.2)
    for r, ti, ei in zip(rs, t, e):
        ax.annotate(r["rung"], (ti, ei), textcoords="offset points", xytext=(4, 3), fontsize=7)
    ref = next(r for r in rows if r["rung"] == "reference")
    ax.axvline(ref["wall_s"], ls="--", color="k", lw=0.8)
    ax.text(ref["wall_s"], ax.get_ylim()[1], " reference", va="top", fontsize=8)
    ax.set_xlabel("wall time of a first run (s, meshing and reduction included)")
    ax.set_ylabel(f"relative error of the {primary_label}")
    ax.set_title(f"{title}: accuracy bought for time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    return fig


def plot_convergence(key: str, conv: dict, primary_label: str):
    """Error against the reference along one knob (log–log over its resolution), the observed
    order of self-convergence printed on it."""
    pyplot = plt()
    fig, ax = pyplot.subplots(figsize=(6.5, 4.5))
    x = np.asarray(conv["resolution"], float)
    e = np.maximum(conv["error"], ERROR_FLOOR)
    ax.loglog(x, e, "o-", color="C0")
    for v, xi, ei in zip(conv["values"], x, e):
        ax.annotate(f"{v:g}", (xi, ei), textcoords="offset points", xytext=(4, 4), fontsize=8)
    p = conv["observed_order"]
    ax.text(0.03, 0.05, order_text(p), transform=ax.transAxes, fontsize=10, bbox={"fc": "white", "ec": "0.7"})
    ax.set_xlabel(f"{conv['resolution_label']} — {conv['label']} ({key})")
    ax.set_ylabel(f"relative error of the {primary_label}")
    ax.set_title(f"convergence along {key}")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    return fig
