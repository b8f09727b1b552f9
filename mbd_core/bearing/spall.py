"""A spall on a raceway as the path of the ball centre over it (a table for a groove's Δr(θ)).

A spall is a pit of length ℓ (along the rolling direction) and depth d in the raceway. A ball of
radius R_b over it cannot reach the bottom when the pit is short: at arc position s from the pit's
centre (pit edges at ±ℓ/2) it rests on the higher of the two edges or on the bottom, so its centre
sits lower than on the intact raceway by

    Δ(s) = R_b − max(√(R_b² − (ℓ/2 − s)²), √(R_b² − (ℓ/2 + s)²), R_b − d)     for |s| < ℓ/2,

0 elsewhere (the edge term only where |ℓ/2 ∓ s| < R_b). This is the plane picture in the rolling
direction: the raceway's curvature along it and the pit's shape across the contact are left out, and
the contact's size is not (a pit shorter than the contact ellipse loads its rim, which this path does
not see). References for the geometry: Sawalhi & Randall, Mech. Syst. Signal Process. 22 (2008)
1924–1951 (the ball's path over a spall's edges); Ashtekar, Sadeghi & Stacke, Trans. ASME J.
Tribol. 130 (2008) 041103 (dynamic bearing model with dents).

On a groove's radial offset table Δr(θ) (:meth:`mbd_core.multibody.ModelBuilder.add_groove`) the drop
opens the gap: +Δ on an outer raceway (the curvature centres move out), −Δ on an inner one. The table
lives in the ring's frame, so the spall turns with its ring. A contact at angle α sees the radial
offset's share Δ·cos α along its normal; ``depth_along_normal`` divides by cos α so that the normal
gap opens by Δ.
"""

from __future__ import annotations

import math

import numpy as np

from foundation.validation import check_positive

__all__ = ["spall_drop_m", "spall_radial_offset_m"]


def spall_drop_m(arc_m, length_m: float, depth_m: float, ball_radius_m: float) -> np.ndarray:
    """Drop Δ of the ball centre (m, ≥ 0) at arc positions ``arc_m`` from the pit's centre (module docstring)."""
    check_positive("spall", length_m=length_m, depth_m=depth_m, ball_radius_m=ball_radius_m)
    s = np.abs(np.asarray(arc_m, float))
    R, half = ball_radius_m, 0.5 * length_m
    support = np.full(s.shape, R - depth_m)
    for edge in (half - s, half + s):
        on = np.abs(edge) < R
        support[on] = np.maximum(support[on], np.sqrt(R * R - edge[on] ** 2))
    return np.where(s < half, R - support, 0.0)


def spall_radial_offset_m(n_samples: int, raceway_radius_m: float, center_rad: float, length_m: float, depth_m: float,
                          ball_radius_m: float, race: str, contact_angle_rad: float = 0.0) -> np.ndarray:
    """(n_samples,) Δr(θ) table over [0, 2π) of a spall centred at ``center_rad`` on a raceway of
    radius ``raceway_radius_m`` (``race`` "outer" or "inner"), for a groove's ``radial_offset_m``.

    The pit must span a few samples: ℓ ≥ 4·2π·r/n, or the error names ``n_samples``.
    """
    check_positive("spall", raceway_radius_m=raceway_radius_m)
    if race not in ("outer", "inner"):
        raise ValueError(f"spall: race must be 'outer' or 'inner', got {race!r}")
    if not abs(contact_angle_rad) < 0.5 * math.pi:
        raise ValueError(f"spall: contact_angle_rad must lie in (−π/2, π/2), got {contact_angle_rad!r}")
    step_m = 2.0 * math.pi * raceway_radius_m / n_samples
    if length_m < 4.0 * step_m:
        raise ValueError(f"spall: length_m = {length_m:g} m spans fewer than 4 samples of the table "
                         f"({step_m:.3g} m apart); raise n_samples to at least "
                         f"{math.ceil(8.0 * math.pi * raceway_radius_m / length_m)}")
    theta = np.arange(n_samples) * (2.0 * math.pi / n_samples)
    arc = raceway_radius_m * (np.mod(theta - center_rad + math.pi, 2.0 * math.pi) - math.pi)
    drop = spall_drop_m(arc, length_m, depth_m, ball_radius_m) / math.cos(contact_angle_rad)
    return drop if race == "outer" else -drop
