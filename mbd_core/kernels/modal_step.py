"""Time stepping of modal (flexible) bodies in a floating frame of reference.

A modal body is a body of the model (frame origin r, orientation R, world velocity ṙ, body-frame ω)
plus modal coordinates η (√kg) and rates η̇. With u = (v = Rᵀṙ, ω, η̇) its equations of motion are

    M(η) u̇ + h(η, u) = (F, N, Q − Kη − Dη̇)

(:mod:`.modal`, :mod:`cms_reduction.invariants`), F and N the resultant force and moment about the
frame origin in body axes, Q the modal forces of the contacts on the body, K = diag(ω_k²),
D = diag(2ζ_k ω_k). Gravity g enters as F += m Rᵀg, N += S × Rᵀg, Q += I3ᵀ Rᵀg (the weight of every
material point, with S = I2 + I3 η its first moment). Two schemes, both in the kick–drift–kick form
of :mod:`.explicit`:

**Free frame** (all six frame velocities integrated): momentum form. The frame origin is the centre
of mass and the modes do not move it (I2 = 0, I3 = 0; the builder ensures both), so the translation
decouples, p = m ṙ. The rotational and modal momenta (π, p_η) = M_r(η)(ω, η̇), M_r the (ω, η) block
of M, are kicked: π += (h/2) Rᵀ N_W, p_η += (h/2)(Q − Kη − Dη̇ + ∂T/∂η) with
∂T/∂η_k = ωᵀG_kω + Σ_l ω·I5[:, k, l] η̇_l (Boltzmann–Hamel / Lagrange: the η-derivative of the kinetic
energy at fixed velocities). The drift turns the frame by the body rotation vector θ = h ω_mid and
turns π back by the same rotation, so that the world angular momentum R π and the linear momentum
are conserved to round-off by construction for any θ; ω_mid and η̇_mid are taken at the explicit
midpoint (π turned by θ/2, η advanced by h/2), which makes the drift second order. Velocities are
recovered as u = M_r(η)⁻¹ (π, p_η).

**Constrained frame** (fixed, or driven: some frame velocities prescribed): acceleration form. The
integrated components f of u get u_f += (h/2) M_ff⁻¹ (rhs − h')_f (prescribed accelerations are
zero: prescribed velocities are constant); the frame drifts by its velocity, η += h η̇. The frame's
velocity is the world ṙ, kicked in its body components at the frame of the kick: their rate there is
Rᵀr̈ = v̇ + ω × v, so h' is h without the terms in ω × v (:func:`constrained_rhs`; with them, a rotor
driven at Ω whose centre of mass is off the frame origin whirls unstably above about 20 000 rev/min). With
``implicit`` set (Fixed and Driven frames) the kicks solve with the augmented matrix M + (h/2) C̃ + (h/2)² K̃
instead of M, K̃ = diag(0, K), C̃ = diag(0, C) on the integrated components: every force, the elastic
−Kη − Cη̇ included, stays explicit and is evaluated at the state of the kick. For an undamped linear
oscillator this central-difference step has the trapezoidal rule's characteristic polynomial
(λ + 1/λ = 2(1 − a²)/(1 + a²), a = hω/2; both are one line of algebra), so it is stable at any hω, and
with the frame's free components too: the largest generalized eigenvalue of (K̃, M + (h/2)² K̃) is below
4/h² whatever M's coupling of frame and modes, and the explicit damping's kick factor
1 − (h/2)(M + (h/2)C̃)⁻¹C̃ stays in (0, 1]. The frame's own rows are not augmented, so the elastic
forces, internal to the body, leave its momentum alone. A state in equilibrium is a fixed point
(static response exact), and the contacts see the body's velocities at the half step. Modes the step
resolves (hω ≤ 2) keep their own damping. Modes it does not resolve are damped critically (c = 2ω):
undamped, the contact kicks would make them ring at the step's Nyquist frequency; critically damped,
a step multiplies that ringing by 0.62 at hω = 3, 0.76 at 10 and about 1 − 4/(hω) beyond 30 (the
critically damped trapezoidal rule: (hω − 2)/(hω + 2); T. J. R. Hughes, *The Finite Element Method*,
2000, §9.3). They respond quasi-statically, all they can do at that step.

The second kick of both forms depends on the new velocities through the quadratic-velocity terms and
the modal damping; one fixed-point correction (predict, re-evaluate those terms, kick again) keeps
the scheme second order. The contact forces stay at the half-step velocity as for rigid bodies.

**What is kept between kicks.** η changes only in the drift, so the second kick of a step and the
first of the next see the same η. Per body the work arrays keep the η-terms of :func:`.modal.eta_terms`
(S, J(η), G_k, I4(η): the nine O(m²) sums), M(η) and the factor of its integrated block, with the η
they were formed for; a kick forms them again only when η differs from it in any bit, so a run
resumed from its state continues bit for bit. With unit modal mass (I6 = 1) the block
[[A, B], [Bᵀ, 1]] of the frame's integrated components and the modes is solved through the Schur
complement A − B Bᵀ of the frame (:func:`_schur_factor`): O(n_f² m) instead of a Cholesky factor of
order n_f + m.
"""

from __future__ import annotations

import math

from numba import njit

from .forces import rotate, rotate_back
from .modal import _first_moment, eta_terms, mass_matrix, velocity_terms
from .rigid import turn_quaternion


@njit(cache=True, inline="always", _nrt=False)
def _turn_back(px, py, pz, ox, oy, oz):
    """Exp(θ)ᵀ p for the rotation vector θ = (ox, oy, oz): a fixed world vector seen from axes turned by θ."""
    phi = math.sqrt(ox * ox + oy * oy + oz * oz)
    if phi == 0.0:
        return px, py, pz
    ex, ey, ez = ox / phi, oy / phi, oz / phi
    c, s = math.cos(phi), -math.sin(phi)
    d = (1.0 - c) * (ex * px + ey * py + ez * pz)
    return (c * px + s * (ey * pz - ez * py) + d * ex, c * py + s * (ez * px - ex * pz) + d * ey,
            c * pz + s * (ex * py - ey * px) + d * ez)


@njit(cache=True, _nrt=False)
def cholesky_in_place(A, n):
    """Lower Cholesky factor of the leading n × n block of the symmetric positive definite A, in place.

    Returns False when a pivot is not positive (A not positive definite).
    """
    for j in range(n):
        s = A[j, j]
        for k in range(j):
            s -= A[j, k] * A[j, k]
        if not s > 0.0:
            return False
        d = math.sqrt(s)
        A[j, j] = d
        for i in range(j + 1, n):
            t = A[i, j]
            for k in range(j):
                t -= A[i, k] * A[j, k]
            A[i, j] = t / d
    return True


@njit(cache=True, _nrt=False)
def cholesky_solve(L, n, b):
    """Solve (L Lᵀ) x = b in place on b[:n] with the factor from :func:`cholesky_in_place`."""
    for i in range(n):
        s = b[i]
        for k in range(i):
            s -= L[i, k] * b[k]
        b[i] = s / L[i, i]
    for i in range(n - 1, -1, -1):
        s = b[i]
        for k in range(i + 1, n):
            s -= L[k, i] * b[k]
        b[i] = s / L[i, i]


@njit(cache=True, _nrt=False)
def inertia_force(I5, G, omega, eta_dot, out):
    """∂T/∂η at fixed velocities into out (m,): ωᵀG_kω + Σ_l ω·I5[:, k, l] η̇_l, √kg·m/s² (module doc),
    with G_k = G[:, :, k] of :func:`.modal.eta_terms`."""
    m = eta_dot.shape[0]
    for k in range(m):
        s = 0.0
        for i in range(3):
            s += omega[i] * (G[i, 0, k] * omega[0] + G[i, 1, k] * omega[1] + G[i, 2, k] * omega[2])
        for l in range(m):
            s += (omega[0] * I5[0, k, l] + omega[1] * I5[1, k, l] + omega[2] * I5[2, k, l]) * eta_dot[l]
        out[k] = s


@njit(cache=True, _nrt=False)
def _reduced_block(Mfull, n, sel, A):
    """A[:k, :k] = Mfull[sel, sel] for the k = n selected rows (sel (≥ n,) int indices)."""
    for i in range(n):
        for j in range(n):
            A[i, j] = Mfull[sel[i], sel[j]]


@njit(cache=True, _nrt=False)
def constrained_rhs(mass, I3, I5, S, J, G, eta, eta_dot, v_b, omega, f_b, n_b, g_b, modal_f, omega2, damp, elastic,
                    moving, hvec, rhs, frozen=True):
    """Right-hand side (F, N, Q − Kη − Dη̇ + gravity) − h of a modal body into rhs (6 + m,).

    ``frozen`` (the explicit kicks): for the accelerations (a = Rᵀr̈, ω̇, η̈), h without its ω × v terms
    (m ω × v, S × (ω × v), I3ᵀ(ω × v)), which belong to the rate of the body-frame v = Rᵀṙ, not to that
    of the world velocity's body components at a frozen frame, which the kicks integrate (the drift
    turns the frame and keeps ṙ). Not ``frozen`` (the implicit integrator, whose unknowns are
    (v̇, ω̇, η̈) with r̈ = R(v̇ + ω × v)): the whole h.

    ``elastic`` False leaves −Kη − Dη̇ out (integrated in the drift); ``moving`` False (a frame at
    rest and held there) skips the quadratic-velocity vector h, which is then zero. f_b, n_b body-frame force and
    moment about the frame origin (N, N·m); g_b gravity in body axes (m/s²); modal_f (m,) contact
    modal forces. S (3,), J, G: the η-terms of :func:`.modal.eta_terms` at η (J and G are not read
    when ``moving`` is False).
    """
    m = eta.shape[0]
    sx, sy, sz = S[0], S[1], S[2]
    if not moving:  # a frame at rest: no quadratic-velocity terms
        for k in range(6 + m):
            hvec[k] = 0.0
    else:
        velocity_terms(mass, I3, I5, S, J, G, m, v_b, omega, eta_dot, hvec)
    if moving and frozen:
        # the frame velocity is stored in the world and kicked in the frame frozen over the kick: the
        # rate of its body components there is Rᵀr̈ = v̇ + ω × v, so the ω × v terms of h drop out
        a0 = omega[1] * v_b[2] - omega[2] * v_b[1]
        a1 = omega[2] * v_b[0] - omega[0] * v_b[2]
        a2 = omega[0] * v_b[1] - omega[1] * v_b[0]
        hvec[0] -= mass * a0
        hvec[1] -= mass * a1
        hvec[2] -= mass * a2
        hvec[3] -= sy * a2 - sz * a1
        hvec[4] -= sz * a0 - sx * a2
        hvec[5] -= sx * a1 - sy * a0
        for k in range(m):
            hvec[6 + k] -= I3[0, k] * a0 + I3[1, k] * a1 + I3[2, k] * a2
    rhs[0] = f_b[0] + mass * g_b[0] - hvec[0]
    rhs[1] = f_b[1] + mass * g_b[1] - hvec[1]
    rhs[2] = f_b[2] + mass * g_b[2] - hvec[2]
    rhs[3] = n_b[0] + sy * g_b[2] - sz * g_b[1] - hvec[3]
    rhs[4] = n_b[1] + sz * g_b[0] - sx * g_b[2] - hvec[4]
    rhs[5] = n_b[2] + sx * g_b[1] - sy * g_b[0] - hvec[5]
    for k in range(m):
        r = modal_f[k] + I3[0, k] * g_b[0] + I3[1, k] * g_b[1] + I3[2, k] * g_b[2] - hvec[6 + k]
        if elastic:
            r -= omega2[k] * eta[k] + damp[k] * eta_dot[k]
        rhs[6 + k] = r


@njit(cache=True, _nrt=False)
def _keep_terms(I2, I3, I4, I5, I7, I8, I9, e, at, level, j, S, J, G, I4e):
    """The η-terms (:func:`.modal.eta_terms`) of modal body j at η = e into S, J, G, I4e, formed only when e
    differs from ``at``, the η they were formed for (then ``at`` = e, ``level[j]`` = 2; module docstring)."""
    mj = e.shape[0]
    if level[j] >= 2:
        k = 0
        while k < mj and at[k] == e[k]:
            k += 1
        if k == mj:
            return
    eta_terms(I2, I3, I4, I5, I7, I8, I9, e, S, J, G, I4e)
    for k in range(mj):
        at[k] = e[k]
    level[j] = 2


@njit(cache=True, _nrt=False)
def _schur_factor(M, sel, nf, mj, dinv, L):
    """Unit modal mass (I6 = 1): the block of M on the nf frame components ``sel[:nf]`` and the mj modes is
    [[A, B], [Bᵀ, 1]]; the Cholesky factor of the frame's Schur complement A − B Bᵀ into L[:nf, :nf]
    (O(nf² m) instead of O((nf + m)³)). False if it is not positive definite (nor is the block, then).
    With ``dinv`` (mj,) the modal block is diagonal, diag(1/dinv), and the complement A − B diag(dinv) Bᵀ
    (the implicit modes' kick matrix M + (h/2)C + (h/2)²K, :func:`_implicit_modes`); an empty ``dinv``: 1."""
    scaled = dinv.shape[0] > 0
    for r in range(nf):
        for c in range(r + 1):
            s = M[sel[r], sel[c]]
            for k in range(mj):
                t = M[sel[r], 6 + k] * M[sel[c], 6 + k]
                s -= t * dinv[k] if scaled else t
            L[r, c] = s
            L[c, r] = s
    return cholesky_in_place(L, nf)


@njit(cache=True, _nrt=False)
def _schur_solve(M, L, sel, nf, mj, dinv, b):
    """Solve [[A, B], [Bᵀ, 1]] x = b in place on b[:nf + mj] with the factor of :func:`_schur_factor`:
    x_f = (A − B Bᵀ)⁻¹ (b_f − B b_η), x_η = b_η − Bᵀ x_f; with ``dinv`` the modal block diag(1/dinv):
    x_f = (A − B diag(dinv) Bᵀ)⁻¹ (b_f − B diag(dinv) b_η), x_η = diag(dinv)(b_η − Bᵀ x_f)."""
    scaled = dinv.shape[0] > 0
    for r in range(nf):
        s = b[r]
        for k in range(mj):
            t = M[sel[r], 6 + k] * b[nf + k]
            s -= t * dinv[k] if scaled else t
        b[r] = s
    cholesky_solve(L, nf, b)
    for r in range(nf):
        x = b[r]
        for k in range(mj):
            b[nf + k] -= M[sel[r], 6 + k] * x
    if scaled:
        for k in range(mj):
            b[nf + k] *= dinv[k]


@njit(cache=True, _nrt=False)
def _keep_mass(mass, I3, I6, m, level, j, S, J, I4e, M):
    """M(η) from the η-terms into M (``level[j]`` 3), only when not formed since the η-terms."""
    if level[j] < 3:
        mass_matrix(mass, I3, I6, S, J, I4e, m, M)
        level[j] = 3


@njit(cache=True, _nrt=False)
def _keep_factor(mass, I3, I6, m, unit, level, nfac, fac_h, j, S, J, I4e, M, L, n, sel, hh, dinv):
    """M(η) (:func:`_keep_mass`) and the factor of its block on ``sel[:n]`` (frame components first, then
    the m modes) into L (``level[j]`` 4, ``nfac[j]`` = n, ``fac_h[j]`` = hh): with unit modal mass that of
    the frame's Schur complement (:func:`_schur_factor`), else the block's Cholesky factor; only when not
    formed since the η-terms or for another hh. hh > 0: the implicit modes' matrix M + (h/2) C + (h/2)² K,
    C = diag(0, c), K = diag(0, ω²), given as ``dinv`` (m,) = 1/(1 + (h/2) c + (h/2)² ω²); hh = 0: M.
    False if the block is not positive definite."""
    _keep_mass(mass, I3, I6, m, level, j, S, J, I4e, M)
    if level[j] < 4 or nfac[j] != n or fac_h[j] != hh:
        nf = n - m
        if unit:
            ok = _schur_factor(M, sel, nf, m, dinv if hh > 0.0 else M[0, :0], L)
        else:
            _reduced_block(M, n, sel, L)
            if hh > 0.0:
                for k in range(m):
                    L[nf + k, nf + k] += 1.0 / dinv[k] - 1.0
            ok = cholesky_in_place(L, n)
        if not ok:
            return False
        level[j] = 4
        nfac[j] = n
        fac_h[j] = hh
    return True


@njit(cache=True, inline="always", _nrt=False)
def _terms(m, j, e, w):
    """The η-terms of modal body j at η = e in w.modal_S/J/G/I4e[j] (kept while η stays)."""
    _keep_terms(m.modal_I2[j], m.modal_I3[j], m.modal_I4[j], m.modal_I5[j], m.modal_I7[j], m.modal_I8[j],
                m.modal_I9[j], e, w.modal_eta_at[j], w.modal_level, j, w.modal_S[j], w.modal_J[j], w.modal_G[j],
                w.modal_I4e[j])


@njit(cache=True, inline="always", _nrt=False)
def _factor(m, j, e, w, n, sel, hh=0.0):
    """M(η) of modal body j at η = e in w.modal_M[j] and the factor of its block on the components ``sel[:n]``
    in w.modal_L[j] (:func:`_keep_factor`; kept while η and hh stay, a body always integrates the same
    components); hh > 0: of the implicit modes' M + (h/2) C + (h/2)² K (w.modal_dinv filled). False if not
    positive definite."""
    _terms(m, j, e, w)
    o0, o1 = m.modal_off[j], m.modal_off[j + 1]
    return _keep_factor(m.modal_mass[j], m.modal_I3[j], m.modal_I6[j], e.shape[0], m.modal_unit[j] == 1,
                        w.modal_level, w.modal_nfac, w.modal_fac_h, j, w.modal_S[j], w.modal_J[j], w.modal_I4e[j],
                        w.modal_M[j], w.modal_L[j], n, sel, hh, w.modal_dinv[o0:o1])


@njit(cache=True, inline="always", _nrt=False)
def _solve(m, w, j, mj, n, sel, b, hh=0.0):
    """Solve M(η)_ff x = b (hh > 0: the implicit modes' (M + (h/2) C + (h/2)² K)_ff) in place on b[:n] with
    the factor :func:`_factor` left for modal body j."""
    if m.modal_unit[j] == 1:
        o0 = m.modal_off[j]
        _schur_solve(w.modal_M[j], w.modal_L[j], sel, n - mj, mj,
                     w.modal_dinv[o0:o0 + mj] if hh > 0.0 else w.modal_M[j][0, :0], b)
    else:
        cholesky_solve(w.modal_L[j], n, b)


@njit(cache=True, inline="always", _nrt=False)
def _mass(m, j, e, w):
    """M(η) of modal body j at η = e in w.modal_M[j] (kept while η stays)."""
    _terms(m, j, e, w)
    _keep_mass(m.modal_mass[j], m.modal_I3[j], m.modal_I6[j], e.shape[0], w.modal_level, j, w.modal_S[j],
               w.modal_J[j], w.modal_I4e[j], w.modal_M[j])


@njit(cache=True, inline="always", _nrt=False)
def _frame_free(m, j):
    """True when all six frame velocities of modal body j are integrated (momentum form)."""
    f = m.modal_frame_free[j]
    return f[0] + f[1] + f[2] + f[3] + f[4] + f[5] == 6


@njit(cache=True, inline="always", _nrt=False)
def _select(m, j, mj, sel):
    """Indices of the integrated components of u = (v, ω, η̇) of modal body j into sel; returns their count."""
    n = 0
    for c in range(6):
        if m.modal_frame_free[j, c]:
            sel[n] = c
            n += 1
    for k in range(mj):
        sel[n] = 6 + k
        n += 1
    return n


@njit(cache=True, inline="always", _nrt=False)
def _body_vectors(m, q, v, w, i):
    """Body-frame velocity, force, moment and gravity of body i into w.modal_vec rows 0…3."""
    vec = w.modal_vec
    vec[0, 0], vec[0, 1], vec[0, 2] = rotate_back(q, i, v[i, 0], v[i, 1], v[i, 2])
    vec[1, 0], vec[1, 1], vec[1, 2] = rotate_back(q, i, w.body_f[i, 0], w.body_f[i, 1], w.body_f[i, 2])
    vec[2, 0], vec[2, 1], vec[2, 2] = rotate_back(q, i, w.body_t[i, 0], w.body_t[i, 1], w.body_t[i, 2])
    vec[3, 0], vec[3, 1], vec[3, 2] = rotate_back(q, i, m.gravity[0], m.gravity[1], m.gravity[2])


@njit(cache=True, inline="always", _nrt=False)
def _implicit_modes(m, j, w, hh):
    """Implicit modes of modal body j at the step h = 2 hh: the damping w.modal_c = 2ζω, raised to the
    critical 2ω where hω > 2, and w.modal_dinv = 1/(1 + (h/2) c + (h/2)² ω²) (module docstring); formed
    again only when hh differs from the one they were formed for (``w.modal_imp_h[j]``)."""
    if w.modal_imp_h[j] == hh:
        return
    w.modal_imp_h[j] = hh
    for k in range(m.modal_off[j], m.modal_off[j + 1]):
        w2, c = m.modal_omega2[k], m.modal_damp[k]
        a = hh * hh * w2
        if a > 1.0:
            c = max(c, 2.0 * math.sqrt(w2))
        w.modal_c[k] = c
        w.modal_dinv[k] = 1.0 / (1.0 + hh * c + a)


@njit(cache=True, inline="always", _nrt=False)
def _constrained_kick(m, q, v, eta, eta_dot, w, j, hh, correct):
    i, o0, o1 = m.modal_body[j], m.modal_off[j], m.modal_off[j + 1]
    mj = o1 - o0
    e, qf = eta[o0:o1], w.modal_f[o0:o1]
    om2, dmp = m.modal_omega2[o0:o1], m.modal_damp[o0:o1]
    hm = 0.0  # the kick's mass matrix: M, or M + (h/2) C + (h/2)² K with implicit modes
    if m.modal_implicit[j] == 1:
        hm = hh
        _implicit_modes(m, j, w, hh)
        dmp = w.modal_c[o0:o1]
    _body_vectors(m, q, v, w, i)
    vec, u, u0, rhs, hv, sel = w.modal_vec, w.modal_u, w.modal_u0, w.modal_rhs, w.modal_h, w.modal_sel
    for c in range(3):
        u[c] = vec[0, c]
        u[3 + c] = v[i, 3 + c]
    for k in range(mj):
        u[6 + k] = eta_dot[o0 + k]
    for c in range(6 + mj):
        u0[c] = u[c]
    n = _select(m, j, mj, sel)
    unit = n == mj and m.modal_unit[j] == 1
    # a held frame at rest has no velocity terms
    moving = n > mj or v[i, 0] != 0.0 or v[i, 1] != 0.0 or v[i, 2] != 0.0 or v[i, 3] != 0.0 or \
        v[i, 4] != 0.0 or v[i, 5] != 0.0
    S = w.modal_s
    if moving or not unit:  # the η-terms (and M's factor) at this η, formed once per η
        _terms(m, j, e, w)
        S = w.modal_S[j]
        if not unit and not _factor(m, j, e, w, n, sel, hm):
            return False
    else:  # a held frame at rest with unit modal mass: the first moment alone (its weight)
        S[0], S[1], S[2] = _first_moment(m.modal_I2[j], m.modal_I3[j], e)
    for it in range(2 if correct else 1):
        constrained_rhs(m.modal_mass[j], m.modal_I3[j], m.modal_I5[j], S, w.modal_J[j], w.modal_G[j], e,
                        u[6:6 + mj], u[0:3], u[3:6], vec[1], vec[2], vec[3], qf, om2, dmp, True, moving, hv, rhs)
        b = w.modal_b
        for r in range(n):
            b[r] = rhs[sel[r]]
        if not unit:
            _solve(m, w, j, mj, n, sel, b, hm)
        elif hm > 0.0:
            for k in range(mj):
                b[k] *= w.modal_dinv[o0 + k]
        for r in range(n):
            u[sel[r]] = u0[sel[r]] + hh * b[r]
    if m.modal_frame_free[j, 0]:
        v[i, 0], v[i, 1], v[i, 2] = rotate(q, i, u[0], u[1], u[2])
    for c in range(3):
        if m.modal_frame_free[j, 3 + c]:
            v[i, 3 + c] = u[3 + c]
    for k in range(mj):
        eta_dot[o0 + k] = u[6 + k]
    return True


@njit(cache=True, inline="always", _nrt=False)
def _rotational_momenta(m, j, v, eta_dot, w, i, o0, mj, e, p):
    """(π, p_η) = M_r(η)(ω, η̇) of free modal body j into p, with u = (ω, η̇) in w.modal_u, the selection
    of the (ω, η) block in w.modal_sel and M_r(η) factored in w.modal_L[j]; False if not positive definite."""
    u, sel = w.modal_u, w.modal_sel
    n = 3 + mj
    for c in range(3):
        sel[c] = 3 + c
        u[c] = v[i, 3 + c]
    for k in range(mj):
        sel[3 + k] = 6 + k
        u[3 + k] = eta_dot[o0 + k]
    if not _factor(m, j, e, w, n, sel):
        return False
    M = w.modal_M[j]
    for r in range(n):
        s = 0.0
        for c in range(n):
            s += M[sel[r], sel[c]] * u[c]
        p[r] = s
    return True


@njit(cache=True, inline="always", _nrt=False)
def _free_kick(m, q, v, eta, eta_dot, w, j, hh, correct):
    i, o0, o1 = m.modal_body[j], m.modal_off[j], m.modal_off[j + 1]
    mj = o1 - o0
    n = 3 + mj
    e, qf = eta[o0:o1], w.modal_f[o0:o1]
    om2, dmp = m.modal_omega2[o0:o1], m.modal_damp[o0:o1]
    mass = m.modal_mass[j]
    inv_m = hh / mass
    for c in range(3):
        v[i, c] += inv_m * (w.body_f[i, c] + mass * m.gravity[c])
    _body_vectors(m, q, v, w, i)
    u, p0, b, dT = w.modal_u, w.modal_u0, w.modal_b, w.modal_h
    if not _rotational_momenta(m, j, v, eta_dot, w, i, o0, mj, e, p0):
        return False
    for c in range(3):
        p0[c] += hh * w.modal_vec[2, c]
    for it in range(2 if correct else 1):
        inertia_force(m.modal_I5[j], w.modal_G[j], u[0:3], u[3:n], dT)
        for c in range(3):
            b[c] = p0[c]
        for k in range(mj):
            b[3 + k] = p0[3 + k] + hh * (qf[k] - om2[k] * e[k] - dmp[k] * u[3 + k] + dT[k])
        _solve(m, w, j, mj, n, w.modal_sel, b)
        for c in range(n):
            u[c] = b[c]
    for c in range(3):
        v[i, 3 + c] = u[c]
    for k in range(mj):
        eta_dot[o0 + k] = u[3 + k]
    return True


@njit(cache=True, _nrt=False)
def modal_kick(m, q, v, eta, eta_dot, w, hh, correct):
    """Half-step velocity kick (h/2 = hh) of every modal body from the forces in w; False on a
    mass matrix that is not positive definite. ``correct``: the second kick of a step (module doc)."""
    for j in range(m.modal_body.shape[0]):
        ok = _free_kick(m, q, v, eta, eta_dot, w, j, hh, correct) if _frame_free(m, j) else \
            _constrained_kick(m, q, v, eta, eta_dot, w, j, hh, correct)
        if not ok:
            return False
    return True


@njit(cache=True, inline="always", _nrt=False)
def _free_drift(m, q, v, eta, eta_dot, w, j, h):
    i, o0, o1 = m.modal_body[j], m.modal_off[j], m.modal_off[j + 1]
    mj = o1 - o0
    n = 3 + mj
    e, e_mid = eta[o0:o1], w.modal_eta[:mj]
    u, p, b, sel = w.modal_u, w.modal_u0, w.modal_b, w.modal_sel
    if not _rotational_momenta(m, j, v, eta_dot, w, i, o0, mj, e, p):
        return False
    # explicit midpoint: velocities at (π turned by hω/2, η + hη̇/2)
    b[0], b[1], b[2] = _turn_back(p[0], p[1], p[2], 0.5 * h * u[0], 0.5 * h * u[1], 0.5 * h * u[2])
    for k in range(mj):
        b[3 + k] = p[3 + k]
        e_mid[k] = e[k] + 0.5 * h * u[3 + k]
    if not _factor(m, j, e_mid, w, n, sel):
        return False
    _solve(m, w, j, mj, n, sel, b)
    ox, oy, oz = h * b[0], h * b[1], h * b[2]
    q[i, 3], q[i, 4], q[i, 5], q[i, 6] = turn_quaternion(q[i, 3], q[i, 4], q[i, 5], q[i, 6], ox, oy, oz)
    p[0], p[1], p[2] = _turn_back(p[0], p[1], p[2], ox, oy, oz)
    for k in range(mj):
        e[k] += h * b[3 + k]
    if not _factor(m, j, e, w, n, sel):
        return False
    for c in range(n):
        b[c] = p[c]
    _solve(m, w, j, mj, n, sel, b)
    for c in range(3):
        v[i, 3 + c] = b[c]
    for k in range(mj):
        eta_dot[o0 + k] = b[3 + k]
    return True


@njit(cache=True, inline="always", _nrt=False)
def _constrained_drift(m, q, v, eta, eta_dot, j, h):
    i, o0, o1 = m.modal_body[j], m.modal_off[j], m.modal_off[j + 1]
    wx, wy, wz = v[i, 3], v[i, 4], v[i, 5]
    if wx != 0.0 or wy != 0.0 or wz != 0.0:
        q[i, 3], q[i, 4], q[i, 5], q[i, 6] = turn_quaternion(q[i, 3], q[i, 4], q[i, 5], q[i, 6],
                                                             h * wx, h * wy, h * wz)
    for k in range(o0, o1):
        eta[k] += h * eta_dot[k]


@njit(cache=True, _nrt=False)
def modal_drift(m, q, v, eta, eta_dot, w, h):
    """Drift of every modal body over h (frame pose and η); False on a singular mass matrix."""
    for j in range(m.modal_body.shape[0]):
        i = m.modal_body[j]
        for c in range(3):
            q[i, c] += h * v[i, c]
        if _frame_free(m, j):
            if not _free_drift(m, q, v, eta, eta_dot, w, j, h):
                return False
        else:
            _constrained_drift(m, q, v, eta, eta_dot, j, h)
    return True


@njit(cache=True, _nrt=False)
def modal_energy(m, q, v, eta, eta_dot, w):
    """Kinetic energy ½uᵀM(η)u and elastic energy ½Σω_k²η_k² of all modal bodies, J (a tuple)."""
    kin = 0.0
    pot = 0.0
    for j in range(m.modal_body.shape[0]):
        i, o0, o1 = m.modal_body[j], m.modal_off[j], m.modal_off[j + 1]
        mj = o1 - o0
        _mass(m, j, eta[o0:o1], w)
        M = w.modal_M[j]
        _body_vectors(m, q, v, w, i)
        u = w.modal_u
        for c in range(3):
            u[c] = w.modal_vec[0, c]
            u[3 + c] = v[i, 3 + c]
        for k in range(mj):
            u[6 + k] = eta_dot[o0 + k]
            pot += 0.5 * m.modal_omega2[o0 + k] * eta[o0 + k] ** 2
        for r in range(6 + mj):
            for c in range(6 + mj):
                kin += 0.5 * u[r] * M[r, c] * u[c]
    return kin, pot
