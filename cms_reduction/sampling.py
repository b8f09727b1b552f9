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
from fem_rings.nodesets import raceway_curve as raceway_curve_at
from fem_rings.probe import gradient_probe_matrices, probe_matrix

from .body import ReducedBody

__all__ = ["RacewaySample", "sample_raceway", "interp_index", "raceway_displacement", "raceway_modal_force",
           "sample_to_arrays", "samples_from_arrays", "sample_across", "pocket_contact_points",
           "sample_points"]


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


def sample_points(body: ReducedBody, name: str, points_m: np.ndarray, theta_rad: np.ndarray,
                  periodic: bool = False) -> RacewaySample:
    """Mode displacement and small rotation of the body at arbitrary points on or in it."""
    pts = np.atleast_2d(np.asarray(points_m, dtype=float))
    basis = scalar_basis(body.mesh(), 2)
    P = probe_matrix(basis, pts)
    G = gradient_probe_matrices(basis, pts)
    m = body.n_modes
    Phi = body.shapes.reshape(-1, 3, m)                     # (N, 3, m)
    disp = np.stack([P @ Phi[:, c, :] for c in range(3)], axis=1)          # (n, 3, m)
    grad = np.stack([np.stack([G[i] @ Phi[:, c, :] for i in range(3)], axis=1) for c in range(3)], axis=1)
    # grad[p, c, i, k] = ∂u_c/∂x_i ; ω = ½ (∂u_z/∂y − ∂u_y/∂z, ∂u_x/∂z − ∂u_z/∂x, ∂u_y/∂x − ∂u_x/∂y)
    rot = 0.5 * np.stack([grad[:, 2, 1] - grad[:, 1, 2], grad[:, 0, 2] - grad[:, 2, 0],
                          grad[:, 1, 0] - grad[:, 0, 1]], axis=1)
    return RacewaySample(name, np.asarray(theta_rad, float), pts, disp, rot, bool(periodic))


def sample_raceway(body: ReducedBody, curve: RacewayCurve, full_circle: bool, patch=()) -> RacewaySample:
    """Sample the body's modes at the points of ``curve`` (from :func:`fem_rings.nodesets.raceway_curve`).

    With ``patch`` (the (circle, weight) pairs of :func:`fem_rings.nodesets.raceway_patch`) the
    displacement and rotation at each point are the weighted averages Σ w_k D(p_k), Σ w_k Ω(p_k)
    over the patch circles at the same θ (RBE3-type weighted-average interpolation); the sample
    keeps the points of ``curve``. A force f at θ then does the work Σ w_k f·D(p_k) η: the patch
    load of :class:`cms_reduction.augmentation.Augmentation` is its transpose. Empty: the values
    on ``curve`` itself.
    """
    if not patch:
        return sample_points(body, curve.name, curve.points_m, curve.theta_rad, full_circle)
    pts = np.concatenate([c.points_m for c, _ in patch])
    s = sample_points(body, curve.name, pts, curve.theta_rad, full_circle)
    w = np.array([wk for _, wk in patch])
    n = len(curve.theta_rad)
    disp = np.einsum("k,knjm->njm", w, s.displacement.reshape(len(w), n, 3, -1))
    rot = np.einsum("k,knjm->njm", w, s.rotation.reshape(len(w), n, 3, -1))
    return RacewaySample(curve.name, s.theta_rad, np.asarray(curve.points_m, float), disp, rot, s.periodic)


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


def sample_to_arrays(sample: RacewaySample) -> dict:
    """Flat arrays for :attr:`ReducedBody.extras` (keys ``sample:<name>:…``)."""
    k = f"sample:{sample.name}:"
    return {k + "theta_rad": sample.theta_rad, k + "points_m": sample.points_m,
            k + "displacement": sample.displacement, k + "rotation": sample.rotation,
            k + "periodic": np.array(sample.periodic)}


def samples_from_arrays(extras: dict) -> dict:
    """The raceway samples stored in a body's extras, by raceway name."""
    names = sorted({key.split(":")[1] for key in extras if key.startswith("sample:")})
    out = {}
    for n in names:
        k = f"sample:{n}:"
        out[n] = RacewaySample(n, extras[k + "theta_rad"], extras[k + "points_m"], extras[k + "displacement"],
                               extras[k + "rotation"], bool(extras[k + "periodic"]))
    return out


def sample_across(body: ReducedBody, ring, segment: str, n_theta: int, n_across: int) -> list[RacewaySample]:
    """A (θ, s) grid on a straight raceway (a roller track): one circle of samples at each of
    ``n_across`` positions s across the segment (Gauss–Legendre points, where roller slices sit).

    Sample names are ``"<segment>@s<k>"`` with k ascending along the segment.
    """
    segs = [s for s in ring.profile.segments if s.name == segment]
    if len(segs) != 1:
        raise ValueError(f"segment {segment!r}: a (θ, s) grid needs exactly one segment of that name, "
                         f"found {len(segs)}")
    x, _ = np.polynomial.legendre.leggauss(int(n_across))
    out = []
    for k, s in enumerate(0.5 * (x + 1.0)):
        curve = raceway_curve_at(ring, segment, n_theta, segs[0].points(np.array([s]))[0])
        out.append(sample_points(body, f"{segment}@s{k}", curve.points_m, curve.theta_rad, ring.spec.full_circle))
    return out


def pocket_contact_points(pockets) -> tuple[np.ndarray, np.ndarray]:
    """Mid-points of the two circumferential walls of every cage pocket.

    Returns
    -------
    points_m : (n_pockets · 2, 3) float64
        Leading wall (+θ side) then trailing wall of each pocket, at the pocket's pitch radius and z.
    theta_rad : (n_pockets · 2,) float64
        The pocket-centre angle of each point.
    """
    th = pockets.angles_rad
    half = 0.5 * pockets.circumferential_width_m
    centre = np.column_stack((pockets.pitch_radius_m * np.cos(th), pockets.pitch_radius_m * np.sin(th),
                              np.full(len(th), pockets.z_m)))
    tangent = np.column_stack((-np.sin(th), np.cos(th), np.zeros(len(th))))
    pts = np.stack([centre + half * tangent, centre - half * tangent], axis=1).reshape(-1, 3)
    return pts, np.repeat(th, 2)
