"""Figures of the torque on a bearing's rings: over time and its spectrum (any case family)."""

from __future__ import annotations

import numpy as np

from mbd_core.multibody.ring_torque import hann_spectrum

from .results import plt

__all__ = ["amplitude_spectrum", "plot_power_losses", "plot_ring_torque"]


def amplitude_spectrum(ax, signal, dt_s: float, label: str) -> None:
    """:func:`mbd_core.multibody.ring_torque.hann_spectrum` of ``signal`` relative to its largest line,
    on a log axis in kHz."""
    f, amp = hann_spectrum(signal, dt_s)
    top = amp[1:].max() if amp.size > 1 and amp[1:].max() > 0 else 1.0
    ax.semilogy(f[1:] / 1e3, amp[1:] / top, lw=0.8, label=label)


def plot_ring_torque(t_s, torques: dict, settled, title: str):
    """Torque about the bearing axis on each ring over time (top, the settled part shaded) and the
    spectrum of the settled part (bottom). ``torques``: name → (k,) N·m."""
    fig, (ax, bx) = plt().subplots(2, 1, figsize=(9, 6.5), constrained_layout=True)
    t = np.asarray(t_s)
    for name, values in torques.items():
        ax.plot(t, values, lw=0.8, label=f"{name}: mean {np.mean(np.asarray(values)[settled]):.4g} N·m")
        amplitude_spectrum(bx, np.asarray(values)[settled], t[1] - t[0], name)
    ax.axvspan(t[settled][0], t[-1], color="0.92", zorder=0, label="settled part (mean, spectrum)")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("torque about the axis (N·m)")
    ax.set_title(title)
    bx.set_xlabel("frequency (kHz)")
    bx.set_ylabel("amplitude (relative)")
    for a in (ax, bx):
        a.grid(True, alpha=0.3)
        a.legend(loc="best", fontsize=8)
    return fig


def plot_power_losses(losses, title: str):
    """Each loss's mean power (bars, W, largest on top, its share written beside it), with the drives'
    power for comparison (:class:`mbd_core.multibody.power_losses.PowerLosses`)."""
    items = sorted(((k, v) for k, v in losses.losses.items() if v != 0.0), key=lambda kv: kv[1])
    fig, ax = plt().subplots(figsize=(9, 1.6 + 0.35 * max(len(items), 1)), constrained_layout=True)
    total = losses.total_W
    if items:
        names, values = zip(*items)
        ax.barh(range(len(items)), values, color="tab:red", alpha=0.8)
        ax.set_yticks(range(len(items)), names, fontsize=8)
        for j, v in enumerate(values):
            ax.text(v, j, f" {100 * v / total:.1f} %" if total > 0 else "", va="center", fontsize=8)
    ax.axvline(losses.input_W, color="k", lw=1.0, ls="--", label=f"drives' power {losses.input_W:.4g} W")
    ax.set_xlabel("mean power (W)")
    ax.set_title(f"{title}\nwhere the power goes: losses {total:.4g} W over {losses.samples} samples", fontsize=9)
    ax.grid(True, axis="x", alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    return fig
