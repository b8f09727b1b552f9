"""Campbell diagram of a spinning modal body: whirl frequencies against speed.

At each speed Ω the spinning-frame equations (:mod:`.spin`) M η̈ + C η̇ + K η = 0 are solved as a
first-order eigenproblem; an eigenvalue λ = −σ + i ω_r (ω_r > 0) is a mode of frequency ω_r seen
from the spinning body, damping ratio σ/|λ|.

Fixed frame. On a body of revolution every mode is a pattern of n nodal diameters turning round
the axis (or standing, n = 0). Its angular order n follows from the mode vector v and the rotation
generator Q of :mod:`.spin`: n = −Im(vᴴ Q v) / vᴴ I6 v, an integer for an exact body of revolution
(a signed one: the sense of the pattern's travel), close to one for a meshed one. Where modes of
different order meet in the spinning frame (frequencies within ``CLUSTER_RTOL``) the eigensolver
returns arbitrary mixtures; the cluster is turned into the combinations of definite order (the
eigenvectors of the Hermitian pencil (iQ, I6) on it), each with the frequencies of its members
weighted by their share. A pattern
e^{i(nθ + ω_r t)} in the spinning frame, θ = θ_f − Ωt, is e^{i(nθ_f + (ω_r − nΩ) t)} in the fixed
frame: frequency |ω_r − nΩ|, turning at −(ω_r − nΩ)/n, i.e. with the spin (forward) when that is
positive. Lateral modes of a rotor (its bending and its whirl on the supports) have |n| = 1, so a
forward whirl seen at ω_r from the rotor is one of ω_r + Ω from the ground; axial and torsional
modes have n = 0 and keep ω_r; a disc's own modes shift by n Ω.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from .spin import SpinningBody, spinning_matrices

__all__ = ["CampbellDiagram", "CLUSTER_RTOL", "ORDER_TOL", "angular_order", "campbell", "spinning_modes"]

#: modes whose spinning-frame frequencies differ by less than this share are one cluster: within it
#: any combination is a mode as well, and the one of definite angular order is taken
CLUSTER_RTOL = 1e-3

#: a mode whose angular order lies farther than this from an integer is reported as mixed (its
#: fixed-frame frequency NaN, whirl 0, the order as computed): a meshed body not near enough to one
#: of revolution, or modes of different orders close in frequency but beyond ``CLUSTER_RTOL``
ORDER_TOL = 0.2


def spinning_modes(body: SpinningBody, speed_rad_s: float, stationary_damping_per_s: float = 0.0):
    """Modes at one speed: (λ, vectors) with Im λ > 0, sorted by Im λ; vectors (m, k) complex."""
    M, C, K = spinning_matrices(body, speed_rad_s, stationary_damping_per_s)
    m = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((m, m)), np.eye(m)], [-Minv @ K, -Minv @ C]])
    lam, vec = sla.eig(A)
    keep = lam.imag > 1e-9 * max(1.0, np.abs(lam).max())
    lam, vec = lam[keep], vec[:m, keep]
    order = np.argsort(lam.imag)
    return lam[order], vec[:, order]


def _definite_orders(body: SpinningBody, lam: np.ndarray, vec: np.ndarray):
    """(λ, vectors) with every cluster of nearly equal frequencies turned into modes of definite
    angular order (module docstring)."""
    lam, vec = lam.copy(), vec.copy()
    w = lam.imag
    start = 0
    for end in range(1, len(w) + 1):
        if end < len(w) and w[end] - w[end - 1] <= CLUSTER_RTOL * abs(w[end]):
            continue
        if end - start > 1:
            V = vec[:, start:end]
            H = V.conj().T @ (1j * body.rotation) @ V
            G = V.conj().T @ body.mass @ V
            _, Y = sla.eigh(0.5 * (H + H.conj().T), 0.5 * (G + G.conj().T))
            share = np.abs(Y) ** 2 * np.real(np.diag(G))[:, None]
            share /= share.sum(axis=0)
            vec[:, start:end] = V @ Y
            lam[start:end] = share.T @ lam[start:end]
        start = end
    return lam, vec


def angular_order(body: SpinningBody, vectors: np.ndarray) -> np.ndarray:
    """Signed angular order n of each complex mode vector (module docstring); (k,) float."""
    V = np.asarray(vectors, dtype=complex)
    num = np.einsum("ki,kl,li->i", V.conj(), body.rotation, V).imag
    den = np.einsum("ki,kl,li->i", V.conj(), body.mass, V).real
    return -num / den


@dataclass(frozen=True)
class CampbellDiagram:
    """Whirl frequencies against speed (module docstring); k modes per speed, lowest first.

    Attributes
    ----------
    speeds_rad_s : (n,) float64
    spinning_Hz : (n, k) float64
        Frequencies seen from the spinning body.
    fixed_Hz : (n, k) float64
        Frequencies seen from the fixed frame (≥ 0).
    whirl : (n, k) int
        +1 forward, −1 backward, 0 standing (n = 0, or a mixed mode), in the fixed frame.
    order : (n, k) float64
        Angular order n (nodal diameters, signed), as computed; see ``ORDER_TOL``.
    damping_ratio : (n, k) float64
    """

    speeds_rad_s: np.ndarray
    spinning_Hz: np.ndarray
    fixed_Hz: np.ndarray
    whirl: np.ndarray
    order: np.ndarray
    damping_ratio: np.ndarray

    @property
    def speeds_rpm(self) -> np.ndarray:
        return self.speeds_rad_s * 30.0 / np.pi

    def critical_speeds_rad_s(self, whirl: int = 1, order: float = 1.0) -> np.ndarray:
        """Speeds where a mode of the given whirl crosses the line f = order·Ω/2π, ascending.

        The k-th lowest frequency of that whirl is continuous in speed even where modes cross (the
        columns of the diagram are not: they are sorted at each speed); its crossings with the line
        are found between neighbouring speeds and placed by linear interpolation.
        """
        line = order * self.speeds_rad_s / (2.0 * np.pi)
        levels = [np.sort(f[(w == whirl) & np.isfinite(f) & (f > 0.0)]) for f, w in zip(self.fixed_Hz, self.whirl)]
        out = []
        for i in range(len(levels) - 1):
            for k in range(min(len(levels[i]), len(levels[i + 1]))):
                a, b = levels[i][k] - line[i], levels[i + 1][k] - line[i + 1]
                if a * b <= 0.0 and a != b:
                    t = a / (a - b)
                    out.append(self.speeds_rad_s[i] + t * (self.speeds_rad_s[i + 1] - self.speeds_rad_s[i]))
        return np.sort(np.asarray(out))


def campbell(body, speeds_rad_s, n_modes: int | None = None,
             stationary_damping_per_s: float = 0.0) -> CampbellDiagram:
    """Campbell diagram of ``body`` at ``speeds_rad_s``; the lowest ``n_modes`` modes in the
    fixed frame (default: all) at each speed. ``body``: a :class:`SpinningBody`, or a function of
    the speed (rad/s) returning one (bearings whose stiffness changes with speed,
    :func:`.seats.on_bearings`)."""
    body_at = body if callable(body) else (lambda _speed: body)
    speeds = np.asarray(speeds_rad_s, dtype=float).ravel()
    if np.any(~np.isfinite(speeds)):
        raise ValueError("speeds_rad_s must be finite")
    rows = []
    for W in speeds:
        body = body_at(float(W))
        k = body.n_modes if n_modes is None else int(n_modes)
        if not 1 <= k <= body.n_modes:
            raise ValueError(f"n_modes must lie in 1…{body.n_modes}, got {n_modes}")
        lam, vec = _definite_orders(body, *spinning_modes(body, W, stationary_damping_per_s))
        w_r = lam.imag
        order = angular_order(body, vec)
        n = np.round(order)
        mixed = np.abs(order - n) > ORDER_TOL
        shifted = w_r - n * W
        fixed = np.where(mixed, np.nan, np.abs(shifted))
        with np.errstate(divide="ignore", invalid="ignore"):
            whirl = np.where(mixed | (n == 0), 0, np.sign(-shifted / n)).astype(int)
        zeta = -lam.real / np.abs(lam)
        pick = np.argsort(np.where(mixed, w_r, fixed), kind="stable")[:k]
        rows.append((w_r[pick], fixed[pick], whirl[pick], order[pick], zeta[pick]))
    cols = [np.array([r[i] for r in rows]) for i in range(5)]
    two_pi = 2.0 * np.pi
    return CampbellDiagram(speeds, cols[0] / two_pi, cols[1] / two_pi, cols[2].astype(int), cols[3], cols[4])
