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
Both kernels take the same invariant arguments, so a caller passes one tuple to either; the
unused ones are ignored. Nothing is allocated: loops over scalars, results written into ``out``.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, _nrt=False)
def _inertia_entry(I7, I8, I9, eta, i, j):
    """J(η)[i, j] = I7_ij + Σ_k (I8_ijk + I8_jik) η_k + Σ_kl I9_ijkl η_k η_l."""
    m = eta.shape[0]
    s = I7[i, j]
    for k in range(m):
        ek = eta[k]
        s += (I8[i, j, k] + I8[j, i, k]) * ek
        for l in range(m):
            s += I9[i, j, k, l] * ek * eta[l]
    return s


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
def modal_mass_matrix(mass, I2, I3, I4, I5, I6, I7, I8, I9, eta, out):
    """Generalized mass matrix M(η) of a modal body into ``out`` (module docstring for the blocks).

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
        Invariants as in :class:`cms_reduction.invariants.Invariants`.
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
    s0, s1, s2 = _first_moment(I2, I3, eta)
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
    for i in range(3):
        for j in range(i, 3):
            jij = _inertia_entry(I7, I8, I9, eta, i, j)
            out[3 + i, 3 + j] = jij
            out[3 + j, 3 + i] = jij
    for a in range(3):
        for k in range(m):
            c = I4[a, k]
            for l in range(m):
                c += eta[l] * I5[a, l, k]
            out[a, 6 + k] = I3[a, k]
            out[6 + k, a] = I3[a, k]
            out[3 + a, 6 + k] = c
            out[6 + k, 3 + a] = c
    for k in range(m):
        for l in range(m):
            out[6 + k, 6 + l] = I6[k, l]
    return out


@njit(cache=True, _nrt=False)
def modal_velocity_terms(mass, I2, I3, I4, I5, I6, I7, I8, I9, eta, v, omega, eta_dot, out):
    """Quadratic-velocity vector h = (h_v, h_ω, h_η) of a modal body into ``out`` (module docstring).

    Parameters
    ----------
    mass, I2 … I9 : see :func:`modal_mass_matrix` (I4 and I6 do not enter h).
    eta : (m,) float64, √kg
        Modal coordinates.
    v : (3,) float64, m/s
        Velocity of the frame origin in body axes, Rᵀ ṙ.
    omega : (3,) float64, rad/s
        Angular velocity in body axes.
    eta_dot : (m,) float64, √kg/s
        Modal rates.
    out : (6 + m,) float64
        Overwritten with h: N (h_v), N·m (h_ω), √kg·m/s² (h_η).
    """
    m = eta.shape[0]
    w0, w1, w2 = omega[0], omega[1], omega[2]
    s0, s1, s2 = _first_moment(I2, I3, eta)
    # ω × v, ω × S, I3 η̇
    a0 = w1 * v[2] - w2 * v[1]
    a1 = w2 * v[0] - w0 * v[2]
    a2 = w0 * v[1] - w1 * v[0]
    b0 = w1 * s2 - w2 * s1
    b1 = w2 * s0 - w0 * s2
    b2 = w0 * s1 - w1 * s0
    c0, c1, c2 = _times3(I3, eta_dot)
    # h_v = m ω×v + ω×(ω×S) + 2 ω×(I3 η̇)
    out[0] = mass * a0 + (w1 * b2 - w2 * b1) + 2.0 * (w1 * c2 - w2 * c1)
    out[1] = mass * a1 + (w2 * b0 - w0 * b2) + 2.0 * (w2 * c0 - w0 * c2)
    out[2] = mass * a2 + (w0 * b1 - w1 * b0) + 2.0 * (w0 * c1 - w1 * c0)
    # J ω
    j0 = j1 = j2 = 0.0
    for j in range(3):
        wj = omega[j]
        j0 += _inertia_entry(I7, I8, I9, eta, 0, j) * wj
        j1 += _inertia_entry(I7, I8, I9, eta, 1, j) * wj
        j2 += _inertia_entry(I7, I8, I9, eta, 2, j) * wj
    # h_ω = S×(ω×v) + ω×(Jω) + 2 Σ_k η̇_k G_k ω
    out[3] = (s1 * a2 - s2 * a1) + (w1 * j2 - w2 * j1)
    out[4] = (s2 * a0 - s0 * a2) + (w2 * j0 - w0 * j2)
    out[5] = (s0 * a1 - s1 * a0) + (w0 * j1 - w1 * j0)
    for k in range(m):
        # G_k ω with G_k = I8_k + Σ_l I9_lk η_l
        g0 = g1 = g2 = 0.0
        for j in range(3):
            wj = omega[j]
            e0 = I8[0, j, k]
            e1 = I8[1, j, k]
            e2 = I8[2, j, k]
            for l in range(m):
                el = eta[l]
                e0 += I9[0, j, l, k] * el
                e1 += I9[1, j, l, k] * el
                e2 += I9[2, j, l, k] * el
            g0 += e0 * wj
            g1 += e1 * wj
            g2 += e2 * wj
        ed = 2.0 * eta_dot[k]
        out[3] += ed * g0
        out[4] += ed * g1
        out[5] += ed * g2
        # h_η,k = I3[:, k]·(ω×v) − ωᵀ G_k ω + 2 Σ_l η̇_l ω·I5[:, l, k]
        hk = I3[0, k] * a0 + I3[1, k] * a1 + I3[2, k] * a2 - (w0 * g0 + w1 * g1 + w2 * g2)
        for l in range(m):
            hk += 2.0 * eta_dot[l] * (w0 * I5[0, l, k] + w1 * I5[1, l, k] + w2 * I5[2, l, k])
        out[6 + k] = hk
    return out
