"""A rotor on bearings modelled as springs: Craig–Bampton basis at the bearing seats, the seats'
rigid motion per mode, and isotropic seat springs and dampers in the spinning frame.

Basis. Each seat (a node set, the shaft surface under a bearing) is made rigid and given its six
motions as boundary DOFs (Craig & Bampton, AIAA J. 6(7), 1968): the fixed-interface modes (every
seat held) and one static constraint shape per seat motion (the seat moved rigidly by a unit
amount, the rest of the rotor at rest in the static sense). In the modal form of that basis the
rotor is free: its six rigid motions come out at zero frequency, and the bearings hold them.

Springs. A bearing is a stiffness between the seat's lateral motion (u_x, u_y, θ_x, θ_y) and the
ground: k_r per direction, k_θ per tilt, and k_rθ coupling them (u_x with θ_y, u_y with −θ_x,
as in the 5 × 5 bearing stiffness of :func:`mbd_core.quasistatic.solve_high_speed_row` with its
axial row dropped). Isotropic springs (the same all round, e.g. an axially preloaded bearing without
radial load) look the same from the spinning frame, so the rotor keeps constant coefficients;
:func:`isotropic_bearing` takes the isotropic part of a 5 × 5 matrix and says how much anisotropy it
leaves out. Stationary seat damping c_r, c_θ acts on the fixed-frame velocity, u̇ + Ω ẑ × u.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla

from fem_rings.linalg import shift_invert_operator
from fem_rings.modal_basis import deflated_eigsh, rigid_body_fields
from fem_rings.model import FEModel, vector_dofs
from fem_rings.spinning import statically_determinate_holds
from mbd_core.quasistatic import solve_high_speed_row

from .spin import SpinningBody

__all__ = ["BearingSpring", "ball_row_spring", "isotropic_bearing", "seat_basis", "seat_motion", "on_bearings",
           "statically_determinate_holds"]


@dataclass(frozen=True)
class BearingSpring:
    """Isotropic bearing at a seat: stiffness and stationary damping (module docstring).

    k_r_N_m, k_theta_Nm_rad, k_rtheta_N_rad : radial, tilt and coupling stiffness
    c_r_Ns_m, c_theta_Nms_rad : stationary damping (0 by default)
    """

    k_r_N_m: float
    k_theta_Nm_rad: float = 0.0
    k_rtheta_N_rad: float = 0.0
    c_r_Ns_m: float = 0.0
    c_theta_Nms_rad: float = 0.0

    def __post_init__(self) -> None:
        for name in ("k_r_N_m", "k_theta_Nm_rad", "c_r_Ns_m", "c_theta_Nms_rad"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0.0):
                raise ValueError(f"bearing spring: {name} must be finite and ≥ 0, got {v!r}")
        if not math.isfinite(self.k_rtheta_N_rad):
            raise ValueError(f"bearing spring: k_rtheta_N_rad must be finite, got {self.k_rtheta_N_rad!r}")

    def mirrored(self) -> "BearingSpring":
        """The same bearing facing the other way along the shaft (the second row of a back-to-back
        pair): its radial–tilt coupling changes sign."""
        return replace(self, k_rtheta_N_rad=-self.k_rtheta_N_rad)

    def matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """(K, C) 4 × 4 on (u_x, u_y, θ_x, θ_y)."""
        kr, kt, kc = self.k_r_N_m, self.k_theta_Nm_rad, self.k_rtheta_N_rad
        K = np.array([[kr, 0, 0, kc], [0, kr, -kc, 0], [0, -kc, kt, 0], [kc, 0, 0, kt]], dtype=float)
        C = np.diag([self.c_r_Ns_m, self.c_r_Ns_m, self.c_theta_Nms_rad, self.c_theta_Nms_rad])
        return K, C


def isotropic_bearing(K5, c_r_Ns_m: float = 0.0, c_theta_Nms_rad: float = 0.0) -> tuple[BearingSpring, float]:
    """The isotropic part of a 5 × 5 bearing stiffness (x, y, z, θx, θy) and the share it leaves out
    (the Frobenius norm of the anisotropic lateral part over that of the lateral part)."""
    K = np.asarray(K5, dtype=float)
    if K.shape != (5, 5) or not np.all(np.isfinite(K)):
        raise ValueError(f"bearing stiffness must be a finite 5 × 5 matrix, got shape {K.shape}")
    L = K[np.ix_([0, 1, 3, 4], [0, 1, 3, 4])]
    L = 0.5 * (L + L.T)
    spring = BearingSpring(0.5 * (L[0, 0] + L[1, 1]), 0.5 * (L[2, 2] + L[3, 3]), 0.5 * (L[0, 3] - L[1, 2]),
                           c_r_Ns_m, c_theta_Nms_rad)
    iso, _ = spring.matrices()
    return spring, float(np.linalg.norm(L - iso) / max(np.linalg.norm(L), 1e-300))


def ball_row_spring(row, load, speed_rad_s: float, mirrored: bool = False, control: str = "outer",
                    c_r_Ns_m: float = 0.0, c_theta_Nms_rad: float = 0.0) -> tuple[BearingSpring, float]:
    """The isotropic spring of a ball row at its operating point: the row's tangent stiffness from
    its quasi-static equilibrium at speed (centrifugal force and gyroscopic moment of the balls,
    :func:`mbd_core.quasistatic.solve_high_speed_row`) under ``load`` (a RingLoad on its inner ring),
    and the share of anisotropy left out (:func:`isotropic_bearing`). ``mirrored``: the row faces
    the other way along the shaft (the second row of a back-to-back pair), which turns the sign of
    its radial–tilt coupling."""
    quasi = solve_high_speed_row(row, load, speed_rad_s, control)
    spring, left_out = isotropic_bearing(quasi.stiffness, c_r_Ns_m, c_theta_Nms_rad)
    return (spring.mirrored() if mirrored else spring), left_out


def seat_motion(nodes_m: np.ndarray, seat_nodes) -> tuple[np.ndarray, np.ndarray]:
    """Least-squares rigid motion of a seat: (R, dofs) with R (6, 3k) such that the seat's
    (t_x, t_y, t_z, θ_x, θ_y, θ_z) about its centroid is R @ u[dofs]."""
    seat = np.asarray(seat_nodes, dtype=np.int64).ravel()
    x = np.asarray(nodes_m, dtype=float)[seat]
    G = rigid_body_fields(x, x.mean(axis=0))
    return np.linalg.pinv(G), vector_dofs(seat)


def seat_basis(model: FEModel, seats, n_modes: int) -> tuple[np.ndarray, np.ndarray]:
    """Craig–Bampton basis of a rotor at its ``seats`` (node arrays) in modal form (module docstring).

    Returns (frequencies_Hz, shapes): ``n_modes`` fixed-interface modes plus six constraint shapes
    per seat, mass-normalised; the rigid motions at (numerically) zero frequency.
    """
    seats = [np.asarray(s, dtype=np.int64).ravel() for s in seats]
    if not seats:
        raise ValueError("seat_basis: give at least one seat")
    n = model.n_dofs
    boundary = np.unique(np.concatenate([vector_dofs(s) for s in seats]))
    interior = np.setdiff1d(np.arange(n), boundary)
    K, M = model.K.tocsr(), model.M.tocsr()
    KI = K[interior]
    KII, MII = KI[:, interior], M[interior][:, interior]
    # every seat held leaves no rigid motion: one factor of K_II gives the fixed-interface modes
    # (shift 0) and the constraint shapes
    op, factor = shift_invert_operator(KII, MII, 0.0)
    fixed = np.zeros((n, int(n_modes)))
    fixed[interior] = deflated_eigsh(KII, MII, int(n_modes), 0.0, op)[1]
    shapes = []
    for s in seats:
        x = model.nodes_m[s]
        ub = rigid_body_fields(x, x.mean(axis=0))            # (3k, 6)
        U = np.zeros((n, 6))
        U[vector_dofs(s)] = ub
        U[interior] = -factor.solve(np.asarray(KI[:, vector_dofs(s)] @ ub))
        shapes.append(U)
    V = np.hstack([fixed, *shapes])
    Kr, Mr = V.T @ (K @ V), V.T @ (M @ V)
    w2, X = sla.eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T))
    return np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * math.pi), V @ X


def on_bearings(body: SpinningBody, shapes: np.ndarray, nodes_m: np.ndarray, bearings) -> SpinningBody:
    """``body`` with bearing springs and stationary damping at seats: ``bearings`` is a sequence of
    (seat node array, :class:`BearingSpring`). The springs add to the stiffness; the damping adds
    c to the damping and Ω c J to the stiffness (J = ẑ× on (u_x, u_y) and on (θ_x, θ_y)), kept in
    ``support_damping`` and ``support_cross`` (used by :func:`.spin.spinning_matrices`)."""
    phi = np.asarray(shapes, dtype=float)
    K = body.stiffness_rad2_s2.copy()
    C = np.zeros_like(K)
    X = np.zeros_like(K)
    J = np.array([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 0, -1], [0, 0, 1, 0]], dtype=float)
    for seat, spring in bearings:
        R, dofs = seat_motion(nodes_m, seat)
        B = (R @ phi[dofs])[[0, 1, 3, 4]]               # (4, m): u_x, u_y, θ_x, θ_y per mode
        Ks, Cs = spring.matrices()
        K += B.T @ Ks @ B
        C += B.T @ Cs @ B
        X += B.T @ (Cs @ J) @ B
    return replace(body, stiffness_rad2_s2=K, support_damping=body.support_damping + C,
                   support_cross=body.support_cross + X)
