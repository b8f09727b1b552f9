"""Mode shapes sampled along raceways, and the interpolation the contact kernels use.

A ball or roller at ring angle θ sees the raceway displaced by u(θ) = D(θ) η and rotated by
ω(θ) = Ω(θ) η (small rotation ½ curl u), where D and Ω are the mode displacements and rotations at
the contact point. They are sampled once at N_θ points of a raceway curve (isoparametric probes of
the FE field, :mod:`fem_rings.probe`) and interpolated linearly in θ during the run. A contact force
f at θ does the virtual work f·δu = f·D(θ) δη, so its modal force is D(θ)ᵀ f — the transpose of
the same interpolation, which keeps the coupling work-consistent (energy neither created nor lost
by the projection).

The kernels are plain functions on arrays (index pair and weights, then small dot products) so
that the numba contact kernels can call the same arithmetic.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fem_rings.assembly import scalar_basis
from fem_rings.nodesets import RacewayCurve
from fem_rings.probe import gradient_probe_matrices, probe_matrix

from .body import ReducedBody

__all__ = ["RacewaySample", "sample_raceway", "interp_index", "raceway_displacement", "raceway_modal_force"]


@dataclass(frozen=True)
class RacewaySample:
    """Mode displacement and rotation at the points of a raceway curve.

    Attributes
    ----------
    name : str
        Raceway (profile segment) name.
    theta_rad : (n,) float64
        Ascending sample angles, rad.
    points_m : (n, 3) float64
        Sample points on the undeformed raceway, m.
    displacement : (n, 3, m) float64
        Displacement per unit modal coordinate, m/√kg.
    rotation : (n, 3, m) float64
        Small rotation (½ curl u) per unit modal coordinate, rad/√kg.
    periodic : bool
        True for a full circle (θ wraps at 2π).
    """

    name: str
    theta_rad: np.ndarray
    points_m: np.ndarray
    displacement: np.ndarray
    rotation: np.ndarray
    periodic: bool


def sample_raceway(body: ReducedBody, curve: RacewayCurve, full_circle: bool) -> RacewaySample:
    """Sample the body's modes at the points of ``curve`` (from :func:`fem_rings.nodesets.raceway_curve`)."""
    basis = scalar_basis(body.mesh(), 2)
    P = probe_matrix(basis, curve.points_m)
    G = gradient_probe_matrices(basis, curve.points_m)
    m = body.n_modes
    Phi = body.shapes.reshape(-1, 3, m)                     # (N, 3, m)
    disp = np.stack([P @ Phi[:, c, :] for c in range(3)], axis=1)          # (n, 3, m)
    grad = np.stack([np.stack([G[i] @ Phi[:, c, :] for i in range(3)], axis=1) for c in range(3)], axis=1)
    # grad[p, c, i, k] = ∂u_c/∂x_i ; ω = ½ (∂u_z/∂y − ∂u_y/∂z, ∂u_x/∂z − ∂u_z/∂x, ∂u_y/∂x − ∂u_x/∂y)
    rot = 0.5 * np.stack([grad[:, 2, 1] - grad[:, 1, 2], grad[:, 0, 2] - grad[:, 2, 0],
                          grad[:, 1, 0] - grad[:, 0, 1]], axis=1)
    return RacewaySample(curve.name, np.asarray(curve.theta_rad, float), np.asarray(curve.points_m, float),
                         disp, rot, bool(full_circle))


def interp_index(theta_grid: np.ndarray, theta: float, periodic: bool) -> tuple[int, int, float, float]:
    """Neighbouring sample indices (i0, i1) and linear weights (w0, w1) of angle θ (rad).

    A periodic grid wraps at 2π; otherwise θ is clamped to the sampled range.
    """
    n = len(theta_grid)
    if periodic:
        t = theta % (2.0 * math.pi)
        step = 2.0 * math.pi / n
        s = (t - theta_grid[0]) / step
        i0 = int(math.floor(s)) % n
        w1 = s - math.floor(s)
        return i0, (i0 + 1) % n, 1.0 - w1, w1
    t = min(max(theta, theta_grid[0]), theta_grid[-1])
    i0 = min(int(np.searchsorted(theta_grid, t, side="right")) - 1, n - 2)
    w1 = (t - theta_grid[i0]) / (theta_grid[i0 + 1] - theta_grid[i0])
    return i0, i0 + 1, 1.0 - w1, w1


def raceway_displacement(table: np.ndarray, i0: int, i1: int, w0: float, w1: float, eta: np.ndarray) -> np.ndarray:
    """Raceway displacement (or rotation) (3,) at an interpolated angle: (w0 D[i0] + w1 D[i1]) η."""
    return w0 * (table[i0] @ eta) + w1 * (table[i1] @ eta)


def raceway_modal_force(table: np.ndarray, i0: int, i1: int, w0: float, w1: float, force: np.ndarray) -> np.ndarray:
    """Modal force (m,) of a force (3,) (or moment, with the rotation table) at an interpolated angle.

    The transpose of :func:`raceway_displacement`: force · displacement(η) = modal_force · η.
    """
    return w0 * (table[i0].T @ force) + w1 * (table[i1].T @ force)
