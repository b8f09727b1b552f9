"""numpy twin of mbd_core.kernels.modal: the FFRF mass matrix and quadratic-velocity vector of a modal
body, written with skew matrices and einsum straight from the equations of motion in the
cms_reduction.invariants module docstring (I8, I9 with the transposed skew factor)."""

import numpy as np


def skew(a):
    """ã with ã b = a × b."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def inertia(I7, I8, I9, eta):
    """J(η) = I7 + Σ_k (I8_k + I8_kᵀ) η_k + Σ_kl I9_kl η_k η_l."""
    first = np.einsum("ijk,k->ij", I8, eta)
    return I7 + first + first.T + np.einsum("ijkl,k,l->ij", I9, eta, eta)


def mass_matrix(mass, I2, I3, I4, I5, I6, I7, I8, I9, eta):
    """M(η) = [[m 1, S̃ᵀ, I3], [S̃, J, I4(η)], [I3ᵀ, I4(η)ᵀ, I6]], S = I2 + I3 η."""
    St = skew(I2 + I3 @ eta)
    I4e = I4 + np.einsum("k,akl->al", eta, I5)
    return np.block([
        [mass * np.eye(3), St.T, I3],
        [St, inertia(I7, I8, I9, eta), I4e],
        [I3.T, I4e.T, I6],
    ])


def velocity_terms(mass, I2, I3, I4, I5, I6, I7, I8, I9, eta, v, omega, eta_dot):
    """h = (h_v, h_ω, h_η) of the docstring."""
    S = I2 + I3 @ eta
    St, W = skew(S), skew(omega)
    J = inertia(I7, I8, I9, eta)
    G = I8 + np.einsum("ijlk,l->ijk", I9, eta)                  # G[:, :, k] = G_k
    h_v = mass * W @ v + W @ W @ S + 2.0 * W @ I3 @ eta_dot
    h_w = St @ W @ v + W @ J @ omega + 2.0 * np.einsum("k,ijk,j->i", eta_dot, G, omega)
    h_e = (I3.T @ (W @ v) - np.einsum("i,ijk,j->k", omega, G, omega)
           + 2.0 * np.einsum("l,a,alk->k", eta_dot, omega, I5))
    return np.concatenate([h_v, h_w, h_e])
