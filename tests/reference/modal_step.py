"""Plain-numpy twin of mbd_core.kernels.modal_step: one half kick and one drift of every modal body of a
model, written from the equations of motion in the kernel's module docstring with the twin of the
mass matrix and quadratic-velocity vector (``modal``), linear solves (numpy.linalg.solve) and rotation
matrices (scipy.spatial.transform.Rotation) instead of Cholesky factors and quaternion algebra.

A modal body has u = (v = Rᵀṙ, ω, η̇) and M(η) u̇ + h(η, u) = (F, N, Q − Kη − Dη̇) with gravity g as
F += m Rᵀg, N += S × Rᵀg, Q += I3ᵀ Rᵀg, S = I2 + I3 η.

Free frame (momentum form): ṙ += (h/2)(F_W/m + g); with M_r the (ω, η) block of M and
(π, p_η) = M_r (ω, η̇), the kick adds (h/2)(N, Q − Kη − Dη̇ + ∂T/∂η) and solves back; ∂T/∂η_k =
½ uᵀ (∂M/∂η_k) u, here from the η-derivative of every block of M (M is quadratic in η). The drift
turns π by the explicit-midpoint body rotation θ = h ω_mid: R ← R exp([θ]×), π ← exp([θ]×)ᵀ π,
η ← η + h η̇_mid, with (ω_mid, η̇_mid) = M_r(η + h η̇/2)⁻¹ (exp([hω/2]×)ᵀ π, p_η).

Constrained frame (acceleration form): u_f ← u0_f + (h/2) M_ff⁻¹ (rhs(u) − h(u))_f on the integrated
components f; the frame drifts at its velocity, R ← R exp([h ω]×); η ← η + h η̇. With implicit modes
the kicks solve with M + (h/2) diag(0, c) + (h/2)² diag(0, ω²) instead of M_ff, with the damping
c = 2ζω raised to the critical 2ω for modes with hω > 2.

Both kicks with ``correct`` evaluate the velocity-dependent terms once more at the predicted u.
"""

import numpy as np
from scipy.spatial.transform import Rotation

from . import modal
from .multibody import matrix


def invariants(m, j):
    """(mass, I2, …, I9) of modal body j, cut to its own number of modes (the model pads them)."""
    k = m.modal_off[j + 1] - m.modal_off[j]
    return (m.modal_mass[j], m.modal_I2[j], m.modal_I3[j][:, :k], m.modal_I4[j][:, :k], m.modal_I5[j][:, :k, :k],
            m.modal_I6[j][:k, :k], m.modal_I7[j], m.modal_I8[j][:, :, :k], m.modal_I9[j][:, :, :k, :k])


def mass_matrix_derivative(inv, eta):
    """∂M/∂η_k (m, 6 + m, 6 + m): S̃ has ∂S/∂η_k = I3[:, k]; ∂J/∂η_k = I8_k + I8_kᵀ + Σ_l (I9_kl + I9_lk) η_l;
    the (ω, η) block ∂I4(η)/∂η_k = I5[:, k, :]."""
    mass, I2, I3, I4, I5, I6, I7, I8, I9 = inv
    n = len(eta)
    out = np.zeros((n, 6 + n, 6 + n))
    for k in range(n):
        St = modal.skew(I3[:, k])
        dJ = I8[:, :, k] + I8[:, :, k].T + np.einsum("ijl,l->ij", I9[:, :, k, :] + I9[:, :, :, k], eta)
        out[k, 3:6, :3], out[k, :3, 3:6] = St, St.T
        out[k, 3:6, 3:6] = dJ
        out[k, 3:6, 6:], out[k, 6:, 3:6] = I5[:, k, :], I5[:, k, :].T
    return out


def kinetic_gradient(inv, eta, u):
    """∂T/∂η at fixed u = (v, ω, η̇): ½ uᵀ (∂M/∂η_k) u, √kg·m/s²."""
    return 0.5 * np.einsum("i,kij,j->k", u, mass_matrix_derivative(inv, eta), u)


def constrained_rhs(inv, eta, eta_dot, v_b, omega, f_b, n_b, g_b, modal_f, omega2, damp, elastic, frozen=True):
    """(F + m g, N + S × g, Q + I3ᵀ g [− Kη − Dη̇]) − h, body axes (the kernel's constrained_rhs); ``frozen``:
    h for the rate of the world velocity's body components at a frozen frame, Rᵀr̈ = v̇ + ω × v — the
    ω × v part of v̇ moved into that rate, i.e. h − M(η)[:, :3](ω × v)."""
    mass, I2, I3 = inv[:3]
    h = modal.velocity_terms(*inv, eta, v_b, omega, eta_dot)
    if frozen:
        h = h - modal.mass_matrix(*inv, eta)[:, :3] @ np.cross(omega, v_b)
    gen = np.concatenate([f_b + mass * g_b, n_b + np.cross(I2 + I3 @ eta, g_b), modal_f + I3.T @ g_b])
    if elastic:
        gen[6:] -= omega2 * eta + damp * eta_dot
    return gen - h


def _body(m, j):
    i, o0, o1 = m.modal_body[j], m.modal_off[j], m.modal_off[j + 1]
    return i, slice(o0, o1)


def _free_kick(m, j, q, v, eta, eta_dot, body_f, body_t, modal_f, hh, correct):
    i, s = _body(m, j)
    inv = invariants(m, j)
    mass, I2, I3 = inv[:3]
    R = matrix(q[i, 3:])
    g_b = R.T @ m.gravity
    v[i, :3] += hh * (body_f[i] / mass + m.gravity)
    e = eta[s]
    M_r = modal.mass_matrix(*inv, e)[3:, 3:]
    n_b = R.T @ body_t[i] + np.cross(I2 + I3 @ e, g_b)
    p0 = M_r @ np.concatenate([v[i, 3:], eta_dot[s]])
    p0[:3] += hh * n_b
    u = np.concatenate([v[i, 3:], eta_dot[s]])
    for _ in range(2 if correct else 1):
        full = np.concatenate([R.T @ v[i, :3], u])
        gen = modal_f[s] + I3.T @ g_b - m.modal_omega2[s] * e - m.modal_damp[s] * u[3:] + kinetic_gradient(inv, e, full)
        u = np.linalg.solve(M_r, p0 + hh * np.concatenate([np.zeros(3), gen]))
    v[i, 3:], eta_dot[s] = u[:3], u[3:]


def _constrained_kick(m, j, q, v, eta, eta_dot, body_f, body_t, modal_f, hh, correct):
    i, s = _body(m, j)
    inv = invariants(m, j)
    R = matrix(q[i, 3:])
    e = eta[s]
    n_mod = len(e)
    free = np.concatenate([m.modal_frame_free[j].astype(bool), np.ones(n_mod, bool)])
    f_b, n_b, g_b = R.T @ body_f[i], R.T @ body_t[i], R.T @ m.gravity
    u0 = np.concatenate([R.T @ v[i, :3], v[i, 3:], eta_dot[s]])
    M = modal.mass_matrix(*inv, e)
    damp = m.modal_damp[s]
    if m.modal_implicit[j]:       # augmented mass M + (h/2) diag(0, c) + (h/2)² diag(0, ω²); c critical if hω > 2
        damp = np.array([implicit_damping(w2, c, 2 * hh) for w2, c in zip(m.modal_omega2[s], damp)])
        M[6:, 6:] += np.diag(hh * damp + hh**2 * m.modal_omega2[s])
    M_ff = M[np.ix_(free, free)]
    u = u0.copy()
    for _ in range(2 if correct else 1):
        rhs = constrained_rhs(inv, e, u[6:], u[:3], u[3:6], f_b, n_b, g_b, modal_f[s], m.modal_omega2[s],
                              damp, True)
        u = u0.copy()
        u[free] += hh * np.linalg.solve(M_ff, rhs[free])
    if free[:3].any():
        v[i, :3] = R @ u[:3]
    v[i, 3:] = np.where(free[3:6], u[3:6], v[i, 3:])
    eta_dot[s] = u[6:]


def kick(m, q, v, eta, eta_dot, body_f, body_t, modal_f, hh, correct):
    """Half kick hh = h/2 of every modal body from world forces body_f, moments body_t (n_b, 3) and modal
    forces modal_f (n_η,); returns the new (v, eta_dot)."""
    v, eta_dot = v.copy(), eta_dot.copy()
    for j in range(len(m.modal_body)):
        step = _free_kick if m.modal_frame_free[j].all() else _constrained_kick
        step(m, j, q, v, eta, eta_dot, body_f, body_t, modal_f, hh, correct)
    return v, eta_dot


def quat_near(R, near):
    """Unit quaternion (w, x, y, z) of R on the side of the sphere nearest ``near``."""
    quat = Rotation.from_matrix(R).as_quat(scalar_first=True)
    return -quat if quat @ near < 0 else quat


def expm(theta):
    """exp([θ]×), the rotation by the rotation vector θ."""
    return Rotation.from_rotvec(theta).as_matrix()


def implicit_damping(omega2, damp, h):
    """Damping 2ζω of an implicit mode at the step h: its own, raised to the critical 2ω when hω > 2."""
    return max(damp, 2.0 * np.sqrt(omega2)) if h * np.sqrt(omega2) > 2.0 else damp


def _free_drift(m, j, q, v, eta, eta_dot, h):
    i, s = _body(m, j)
    inv = invariants(m, j)
    e = eta[s].copy()
    omega, ed = v[i, 3:].copy(), eta_dot[s].copy()
    p = modal.mass_matrix(*inv, e)[3:, 3:] @ np.concatenate([omega, ed])
    pi, p_eta = p[:3], p[3:]
    e_mid = e + 0.5 * h * ed
    u_mid = np.linalg.solve(modal.mass_matrix(*inv, e_mid)[3:, 3:],
                            np.concatenate([expm(0.5 * h * omega).T @ pi, p_eta]))
    turn = expm(h * u_mid[:3])
    q[i, 3:] = quat_near(matrix(q[i, 3:]) @ turn, q[i, 3:])
    e_new = e + h * u_mid[3:]
    u = np.linalg.solve(modal.mass_matrix(*inv, e_new)[3:, 3:], np.concatenate([turn.T @ pi, p_eta]))
    eta[s], v[i, 3:], eta_dot[s] = e_new, u[:3], u[3:]


def _constrained_drift(m, j, q, v, eta, eta_dot, h):
    i, s = _body(m, j)
    if np.any(v[i, 3:] != 0.0):
        q[i, 3:] = quat_near(matrix(q[i, 3:]) @ expm(h * v[i, 3:]), q[i, 3:])
    eta[s] += h * eta_dot[s]


def drift(m, q, v, eta, eta_dot, h):
    """Drift of every modal body over h (frame pose, η; η̇ and ω where the scheme changes them);
    returns new (q, v, eta, eta_dot)."""
    q, v, eta, eta_dot = q.copy(), v.copy(), eta.copy(), eta_dot.copy()
    for j in range(len(m.modal_body)):
        i = m.modal_body[j]
        q[i, :3] += h * v[i, :3]
        step = _free_drift if m.modal_frame_free[j].all() else _constrained_drift
        step(m, j, q, v, eta, eta_dot, h)
    return q, v, eta, eta_dot


def energy(m, q, v, eta, eta_dot):
    """(½ uᵀ M(η) u, ½ Σ ω_k² η_k²) summed over the modal bodies, J."""
    kin = pot = 0.0
    for j in range(len(m.modal_body)):
        i, s = _body(m, j)
        u = np.concatenate([matrix(q[i, 3:]).T @ v[i, :3], v[i, 3:], eta_dot[s]])
        kin += 0.5 * u @ modal.mass_matrix(*invariants(m, j), eta[s]) @ u
        pot += 0.5 * np.sum(m.modal_omega2[s] * eta[s] ** 2)
    return kin, pot
