"""Flat arrays of contact points (balls and roller slices) and their forces on the moving ring.

The model of each row is described in :mod:`mbd_core.quasistatic.rows`. Here every ball and
every roller slice becomes one entry of structure-of-arrays groups, so that forces and the
analytic Jacobian of a whole bearing are a few vectorised numpy expressions.

Generalised coordinates q = (x, y, z, θx, θy) of the moving ring (m, rad). A point p of the
moving ring moves by u = B(p)·q with B(p) = [I₃ | −[p]ₓ(:, :2)] (small rotations).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .rows import BallRow, Bearing, FourPointRow, RollerRow

__all__ = ["BallGroup", "SliceGroup", "build_groups", "displacement_matrix", "shift_ball_centres"]


@dataclass(frozen=True)
class BallGroup:
    """All balls of a bearing.

    Attributes (n = number of balls)
    ----------
    p_m : (n, 3) moving-ring groove-centre position, m
    t : (n, 3) tangential unit vector e_t at the ball
    s0_m : (n, 3) unloaded centre-distance vector A·d̂ − (P_d/2)·s_r·e_r, m
    free_length_m : (n,) A, m (approach δ = |s| − free_length)
    s0_excess_m2 : (n,) |s0|² − A², m² (exact, so that δ = (|s0|² − A² + 2 s0·u + |u|²)/(|s| + A)
        keeps its relative precision when δ ≪ A)
    K : (n,) load–deflection constant, N/m^1.5
    radial_sign, axial_sign : (n,) ±1, for the loaded contact angle
    angle_min_rad, angle_max_rad : (n,) loaded contact angles the groove can carry, rad
    e_r : (n, 3) radial unit vector
    row : (n,) int row index; element : (n,) int index of the ball within its row (a four-point
        ball has two entries, one per diagonal, :mod:`.rows_four_point`)
    """

    p_m: np.ndarray
    t: np.ndarray
    s0_m: np.ndarray
    free_length_m: np.ndarray
    s0_excess_m2: np.ndarray
    K: np.ndarray
    radial_sign: np.ndarray
    axial_sign: np.ndarray
    angle_min_rad: np.ndarray
    angle_max_rad: np.ndarray
    e_r: np.ndarray
    row: np.ndarray
    element: np.ndarray


@dataclass(frozen=True)
class SliceGroup:
    """All roller slices of a bearing.

    Attributes (n = number of slices)
    ----------
    p_m : (n, 3) slice centre on the moving raceway, m
    normal : (n, 3) unit vector along which a moving-ring displacement loads the slice
    offset_m : (n,) gap + profile drop, m (approach δ = u·normal − offset)
    K : (n,) slice constant c_L/n_s, N/m^(10/9)
    exponent : (n,) load exponent (10/9)
    row, element, slice : (n,) int row index, roller index within the row, slice index
    """

    p_m: np.ndarray
    normal: np.ndarray
    offset_m: np.ndarray
    K: np.ndarray
    exponent: np.ndarray
    row: np.ndarray
    element: np.ndarray
    slice: np.ndarray


def _frame(psi: np.ndarray):
    c, s = np.cos(psi), np.sin(psi)
    z = np.zeros_like(psi)
    e_r = np.stack([c, s, z], axis=1)
    e_t = np.stack([-s, c, z], axis=1)
    return e_r, e_t


def _ball_pair_arrays(i_row: int, row, psi: np.ndarray, axial_sign: np.ndarray, element: np.ndarray):
    """Entries of ball pairs (moving and fixed groove along one line of centres) at azimuths ``psi``
    with axial signs ``axial_sign`` (n,) of a :class:`BallRow` or :class:`FourPointRow`."""
    n = len(psi)
    e_r, e_t = _frame(psi)
    e_z = np.array([0.0, 0.0, 1.0])
    a0, D = row.contact_angle_rad, row.ball_diameter_m
    sr = row.radial_sign
    d_hat = (sr * np.cos(a0)) * e_r + (axial_sign * np.sin(a0))[:, None] * e_z
    ball_centre = 0.5 * row.pitch_diameter_m * e_r + row.axial_position_m * e_z
    A, c = row.curvature_centre_distance_m, row.radial_clearance_m
    lo, hi = row.groove_angle_range_rad
    # the clearance moves the grooves apart radially (concentric rings): ISO/TS 16281, Harris ch. 2
    return dict(
        p_m=ball_centre + (row.conformity_moving - 0.5) * D * d_hat,
        t=e_t,
        s0_m=A * d_hat - (c * sr) * e_r,
        free_length_m=np.full(n, A),
        s0_excess_m2=np.full(n, c * (c - 2.0 * A * np.cos(a0))),  # |A·d̂ − c·s_r·e_r|² − A², c = P_d/2
        K=np.full(n, row.contact_stiffness()),
        radial_sign=np.full(n, float(sr)),
        axial_sign=np.asarray(axial_sign, dtype=float),
        angle_min_rad=np.full(n, lo),
        angle_max_rad=np.full(n, hi),
        e_r=e_r,
        row=np.full(n, i_row),
        element=element,
    )


def _ball_arrays(i_row: int, row: BallRow | FourPointRow) -> dict[str, np.ndarray]:
    """One entry per ball of a :class:`BallRow`; two per ball of a :class:`FourPointRow`, one per
    diagonal (+α, −α), interleaved ball by ball."""
    n = row.n_balls
    psi = row.azimuths_rad()
    if isinstance(row, FourPointRow):
        k = len(row.DIAGONAL_SIGNS)
        return _ball_pair_arrays(i_row, row, np.repeat(psi, k), np.tile(np.array(row.DIAGONAL_SIGNS, float), n),
                                 np.repeat(np.arange(n), k))
    return _ball_pair_arrays(i_row, row, psi, np.full(n, float(row.axial_sign)), np.arange(n))


def _slice_arrays(i_row: int, row: RollerRow) -> dict[str, np.ndarray]:
    """Slices of a roller row: centres along each roller's axis, its normal (:meth:`RollerRow.roller_frames`)."""
    n, ns = row.n_rollers, row.n_slices
    e_r, _ = _frame(row.azimuths_rad())
    axis, normal = (np.repeat(v, ns, axis=0) for v in row.roller_frames(e_r))
    L = row.roller_length_m
    x = np.tile(-0.5 * L + (np.arange(ns) + 0.5) * L / ns, n)  # slice centres along the roller
    drop = row.drop_m(x)
    centre = 0.5 * row.pitch_diameter_m * e_r + row.axial_position_m * np.array([0.0, 0.0, 1.0])
    p = np.repeat(centre, ns, axis=0) + x[:, None] * axis
    return dict(
        p_m=p,
        normal=normal,
        offset_m=row.gap_m + drop,
        K=np.full(n * ns, row.contact_stiffness() / ns),
        exponent=np.full(n * ns, row.exponent),
        row=np.full(n * ns, i_row),
        element=np.repeat(np.arange(n), ns),
        slice=np.tile(np.arange(ns), n),
    )


def _stack(parts: list[dict[str, np.ndarray]], keys: tuple[str, ...], widths: dict[str, int]):
    out = {}
    for k in keys:
        if parts:
            out[k] = np.concatenate([p[k] for p in parts])
        else:
            shape = (0, widths[k]) if widths.get(k) else (0,)
            out[k] = np.zeros(shape, dtype=int if k in ("row", "element", "slice") else float)
    return out


def build_groups(bearing: Bearing) -> tuple[BallGroup, SliceGroup]:
    """Flatten the rows of a bearing into one ball group and one slice group."""
    balls = [_ball_arrays(i, r) for i, r in enumerate(bearing.rows) if isinstance(r, (BallRow, FourPointRow))]
    slices = [_slice_arrays(i, r) for i, r in enumerate(bearing.rows) if isinstance(r, RollerRow)]
    vec3 = {"p_m": 3, "t": 3, "s0_m": 3, "e_r": 3, "normal": 3}
    bg = BallGroup(**_stack(balls, tuple(BallGroup.__dataclass_fields__), vec3))
    sg = SliceGroup(**_stack(slices, tuple(SliceGroup.__dataclass_fields__), vec3))
    return bg, sg


def shift_ball_centres(g: BallGroup, ds_m: np.ndarray) -> BallGroup:
    """The ball group with every unloaded centre-distance vector s0 moved by ``ds_m`` (n, 3), m."""
    s0 = g.s0_m + ds_m
    excess = g.s0_excess_m2 + np.einsum("ij,ij->i", 2.0 * g.s0_m + ds_m, ds_m)
    return replace(g, s0_m=s0, s0_excess_m2=excess)


def displacement_matrix(p_m: np.ndarray) -> np.ndarray:
    """B(p) with u = B·q for q = (x, y, z, θx, θy): (n, 3, 5)."""
    n = p_m.shape[0]
    B = np.zeros((n, 3, 5))
    B[:, 0, 0] = B[:, 1, 1] = B[:, 2, 2] = 1.0
    px, py, pz = p_m[:, 0], p_m[:, 1], p_m[:, 2]
    # θ × p for θ = (θx, θy, 0): (θy·pz, −θx·pz, θx·py − θy·px)
    B[:, 0, 4] = pz
    B[:, 1, 3] = -pz
    B[:, 2, 3] = py
    B[:, 2, 4] = -px
    return B
