"""Figures of the slewing-ring studies (matplotlib, off-screen). Loads in tonnes-force (9.81 kN)
as the thesis plots them; angles in degrees."""

from __future__ import annotations

import numpy as np

from ..results import plt
from . import scene
from .case import SlewingCase

__all__ = ["plot_static", "plot_ball_loads", "plot_travel", "plot_dynamic"]

TONNE_N = 9810.0


def plot_static(curves: dict, analytic_N: float, nominal_N: float, case: SlewingCase):
    """Load per ball with a rigid and a modal top structure against the analytic thrust load
    (loaded contact angle) and the thesis' W / (Z sin α0)."""
    fig, ax = plt().subplots(figsize=(8, 4.5), constrained_layout=True)
    for label, q in curves.items():
        ax.plot(np.arange(1, len(q) + 1), q / 1e3, marker="o", ms=4, lw=1, label=f"{label} top structure")
    ax.axhline(analytic_N / 1e3, color="k", ls="--", lw=1, label=f"analytic, loaded angle: {analytic_N / 1e3:.2f} kN")
    ax.axhline(nominal_N / 1e3, color="0.5", ls=":", lw=1, label=f"W/(Z sin 60°) = {nominal_N / 1e3:.2f} kN")
    ax.set_xlabel("ball number")
    ax.set_ylabel("normal ball load Q (kN)")
    ax.set_ylim(0.97 * analytic_N / 1e3, 1.03 * analytic_N / 1e3)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title(f"Static load per ball, {case.geometry.variant} ring, {case.dead_load_t:g} t (±3 % scale)")
    return fig


def plot_ball_loads(curves: dict, azimuth_rad, case: SlewingCase, title: str, normalised: bool = False):
    """Load per ball (the thesis' Fig. 31–35): ``curves`` label → loads (Z,) at ``azimuth_rad``, or
    label → (azimuth, loads) with ``azimuth_rad`` None; the undulation profile (×1) on the right axis."""
    fig, ax = plt().subplots(figsize=(9, 4.8), constrained_layout=True)
    for label, v in curves.items():
        az, q = (azimuth_rad, v) if azimuth_rad is not None else v
        deg = np.degrees(np.mod(az, 2 * np.pi))
        order = np.argsort(deg)
        y = q[order] if normalised else q[order] / TONNE_N
        name = label if isinstance(label, str) else f"undulation ×{label:g}"
        ax.plot(deg[order], y, marker="o", ms=3.5, lw=1, label=name)
    ax.set_xlabel("ball azimuth ψ (deg)")
    ax.set_ylabel("ball load / nominal (-)" if normalised else "normal ball load (t = 9.81 kN)")
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 30))
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    th = np.linspace(0, 2 * np.pi, 721)
    ax2 = ax.twinx()
    ax2.plot(np.degrees(th), 1e3 * scene.undulation_m(case.undulation.__class__(scale=1.0,
             profile_deg_mm=case.undulation.profile_deg_mm), th), color="0.6", ls=":", lw=1.2)
    ax2.set_ylabel("bottom-race undulation ×1, h (mm), dotted", color="0.4")
    ax2.set_ylim(-2.0, 2.0)
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title)
    return fig


def plot_travel(histories: dict, case: SlewingCase, title: str, thermal: bool = True):
    """Load on one ball as it goes round (the thesis' Fig. 37–38): ``histories`` label →
    (ball azimuth deg, load N, top-race rotation deg). Shaded: the bottom race's thermal sector
    (fixed); dots on a curve: positions where the ball is in the top race's sector (``thermal``)."""
    fig, ax = plt().subplots(figsize=(9, 4.8), constrained_layout=True)
    a, b = case.thermal.bottom_sector_deg
    if thermal:
        ax.axvspan(a, b, color="tab:blue", alpha=0.12, label=f"bottom race offset sector {a:g}–{b:g}°")
    ta, tb = case.thermal.top_sector_deg
    for label, (psi_deg, q, phi_deg) in histories.items():
        psi = np.asarray(psi_deg)
        order = np.argsort(psi)
        line, = ax.plot(psi[order], q[order] / TONNE_N, lw=1.2, label=label)
        in_top = (np.mod(psi - phi_deg, 360.0) >= ta) & (np.mod(psi - phi_deg, 360.0) <= tb)
        if thermal and in_top.any():
            ax.plot(psi[in_top], q[in_top] / TONNE_N, "o", ms=3, color=line.get_color())
    if thermal:
        ax.plot([], [], "o", ms=3, color="0.3", label=f"ball under the top race's sector {ta:g}–{tb:g}°")
    ax.set_xlabel("ball azimuth ψ (deg)")
    ax.set_ylabel("normal ball load (t = 9.81 kN)")
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 30))
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(title)
    return fig


def plot_dynamic(t_s, ball_loads_N, spacer_forces_N, analytic_N: float, case: SlewingCase):
    """Ball loads (all balls, thin lines) and spacer–load ball forces over time."""
    rows = 2 if spacer_forces_N is not None else 1
    fig, axes = plt().subplots(rows, 1, figsize=(9, 3.2 * rows + 0.8), constrained_layout=True, squeeze=False)
    ax = axes[0, 0]
    ax.plot(t_s, ball_loads_N / 1e3, lw=0.6, alpha=0.7)
    ax.axhline(analytic_N / 1e3, color="k", ls="--", lw=1, label=f"analytic, flat races: {analytic_N / 1e3:.2f} kN")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("normal ball load (kN)")
    lo, hi = float(np.min(ball_loads_N)), float(np.max(ball_loads_N))
    pad = max(0.03 * analytic_N, 0.05 * (hi - lo))  # at least ±3 % of the analytic load
    ax.set_ylim(min(lo, analytic_N) / 1e3 - pad / 1e3, max(hi, analytic_N) / 1e3 + pad / 1e3)
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title(f"{case.geometry.variant} ring, top race at {case.analysis.speed_rpm:g} rpm: every load ball "
                 "(y range at least ±3 %)")
    if spacer_forces_N is not None:
        ax = axes[1, 0]
        ax.plot(t_s, spacer_forces_N, lw=0.6, alpha=0.7)
        ax.set_xlabel("time t (s)")
        ax.set_ylabel("spacer–load ball force (N)")
        ax.set_ylim(bottom=0.0, top=max(1.0, 1.1 * float(np.max(spacer_forces_N))))
        ax.grid(True, alpha=0.3)
    return fig
