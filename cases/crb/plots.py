"""Figures of the cylindrical roller bearing studies (matplotlib, off-screen)."""

from __future__ import annotations

import numpy as np

from ..results import plt

__all__ = ["plot_torque_speed", "plot_rib_film", "plot_rollers"]


def _finish(fig, ax, xlabel: str, ylabel: str, title: str):
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3, which="both")
    ax.legend(loc="best", fontsize=8)
    ax.set_title(title, fontsize=10)
    return fig


def plot_torque_speed(speeds, ours: dict, catalogue: dict, title: str):
    """Friction torque over speed, one colour per axial load: ours (solid, its raceway rolling part
    dotted) and the catalogue model's (dashed)."""
    fig, ax = plt().subplots(figsize=(8, 5), constrained_layout=True)
    for i, (axial, (total, rolling)) in enumerate(ours.items()):
        colour = f"C{i}"
        ax.plot(speeds, total, "o-", color=colour, label=f"F_a = {axial / 1e3:g} kN, contacts")
        ax.plot(speeds, catalogue[axial], "--", color=colour, label=f"F_a = {axial / 1e3:g} kN, catalogue model")
        if i == 0:
            ax.plot(speeds, rolling, ":", color="k", label="raceway rolling part (contacts, every F_a)")
    ax.set_ylim(bottom=0.0)
    return _finish(fig, ax, "shaft speed (rev/min)", "friction torque (N·m)", title)


def plot_rib_film(speeds, lambdas: dict, shares: dict, title: str):
    """The inner rib contacts' smallest film parameter Λ and largest asperity load share φ over speed."""
    fig, (a1, a2) = plt().subplots(1, 2, figsize=(10, 4.2), constrained_layout=True)
    for i, axial in enumerate(lambdas):
        a1.plot(speeds, lambdas[axial], "o-", color=f"C{i + 1}", label=f"F_a = {axial / 1e3:g} kN")
        a2.plot(speeds, shares[axial], "o-", color=f"C{i + 1}", label=f"F_a = {axial / 1e3:g} kN")
    a1.axhline(1.0, color="k", lw=0.8, ls="--", label="Λ = 1")
    _finish(fig, a1, "shaft speed (rev/min)", "smallest film parameter Λ at the ribs", "")
    _finish(fig, a2, "shaft speed (rev/min)", "largest asperity load share φ at the ribs", "")
    fig.suptitle(title, fontsize=10)
    return fig


def plot_rollers(run, title: str):
    """Per roller: raceway load, rib load, and each roller's share of the lost power."""
    fig, (a1, a2) = plt().subplots(1, 2, figsize=(10, 4.2), constrained_layout=True)
    deg = np.degrees(run.angles_rad)
    deg = np.where(deg > 180.0, deg - 360.0, deg)
    order = np.argsort(deg)
    a1.plot(deg[order], run.roller_load_N[order] / 1e3, "o-", label="raceway load Q")
    a1.plot(deg[order], run.rib_load_N[order] / 1e3, "s-", label="rib load")
    _finish(fig, a1, "roller position from the load line (°)", "load (kN)", "")
    a2.bar(deg[order], run.rolling_power_W[order], width=8, label="raceway rolling")
    a2.bar(deg[order], run.rib_power_W[order], width=8, bottom=run.rolling_power_W[order], label="ribs")
    _finish(fig, a2, "roller position from the load line (°)", "lost power (W)", "")
    fig.suptitle(title, fontsize=10)
    return fig
