"""Static equilibrium of a multibody model: a start without start-up shock.

Unknowns are the free translations of every body and the free rotations (small rotation vector,
body frame) of the bodies that are not spheres (a ball's orientation carries no static stiffness
without friction). The residual is the force and moment on each body from
:func:`mbd_core.kernels.forces.compute_forces` at zero velocity (no damping, no friction); the
returned state has the new positions and the velocities of the given state (set rolling
velocities there, e.g. with :func:`mbd_core.multibody.bearings.set_rolling_velocities`). Neutral directions — a ball's place along its groove when there is no
cage, a ring's spin — are handled by the Levenberg–Marquardt damping of
``scipy.optimize.least_squares``, which leaves them where they are.

The modal coordinates of modal bodies are unknowns too, with the residual of their modal equations
Q + I3ᵀRᵀg − Kη = 0 (contact modal forces Q, weight, modal stiffness), and so are the free frame
components of modal bodies, as for rigid bodies (their weight from the invariants). A driven
frame's centrifugal load is not included: velocities are zero.

Search: Levenberg–Marquardt (MINPACK, finite-difference Jacobian) with soft springs from each body
to its start, relaxed in stages (:data:`SPRING_STAGES`). The stages on the way are solved loosely
(:data:`STAGE_TOL`), the last one until the sum of squares stalls (:data:`STALL_TOL`), and further
to ``tol`` only when the forces left exceed :data:`GOOD_RESIDUAL` of the load scale. On the
full-scale slewing ring with the quick modal top (498 unknowns) every stage to ``tol`` took 174 191
force evaluations (66 s), the last stage creeping at about 2e-4 of the cost per iteration without
changing the result (the contacts on a sampled modal groove make the residual only piecewise
smooth); so: 11 004 evaluations (4.5 s), the same forces left (13.9 N of 6.8 MN).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..kernels.forces import STATUS_OK, compute_forces
from .explicit import DivergenceError, _failure_text
from .model import Model, State, make_work

__all__ = ["StaticEquilibriumError", "StaticResult", "static_equilibrium"]

log = logging.getLogger(__name__)


class StaticEquilibriumError(RuntimeError):
    """No static equilibrium was found; the message gives the residual and where it is largest."""


@dataclass(frozen=True)
class StaticResult:
    """Equilibrium state and how well it holds.

    ``force_residual_N`` is the largest force left on a free component, ``moment_residual_Nm``
    the largest moment; ``force_scale_N`` the largest external force (the residual's yardstick).
    """

    state: State
    force_residual_N: float
    moment_residual_Nm: float
    force_scale_N: float
    n_evaluations: int


def _spherical(inertia: np.ndarray) -> bool:
    return float(np.ptp(inertia)) <= 1e-9 * float(np.max(inertia))


def _rotate_quats(q: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """q ⊗ exp(φ/2) row by row for body-frame rotation vectors φ (k, 3); q (k, 4)."""
    angle = np.linalg.norm(phi, axis=1)
    safe = np.where(angle > 0, angle, 1.0)
    w2 = np.cos(angle / 2)
    v2 = (np.sin(angle / 2) / safe)[:, None] * phi
    w1, v1 = q[:, 0], q[:, 1:]
    out = np.concatenate([(w1 * w2 - np.sum(v1 * v2, axis=1))[:, None],
                          w1[:, None] * v2 + w2[:, None] * v1 + _cross(v1, v2)], axis=1)
    return out / np.linalg.norm(out, axis=1)[:, None]


#: the relative stiffness of the start springs, relaxed stage by stage (static_equilibrium)
SPRING_STAGES = (1.0, 1e-2, 1e-4, 0.0)
#: the solver tolerance of the stages before the last
STAGE_TOL = 1e-4
#: the relative reduction of the sum of squares per iteration below which the last stage has stalled
STALL_TOL = 1e-3
#: forces and moments (per length scale) left below this share of the load scale, and modal
#: equations left below this raceway displacement (m), need no further search
GOOD_RESIDUAL = 1e-5
GOOD_MODAL_RESIDUAL_M = 1e-10


def static_equilibrium(model: Model, state: State, tol: float = 1e-10, max_evaluations: int = 2000,
                       fixed_azimuth=()) -> StaticResult:
    """Find the equilibrium closest to ``state`` (returns a new state; ``state`` is unchanged).

    ``fixed_azimuth``: bodies (indices or names, e.g. the balls of a row) held at their angle about
    the world z axis, free radially and axially only — the quasi-static convention that the cage
    carries the circumferential forces (a deformed or undulated raceway pushes balls along it).

    Raises :class:`~mbd_core.multibody.explicit.DivergenceError` if forces become non-finite and
    :class:`StaticEquilibriumError` (a ``RuntimeError``) if no equilibrium is found (the residual
    stays above 1e-4 of the load scale).
    """
    # trial points of the solver may penetrate deeply: no divergence bound here
    a = model.arrays._replace(pair_delta_max=np.full(model.n_pairs, np.inf))
    free = a.body_free.astype(bool)
    free[a.modal_body] = a.modal_frame_free.astype(bool)  # the free components of modal frames
    held = {model.body(x) if isinstance(x, str) else int(x) for x in fixed_azimuth}
    unknowns = []  # (body, component 0..5)
    directions = []  # unit direction of each translation unknown
    for i in range(model.n_bodies):
        if i in held:
            psi = np.arctan2(state.q[i, 1], state.q[i, 0])
            for j, d in ((0, (np.cos(psi), np.sin(psi), 0.0)), (2, (0.0, 0.0, 1.0))):
                if free[i, j]:
                    unknowns.append((i, j))
                    directions.append(d)
        else:
            for j in range(3):
                if free[i, j]:
                    unknowns.append((i, j))
                    directions.append(np.eye(3)[j])
        if not _spherical(a.body_inertia[i]):
            for j in range(3, 6):
                if free[i, j]:
                    unknowns.append((i, j))
    body_idx = np.array([u[0] for u in unknowns], dtype=int)
    comp_idx = np.array([u[1] for u in unknowns], dtype=int)
    n_r = len(unknowns)
    work = make_work(model)
    base = state.copy()
    base.v[:] = 0.0
    base.eta_dot[:] = 0.0
    d_ref = _modal_displacement_scale(model)
    omega2 = np.maximum(a.modal_omega2, 1e-300)
    force_scale = _force_scale_N(model, free)
    lengths = [r for r in a.pair_radius if r > 0]
    length_scale = max(lengths) if lengths else 1.0
    trial = base.copy()
    count = [0]

    trans = comp_idx < 3
    rot = ~trans
    dirs = np.array(directions, dtype=float).reshape(-1, 3)
    rot_bodies = np.unique(body_idx[rot])
    shift = np.zeros((model.n_bodies, 3))
    phi = np.zeros((model.n_bodies, 3))

    def place(x):
        trial.eta[:] = x[n_r:]
        x = x[:n_r]
        shift[:] = 0.0
        np.add.at(shift, body_idx[trans], x[trans, None] * dirs)
        phi[body_idx[rot], comp_idx[rot] - 3] = x[rot]
        trial.q[:, :3] = base.q[:, :3] + shift
        if rot_bodies.size:
            trial.q[rot_bodies, 3:] = _rotate_quats(base.q[rot_bodies, 3:], phi[rot_bodies])

    spring = [0.0]

    def residual(x):
        place(x)
        count[0] += 1
        status, index = compute_forces(a, trial.t, trial.q, trial.v, trial.eta, trial.eta_dot, work)
        if status != STATUS_OK:
            raise DivergenceError("static equilibrium: " + _failure_text(model, status, index, trial.t, work))
        r = np.empty(n_r)
        f, t = _frame_loads(model, trial, work)
        r[trans] = np.sum(f[body_idx[trans]] * dirs, axis=1) / force_scale
        if rot_bodies.size:
            tb = _rotate_back_vecs(trial.q[body_idx[rot], 3:], t[body_idx[rot]])
            r[rot] = tb[np.arange(tb.shape[0]), comp_idx[rot] - 3] / (force_scale * length_scale)
        # in raceway displacement: (Q/ω² − η)·d, per 0.1 mm — the scale of the rigid unknowns
        r_modal = (_modal_residual(model, trial, work) / omega2 * d_ref) / 1e-4
        return np.concatenate([r - spring[0] * spring_k * x[:n_r], r_modal])

    if not unknowns and model.n_modal == 0:
        return StaticResult(base, 0.0, 0.0, force_scale, 0)
    x_scale = np.concatenate([np.where(comp_idx < 3, 1e-4, 1e-4 / length_scale), 1e-4 / d_ref])
    # A soft spring from each body to its start, so stiff that the body's own load moves it by
    # 1 mm, gives the solver a gradient while contacts are still open (Hertz forces have zero slope
    # at touch-down); it is relaxed in steps down to zero (continuation), so that bodies resting in
    # a clearance (a cage on its balls) do not jump out of contact on the way.
    own = np.abs(a.body_force[body_idx, 3 + comp_idx % 3]) / (force_scale * length_scale)
    own[trans] = np.abs(np.sum(a.body_force[body_idx[trans], :3] * dirs, axis=1)) / force_scale
    spring_k = np.maximum(own, 1e-6) / np.where(comp_idx < 3, 1e-3, 1e-3 / length_scale)
    x0 = np.concatenate([np.zeros(n_r), base.eta])

    def solve(x, t, ftol):
        return least_squares(residual, x, method="lm", x_scale=x_scale, xtol=t, ftol=ftol, gtol=t,
                             max_nfev=max_evaluations).x

    def left_over(x):
        """Largest force N, moment N·m and modal raceway displacement m left at x (no start springs)."""
        spring[0] = 0.0
        r_all = residual(x)
        r, r_modal = r_all[:n_r], r_all[n_r:]
        return (float(np.abs(r[comp_idx < 3]).max(initial=0.0)) * force_scale,
                float(np.abs(r[comp_idx >= 3]).max(initial=0.0)) * force_scale * length_scale,
                float(np.abs(r_modal).max(initial=0.0)) * 1e-4, r)

    for spring[0] in SPRING_STAGES[:-1]:
        x0 = solve(x0, max(tol, STAGE_TOL), max(tol, STAGE_TOL))  # stages on the way lead the search only
    # the last stage (no springs) until the sum of squares stalls; where contacts sit on the kinks of
    # a sampled modal groove the finite-difference Jacobian lets the search creep for hundreds of
    # iterations at a few 1e-4 of the cost each, with nothing left to gain: it goes on to ``tol``
    # only when the forces left are not yet below GOOD_RESIDUAL of the load scale
    spring[0] = SPRING_STAGES[-1]
    x = solve(x0, tol, max(tol, STALL_TOL))
    f_res, m_res, q_res, r = left_over(x)
    if max(f_res, m_res / length_scale) > GOOD_RESIDUAL * force_scale or q_res > GOOD_MODAL_RESIDUAL_M:
        spring[0] = SPRING_STAGES[-1]
        x = solve(x, tol, tol)
        f_res, m_res, q_res, r = left_over(x)
    place(x)
    if q_res > 1e-8:
        raise StaticEquilibriumError(f"static equilibrium not found: the modal equations are off by {q_res:.3g} m of raceway "
                           f"displacement after {count[0]} evaluations")
    if max(f_res, m_res / length_scale) > 1e-4 * force_scale:
        worst = int(np.argmax(np.abs(r)))
        axes = ("radial", "", "axial") if body_idx[worst] in held else "xyz"
        raise StaticEquilibriumError(
            f"static equilibrium not found: residual force {f_res:.3g} N, moment {m_res:.3g} N·m "
            f"(load scale {force_scale:.3g} N), largest on body {model.body_names[body_idx[worst]]!r} "
            f"(component {axes[comp_idx[worst] % 3]}{'' if comp_idx[worst] < 3 else ' rotation'}) after "
            f"{count[0]} evaluations — can the bearing carry the load?")
    result = trial.copy()
    result.v[:] = state.v
    result.eta_dot[:] = state.eta_dot
    log.info("static equilibrium: residual %.3g N, %.3g N·m after %d evaluations", f_res, m_res, count[0])
    return StaticResult(result, f_res, m_res, force_scale, count[0])


def _force_scale_N(model: Model, free: np.ndarray) -> float:
    """The largest external force on a body with a free translation, N (at least 1 N): its applied
    force (rigid bodies: with their weight) or, for a modal body, its weight m|g|, which its
    ``body_force`` leaves out (added in :func:`_frame_loads`). Without the latter a floating modal
    ring carrying the dead load was measured against a ball's weight, 2e4× too small, and the
    equilibrium search stalled or not depending on the modal basis."""
    a = model.arrays
    movable = free[:, :3].any(axis=1)
    scale = float(np.abs(a.body_force[movable, :3]).max(initial=0.0))
    g = float(np.linalg.norm(a.gravity))
    for j, i in enumerate(a.modal_body):
        if movable[i]:
            scale = max(scale, float(a.modal_mass[j]) * g)
    return max(scale, 1.0)


def _modal_displacement_scale(model: Model) -> np.ndarray:
    """Per modal coordinate, the largest raceway displacement per unit η (m/√kg) of its body's sampled
    grooves, or 1/√m of the body without any: the yardstick of the modal residual and unknowns."""
    a = model.arrays
    d = np.zeros(model.n_modal)
    for j in range(a.modal_body.shape[0]):
        o0, o1 = a.modal_off[j], a.modal_off[j + 1]
        d[o0:o1] = 1.0 / np.sqrt(a.modal_mass[j])
        for g in np.flatnonzero(a.groove_modal == j):
            tab = a.samp_disp[a.groove_samp_off[g]:a.groove_samp_off[g + 1], :, :o1 - o0]
            d[o0:o1] = np.maximum(d[o0:o1], np.linalg.norm(tab, axis=1).max(axis=0))
    return d


def _frame_loads(model: Model, state: State, work):
    """World force and moment on every body's reference point: the work's, plus the weight of the
    modal bodies (m g at the centre of mass S/m: moment R(S × Rᵀg) about the frame origin), which
    their body_force leaves out."""
    a = model.arrays
    if not a.modal_body.size:
        return work.body_f, work.body_t
    f, t = work.body_f.copy(), work.body_t.copy()
    for j, i in enumerate(a.modal_body):
        o0, o1 = a.modal_off[j], a.modal_off[j + 1]
        q = state.q[i:i + 1, 3:]
        S_w = _rotate_vecs(q, (a.modal_I2[j] + a.modal_I3[j, :, :o1 - o0] @ state.eta[o0:o1])[None])[0]
        f[i] += a.modal_mass[j] * a.gravity
        t[i] += _cross(S_w, a.gravity)
    return f, t


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a × b over the last axis (3), broadcast; np.cross's axis handling costs more than the
    products on the small arrays of each residual evaluation (about 60 % of a static search)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def _rotate_vecs(q: np.ndarray, x: np.ndarray) -> np.ndarray:
    """R(q_k) x_k row by row; q (k, 4), x (k, 3)."""
    w, v = q[:, :1], q[:, 1:]
    t = 2.0 * _cross(v, x)
    return x + w * t + _cross(v, t)


def _modal_residual(model: Model, state: State, work) -> np.ndarray:
    """Q + I3ᵀRᵀg − Kη of every modal coordinate, √kg·m/s²."""
    a = model.arrays
    r = np.empty(model.n_modal)
    for j, i in enumerate(a.modal_body):
        o0, o1 = a.modal_off[j], a.modal_off[j + 1]
        g_b = _rotate_back_vecs(state.q[i:i + 1, 3:], a.gravity[None])[0]
        r[o0:o1] = (work.modal_f[o0:o1] + a.modal_I3[j, :, :o1 - o0].T @ g_b
                    - a.modal_omega2[o0:o1] * state.eta[o0:o1])
    return r


def _rotate_back_vecs(q: np.ndarray, x: np.ndarray) -> np.ndarray:
    """R(q_k)ᵀ x_k row by row; q (k, 4), x (k, 3)."""
    w, v = q[:, :1], -q[:, 1:]
    t = 2.0 * _cross(v, x)
    return x + w * t + _cross(v, t)
