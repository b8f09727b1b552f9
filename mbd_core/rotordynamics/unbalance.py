"""Steady response of a spinning modal body to an unbalance.

An unbalance U = m_u e (kg·m) turns with the rotor: in the spinning frame its centrifugal force
U Ω² has a fixed direction (x here), and on isotropic supports the steady response is static there
(:func:`.spin.spinning_matrices`, η̇ = 0):

    K(Ω) η = U Ω² Φ_xᵀ w,     K(Ω) = K + Ω² (S − P) + Ω c_s A (+ the bearings' Ω c J),

w spreading the force over the nodes of the unbalance plane (equal shares). A static deflection in
the spinning frame is, in the fixed frame, a circular orbit at the running speed: its radius is
|u_xy| and it trails the unbalance by the phase angle of u_xy. Damping that turns with the rotor
does nothing to it; only stationary damping (c_s) limits the peak at a critical speed (the Jeffcott
rotor: radius = ε r² / √((1 − r²)² + (2ζr)²), ε = U/m, r = Ω/ω_n; Genta, *Dynamics of Rotating
Systems*, §4.4).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .spin import SpinningBody, spinning_matrices

__all__ = ["UnbalanceResponse", "unbalance_response"]


@dataclass(frozen=True)
class UnbalanceResponse:
    """Orbit of a node set at each speed.

    Attributes
    ----------
    speeds_rad_s : (n,) float64
    radius_m : (n,) float64
        Radius of the circular orbit of the node set's mean lateral displacement, m.
    phase_lag_rad : (n,) float64
        Angle by which the displacement trails the unbalance, in [0, 2π).
    """

    speeds_rad_s: np.ndarray
    radius_m: np.ndarray
    phase_lag_rad: np.ndarray


def _mean_lateral(shapes: np.ndarray, nodes: np.ndarray) -> np.ndarray:
    """(2, m): mean x and y displacement of ``nodes`` per unit modal coordinate."""
    nodes = np.asarray(nodes, dtype=np.int64).ravel()
    if len(nodes) == 0:
        raise ValueError("the unbalance plane and the measured plane need at least one node each")
    return np.stack([shapes[3 * nodes + c].mean(axis=0) for c in (0, 1)])


def unbalance_response(body: SpinningBody, shapes: np.ndarray, unbalance_kg_m: float, unbalance_nodes,
                       measured_nodes, speeds_rad_s, stationary_damping_per_s: float = 0.0) -> UnbalanceResponse:
    """Steady orbit of ``measured_nodes`` under an unbalance spread over ``unbalance_nodes``
    (module docstring); ``shapes`` (3N, m) the body's mode shapes."""
    speeds = np.asarray(speeds_rad_s, dtype=float).ravel()
    if not np.isfinite(unbalance_kg_m) or unbalance_kg_m < 0.0:
        raise ValueError(f"unbalance_kg_m must be ≥ 0, got {unbalance_kg_m}")
    load = _mean_lateral(shapes, unbalance_nodes)[0]  # Φ_xᵀ w, equal shares w summing to 1
    out = _mean_lateral(shapes, measured_nodes)
    radius, lag = np.empty(len(speeds)), np.empty(len(speeds))
    for i, W in enumerate(speeds):
        _, _, K = spinning_matrices(body, W, stationary_damping_per_s)
        eta = np.linalg.solve(K, unbalance_kg_m * W * W * load)
        ux, uy = out @ eta
        radius[i] = np.hypot(ux, uy)
        lag[i] = (-np.arctan2(uy, ux)) % (2.0 * np.pi)
    return UnbalanceResponse(speeds, radius, lag)
