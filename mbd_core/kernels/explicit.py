"""Explicit symplectic time stepping of a rigid multibody model (the whole loop compiled).

One step of size h (velocity Verlet in kick–drift–kick form):

    kick   v ← v + (h/2) M⁻¹ F,   ω ← ω + (h/2) I⁻¹ τ_B        (free components only)
    drift  r ← r + h v;  rotation: symplectic splitting of the free rigid-body rotation
           (:func:`.rigid.free_rotation_step`, gyroscopic terms exact) for bodies whose three
           rotations are free; q ← q ⊗ exp(h ω/2) for spheres (their free rotation keeps ω, so
           this is exact) and for bodies with a prescribed spin
    force  F, τ at (t + h, q, v)
    kick   as above.

Modal bodies follow the same kick–drift–kick with their own kick and drift (:mod:`.modal_step`;
first kick and drift after the rigid ones, which do not depend on them).

Implicit friction (bodies with ``m.body_fric_implicit``: rigid bodies with at least one free
component): the friction of each contact point is a damper F_t = −C_p v_t, frozen at the force
evaluation: across the slip its coefficient is the secant c = μ(u) F_n / u ≥ 0 (u = |v_t| there),
along the slip the larger of the secant and the slope F_n dμ/du (:mod:`.friction_damping`). Its
velocity dependence is taken implicitly in both kicks, in the coordinates the velocities are stored
in (u = (v world, ω body frame), mass matrix M = diag(m, m, m, I₁, I₂, I₃)):

    (M + (h/2) C)_ff Δu_f = (h/2) (F − C (u − u_e))_f,

f the body's free components (prescribed ones keep their values), C = Tᵀ (Σ Jᵀ C_p J) T with
T = diag(1, R) over the body's contact points, u_e the velocity at the force evaluation; a body
whose rotation is only partly free has its gyroscopic torque −ω × Iω in F (as below). For a lone
damper m u̇ = −c u the two kicks give u ← u / (1 + hc/2m)²: no step is too large for the friction,
and the slip never reverses within a step (the secant form, unlike the tangent dμ/du, also holds
for a sliding contact, where μ is flat; a linearly implicit treatment in the style of the Rosenbrock
methods, Hairer & Wanner, *Solving ODEs II*, §IV.7, with a frozen secant instead of the Jacobian).
Where the law is steeper than its secant (the start of a regularised Coulomb step, μ ∝ u² there)
the secant alone would let a settling slip overshoot by a factor −(1 − b c)/(1 + b c) per kick
(b = h/(2 m_t)), which at steps far above the friction limit is close to −1 and rang at 2 kHz in a
driven ball bearing at a 1 mm/s transition speed; with the slope along the slip the factor is
1/(1 + b dF/du) ∈ (0, 1). Steady rolling and sliding are unchanged: at a fixed point u = u_e. The
other body of a pair enters with its velocity of the evaluation (a block-Jacobi split; for two
bodies the relative slip then changes by a factor 1 − α_a − α_b, α = hc/(2m + hc) ∈ (0, 1), per
kick). Modal bodies and models built without ``implicit_friction`` are kicked explicitly.

Bodies whose rotation is only partly free (a ring driven about its axis but free to tilt) get the
gyroscopic term −ω × Iω explicitly in the kick of their free components, evaluated at the current
ω: that part is first order and lets a tilt rate grow by about (1 + h²Ω²/4) per step at spin Ω —
negligible at contact-limited steps (h Ω ≲ 1e-3), not for large steps on a fast-spinning ring.
Prescribed components of v keep their prescribed values. For conservative forces on free bodies the
scheme is symplectic and second order (Hairer, Lubich & Wanner, *Geometric Numerical Integration*,
2nd ed., ch. VI and VII.5); velocity-dependent forces (damping, friction) are evaluated with the
half-step velocity.

The forces from the last evaluation (``w.body_f``, ``w.body_t``) are part of the integrator state:
a run resumed from (q, v, forces) continues bit for bit.
"""

from __future__ import annotations

from numba import njit

from .forces import STATUS_ENERGY, STATUS_MODAL, STATUS_OK, compute_forces, rotate, rotate_back
from .modal_step import cholesky_in_place, cholesky_solve, modal_drift, modal_energy, modal_kick
from .rigid import free_rotation_step, turn_quaternion


@njit(cache=True, inline="always", _nrt=False)
def _kick_body(q, v, i, body_f, body_t, body_mass, body_inertia, body_free, hh):
    """The explicit kick of body i's free components (module docstring)."""
    free = body_free[i]
    inv_m = hh / body_mass[i]
    for j in range(3):
        if free[j]:
            v[i, j] += inv_m * body_f[i, j]
    n_rot = free[3] + free[4] + free[5]
    if n_rot == 0:
        return
    tx, ty, tz = rotate_back(q, i, body_t[i, 0], body_t[i, 1], body_t[i, 2])
    inertia = body_inertia[i]
    if n_rot < 3:
        tx, ty, tz = _minus_gyroscopic(v, i, inertia, tx, ty, tz)
    if free[3]:
        v[i, 3] += hh * tx / inertia[0]
    if free[4]:
        v[i, 4] += hh * ty / inertia[1]
    if free[5]:
        v[i, 5] += hh * tz / inertia[2]


@njit(cache=True, inline="always", _nrt=False)
def _minus_gyroscopic(v, i, inertia, tx, ty, tz):
    """Body-frame torque τ − ω × Iω of a body whose rotation is only partly free (module docstring)."""
    wx, wy, wz = v[i, 3], v[i, 4], v[i, 5]
    lx, ly, lz = inertia[0] * wx, inertia[1] * wy, inertia[2] * wz
    return tx - (wy * lz - wz * ly), ty - (wz * lx - wx * lz), tz - (wx * ly - wy * lx)


@njit(cache=True, _nrt=False)
def _kick(q, v, body_f, body_t, body_mass, body_inertia, body_free, implicit, hh):
    for i in range(body_mass.shape[0]):
        if implicit[i] == 0:  # the others: _friction_kick
            _kick_body(q, v, i, body_f, body_t, body_mass, body_inertia, body_free, hh)


@njit(cache=True, _nrt=False)
def _friction_kick(q, v, w, body_mass, body_inertia, body_free, implicit, hh):
    """Kick of the bodies with implicit friction (module docstring): the linear system in the
    coordinates the velocities are stored in, u = (v world, ω body frame), where the mass matrix is
    diag(m, m, m, I₁, I₂, I₃) and the damping C' = Tᵀ C T, T = diag(1, R); prescribed components
    keep their values (the system is solved for the free ones only)."""
    A, r, g = w.fric_a, w.fric_r, w.fric_g
    rot = w.fric_rot
    free_idx = w.fric_idx
    for i in range(body_mass.shape[0]):
        if implicit[i] == 0:
            continue
        C, ve = w.fric_c[i], w.fric_v[i]
        if C[0, 0] + C[1, 1] + C[2, 2] == 0.0:  # no friction on it (each point adds 2c or more to this trace)
            _kick_body(q, v, i, w.body_f, w.body_t, body_mass, body_inertia, body_free, hh)
            continue
        for k in range(3):  # R, column by column
            rot[0, k], rot[1, k], rot[2, k] = rotate(q, i, 1.0 if k == 0 else 0.0, 1.0 if k == 1 else 0.0,
                                                     1.0 if k == 2 else 0.0)
        # C' = Tᵀ C T in A (upper left as it is; C_vω R; Rᵀ C_ωv = (C_vω R)ᵀ, C being symmetric; Rᵀ C_ωω R,
        # with C_ωω R formed once in the lower right of A first)
        for j in range(3):
            for k in range(3):
                A[j, k] = C[j, k]
                s_vw, t = 0.0, 0.0
                for l in range(3):
                    s_vw += C[j, 3 + l] * rot[l, k]
                    t += C[3 + j, 3 + l] * rot[l, k]
                A[j, 3 + k] = s_vw
                A[3 + k, j] = s_vw
                A[3 + j, 3 + k] = t
        for k in range(3):  # (g is free scratch until the right-hand side)
            t0, t1, t2 = A[3, 3 + k], A[4, 3 + k], A[5, 3 + k]
            for j in range(3):
                g[j] = rot[0, j] * t0 + rot[1, j] * t1 + rot[2, j] * t2
            for j in range(3):
                A[3 + j, 3 + k] = g[j]
        for j in range(6):
            r[j] = v[i, j] - ve[j]  # velocity change since the evaluation
        tx, ty, tz = rotate_back(q, i, w.body_t[i, 0], w.body_t[i, 1], w.body_t[i, 2])
        free = body_free[i]
        inertia = body_inertia[i]
        if free[3] + free[4] + free[5] < 3:
            tx, ty, tz = _minus_gyroscopic(v, i, inertia, tx, ty, tz)
        n = 0
        for j in range(6):
            if free[j]:
                free_idx[n] = j
                n += 1
        # (M' + (h/2) C')_ff Δu_f = (h/2) (F' − C' (u − u_e))_f, compacted into the leading n × n block
        for a in range(n):
            j = free_idx[a]
            s = 0.0
            for k in range(6):
                s += A[j, k] * r[k]
            f = w.body_f[i, j] if j < 3 else (tx if j == 3 else (ty if j == 4 else tz))
            g[a] = hh * (f - s)
        for a in range(n):
            j = free_idx[a]
            for b in range(n):
                A[a, b] = hh * A[j, free_idx[b]]
            A[a, a] += body_mass[i] if j < 3 else inertia[j - 3]
        cholesky_in_place(A, n)
        cholesky_solve(A, n, g)
        for a in range(n):
            v[i, free_idx[a]] += g[a]


@njit(cache=True, _nrt=False)
def _spin(q, i, wx, wy, wz, h):
    """q_i ← q_i ⊗ exp(h ω / 2) for a constant body-frame ω."""
    if wx == 0.0 and wy == 0.0 and wz == 0.0:
        return
    q[i, 3], q[i, 4], q[i, 5], q[i, 6] = turn_quaternion(q[i, 3], q[i, 4], q[i, 5], q[i, 6], h * wx, h * wy, h * wz)


@njit(cache=True, _nrt=False)
def _drift(q, v, body_inertia, body_free, body_modal, pi, h):
    for i in range(body_inertia.shape[0]):
        if body_modal[i] >= 0:  # drifted by modal_drift
            continue
        for j in range(3):
            q[i, j] += h * v[i, j]
        free = body_free[i]
        inertia = body_inertia[i]
        spherical = inertia[0] == inertia[1] and inertia[1] == inertia[2]
        if free[3] and free[4] and free[5] and not spherical:
            for j in range(3):
                pi[j] = inertia[j] * v[i, 3 + j]
            free_rotation_step(q[i, 3:], pi, inertia, h)
            for j in range(3):
                v[i, 3 + j] = pi[j] / inertia[j]
        else:
            _spin(q, i, v[i, 3], v[i, 4], v[i, 5], h)


@njit(cache=True, _nrt=False)
def kinetic_energy(body_mass, body_inertia, v):
    """Σ ½ m |v|² + ½ ωᵀ I ω over all bodies, J."""
    e = 0.0
    for i in range(body_mass.shape[0]):
        e += 0.5 * body_mass[i] * (v[i, 0] ** 2 + v[i, 1] ** 2 + v[i, 2] ** 2)
        for j in range(3):
            e += 0.5 * body_inertia[i, j] * v[i, 3 + j] ** 2
    return e


@njit(cache=True, inline="always", _nrt=False)
def _store_row(dst, k, src):
    """dst[k] = src for a 1-D src (element by element: the kernels run without numba's runtime,
    whose array assignment would allocate)."""
    for i in range(src.shape[0]):
        dst[k, i] = src[i]


@njit(cache=True, inline="always", _nrt=False)
def _store_rows(dst, k, src):
    """dst[k] = src for a 2-D src."""
    for i in range(src.shape[0]):
        for j in range(src.shape[1]):
            dst[k, i, j] = src[i, j]


@njit(cache=True, _nrt=False)
def _record(m, q, v, eta, eta_dot, w, t, k, rec):
    rec.t[k] = t
    _store_rows(rec.q, k, q)
    _store_rows(rec.v, k, v)
    _store_row(rec.eta, k, eta)
    _store_row(rec.eta_dot, k, eta_dot)
    _store_row(rec.fn, k, w.contact_fn)
    _store_row(rec.delta, k, w.contact_delta)
    _store_row(rec.slip, k, w.contact_slip)
    _store_row(rec.ft, k, w.contact_ft)
    _store_row(rec.angle, k, w.contact_angle)
    _store_row(rec.theta, k, w.contact_theta)
    for c in range(w.contact_point.shape[0]):
        for j in range(3):
            rec.point[k, c, j] = w.contact_point[c, j]
            rec.normal[k, c, j] = w.contact_normal[c, j]


@njit(cache=True, _nrt=False)
def record_now(m, q, v, eta, eta_dot, w, t, k, rec):
    """Store the current state and contact outputs as sample k of the record buffers."""
    _record(m, q, v, eta, eta_dot, w, t, k, rec)


@njit(cache=True, _nrt=False)
def total_kinetic_energy(m, q, v, eta, eta_dot, w):
    """Kinetic energy of the rigid bodies plus ½uᵀM(η)u of the modal bodies, J."""
    e = kinetic_energy(m.body_mass, m.body_inertia, v)
    if m.modal_body.shape[0] == 0:
        return e
    for j in range(m.modal_body.shape[0]):  # their rigid-body estimate is replaced
        i = m.modal_body[j]
        e -= 0.5 * m.body_mass[i] * (v[i, 0] ** 2 + v[i, 1] ** 2 + v[i, 2] ** 2)
        for c in range(3):
            e -= 0.5 * m.body_inertia[i, c] * v[i, 3 + c] ** 2
    return e + modal_energy(m, q, v, eta, eta_dot, w)[0]


@njit(cache=True, _nrt=False)
def run_explicit(m, q, v, eta, eta_dot, w, t_origin, step0, n_steps, h, every, rec, energy_limit):
    """Advance n_steps steps from global step ``step0`` (t = t_origin + step·h), in place.

    ``w.body_f``/``w.body_t``/``w.modal_f`` must hold the forces at the current state. With
    ``w.flex_skip[0]`` set, the steps that are not recorded (nor the last) skip the deformation of
    contacts open beyond their surface's motion bound (:mod:`.forces`; same forces). After every global step
    that is a multiple of ``every`` the state is stored in the record buffers ``rec`` (sample index
    counted from 0 within this call). Every 16th global step the kinetic energy is compared with
    ``energy_limit`` (J); above it the run stops with ``STATUS_ENERGY``. Returns (status, index,
    steps done, samples stored): status 0 when all steps were done; otherwise the stage that failed
    (see :mod:`.forces`) with the contact or body index (−1 for the energy check; the modal index
    for ``STATUS_MODAL``), and the state is that of the failed step (not recorded). Modal bodies
    are stepped by :mod:`.modal_step` inside the same kick–drift–kick.
    """
    k = 0
    mass, inertia, free, f, tau = m.body_mass, m.body_inertia, m.body_free, w.body_f, w.body_t
    imp = m.body_fric_implicit
    modal = m.modal_body.shape[0] > 0
    implicit = False
    for i in range(imp.shape[0]):
        implicit = implicit or imp[i] != 0
    may_skip = w.flex_skip[0] != 0
    for s in range(n_steps):
        step = step0 + s + 1
        t = t_origin + step * h
        _kick(q, v, f, tau, mass, inertia, free, imp, 0.5 * h)
        if implicit:
            _friction_kick(q, v, w, mass, inertia, free, imp, 0.5 * h)
        _drift(q, v, inertia, free, m.body_modal, w.pi, h)
        if modal:
            if not (modal_kick(m, q, v, eta, eta_dot, w, 0.5 * h, False)
                    and modal_drift(m, q, v, eta, eta_dot, w, h)):
                return STATUS_MODAL, -1, s, k
        # open surface contacts are skipped except where the outputs are kept: recorded steps and the
        # last one, whose work arrays the caller reads (checkpoints)
        w.flex_skip[1] = 1 if may_skip and step % every != 0 and s != n_steps - 1 else 0
        status, index = compute_forces(m, t, q, v, eta, eta_dot, w)
        w.flex_skip[1] = 0
        if status != STATUS_OK:
            return status, index, s, k
        _kick(q, v, f, tau, mass, inertia, free, imp, 0.5 * h)
        if implicit:
            _friction_kick(q, v, w, mass, inertia, free, imp, 0.5 * h)
        if modal and not modal_kick(m, q, v, eta, eta_dot, w, 0.5 * h, True):
            return STATUS_MODAL, -1, s, k
        if step % 16 == 0:
            e = total_kinetic_energy(m, q, v, eta, eta_dot, w) if modal else kinetic_energy(mass, inertia, v)
            if not (e <= energy_limit):
                return STATUS_ENERGY, -1, s, k
        if step % every == 0:
            _record(m, q, v, eta, eta_dot, w, t, k, rec)
            k += 1
    return STATUS_OK, -1, n_steps, k
