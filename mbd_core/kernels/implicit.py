"""Generalized-α kernels on R³ × SO(3): accelerations, the group update, the step residual and its
finite-difference Jacobian.

Each body's configuration is (r, R) ∈ R³ × SO(3), r the world position and R(q) the rotation body →
world (unit quaternion q); its velocity v = (ṙ world, ω body frame) is the left-trivialised
tangent vector, so that the group update with an increment Δq (n_b, 6) is

    r ← r + h Δq_r,      q ← q ⊗ exp(h Δq_ω / 2),

exp of the body-frame rotation vector h Δq_ω (Brüls & Cardona, J. Comput. Nonlinear Dyn. 5 (2010)
031002, eq. 8; Arnold & Brüls, Multibody Syst. Dyn. 18 (2007) 185). The accelerations of the free
components are Newton–Euler, with the principal inertia I = diag(I₁, I₂, I₃):

    v̇_r = F / m,      v̇_ω = I⁻¹ (τ_B − ω × I ω),      τ_B = Rᵀ τ,

held components (``body_free`` = 0) have v̇ = 0. The per-step arrays ``s`` of :func:`residual` and
:func:`fd_jacobian` are :class:`mbd_core.multibody.implicit.StepArrays`; the coefficients ``c``
are :class:`mbd_core.multibody.implicit.GenAlphaCoefficients` (α_m, α_f, β, γ).
"""

from __future__ import annotations

from numba import njit

from .forces import STATUS_OK, compute_forces, rotate_back
from .rigid import turn_quaternion

SQRT_EPS = 1.4901161193847656e-08


@njit(cache=True)
def accelerations(m, t, q, v, w, out):
    """v̇ (n_b, 6) of the free components at (t, q, v) into ``out``; held components 0.

    Translations in world axes (m/s²), rotations in body axes (rad/s²). Fills the work arrays ``w``
    like :func:`.forces.compute_forces` and returns its (status, index).
    """
    status, index = compute_forces(m, t, q, v, w.modal_f[:0], w.modal_f[:0], w)  # rigid models only
    for i in range(m.body_mass.shape[0]):
        free = m.body_free[i]
        for j in range(3):
            out[i, j] = w.body_f[i, j] / m.body_mass[i] if free[j] else 0.0
        tx, ty, tz = rotate_back(q, i, w.body_t[i, 0], w.body_t[i, 1], w.body_t[i, 2])
        inertia = m.body_inertia[i]
        wx, wy, wz = v[i, 3], v[i, 4], v[i, 5]
        lx, ly, lz = inertia[0] * wx, inertia[1] * wy, inertia[2] * wz
        out[i, 3] = (tx - (wy * lz - wz * ly)) / inertia[0] if free[3] else 0.0
        out[i, 4] = (ty - (wz * lx - wx * lz)) / inertia[1] if free[4] else 0.0
        out[i, 5] = (tz - (wx * ly - wy * lx)) / inertia[2] if free[5] else 0.0
    return status, index


@njit(cache=True)
def compose(q, dq, h, out):
    """out = q ∘ exp(h dq): r + h dq_r and q ⊗ (cos(φ/2), sin(φ/2) e), φ e = h dq_ω (body frame).

    ``q``, ``out`` (n_b, 7); ``dq`` (n_b, 6) m/s, rad/s. ``out`` may be ``q``. The quaternion is
    renormalised.
    """
    for i in range(q.shape[0]):
        for j in range(3):
            out[i, j] = q[i, j] + h * dq[i, j]
        out[i, 3], out[i, 4], out[i, 5], out[i, 6] = turn_quaternion(
            q[i, 3], q[i, 4], q[i, 5], q[i, 6], h * dq[i, 3], h * dq[i, 4], h * dq[i, 5])


@njit(cache=True)
def residual(m, t1, h, c, s, w, x, out):
    """Residual of one generalized-α step for the free accelerations x = v̇_{n+1}[free] into ``out``.

    From the step's start (s.q0, s.v0, s.vd0 = v̇_n, s.a0 = a_n), Chung & Hulbert (J. Appl. Mech.
    60 (1993) 371) in the Lie-group form of Arnold & Brüls (2007):

        (1 − α_m) a_{n+1} = (1 − α_f) v̇_{n+1} + α_f v̇_n − α_m a_n
        Δq = v_n + h (½ − β) a_n + h β a_{n+1},        q_{n+1} = q_n ∘ exp(h Δq)
        v_{n+1} = v_n + h (1 − γ) a_n + h γ a_{n+1}
        out = v̇_{n+1} − f(t_{n+1}, q_{n+1}, v_{n+1})      (free components)

    Fills s.vd1, s.a1, s.dq, s.q1, s.v1, s.f1 and the work ``w`` at the trial state; returns the
    (status, index) of the force evaluation.
    """
    am, af, beta, gamma = c.alpha_m, c.alpha_f, c.beta, c.gamma
    for k in range(x.shape[0]):
        f = s.free_idx[k]
        s.vd1[f // 6, f % 6] = x[k]
    for i in range(s.q0.shape[0]):
        for j in range(6):
            a1 = ((1.0 - af) * s.vd1[i, j] + af * s.vd0[i, j] - am * s.a0[i, j]) / (1.0 - am)
            s.a1[i, j] = a1
            s.dq[i, j] = s.v0[i, j] + h * ((0.5 - beta) * s.a0[i, j] + beta * a1)
            s.v1[i, j] = s.v0[i, j] + h * ((1.0 - gamma) * s.a0[i, j] + gamma * a1)
    compose(s.q0, s.dq, h, s.q1)
    status, index = accelerations(m, t1, s.q1, s.v1, w, s.f1)
    for k in range(x.shape[0]):
        f = s.free_idx[k]
        out[k] = x[k] - s.f1[f // 6, f % 6]
    return status, index


@njit(cache=True)
def fd_jacobian(m, t1, h, c, s, w, x, eps_floor, jac):
    """Forward-difference Jacobian ∂residual/∂x (n_free, n_free) at x into ``jac``.

    Column k uses the step ε_k = max(√ε_mach |x_k|, eps_floor); x is restored exactly. Returns the
    (status, index) of the first failed force evaluation, else that of the last. ``s.res`` holds the
    residual at x afterwards, the trial arrays and ``w`` that of the last perturbed x.
    """
    status, index = residual(m, t1, h, c, s, w, x, s.res)
    if status != STATUS_OK:
        return status, index
    for k in range(x.shape[0]):
        xk = x[k]
        x[k] = xk + max(SQRT_EPS * abs(xk), eps_floor)
        eps = x[k] - xk  # the step actually taken
        status, index = residual(m, t1, h, c, s, w, x, s.res_p)
        x[k] = xk
        if status != STATUS_OK:
            return status, index
        for r in range(x.shape[0]):
            jac[r, k] = (s.res_p[r] - s.res[r]) / eps
    return status, index
