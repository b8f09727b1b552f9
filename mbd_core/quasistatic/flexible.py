"""Quasi-static load distribution of a bearing whose rings bend (modal coordinates as unknowns).

Unknowns x = (q, η_1, …, η_k): the rigid displacement q = (x, y, z, θx, θy) of the moving ring
(m, rad) and the modal coordinates η of every flexible ring (√kg). Balls follow the rigid-ring
model of :mod:`.rows` (groove curvature centres on a line through the ball, Q = K·δ^1.5,
δ = |s| − A − gap with s the vector from the fixed to the moving ring's groove centre, its
component along the rolling direction e_t removed since the ball rolls freely).

Flexible ring. A ring reduced by Craig–Bampton and grounded at its interfaces (a bolted face:
:func:`cms_reduction.reduced_body`), mass-normalised modes with the modal stiffness
K_η = diag(ω²), its raceway sampled at angles θ_j (:mod:`cms_reduction.sampling`): p_j the
raceway point, D_j (3, m) its displacement and Ω_j (3, m) its small rotation per unit η. A ball
at azimuth ψ_i takes D_i, Ω_i and p_i by linear interpolation in θ with the same weights
(:func:`cms_reduction.sampling.interp_index`). The groove section is taken to move rigidly with
its raceway point, so the ring's groove curvature centre c_i moves by

    u_i = D_i η + (Ω_i η) × (c_i − p_i) = T_i η,        T_i = D_i − [c_i − p_i]ₓ Ω_i.

A flexible moving ring rides on q (its grounded interfaces are attached to the rigid moving
structure): its groove centre moves by B(c_i) q + T_i η, B of :func:`.elements.displacement_matrix`.
Groove offsets of either ring — an axial undulation h(θ) and a radial offset Δr(θ), in the
ring's own angle θ — add Δc_i = Δr·e_r + h·e_z to that ring's curvature centre. Hence

    s_i = s0_i + Δc_m,i − Δc_f,i + P_i G_i x,      P_i = I − e_t e_tᵀ,
    G_i = [B(c_m,i) | +T_i of a flexible moving ring | −T_i of a flexible fixed ring].

Equilibrium by virtual work. Ball i pushes the moving ring with F_i = −Q_i ŝ_i and the fixed
ring with −F_i, at points of the line through both groove centres (the contact normal), so a
force f_i on a flexible ring does the virtual work f_i·δu_i = (T_iᵀ f_i)·δη:

    R(x) = Σ_i G_iᵀ F_i + (f_ext, −K_η,1 η_1, …, −K_η,k η_k) = 0,

i.e. for each flexible ring K_η η = Σ_i [D_iᵀ f_i + Ω_iᵀ ((c_i − p_i) × f_i)]. Since F_i lies
in the meridian plane (P_i F_i = F_i), the Jacobian is the symmetric

    dR/dx = −Σ_i (P_i G_i)ᵀ [Q_i' ŝ_i ŝ_iᵀ + (Q_i/|s_i|)(I − ŝ_i ŝ_iᵀ)] (P_i G_i) − diag(0, K_η),

Q' = 1.5·K·δ^0.5 (the chain rule through s_i, as in the rigid solver).

Roller rows: slice k (centre p_k on the roller axis, normal n_k) of a roller at ψ takes the raceway
fields at ψ the same way, the slice point moving with the section, T_k = D − [p_k − p]ₓ Ω (a tilt
of the raceway about e_t loads one roller end more), so δ_k = n_k·(G_k x) − gap − drop with G_k as
above and the slice forces project with G_kᵀ n_k. Offsets shift a raceway by n_k·Δc_k. Crossed roller
rows: the raceway is sampled at the apex of the V-groove, which lies half a roller diameter from the
roller axis along both diagonals' normals, and each roller's slices take the fields there the same
way (the section between the apex and the contact line moving as a rigid piece, as the four-point
row's two curvature centres do with their gothic-arch apex).

Solution (:mod:`.flexible_solve`): Newton with backtracking (:func:`.solver.damped_newton`), first on q with η = 0 (the
rigid-ring solution with the offsets), then on (q, η) from there. Each η_j is scaled by the
largest raceway displacement of its mode, so that every scaled unknown is a length (m) and every
scaled residual a force (N), like the moments and rotations of the rigid solver.

References: Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed. (2007), ch. 7 (ball loads);
Craig & Bampton, AIAA J. 6(7), 1313–1319 (1968) (reduced ring).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .elements import BallGroup, SliceGroup, build_groups, displacement_matrix, shift_ball_centres
from .rows import BallRow, Bearing, FourPointRow
from .solver import RingLoad, _scaling, ball_forces, slice_forces


__all__ = ["FlexibleRing", "GrooveOffset", "FlexibleBearingModel", "build_flexible_model"]

RING_SIDES = ("fixed", "moving")
#: Rows whose elements are balls (a four-point ball: two entries, one per diagonal, each with its own
#: pair of groove curvature centres that move with the ring's section like any ball row's).
BALL_ROWS = (BallRow, FourPointRow)
#: Relative tolerance on where the raceway samples lie: f·D from the ring's groove curvature centre
#: (balls), half a roller diameter from the roller axis (rollers).
GEOMETRY_RTOL = 0.02


def _side(owner: str, side: str) -> None:
    if side not in RING_SIDES:
        raise ValueError(f"{owner}: ring must be 'fixed' or 'moving', got {side!r}")


def _samples(body) -> dict:
    # imported here: cms_reduction imports mbd_core, so a module-level import would be circular
    from cms_reduction.sampling import samples_from_arrays

    return samples_from_arrays(body.extras)


@dataclass(frozen=True)
class FlexibleRing:
    """A ring of the bearing that bends: a reduced body grounded at its interfaces, or (moving ring
    only) a floating body whose frame is the rigid displacement q.

    A floating moving ring has free–free elastic modes, mass-orthogonal to its rigid motion, so a
    load spread like its mass (its weight, or a dead load carried as mass) does no work on η and
    only the element forces bend it: K_η η = Σ Tᵢᵀ fᵢ holds as for a grounded ring.

    Parameters
    ----------
    name : str
        Label (names the ring's modal coordinates in the result).
    body : cms_reduction.ReducedBody
        Body with raceway samples in its extras; grounded, or floating for the moving ring.
    ring : {"fixed", "moving"}
        Which ring of the rows it is. A moving ring's interfaces ride on the rigid displacement q.
    raceways : mapping row name → raceway sample name
        The rows whose raceways this ring carries, e.g. ``{"load balls": "groove"}``: for a ball
        row the groove sampled on a circle at (or near) the contact point, for a roller row the
        raceway sampled on one circle across it (e.g. mid-width).
    rotation_rad : float
        Angle of the body's frame from the bearing frame about the axis: a ball at azimuth ψ
        sits at body angle ψ − rotation_rad.
    """

    name: str
    body: Any
    ring: str
    raceways: Any
    rotation_rad: float = 0.0

    def __post_init__(self) -> None:
        from cms_reduction.body import ReducedBody

        who = f"flexible ring {self.name!r}"
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"flexible ring: name must be a non-empty string, got {self.name!r}")
        if not isinstance(self.body, ReducedBody):
            raise ValueError(f"{who}: body must be a ReducedBody, got {type(self.body).__name__}")
        _side(who, self.ring)
        if self.body.floating and self.ring != "moving":
            raise ValueError(f"{who}: body {self.body.name!r} is floating (free–free modes); a fixed ring must be "
                             "grounded (reduce it with grounded interfaces, InterfaceSpec(grounded=True))")
        pairs = tuple(self.raceways.items()) if isinstance(self.raceways, Mapping) else tuple(self.raceways)
        if not pairs or not all(isinstance(p, tuple) and len(p) == 2 and all(isinstance(v, str) for v in p)
                                for p in pairs):
            raise ValueError(f"{who}: raceways must map row names to raceway sample names, got {self.raceways!r}")
        object.__setattr__(self, "raceways", pairs)
        if not (isinstance(self.rotation_rad, (int, float)) and math.isfinite(self.rotation_rad)):
            raise ValueError(f"{who}: rotation_rad must be a finite number, got {self.rotation_rad!r}")
        samples = _samples(self.body)
        for row, name in pairs:
            if name not in samples:
                raise ValueError(f"{who}: raceways[{row!r}] = {name!r} is not a raceway sample of body "
                                 f"{self.body.name!r}; it has {sorted(samples)}")
            if samples[name].displacement.shape[2] != self.body.n_modes:
                raise ValueError(f"{who}: raceway sample {name!r} has {samples[name].displacement.shape[2]} "
                                 f"modes, body {self.body.name!r} {self.body.n_modes}")


@dataclass(frozen=True)
class GrooveOffset:
    """Offsets of one ring's groove curvature centre (or roller raceway) as functions of the ring's
    own angle θ.

    Parameters
    ----------
    row : str
        Row whose groove or raceway is offset.
    ring : {"fixed", "moving"}
    axial_m : callable θ (n,) rad → (n,) m, optional
        Axial undulation h(θ), along +z.
    radial_m : callable θ (n,) rad → (n,) m, optional
        Radial offset Δr(θ), outwards (e.g. differential thermal expansion).
    rotation_rad : float
        Angle of the ring's frame from the bearing frame: the ball at azimuth ψ sees θ = ψ − rotation_rad.
    """

    row: str
    ring: str
    axial_m: Callable | None = None
    radial_m: Callable | None = None
    rotation_rad: float = 0.0

    def __post_init__(self) -> None:
        who = f"groove offset of row {self.row!r}"
        _side(who, self.ring)
        if self.axial_m is None and self.radial_m is None:
            raise ValueError(f"{who}: give axial_m, radial_m or both")
        for name in ("axial_m", "radial_m"):
            f = getattr(self, name)
            if f is not None and not callable(f):
                raise ValueError(f"{who}: {name} must be a function of the angle θ (rad), got {f!r}")
        if not (isinstance(self.rotation_rad, (int, float)) and math.isfinite(self.rotation_rad)):
            raise ValueError(f"{who}: rotation_rad must be a finite number, got {self.rotation_rad!r}")

    def centre_offset_m(self, psi_rad: np.ndarray) -> np.ndarray:
        """Δc = Δr·e_r + h·e_z (n, 3), m, at element azimuths ψ (n,) rad."""
        theta = np.asarray(psi_rad, dtype=float) - self.rotation_rad
        out = {}
        for name in ("axial_m", "radial_m"):
            f = getattr(self, name)
            v = np.zeros_like(theta) if f is None else np.broadcast_to(np.asarray(f(theta), dtype=float),
                                                                         theta.shape)
            if not np.all(np.isfinite(v)):
                raise ValueError(f"groove offset of row {self.row!r}: {name} returned non-finite values")
            out[name] = v
        c, s = np.cos(psi_rad), np.sin(psi_rad)
        return np.column_stack((out["radial_m"] * c, out["radial_m"] * s, out["axial_m"]))


@dataclass(frozen=True)
class _Coupling:
    """The elements of one row on one flexible ring, at their Z azimuths (m modes)."""

    ring: str
    row: str
    azimuth_rad: np.ndarray  # (Z,)
    points_m: np.ndarray     # (Z, 3) interpolated raceway points p_i
    D: np.ndarray            # (Z, 3, m) displacement per unit η
    Omega: np.ndarray        # (Z, 3, m) rotation per unit η
    T: np.ndarray | None     # (Z, 3, m) groove-centre displacement per unit η (balls), None for rollers


@dataclass(frozen=True, eq=False)
class FlexibleBearingModel:
    """A bearing with flexible rings, flattened for the solver (build with :func:`build_flexible_model`).

    Attributes (N = 5 + Σ modes of the flexible rings, n = balls, n_s = slices)
    ----------
    bearing : Bearing
    rings : tuple of FlexibleRing
    offsets : tuple of GrooveOffset
    balls : BallGroup
        With s0_m including the groove offsets.
    slices : SliceGroup
    ball_dofs : (n, 3, N) G_i, groove-centre distance change per unknown
    slice_dofs : (n_s, N) approach of each slice per unknown
    stiffness_diag : (N,) 0 for q, ω² for each η, 1/s²
    ring_dofs : tuple of slice, the columns of each ring's η
    dof_scale : (N,) scaled unknown = dof_scale·x (m)
    couplings : tuple of _Coupling
    """

    bearing: Bearing
    rings: tuple
    offsets: tuple
    balls: BallGroup
    slices: SliceGroup
    ball_dofs: np.ndarray
    slice_dofs: np.ndarray
    stiffness_diag: np.ndarray
    ring_dofs: tuple
    dof_scale: np.ndarray
    couplings: tuple

    @property
    def n_unknowns(self) -> int:
        return len(self.stiffness_diag)

    def load_vector(self, load: RingLoad) -> np.ndarray:
        """External generalised force (N,): the ring load on q, nothing on η."""
        f = np.zeros(self.n_unknowns)
        f[:5] = load.as_array()
        return f

    def residual(self, x: np.ndarray, load: RingLoad, jacobian: bool = True):
        """R(x) (N,) and dR/dx (N, N) (or None) of the module docstring, unscaled (N, N·m, N·m/√kg)."""
        _, _, _, rb, Jb = ball_forces(self.balls, self.ball_dofs, x, jacobian)
        _, _, rs, Js = slice_forces(self.slices, self.slice_dofs, x, jacobian)
        R = rb + rs + self.load_vector(load) - self.stiffness_diag * x
        return R, (None if not jacobian else Jb + Js - np.diag(self.stiffness_diag))


def _row_index(bearing: Bearing, row: str, who: str) -> int:
    names = [r.name for r in bearing.rows]
    if row not in names:
        raise ValueError(f"{who}: bearing {bearing.name!r} has no row {row!r}; rows: {names}")
    return names.index(row)


def _azimuths(bearing: Bearing, group, mask: np.ndarray) -> np.ndarray:
    """Azimuth (rad) of the element of every selected ball or slice of a group."""
    table = {i: bearing.rows[i].azimuths_rad() for i in np.unique(group.row[mask])}
    return np.array([table[i][e] for i, e in zip(group.row[mask], group.element[mask])], dtype=float)


def _rotate_z(v: np.ndarray, angle_rad: float) -> np.ndarray:
    """Rotate vectors about z; the components are on axis 1 of ``v``."""
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    out = v.copy()
    out[:, 0] = c * v[:, 0] - s * v[:, 1]
    out[:, 1] = s * v[:, 0] + c * v[:, 1]
    return out


def _interpolate(sample, theta_body: np.ndarray, who: str):
    """p (Z, 3), D (Z, 3, m), Ω (Z, 3, m) at body angles θ, linear in θ with the same weights for
    all three, and the index of the sample just below each θ."""
    from cms_reduction.sampling import interp_index

    grid = sample.theta_rad
    idx = np.zeros((len(theta_body), 2), dtype=int)
    w = np.zeros((len(theta_body), 2))
    for k, th in enumerate(theta_body):
        if not sample.periodic:
            th = grid[0] + (th - grid[0]) % (2.0 * np.pi)
            if th > grid[-1] + 1e-9:
                raise ValueError(f"{who}: an element at body angle {math.degrees(th):.6g}° lies outside raceway "
                                 f"sample {sample.name!r} ({math.degrees(grid[0]):.6g}°–"
                                 f"{math.degrees(grid[-1]):.6g}°, not periodic)")
        i0, i1, w0, w1 = interp_index(grid, float(th), sample.periodic)
        idx[k], w[k] = (i0, i1), (w0, w1)

    def lerp(a):
        shape = (-1,) + (1,) * (a.ndim - 1)
        return w[:, 0].reshape(shape) * a[idx[:, 0]] + w[:, 1].reshape(shape) * a[idx[:, 1]]

    return lerp(sample.points_m), lerp(sample.displacement), lerp(sample.rotation), idx[:, 0]


def _ring_fields(ring: FlexibleRing, sample_name: str, psi_rad: np.ndarray, who: str):
    """Raceway p, D, Ω at bearing azimuths ψ in the bearing frame, and the nearest sample points."""
    sample = _samples(ring.body)[sample_name]
    p, D, W, i_near = _interpolate(sample, psi_rad - ring.rotation_rad, who)
    a = ring.rotation_rad
    return _rotate_z(p, a), _rotate_z(D, a), _rotate_z(W, a), _rotate_z(sample.points_m[i_near], a)


def _transfer(D: np.ndarray, W: np.ndarray, lever_m: np.ndarray) -> np.ndarray:
    """T = D − [d]ₓ Ω (k, 3, m): displacement of the point p + d moving rigidly with the section at p."""
    return D - np.swapaxes(np.cross(lever_m[:, None, :], np.swapaxes(W, 1, 2)), 1, 2)


def _check_distance(actual_m: np.ndarray, expected_m: float, what: str, who: str) -> None:
    worst = int(np.argmax(np.abs(actual_m - expected_m)))
    if abs(actual_m[worst] - expected_m) > GEOMETRY_RTOL * abs(expected_m):
        raise ValueError(f"{who}: the raceway samples lie {actual_m[worst] * 1e3:.4g} mm from {what}, expected "
                         f"{expected_m * 1e3:.4g} mm: does the body belong to this ring and row (section, pitch "
                         "diameter, which ring)?")


def _ball_coupling(bearing: Bearing, balls: BallGroup, ring: FlexibleRing, i_row: int, sample_name: str,
                   centre_offset_m: np.ndarray):
    """Coupling of a ball row, its ball indices and T_i (Z, 3, m) of the groove curvature centres."""
    row = bearing.rows[i_row]
    who = f"flexible ring {ring.name!r}, row {row.name!r}"
    mask = balls.row == i_row
    psi = _azimuths(bearing, balls, mask)
    p, D, W, p_near = _ring_fields(ring, sample_name, psi, who)
    moving = ring.ring == "moving"
    c = balls.p_m[mask] if moving else balls.p_m[mask] - balls.s0_m[mask]
    rz_gap = np.hypot(np.hypot(c[:, 0], c[:, 1]) - np.hypot(p_near[:, 0], p_near[:, 1]), c[:, 2] - p_near[:, 2])
    radius = (row.conformity_moving if moving else row.conformity_fixed) * row.ball_diameter_m
    _check_distance(rz_gap, radius, "the ring's groove curvature centre (the groove radius f·D)", who)
    T = _transfer(D, W, c + centre_offset_m[mask] - p)
    return _Coupling(ring.name, row.name, psi, p, D, W, T), np.flatnonzero(mask), T


def _slice_coupling(bearing: Bearing, slices: SliceGroup, ring: FlexibleRing, i_row: int, sample_name: str):
    """Coupling of a roller row, its slice indices and the approach per unit η (k, m) of its slices."""
    row = bearing.rows[i_row]
    who = f"flexible ring {ring.name!r}, row {row.name!r}"
    mask = slices.row == i_row
    ns = row.n_slices
    psi = row.azimuths_rad()
    p, D, W, p_near = _ring_fields(ring, sample_name, psi, who)
    normal = slices.normal[mask]
    # the raceway lies half a roller diameter from the roller axis: beyond it along n on the fixed
    # ring (the moving ring moves along +n to load the roller), before it on the moving ring;
    # measured in the section, as the nearest sample need not sit at the roller's azimuth
    axis = slices.p_m[mask].reshape(row.n_rollers, ns, 3).mean(axis=1)
    n_r = np.einsum("ij,ij->i", normal[::ns], axis / np.hypot(axis[:, 0], axis[:, 1])[:, None])
    side = -1.0 if ring.ring == "moving" else 1.0
    reach = side * (n_r * (np.hypot(p_near[:, 0], p_near[:, 1]) - np.hypot(axis[:, 0], axis[:, 1]))
                    + normal[::ns, 2] * (p_near[:, 2] - axis[:, 2]))
    _check_distance(reach, 0.5 * row.roller_diameter_m, "the roller axis (half the roller diameter)", who)
    T = _transfer(np.repeat(D, ns, axis=0), np.repeat(W, ns, axis=0), slices.p_m[mask] - np.repeat(p, ns, axis=0))
    approach = np.einsum("kjm,kj->km", T, normal)
    return _Coupling(ring.name, row.name, psi, p, D, W, None), np.flatnonzero(mask), approach


def _offsets(bearing: Bearing, balls: BallGroup, slices: SliceGroup, offsets) -> dict:
    """Δc (n, 3) of every ball and slice, per ring side."""
    delta = {side: (np.zeros_like(balls.s0_m), np.zeros_like(slices.p_m)) for side in RING_SIDES}
    for o in offsets:
        i = _row_index(bearing, o.row, f"groove offset of row {o.row!r}")
        k, group = (0, balls) if isinstance(bearing.rows[i], BALL_ROWS) else (1, slices)
        mask = group.row == i
        delta[o.ring][k][mask] += o.centre_offset_m(_azimuths(bearing, group, mask))
    return delta


def _checked_inputs(bearing: Bearing, rings, offsets):
    """Validated (rings, offsets) tuples."""
    if not isinstance(bearing, Bearing):
        raise TypeError(f"bearing must be a Bearing, got {type(bearing).__name__}")
    rings, offsets = tuple(rings), tuple(offsets)
    for k, r in enumerate(rings):
        if not isinstance(r, FlexibleRing):
            raise TypeError(f"rings[{k}] must be a FlexibleRing, got {type(r).__name__}")
    for k, o in enumerate(offsets):
        if not isinstance(o, GrooveOffset):
            raise TypeError(f"offsets[{k}] must be a GrooveOffset, got {type(o).__name__}")
    names = [r.name for r in rings]
    if len(set(names)) != len(names):
        raise ValueError(f"flexible rings: names must be unique, got {names}")
    taken = {}
    for r in rings:
        for row, _ in r.raceways:
            _row_index(bearing, row, f"flexible ring {r.name!r}")
            if (row, r.ring) in taken:
                raise ValueError(f"flexible ring {r.name!r}: the {r.ring} ring of row {row!r} is already "
                                 f"flexible ring {taken[row, r.ring]!r}")
            taken[row, r.ring] = r.name
    return rings, offsets


def build_flexible_model(bearing: Bearing, rings=(), offsets=()) -> FlexibleBearingModel:
    """Flatten a bearing, its flexible rings and groove offsets for :func:`solve_flexible_load_distribution`.

    Parameters
    ----------
    bearing : Bearing
    rings : sequence of FlexibleRing
        At most one per ring side of a row; rows not named by any ring have rigid raceways.
    offsets : sequence of GrooveOffset
        Offsets of the same ring and row add up.

    Raises ValueError naming the field for a ring or offset that does not fit the bearing.
    """
    rings, offsets = _checked_inputs(bearing, rings, offsets)
    balls, slices = build_groups(bearing)
    delta = _offsets(bearing, balls, slices, offsets)
    starts = 5 + np.concatenate(([0], np.cumsum([r.body.n_modes for r in rings]))).astype(int)
    ring_dofs = tuple(slice(int(starts[k]), int(starts[k + 1])) for k in range(len(rings)))
    N = int(starts[-1])
    G = np.zeros((len(balls.K), 3, N))
    G[:, :, :5] = displacement_matrix(balls.p_m)
    w = np.zeros((len(slices.K), N))
    w[:, :5] = np.einsum("nji,nj->ni", displacement_matrix(slices.p_m), slices.normal)
    stiffness, scale = np.zeros(N), np.zeros(N)
    scale[:5] = _scaling(bearing)
    couplings = []
    for ring, cols in zip(rings, ring_dofs):
        stiffness[cols] = ring.body.omega_rad_s**2
        sign = 1.0 if ring.ring == "moving" else -1.0
        amplitude = np.zeros(ring.body.n_modes)
        for row_name, sample_name in ring.raceways:
            i_row = _row_index(bearing, row_name, f"flexible ring {ring.name!r}")
            if isinstance(bearing.rows[i_row], BALL_ROWS):
                c, idx, T = _ball_coupling(bearing, balls, ring, i_row, sample_name, delta[ring.ring][0])
                G[idx, :, cols] += sign * T
            else:
                c, idx, wk = _slice_coupling(bearing, slices, ring, i_row, sample_name)
                w[idx, cols] += sign * wk
            couplings.append(c)
            disp = _samples(ring.body)[sample_name].displacement
            amplitude = np.maximum(amplitude, np.linalg.norm(disp, axis=1).max(axis=0))
        scale[cols] = np.maximum(amplitude, 1e-6 * max(amplitude.max(), 1e-300))
    rel = {k: delta["moving"][k] - delta["fixed"][k] for k in (0, 1)}
    balls = shift_ball_centres(balls, rel[0])
    slices = replace(slices, offset_m=slices.offset_m - np.einsum("ij,ij->i", rel[1], slices.normal))
    return FlexibleBearingModel(bearing, rings, offsets, balls, slices, G, w, stiffness, ring_dofs, scale,
                                tuple(couplings))
