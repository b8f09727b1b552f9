"""The friction torque of a dynamic run on its two rings, written into a run folder: mean, ripple and
spectrum peaks over the settled part (summary ``ring_torque``), ``ring_torque.csv`` and
``ring_torque.png`` (:func:`mbd_core.multibody.ring_torque.axial_torques`); and where the power goes:
each loss's mean power and share over the settled part (summary ``ring_torque.power_losses``),
``power_losses.csv`` and ``power_losses.png`` (:func:`mbd_core.multibody.power_losses.power_losses`)."""

from __future__ import annotations

import numpy as np

from mbd_core.multibody.power_losses import PowerLosses, power_losses
from mbd_core.multibody.ring_torque import axial_angular_momentum, axial_torques, spectrum_peaks_Hz

__all__ = ["TORQUE_SAMPLES", "LOSS_SAMPLES", "write_power_losses", "write_ring_torque"]

#: samples at which the forces are re-evaluated for the torque (evenly picked from the record)
TORQUE_SAMPLES = 4000
#: samples of the settled part at which the losses are evaluated (each takes three force evaluations
#: per contact group)
LOSS_SAMPLES = 400
#: an energy balance off by more than this share of the drives' power is reported as a warning
BALANCE_WARNING = 0.05


def write_ring_torque(model, run: dict, rings: dict, settled_from_s: float, out, title: str,
                      friction: str | object = "not checked", label: str = "") -> dict:
    """``rings``: key (``moving``, ``fixed``) → body index. The torque the rolling elements, cages and
    drag put on each ring about the axis at up to :data:`TORQUE_SAMPLES` recorded samples; means and
    ripple over t ≥ ``settled_from_s``. When the bodies between the rings are rigid, their angular
    momentum balance is checked too: T_moving + T_fixed = −dL/dt (``balance_residual_Nm``).

    ``friction``: the contacts' friction law, None for frictionless contacts, or "not checked". A
    regularised Coulomb law is its own model only above its transition speed; when the loaded contacts slip slower (median), the
    torque is that of the regularisation, and the run says so in its warnings.

    ``label``: one of several runs in the folder: its files are ``ring_torque_<label>.csv`` and
    ``.png`` and its figures ``ring_torque[label]`` in the summary.

    The losses over the settled part go into ``figures["power_losses"]`` (:func:`write_power_losses`)."""
    from .torque_plots import plot_ring_torque

    keys, bodies = list(rings), list(rings.values())
    if np.size(run["t"]) < 2:
        out.warn([f"friction torque{' (' + label + ')' if label else ''}: the run recorded {np.size(run['t'])} "
                  "sample; record more often (or run longer) to have the torque and the power losses"])
        return {}
    t, torque = axial_torques(model, run, bodies, TORQUE_SAMPLES)
    settled = t >= settled_from_s
    if settled.sum() < 2:
        settled = np.ones_like(t, dtype=bool)
    figures = {}
    for j, key in enumerate(keys):
        values = torque[settled, j]
        figures[f"{key}_ring_Nm"] = float(values.mean())
        figures[f"{key}_ring_ripple_Nm"] = float(values.std())
        figures[f"{key}_ring_peaks_Hz"] = spectrum_peaks_Hz(values, t[1] - t[0]) if values.size > 8 else []
    between = [i for i in range(model.n_bodies) if i not in bodies]
    if not np.any(model.arrays.body_modal[between] >= 0):
        ts = np.asarray(run["t"])
        keep = ts >= t[settled][0]
        momentum = axial_angular_momentum(model, {"q": run["q"][keep], "v": run["v"][keep]}, between)
        rate = (momentum[-1] - momentum[0]) / (ts[keep][-1] - ts[keep][0])
        figures["balance_residual_Nm"] = float(torque[settled].sum(axis=1).mean() + rate)
    losses = power_losses(model, run, t[settled][0], LOSS_SAMPLES)
    write_power_losses(losses, out, title, f"power_losses_{label}" if label else "power_losses", label)
    figures["power_losses"] = losses.summary()
    if label:
        out.summary.setdefault("ring_torque", {})[label] = figures
    else:
        out.summary["ring_torque"] = figures
    _validity(run, settled_from_s, friction, out)
    stem = f"ring_torque_{label}" if label else "ring_torque"
    out.write_csv(f"{stem}.csv", ["t_s"] + [f"{k}_ring_torque_Nm" for k in keys],
                  (np.concatenate([[ti], row]) for ti, row in zip(t, torque)))
    out.save_figure(plot_ring_torque(t, {f"{k} ring": torque[:, j] for j, k in enumerate(keys)}, settled, title),
                    f"{stem}.png")
    out.note(f"{label + ' ' if label else ''}friction torque about the axis: " + ", ".join(
        f"{k} ring {figures[f'{k}_ring_Nm']:.4g} N·m (ripple {figures[f'{k}_ring_ripple_Nm']:.2g})" for k in keys))
    return figures


def write_power_losses(losses: PowerLosses, out, title: str, stem: str = "power_losses", label: str = "") -> None:
    """Each loss's mean power and share beside the drives' power (:func:`mbd_core.multibody.power_losses.power_losses`):
    ``<stem>.csv`` and ``.png``, a note (prefixed with ``label``), and a warning when the energy balance
    is off by more than :data:`BALANCE_WARNING` of the drives' power (the samples too sparse for the
    losses' fluctuation, or a run that has not settled)."""
    from .torque_plots import plot_power_losses

    shares = losses.shares()
    out.write_csv(f"{stem}.csv", ["loss", "mean_power_W", "share"],
                  ([name, value, shares.get(name, 0.0)] for name, value in losses.losses.items()))
    out.save_figure(plot_power_losses(losses, title), f"{stem}.png")
    ranked = sorted(shares.items(), key=lambda kv: -kv[1])[:3]
    stored = "" if losses.stored_W is None else f", into stored energy {losses.stored_W:.4g} W"
    out.note(f"{label + ' ' if label else ''}power: drives {losses.input_W:.4g} W (± {losses.input_error_W:.2g}), "
             f"external loads {losses.external_W:.4g} W{stored}, losses {losses.total_W:.4g} W"
             + (": " + ", ".join(f"{name} {100 * share:.1f} %" for name, share in ranked) if ranked else ""))
    residual = losses.balance_residual_W
    scale = max(abs(losses.input_W), losses.total_W)
    if residual is not None and scale > 0.0 and abs(residual) > BALANCE_WARNING * scale:
        out.warn([f"power losses{' (' + label + ')' if label else ''}: the energy balance is off by "
                  f"{100 * residual / scale:.1f} % of the drives' power ({losses.samples} samples): the losses' "
                  "means are uncertain by about as much"])


def _validity(run: dict, settled_from_s: float, friction, out) -> None:
    if isinstance(friction, str):
        return
    if friction is None:
        out.warn(["friction torque: the contacts are frictionless; the torque holds only damping and drag"])
        return
    v_static = getattr(friction, "v_static_m_s", None)
    if v_static is None:
        return
    keep = np.asarray(run["t"]) >= settled_from_s
    fn, slip = np.asarray(run["fn"])[keep], np.asarray(run["slip"])[keep]
    loaded = fn > 0.0
    if not loaded.any():
        return
    median = float(np.median(slip[loaded]))
    if median < v_static:
        out.warn([f"friction torque: the loaded contacts slip at {1e3 * median:.3g} mm/s (median), below the "
                  f"friction law's transition speed {1e3 * v_static:.3g} mm/s; the torque is that of the law's "
                  "regularisation there, not of Coulomb friction"])
