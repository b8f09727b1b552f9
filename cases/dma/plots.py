"""Figures of the DMA bearing studies (matplotlib, off-screen): torques in N·m per ball."""

from __future__ import annotations

import numpy as np

from ..results import plt
from ..torque_plots import amplitude_spectrum
from .torque import TorqueRun

__all__ = ["plot_torque", "plot_spectrum", "plot_models", "plot_speed"]


def _finish(fig, ax, xlabel: str, ylabel: str, title: str):
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3, which="both")
    ax.legend(loc="best", fontsize=8)
    ax.set_title(title)
    return fig


def plot_torque(run: TorqueRun, title: str):
    """Torque per ball on each race over time; the settled part shaded."""
    fig, ax = plt().subplots(figsize=(8, 4.5), constrained_layout=True)
    t = run.t_s * 1e3
    for which, colour in (("outer", "C0"), ("inner", "C1")):
        y = getattr(run, f"{which}_Nm") / run.n_balls
        ax.plot(t, y, lw=0.7, color=colour,
                label=f"{which} race, mean {run.mean_per_ball(which):.3g} N·m (settled part)")
    ax.axvspan(t[run.settled][0], t[-1], color="0.9", zorder=0, label="settled part (means, spectra)")
    return _finish(fig, ax, "time (ms)", "torque per ball about the axis (N·m)", title)


def plot_spectrum(run: TorqueRun, title: str):
    """Amplitude spectra (settled part, Hann window) of ball 0's axial and radial position and of the
    inner race torque, with the linearised Hertz contact frequency marked."""
    fig, ax = plt().subplots(figsize=(8, 4.5), constrained_layout=True)
    dt = run.t_s[1] - run.t_s[0]
    for sig, label in ((run.ball_axial_m, "ball 1, axial position"), (run.ball_radial_m, "ball 1, radial position"),
                       (run.inner_Nm, "inner race torque")):
        amplitude_spectrum(ax, sig[run.settled], dt, label)
    ax.axvline(run.contact_frequency_Hz / 1e3, color="k", ls="--", lw=1,
               label=f"Hertz contact frequency {run.contact_frequency_Hz / 1e3:.2f} kHz")
    ax.set_xlim(0.0, min(30.0, 0.5 / dt / 1e3))
    return _finish(fig, ax, "frequency (kHz)", "amplitude (relative)", title)


def plot_models(labels, inner, outer, reference: dict, title: str):
    """Mean torque per ball on each race for each traction model, the report's values beside them."""
    fig, ax = plt().subplots(figsize=(8, 4.5), constrained_layout=True)
    x = np.arange(len(labels))
    ax.bar(x - 0.2, np.abs(inner), 0.4, label="inner race (ours)", color="C1")
    ax.bar(x + 0.2, np.abs(outer), 0.4, label="outer race (ours)", color="C0")
    for i, label in enumerate(labels):
        for key, dx, marker in (("inner", -0.2, "v"), ("outer", 0.2, "^")):
            value = reference.get(label, {}).get(key)
            if value is not None:
                ax.plot(x[i] + dx, value, marker, color="k", ms=8,
                        label="DREB report" if (i, key) == (0, "inner") else None)
    ax.set_xticks(x, labels)
    ax.set_yscale("log")
    return _finish(fig, ax, "", "|mean torque| per ball (N·m)", title)


def plot_speed(speeds, torques: dict, title: str):
    """Bearing torque (all balls) on each race over the outer race speed, one line per thrust."""
    fig, ax = plt().subplots(figsize=(8, 4.5), constrained_layout=True)
    for (load, which), values in torques.items():
        ax.plot(speeds, np.abs(values), "o-" if which == "inner" else "s--", label=f"{load:g} N, {which} race")
    return _finish(fig, ax, "outer race speed (rev/min)", "|mean torque| of the bearing (N·m)", title)
