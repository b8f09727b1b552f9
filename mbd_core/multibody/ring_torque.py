"""Torque about the bearing axis on rings (or any bodies) over a recorded run, and its spectrum.

A bearing's friction torque is what its rolling elements (and cage, drag, bushings) put on a ring
about the bearing axis. At each recorded sample the force stage is evaluated again from the recorded
state (:func:`mbd_core.multibody.evaluate_forces`) with the bodies' own external loads removed (constant
loads, gravity of rigid bodies and load histories), so the torque is that of the model's internal
forces only:

    T_i = (r_i × F_i)_z + M_i,z        (world z, through the origin: the bearing axis),

F_i and M_i the force and moment on body i about its centre r_i. The force stage is deterministic,
so the torque equals the one of the run at that instant — for explicit friction. With implicit
friction (``ModelBuilder(implicit_friction=True)``) the integrator applies the friction of a damper
frozen at the force evaluation, which the re-evaluated force only approximates.

Check: the bodies between the rings (elements, cages, spacers) get all their forces from the rings,
so the rings' torques balance the rate of their angular momentum about the axis,
T_ring,1 + T_ring,2 = −dL/dt with L = Σ m (x v_y − y v_x) + (R I ω)_z (:func:`axial_angular_momentum`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .explicit import evaluate_forces
from .model import Model, State

__all__ = ["axial_torques", "axial_angular_momentum", "hann_spectrum", "internal_model", "spectrum_peaks_Hz"]


def internal_model(model: Model) -> Model:
    """The model without the bodies' external loads (constant, gravity of rigid bodies, histories,
    unbalances)."""
    a = model.arrays
    arrays = a._replace(body_force=np.zeros_like(a.body_force), load_body=np.zeros(0, dtype=a.load_body.dtype),
                        load_off=np.zeros(1, dtype=a.load_off.dtype), unb_body=np.zeros(0, dtype=a.unb_body.dtype))
    return dataclasses.replace(model, arrays=arrays)


def axial_torques(model: Model, run: dict, bodies, max_samples: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(t (k,) s, T (k, len(bodies)) N·m): the internal forces' moment about the world z axis on each
    of ``bodies`` at the run's samples (every one, or about ``max_samples`` evenly picked)."""
    t = np.asarray(run["t"])
    stride = 1 if not max_samples or t.size <= max_samples else int(np.ceil(t.size / max_samples))
    picks = np.arange(0, t.size, stride)
    internal = internal_model(model)
    n_eta = int(model.arrays.modal_off[-1]) if model.arrays.modal_off.size else 0
    out = np.empty((picks.size, len(bodies)))
    work = None
    for row, k in enumerate(picks):
        eta = run["eta"][k].copy() if n_eta else np.zeros(0)
        eta_dot = run["eta_dot"][k].copy() if n_eta else np.zeros(0)
        state = State(float(t[k]), run["q"][k].copy(), run["v"][k].copy(), eta, eta_dot)
        work = evaluate_forces(internal, state, work)
        for j, b in enumerate(bodies):
            r, f = state.q[b, :3], work.body_f[b]
            out[row, j] = r[0] * f[1] - r[1] * f[0] + work.body_t[b, 2]
    return t[picks], out


def axial_angular_momentum(model: Model, run: dict, bodies) -> np.ndarray:
    """L_z (k,) N·m·s of the rigid ``bodies`` about the world z axis at every sample: orbital
    m (x v_y − y v_x) plus spin (R I ω)_z, ω in the body frame, I the principal inertia."""
    idx = list(bodies)
    if np.any(model.arrays.body_modal[idx] >= 0):
        raise ValueError("axial_angular_momentum: the bodies must be rigid")
    q, v = np.asarray(run["q"])[:, idx], np.asarray(run["v"])[:, idx]
    m, inertia = model.arrays.body_mass[idx], model.arrays.body_inertia[idx]
    orbital = m * (q[..., 0] * v[..., 1] - q[..., 1] * v[..., 0])
    h = inertia * v[..., 3:]                                   # I ω, body frame
    w, x, y, z = (q[..., 3 + i] for i in range(4))
    # third row of the rotation matrix of the unit quaternion (w, x, y, z): world z of a body vector
    spin = (2 * (x * z - w * y) * h[..., 0] + 2 * (y * z + w * x) * h[..., 1]
            + (1 - 2 * (x * x + y * y)) * h[..., 2])
    return np.sum(orbital + spin, axis=-1)


def hann_spectrum(signal, dt_s: float) -> tuple[np.ndarray, np.ndarray]:
    """(f Hz, amplitude) of the Hann-windowed one-sided spectrum of ``signal`` sampled every ``dt_s``,
    its mean removed."""
    s = np.asarray(signal, float)
    return np.fft.rfftfreq(s.size, dt_s), np.abs(np.fft.rfft((s - s.mean()) * np.hanning(s.size)))


def spectrum_peaks_Hz(signal, dt_s: float, n_peaks: int = 3) -> list[float]:
    """Frequencies of the ``n_peaks`` highest local maxima of :func:`hann_spectrum`, Hz, highest first;
    the lowest three bins (below three periods in the record) are left out, where the window's
    leakage of a slow drift sits."""
    if np.size(signal) < 8:
        return []
    f, amp = hann_spectrum(signal, dt_s)
    local = np.flatnonzero((amp[1:-1] > amp[:-2]) & (amp[1:-1] >= amp[2:])) + 1
    local = local[local >= 3]
    top = local[np.argsort(amp[local])[::-1][:n_peaks]]
    return [float(f[i]) for i in top]
