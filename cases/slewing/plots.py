"""Figures of the slewing-ring studies (matplotlib, off-screen). Forces in N as in every output
file (README, output units; the thesis plots tonnes-force of 9.81 kN); angles in degrees; balls
numbered 1…Z as in the CSV files."""

from __future__ import annotations

import numpy as np

from ..results import label_lines, newtons, plt
from . import scene
from .case import SlewingCase

__all__ = ["plot_static", "plot_ball_loads", "plot_travel", "plot_dynamic"]


def plot_static(curves: dict, analytic_N: float, nominal_N: float, case: SlewingCase):
    """Load per ball with a rigid and a modal top structure against the analytic thrust load
    (loaded contact angle) and the thesis' W / (Z sin α0)."""
    fig, ax = plt().subplots(figsize=(8, 4.5), constrained_layout=True)
    for label, q in curves.items():
        ax.plot(np.arange(1, len(q) + 1), q, marker="o", ms=4, lw=1, label=f"{label} top structure")
    ax.axhline(analytic_N, color="k", ls="--", lw=1, label=f"analytic, loaded angle: {newtons(analytic_N)}")
    ax.axhline(nominal_N, color="0.5", ls=":", lw=1, label=f"W/(Z sin 60°) = {newtons(nominal_N)}")
    ax.set_xlabel("ball number")
    ax.set_ylabel("normal ball load Q (N)")
    ax.set_ylim(0.97 * analytic_N, 1.03 * analytic_N)
    ax.ticklabel_format(axis="y", useOffset=False, style="plain")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title(f"Static load per ball, {case.geometry.variant} ring, dead load {newtons(case.dead_load_N)}")
    return fig


def plot_ball_loads(curves: dict, azimuth_rad, case: SlewingCase, title: str, normalised: bool = False):
    """Load per ball (the thesis' Fig. 31–35): ``curves`` label → loads (Z,) at ``azimuth_rad``, or
    label → (azimuth, loads) with ``azimuth_rad`` None; the undulation profile (×1) on the right axis."""
    fig, ax = plt().subplots(figsize=(9, 4.8), constrained_layout=True)
    for label, v in curves.items():
        az, q = (azimuth_rad, v) if azimuth_rad is not None else v
        deg = np.degrees(np.mod(az, 2 * np.pi))
        order = np.argsort(deg)
        y = q[order]
        name = label if isinstance(label, str) else f"undulation ×{label:g}"
        ax.plot(deg[order], y, marker="o", ms=3.5, lw=1, label=name)
    ax.set_xlabel("ball azimuth ψ (deg)")
    ax.set_ylabel("ball load / nominal (-)" if normalised else "normal ball load (N)")
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
        line, = ax.plot(psi[order], q[order], lw=1.2, label=label)
        in_top = (np.mod(psi - phi_deg, 360.0) >= ta) & (np.mod(psi - phi_deg, 360.0) <= tb)
        if thermal and in_top.any():
            ax.plot(psi[in_top], q[in_top], "o", ms=3, color=line.get_color())
    if thermal:
        ax.plot([], [], "o", ms=3, color="0.3", label=f"ball under the top race's sector {ta:g}–{tb:g}°")
    ax.set_xlabel("ball azimuth ψ (deg)")
    ax.set_ylabel("normal ball load (N)")
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 30))
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(title)
    return fig


def plot_dynamic(t_s, ball_loads_N, spacer_forces_N, analytic_N: float, case: SlewingCase, settled_from_s: float):
    """Ball loads (every load ball, one line each) and spacer–load ball forces over time.

    The samples before ``settled_from_s`` (the start's transient, which the summary's figures
    exclude as well) are not drawn; their window is shaded and labelled. Lines are numbered 1…Z
    as in the CSV files: balls by ball, spacer contacts by spacer (colour bar when there are many).
    """
    t_s = np.asarray(t_s)
    keep = t_s >= settled_from_s
    rows = 2 if spacer_forces_N is not None else 1
    fig, axes = plt().subplots(rows, 1, figsize=(9, 3.2 * rows + 0.8), constrained_layout=True, squeeze=False)
    ax = axes[0, 0]
    q = np.asarray(ball_loads_N)[keep]
    _start_up(ax, t_s, settled_from_s)
    ax.axhline(analytic_N, color="k", ls="--", lw=1, label=f"analytic, flat races: {newtons(analytic_N)}")
    lines = ax.plot(t_s[keep], q, lw=0.6, alpha=0.8)
    label_lines(ax, lines, range(1, q.shape[1] + 1), "ball")
    ax.set_ylabel("normal ball load (N)")
    lo, hi = float(np.min(q)), float(np.max(q))
    pad = max(0.03 * analytic_N, 0.05 * (hi - lo))  # a nearly flat load still shows its ripple in scale
    ax.set_ylim(min(lo, analytic_N) - pad, max(hi, analytic_N) + pad)
    ax.ticklabel_format(axis="y", useOffset=False, style="plain")
    ax.set_title(f"{case.geometry.variant} ring, top race at {case.analysis.speed_rpm:g} r/min: every load ball")
    if spacer_forces_N is not None:
        ax = axes[1, 0]
        fs = np.asarray(spacer_forces_N)[keep]
        left_out = np.asarray(spacer_forces_N)[~keep]
        _start_up(ax, t_s, settled_from_s, float(left_out.max()) if left_out.size else None)
        lines = ax.plot(t_s[keep], fs, lw=0.6, alpha=0.8)
        # pairs come as (ball j–spacer j, ball j+1–spacer j) for each spacer j
        label_lines(ax, lines, np.arange(fs.shape[1]) // 2 + 1, "spacer")
        ax.set_ylabel("spacer–load ball force (N)")
        ax.set_ylim(bottom=0.0, top=max(1.0, 1.1 * float(np.max(fs))))
        ax.set_title(f"spacer–load ball contacts: peak {newtons(float(np.max(fs)))}")
    for ax in axes[:, 0]:
        ax.set_xlabel("time t (s)")
        ax.set_xlim(t_s[0], t_s[-1])
        ax.grid(True, alpha=0.3)
    return fig


def _start_up(ax, t_s, settled_from_s: float, peak_N: float | None = None) -> None:
    """Shade the start-up window that the figure and the summary's figures leave out (with the
    peak force in it, ``peak_N``, when given)."""
    if settled_from_s > t_s[0]:
        peak = "" if peak_N is None else f", peak {newtons(peak_N)}"
        ax.axvspan(t_s[0], settled_from_s, color="0.88", label=f"start-up{peak}: not drawn, not in the summary's figures")


def plot_race_stress(t_s, histories: dict, case: SlewingCase, settled_from_s: float):
    """Per race with stress modes (:mod:`.dynamic_stress`): its largest nodal von Mises stress over
    time, away from the groove (ring) and within its zone (groove, dashed), and the stress
    at the node of the ring's peak (dotted), MPa; the start-up window shaded and not drawn."""
    t_s = np.asarray(t_s)
    keep = t_s >= settled_from_s
    fig, ax = plt().subplots(figsize=(9, 4.0), constrained_layout=True)
    _start_up(ax, t_s, settled_from_s)
    for k, (name, h) in enumerate(histories.items()):
        ax.plot(t_s[keep], h["ring"].von_mises_Pa[keep] / 1e6, color=f"C{k}", lw=1.0,
                label=f"{name}: ring (beyond {1e3 * h['groove_zone_m']:.0f} mm of the groove)")
        ax.plot(t_s[keep], h["groove"].von_mises_Pa[keep] / 1e6, color=f"C{k}", lw=0.8, ls="--",
                label=f"{name}: groove zone (line loads: mesh-dependent)")
        if "at_peak_node" in h:
            ax.plot(t_s[keep], h["at_peak_node"][keep] / 1e6, color=f"C{k}", lw=0.8, ls=":",
                    label=f"{name}: at the node of the ring peak")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("largest nodal von Mises stress (MPa)")
    ax.set_xlim(t_s[0], t_s[-1])
    ax.set_ylim(bottom=0.0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"{case.geometry.variant} ring, top race at {case.analysis.speed_rpm:g} r/min: race stress over time")
    return fig
