"""Unbalances: point masses off a body's axis, as the centrifugal force they put on it.

An unbalance U = m_u e (kg·m, the vector e in the body frame) at a body point p turning with the body
at angular velocity ω (body frame) pulls on the body with the centripetal reaction

    F = m_u (ω² e − (ω·e) ω)   (body frame),

i.e. U Ω² outward for a spin Ω about the axis of a rotor, constant in the body frame and turning with
it in the world (G. Genta, *Dynamics of Rotating Systems*, Springer 2005, for the unbalance as a
rotating force). The Euler part m_u ω̇ × e of a speed change and the unbalance's own inertia are
left out (a balance grade's grams beside a rotor's tenths of a kilogram). On a modal body the
point moves with the modes, p + D η, and the force enters the modal coordinates as Dᵀ F (D the mode
shapes at p, :func:`cms_reduction.sampling.sample_points`).

Arrays (:class:`mbd_core.multibody.model.ModelArrays`): unb_body (n_u,) int64, unb_point (n_u, 3) m in
the body's frame, unb_kg_m (n_u, 3) the vector U = m_u e, body frame, kg·m; unb_disp (n_u, 3, M) m/√kg
the mode shapes at the point (zero on a rigid body).
"""

from __future__ import annotations

from numba import njit

from .body_frames import _add_force, _to_world, rotate


@njit(cache=True, _nrt=False)
def unbalance_force_body(ux, uy, uz, wx, wy, wz):
    """F = ω² U − (ω·U) ω, body frame, N (module docstring)."""
    w2 = wx * wx + wy * wy + wz * wz
    wu = wx * ux + wy * uy + wz * uz
    return w2 * ux - wu * wx, w2 * uy - wu * wy, w2 * uz - wu * wz


@njit(cache=True, _nrt=False)
def _unbalances(m, q, v, eta, w):
    """Add every unbalance's force to ``w.body_f``/``w.body_t`` and, on modal bodies, to ``w.modal_f``."""
    for j in range(m.unb_body.shape[0]):
        i = m.unb_body[j]
        fx, fy, fz = unbalance_force_body(m.unb_kg_m[j, 0], m.unb_kg_m[j, 1], m.unb_kg_m[j, 2],
                                          v[i, 3], v[i, 4], v[i, 5])
        px, py, pz = m.unb_point[j, 0], m.unb_point[j, 1], m.unb_point[j, 2]
        mb = m.body_modal[i]
        if mb >= 0:
            o0 = m.modal_off[mb]
            for k in range(m.modal_off[mb + 1] - o0):
                d0, d1, d2 = m.unb_disp[j, 0, k], m.unb_disp[j, 1, k], m.unb_disp[j, 2, k]
                px += d0 * eta[o0 + k]
                py += d1 * eta[o0 + k]
                pz += d2 * eta[o0 + k]
                w.modal_f[o0 + k] += d0 * fx + d1 * fy + d2 * fz
        wx_, wy_, wz_ = _to_world(q, i, px, py, pz)
        gx, gy, gz = rotate(q, i, fx, fy, fz)
        _add_force(q, w.body_f, w.body_t, i, gx, gy, gz, wx_, wy_, wz_)
