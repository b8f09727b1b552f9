"""Generalized mass matrix and quadratic-velocity vector of a modal body (floating frame of reference).

The body's velocities are u = (v, ω, η̇): v = Rᵀ ṙ and ω in the body frame, η̇ the modal rates.
From the inertia invariants I1…I9 of :mod:`cms_reduction.invariants` (definitions, signs and the
equations of motion are in its module docstring; R. Schwertassek & O. Wallrapp, *Dynamik flexibler
Mehrkörpersysteme*, Vieweg 1999; A. A. Shabana, *Dynamics of Multibody Systems*, 3rd ed., 2005,
ch. 5), with S = I2 + I3 η, J(η) = I7 + Σ_k (I8_k + I8_kᵀ) η_k + Σ_kl I9_kl η_k η_l,
I4(η) = I4 + Σ_k η_k I5[:, k, :] and G_k = I8_k + Σ_l I9_lk η_l:

    M(η) = [ m 1    S̃ᵀ       I3    ]        M(η) u̇ + h = (F, N, Q − Kη − Dη̇)
           [ S̃      J(η)     I4(η) ]
           [ I3ᵀ    I4(η)ᵀ   I6    ]

    h_v   = m ω̃ v + ω̃ ω̃ S + 2 ω̃ I3 η̇
    h_ω   = S̃ ω̃ v + ω̃ J ω + 2 Σ_k η̇_k G_k ω
    h_η,k = I3[:, k]·(ω̃ v) − ωᵀ G_k ω + 2 Σ_l η̇_l ωᵀ I5[:, l, k]

Rows and columns are ordered (v, ω, η): 0:3, 3:6, 6:6+m. The kinetic energy is ½ uᵀ M(η) u, and
for the free body uᵀ h = ½ uᵀ Ṁ u (the power of h balances the change of the mass matrix).
The kernels split the work by what it depends on: :func:`eta_terms` forms the η-dependent parts
(S, J(η), the G_k, I4(η); O(m²) each, nine of them), :func:`mass_matrix` and :func:`velocity_terms`
assemble M and h from them (O(m²) copies and O(m²) multiply-adds with the velocities). The stepping
keeps the η-terms while η does not change. The kernels allocate nothing and write into ``out``;
:func:`modal_mass_matrix` and :func:`modal_velocity_terms` take the invariants and η for callers
outside the stepping (they allocate the η-terms' scratch).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, _nrt=False)
def _times3(A, x):
    """A x for A (3, m) and x (m,), as a tuple."""
    y0 = y1 = y2 = 0.0
    for k in range(x.shape[0]):
        y0 += A[0, k] * x[k]
        y1 += A[1, k] * x[k]
        y2 += A[2, k] * x[k]
    return y0, y1, y2


@njit(cache=True, _nrt=False)
def _first_moment(I2, I3, eta):
    """S = I2 + I3 η, the first moment of the deformed body, as a tuple."""
    y0, y1, y2 = _times3(I3, eta)
    return I2[0] + y0, I2[1] + y1, I2[2] + y2


@njit(cache=True, _nrt=False)
def eta_terms(I2, I3, I4, I5, I7, I8, I9, eta, S, J, G, I4e):
    """The parts of M(η) and h that depend on η alone, into S (3,), J (3, 3), G (3, 3, ≥ m), I4e (3, ≥ m).

    S = I2 + I3 η; G_k = I8_k + Σ_l I9[:, :, l, k] η_l (G[:, :, k]); J(η) from G, since
    Σ_k η_k G_k = Σ_k η_k I8_k + Σ_kl I9_kl η_k η_l: J_ij = I7_ij + Σ_k (I8_jik + G_ij,k) η_k;
    I4(η) = I4 + Σ_l η_l I5[:, l, :] (about 13 m² multiply-adds). With them :func:`mass_matrix` only
    copies and :func:`velocity_terms` takes 3 m² multiply-adds (the η̇–I5 term) instead of about 21 m²;
    the stepping keeps them while η stays (:mod:`.modal_step`). The sums run over the modes innermost (contiguous in the invariants).
    """
    m = eta.shape[0]
    S[0], S[1], S[2] = _first_moment(I2, I3, eta)
    for i in range(3):
        for j in range(3):
            for k in range(m):
                G[i, j, k] = I8[i, j, k]
            for l in range(m):
                el = eta[l]
                for k in range(m):
                    G[i, j, k] += I9[i, j, l, k] * el
    for i in range(3):
        for j in range(i, 3):
            s = I7[i, j]
            for k in range(m):
                s += (I8[j, i, k] + G[i, j, k]) * eta[k]
            J[i, j] = s
            J[j, i] = s
    for a in range(3):
        for k in range(m):
            I4e[a, k] = I4[a, k]
        for l in range(m):
            el = eta[l]
            for k in range(m):
                I4e[a, k] += I5[a, l, k] * el


@njit(cache=True, _nrt=False)
def mass_matrix(mass, I3, I6, S, J, I4e, m, out):
    """Generalized mass matrix M(η) of a modal body with m modes into ``out`` (6 + m, 6 + m) from the
    η-terms of :func:`eta_terms` (module docstring for the blocks); exactly symmetric."""
    s0, s1, s2 = S[0], S[1], S[2]
    for i in range(6 + m):
        for j in range(6 + m):
            out[i, j] = 0.0
    for i in range(3):
        out[i, i] = mass
    # S̃ at rows ω, columns v; S̃ᵀ = −S̃ at rows v, columns ω
    out[3, 1] = -s2
    out[3, 2] = s1
    out[4, 0] = s2
    out[4, 2] = -s0
    out[5, 0] = -s1
    out[5, 1] = s0
    for i in range(3):
        for j in range(3):
            out[j, 3 + i] = out[3 + i, j]
            out[3 + i, 3 + j] = J[i, j]
    for a in range(3):
        for k in range(m):
            out[a, 6 + k] = I3[a, k]
            out[6 + k, a] = I3[a, k]
            out[3 + a, 6 + k] = I4e[a, k]
            out[6 + k, 3 + a] = I4e[a, k]
    for k in range(m):
        for l in range(m):
            out[6 + k, 6 + l] = I6[k, l]
    return out


@njit(cache=True, _nrt=False)
def velocity_terms(mass, I3, I5, S, J, G, m, v, omega, eta_dot, out):
    """Quadratic-velocity vector h = (h_v, h_ω, h_η) of a modal body with m modes into ``out`` (6 + m,)
    from the η-terms of :func:`eta_terms` (module docstring); v = Rᵀṙ m/s and ω rad/s in body axes,
    η̇ √kg/s. Units of h: N, N·m, √kg·m/s²."""
    w0, w1, w2 = omega[0], omega[1], omega[2]
    s0, s1, s2 = S[0], S[1], S[2]
    # ω × v, ω × S, I3 η̇
    a0 = w1 * v[2] - w2 * v[1]
    a1 = w2 * v[0] - w0 * v[2]
    a2 = w0 * v[1] - w1 * v[0]
    b0 = w1 * s2 - w2 * s1
    b1 = w2 * s0 - w0 * s2
    b2 = w0 * s1 - w1 * s0
    c0, c1, c2 = _times3(I3, eta_dot[:m])
    # h_v = m ω×v + ω×(ω×S) + 2 ω×(I3 η̇)
    out[0] = mass * a0 + (w1 * b2 - w2 * b1) + 2.0 * (w1 * c2 - w2 * c1)
    out[1] = mass * a1 + (w2 * b0 - w0 * b2) + 2.0 * (w2 * c0 - w0 * c2)
    out[2] = mass * a2 + (w0 * b1 - w1 * b0) + 2.0 * (w0 * c1 - w1 * c0)
    j0 = J[0, 0] * w0 + J[0, 1] * w1 + J[0, 2] * w2
    j1 = J[1, 0] * w0 + J[1, 1] * w1 + J[1, 2] * w2
    j2 = J[2, 0] * w0 + J[2, 1] * w1 + J[2, 2] * w2
    # h_ω = S×(ω×v) + ω×(Jω) + 2 Σ_k η̇_k G_k ω
    h3 = (s1 * a2 - s2 * a1) + (w1 * j2 - w2 * j1)
    h4 = (s2 * a0 - s0 * a2) + (w2 * j0 - w0 * j2)
    h5 = (s0 * a1 - s1 * a0) + (w0 * j1 - w1 * j0)
    # h_η,k = I3[:, k]·(ω×v) − ωᵀ G_k ω + 2 Σ_l η̇_l ω·I5[:, l, k]; the last sum first, over k innermost
    for k in range(m):
        out[6 + k] = I3[0, k] * a0 + I3[1, k] * a1 + I3[2, k] * a2
    for a in range(3):
        wa = 2.0 * omega[a]
        for l in range(m):
            c = wa * eta_dot[l]
            for k in range(m):
                out[6 + k] += c * I5[a, l, k]
    for k in range(m):
        g0 = G[0, 0, k] * w0 + G[0, 1, k] * w1 + G[0, 2, k] * w2
        g1 = G[1, 0, k] * w0 + G[1, 1, k] * w1 + G[1, 2, k] * w2
        g2 = G[2, 0, k] * w0 + G[2, 1, k] * w1 + G[2, 2, k] * w2
        ed = 2.0 * eta_dot[k]
        h3 += ed * g0
        h4 += ed * g1
        h5 += ed * g2
        out[6 + k] -= w0 * g0 + w1 * g1 + w2 * g2
    out[3], out[4], out[5] = h3, h4, h5
    return out


def _scratch(m):
    return np.zeros(3), np.zeros((3, 3)), np.zeros((3, 3, m)), np.zeros((3, m))


def modal_mass_matrix(mass, I2, I3, I4, I5, I6, I7, I8, I9, eta, out):
    """Generalized mass matrix M(η) of a modal body into ``out`` (for callers outside the stepping,
    which keeps the η-terms between calls: :func:`eta_terms`, :func:`mass_matrix`).

    Parameters
    ----------
    mass : float, kg
        I1.
    I2 : (3,) float64, kg·m
    I3 : (3, m) float64, √kg·m
    I4 : (3, m) float64, √kg·m²
    I5 : (3, m, m) float64, m²
    I6 : (m, m) float64
    I7 : (3, 3) float64, kg·m²
    I8 : (3, 3, m) float64, √kg·m²
    I9 : (3, 3, m, m) float64, m²
        Invariants as in :class:`cms_reduction.invariants.Invariants` (zero-padded beyond m allowed).
    eta : (m,) float64, √kg
        Modal coordinates.
    out : (6 + m, 6 + m) float64
        Overwritten with M(η), symmetric; units kg, kg·m, kg·m², √kg·m, √kg·m², 1 by block.

    Notes
    -----
    J(η) is evaluated on its upper triangle and mirrored, which relies on the symmetries of the
    invariants (I7 symmetric, I9_ijkl = I9_jilk); I6 is copied as given.
    """
    m = eta.shape[0]
    S, J, G, I4e = _scratch(I8.shape[2])
    eta_terms(I2, I3, I4, I5, I7, I8, I9, eta, S, J, G, I4e)
    return mass_matrix(mass, I3, I6, S, J, I4e, m, out)


def modal_velocity_terms(mass, I2, I3, I4, I5, I6, I7, I8, I9, eta, v, omega, eta_dot, out):
    """Quadratic-velocity vector h = (h_v, h_ω, h_η) of a modal body into ``out`` (6 + m,) (for callers
    outside the stepping; :func:`velocity_terms`). Arguments as :func:`modal_mass_matrix` (I4 and I6 do
    not enter h), v = Rᵀṙ m/s, ω rad/s (body axes), η̇ √kg/s; h in N, N·m, √kg·m/s²."""
    S, J, G, I4e = _scratch(I8.shape[2])
    eta_terms(I2, I3, I4, I5, I7, I8, I9, eta, S, J, G, I4e)
    return velocity_terms(mass, I3, I5, S, J, G, eta.shape[0], v, omega, eta_dot, out)
