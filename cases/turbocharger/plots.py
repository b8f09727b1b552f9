"""Plots of the turbocharger studies (:mod:`.studies`)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .analysis import RunFigures  # noqa: E402

__all__ = ["plot_ball_loads", "plot_orbits", "plot_damper", "plot_spectrum", "plot_over_speed", "plot_damper_sweep",
           "plot_waterfall", "plot_cage"]


def plot_ball_loads(run: RunFigures, title: str):
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True, constrained_layout=True)
    for ax, loads, side in zip(axes, run.inner_loads_N, ("turbine", "compressor")):
        ax.plot(run.t_s * 1e3, loads[:, 0], lw=1.0, label="ball 1")
        ax.fill_between(run.t_s * 1e3, loads.min(axis=1), loads.max(axis=1), color="C0", alpha=0.2,
                        label="all balls (min … max)")
        share = 100.0 * float(np.mean(loads <= 0.0))
        ax.set_title(f"{side}-side row: inner contact loads, unloaded {share:.0f} % of the time", fontsize=10)
        ax.set_ylabel("load [N]")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
    axes[-1].set_xlabel("time [ms]")
    fig.suptitle(title, fontsize=10)
    return fig


def plot_orbits(run: RunFigures, clearance_m: float, title: str):
    fig, axes = plt.subplots(1, len(run.orbits_m), figsize=(3.2 * len(run.orbits_m), 3.6), constrained_layout=True)
    for ax, (name, xy) in zip(axes, run.orbits_m.items()):
        ax.plot(xy[:, 0] * 1e6, xy[:, 1] * 1e6, lw=0.8)
        if "bearing" in name:
            th = np.linspace(0, 2 * np.pi, 200)
            ax.plot(clearance_m * 1e6 * np.cos(th), clearance_m * 1e6 * np.sin(th), "k--", lw=0.7,
                    label="damper clearance")
            ax.legend(loc="upper right", fontsize=7)
        ax.set_aspect("equal")
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("x [µm]")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("y [µm]")
    fig.suptitle(f"{title}: orbits of the rotor's axis", fontsize=10)
    return fig


def plot_damper(run: RunFigures, title: str):
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 5), sharex=True, constrained_layout=True)
    for j, side in enumerate(("turbine", "compressor")):
        a1.plot(run.t_s * 1e3, run.eccentricity[:, j], lw=0.9, label=side)
        a2.plot(run.t_s * 1e3, np.linalg.norm(run.housing_N[:, j], axis=1), lw=0.9, label=side)
    a1.set_ylabel("damper eccentricity ε")
    a2.set_ylabel("force into the housing [N]")
    a2.set_xlabel("time [ms]")
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    a1.set_title(title, fontsize=10)
    return fig


def plot_spectrum(run: RunFigures, title: str):
    f, amp = run.spectrum
    top = 8.0 * max(run.frequencies_Hz.values())
    sel = (f > 0) & (f <= top)
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    ax.semilogy(f[sel], np.maximum(amp[sel], 1e-6), lw=0.8)
    for k, (name, value) in enumerate(run.frequencies_Hz.items()):
        ax.axvline(value, color=f"C{k + 1}", lw=0.9, ls="--", label=f"{name} {value:.0f} Hz")
        if name in ("BPFO", "BPFI"):   # their harmonics, where a spall's impacts show
            for n in range(2, int(top / value) + 1):
                ax.axvline(n * value, color=f"C{k + 1}", lw=0.5, ls=":")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("amplitude [N]")
    ax.set_title(f"{title}: turbine-side housing force, x", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return fig


def plot_over_speed(speeds_rpm, radius_um: dict, min_load_N, title: str):
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True, constrained_layout=True)
    for name, r in radius_um.items():
        a1.plot(speeds_rpm, r, "o-", label=name)
    a1.set_ylabel("orbit radius [µm]")
    a1.legend(fontsize=8)
    for j, side in enumerate(("turbine", "compressor")):
        a2.plot(speeds_rpm, [x[j] for x in min_load_N], "o-", label=f"{side}-side row")
    a2.axhline(0.0, color="k", lw=0.7)
    a2.set_ylabel("least inner contact load [N]")
    a2.set_xlabel("speed [rev/min]")
    a2.legend(fontsize=8)
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
    a1.set_title(title, fontsize=10)
    return fig


def plot_damper_sweep(lengths_m, clearances_m, force_N, radius_um, title: str):
    """``force_N``/``radius_um`` [i_clearance][i_length]."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for i, c in enumerate(clearances_m):
        a1.plot(np.array(lengths_m) * 1e3, force_N[i], "o-", label=f"c = {c * 1e6:.0f} µm")
        a2.plot(np.array(lengths_m) * 1e3, radius_um[i], "o-", label=f"c = {c * 1e6:.0f} µm")
    a1.set_ylabel("largest force into the housing [N]")
    a2.set_ylabel("orbit radius at the turbine bearing [µm]")
    for ax in (a1, a2):
        ax.set_xlabel("damper land length [mm]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title, fontsize=10)
    return fig


def plot_waterfall(speeds_rpm, runs: list[RunFigures], title: str):
    """The turbine-side housing force's spectrum at each speed (colour: log amplitude), with the orders
    1× and 2× and each run's BPFO and BPFI."""
    top = 1.2 * max(r.frequencies_Hz["BPFI"] for r in runs) * 4
    f_edges = np.linspace(0.0, top, 601)
    grid = 0.5 * (f_edges[1:] + f_edges[:-1])
    image = np.array([np.interp(grid, r.spectrum[0], r.spectrum[1]) for r in runs])
    fig, ax = plt.subplots(figsize=(8, 5), constrained_layout=True)
    edges = np.concatenate([[speeds_rpm[0] - 0.5 * (speeds_rpm[1] - speeds_rpm[0]) if len(speeds_rpm) > 1
                             else 0.9 * speeds_rpm[0]],
                            0.5 * (np.array(speeds_rpm[1:]) + np.array(speeds_rpm[:-1])),
                            [speeds_rpm[-1] + (0.5 * (speeds_rpm[-1] - speeds_rpm[-2]) if len(speeds_rpm) > 1
                                               else 0.1 * speeds_rpm[-1])]])
    mesh = ax.pcolormesh(f_edges / 1e3, edges, np.log10(np.maximum(image, 1e-3)), shading="flat", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="log10 amplitude [N]")
    for key, style in (("1x", "w-"), ("BPFO", "r--"), ("BPFI", "m--")):
        ax.plot([r.frequencies_Hz[key] / 1e3 for r in runs], speeds_rpm, style, lw=0.9, label=key)
    ax.plot([2 * r.frequencies_Hz["1x"] / 1e3 for r in runs], speeds_rpm, "w:", lw=0.9, label="2x")
    ax.set_xlabel("frequency [kHz]")
    ax.set_ylabel("speed [rev/min]")
    ax.set_xlim(0, top / 1e3)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title(f"{title}: turbine-side housing force, x", fontsize=10)
    return fig


def plot_cage(run: RunFigures, pocket_clearance_m: float, title: str):
    """The turbine-side cage's centre relative to its outer ring: its whirl orbit and its distance
    over time, beside the pocket play."""
    xy = run.cage_whirl_m * 1e6
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True,
                                 gridspec_kw={"width_ratios": [1, 1.6]})
    a1.plot(xy[:, 0], xy[:, 1], lw=0.6)
    a1.set_aspect("equal")
    a1.set_xlabel("x [µm]")
    a1.set_ylabel("y [µm]")
    a1.set_title("cage centre whirl", fontsize=9)
    a2.plot(run.t_s * 1e3, np.linalg.norm(xy, axis=1), lw=0.8, label="cage centre off the ring's")
    a2.axhline(pocket_clearance_m * 1e6, color="k", ls="--", lw=0.7, label="pocket play")
    a2.set_xlabel("time [ms]")
    a2.set_ylabel("distance [µm]")
    a2.legend(fontsize=8)
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
    fig.suptitle(f"{title}: turbine-side cage", fontsize=10)
    return fig
