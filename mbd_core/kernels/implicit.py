"""Generalized-α kernels on (R³ × SO(3))ⁿ × Rᵐ: accelerations, the group update, the step residual
and its finite-difference Jacobian.

Each body's configuration is (r, R) ∈ R³ × SO(3), r the world position and R(q) the rotation body →
world (unit quaternion q); its velocity v = (ṙ world, ω body frame) is the left-trivialised
tangent vector, so that the group update with an increment Δq (n_b, 6) is

    r ← r + h Δq_r,      q ← q ⊗ exp(h Δq_ω / 2),

exp of the body-frame rotation vector h Δq_ω (Brüls & Cardona, J. Comput. Nonlinear Dyn. 5 (2010)
031002, eq. 8; Arnold & Brüls, Multibody Syst. Dyn. 18 (2007) 185). Modal coordinates η (√kg) are a
vector space: η ← η + h Δη, as translations. The accelerations of the free components of rigid
bodies are Newton–Euler, with the principal inertia I = diag(I₁, I₂, I₃):

    v̇_r = F / m,      v̇_ω = I⁻¹ (τ_B − ω × I ω),      τ_B = Rᵀ τ,

held components (``body_free`` = 0) have v̇ = 0. A modal body's integrated components (those of
``modal_frame_free`` and all of η̇) solve the equations of motion of :mod:`.modal_step` (the same
as the explicit scheme's, with the elastic and damping forces −Kη − Dη̇ always included),

    M_ff(η) u̇_f = (F, N, Q − Kη − Dη̇ + gravity − h(η, u))_f,      u = (Rᵀṙ, ω, η̇),

held components have u̇ = 0, and the frame's translation acceleration in world axes is
r̈ = R (u̇_v + ω × u_v), the derivative of ṙ = R u_v.

The per-step arrays ``s`` of :func:`residual` and :func:`fd_jacobian` are
:class:`mbd_core.multibody.implicit.StepArrays`: generalized velocities are flat vectors of
6 n_b + n_η components, the bodies' (n_b, 6) row by row and then η̇; the coefficients ``c`` are
:class:`mbd_core.multibody.implicit.GenAlphaCoefficients` (α_m, α_f, β, γ).
"""

from __future__ import annotations

from numba import njit

from .forces import STATUS_MODAL, STATUS_OK, compute_forces, rotate, rotate_back
from .modal_step import _body_vectors, _factor, _select, _solve, _terms, constrained_rhs
from .rigid import turn_quaternion

SQRT_EPS = 1.4901161193847656e-08


@njit(cache=True, _nrt=False)
def _rigid_accelerations(m, q, v, w, out):
    """Newton–Euler v̇ (n_b, 6) of the free components from the forces in ``w``; held components 0."""
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


@njit(cache=True, _nrt=False)
def accelerations(m, t, q, v, w, out):
    """v̇ (n_b, 6) of the free components of a rigid model at (t, q, v) into ``out``; held components 0.

    Translations in world axes (m/s²), rotations in body axes (rad/s²). Fills the work arrays ``w``
    like :func:`.forces.compute_forces` and returns its (status, index).
    """
    status, index = compute_forces(m, t, q, v, w.modal_f[:0], w.modal_f[:0], w)
    _rigid_accelerations(m, q, v, w, out)
    return status, index


@njit(cache=True, _nrt=False)
def modal_accelerations(m, q, v, eta, eta_dot, w, out, out_eta):
    """Accelerations of the modal bodies from the forces in ``w`` (module docstring).

    Writes the frame rows of ``out`` (n_b, 6) (r̈ world m/s², ω̇ body rad/s², 0 where held) and
    η̈ into ``out_eta`` (n_η,) √kg/s². Returns −1, or the modal index of a body whose integrated
    mass matrix block is not positive definite.
    """
    for j in range(m.modal_body.shape[0]):
        i, o0, o1 = m.modal_body[j], m.modal_off[j], m.modal_off[j + 1]
        mj = o1 - o0
        e = eta[o0:o1]
        _body_vectors(m, q, v, w, i)
        vec, u, ud, rhs, b, sel = w.modal_vec, w.modal_u, w.modal_u0, w.modal_rhs, w.modal_b, w.modal_sel
        for c in range(3):
            u[c] = vec[0, c]
            u[3 + c] = v[i, 3 + c]
        _terms(m, j, e, w)
        constrained_rhs(m.modal_mass[j], m.modal_I3[j], m.modal_I5[j], w.modal_S[j], w.modal_J[j], w.modal_G[j], e,
                        eta_dot[o0:o1], u[0:3], u[3:6], vec[1], vec[2], vec[3], w.modal_f[o0:o1], m.modal_omega2[o0:o1],
                        m.modal_damp[o0:o1], True, True, w.modal_h, rhs, False)
        n = _select(m, j, mj, sel)
        for r in range(n):
            b[r] = rhs[sel[r]]
        if not (n == mj and m.modal_unit[j] == 1):  # else M_ff = I6 = 1
            if not _factor(m, j, e, w, n, sel):
                return j
            _solve(m, w, j, mj, n, sel, b)
        for c in range(6 + mj):
            ud[c] = 0.0
        for r in range(n):
            ud[sel[r]] = b[r]
        if m.modal_frame_free[j, 0]:
            ax = ud[0] + u[4] * u[2] - u[5] * u[1]
            ay = ud[1] + u[5] * u[0] - u[3] * u[2]
            az = ud[2] + u[3] * u[1] - u[4] * u[0]
            out[i, 0], out[i, 1], out[i, 2] = rotate(q, i, ax, ay, az)
        else:
            out[i, 0] = out[i, 1] = out[i, 2] = 0.0
        for c in range(3):
            out[i, 3 + c] = ud[3 + c]
        for k in range(mj):
            out_eta[o0 + k] = ud[6 + k]
    return -1


@njit(cache=True, _nrt=False)
def step_accelerations(m, t, q, v, eta, eta_dot, w, out, out_eta):
    """Accelerations of every integrated component at (t, q, v, η, η̇): rigid bodies into ``out``
    (n_b, 6) as :func:`accelerations`, modal bodies as :func:`modal_accelerations`.

    Returns the (status, index) of the force evaluation, or (``STATUS_MODAL``, modal index).
    """
    status, index = compute_forces(m, t, q, v, eta, eta_dot, w)
    _rigid_accelerations(m, q, v, w, out)
    if status == STATUS_OK and m.modal_body.shape[0] > 0:
        j = modal_accelerations(m, q, v, eta, eta_dot, w, out, out_eta)
        if j >= 0:
            return STATUS_MODAL, j
    return status, index


@njit(cache=True, _nrt=False)
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


@njit(cache=True, _nrt=False)
def residual(m, t1, h, c, s, w, x, out):
    """Residual of one generalized-α step for the free accelerations x = v̇_{n+1}[free] into ``out``.

    From the step's start (s.q0, s.e0 = η_n, s.v0, s.vd0 = v̇_n, s.a0 = a_n), Chung & Hulbert
    (J. Appl. Mech. 60 (1993) 371) in the Lie-group form of Arnold & Brüls (2007):

        (1 − α_m) a_{n+1} = (1 − α_f) v̇_{n+1} + α_f v̇_n − α_m a_n
        Δq = v_n + h (½ − β) a_n + h β a_{n+1},        q_{n+1} = q_n ∘ exp(h Δq),  η_{n+1} = η_n + h Δq_η
        v_{n+1} = v_n + h (1 − γ) a_n + h γ a_{n+1}
        out = v̇_{n+1} − f(t_{n+1}, q_{n+1}, η_{n+1}, v_{n+1})      (free components)

    Fills s.vd1, s.a1, s.dq, s.q1, s.e1, s.v1, s.f1 and the work ``w`` at the trial state; returns
    the (status, index) of :func:`step_accelerations`.
    """
    am, af, beta, gamma = c.alpha_m, c.alpha_f, c.beta, c.gamma
    nb = s.q0.shape[0]
    n6 = 6 * nb
    for k in range(x.shape[0]):
        s.vd1[s.free_idx[k]] = x[k]
    for f in range(s.v0.shape[0]):
        a1 = ((1.0 - af) * s.vd1[f] + af * s.vd0[f] - am * s.a0[f]) / (1.0 - am)
        s.a1[f] = a1
        s.dq[f] = s.v0[f] + h * ((0.5 - beta) * s.a0[f] + beta * a1)
        s.v1[f] = s.v0[f] + h * ((1.0 - gamma) * s.a0[f] + gamma * a1)
    compose(s.q0, s.dq[:n6].reshape((nb, 6)), h, s.q1)
    for k in range(s.e0.shape[0]):
        s.e1[k] = s.e0[k] + h * s.dq[n6 + k]
    status, index = step_accelerations(m, t1, s.q1, s.v1[:n6].reshape((nb, 6)), s.e1, s.v1[n6:], w,
                                       s.f1[:n6].reshape((nb, 6)), s.f1[n6:])
    for k in range(x.shape[0]):
        out[k] = x[k] - s.f1[s.free_idx[k]]
    return status, index


@njit(cache=True, _nrt=False)
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
