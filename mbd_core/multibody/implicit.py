"""Implicit generalized-α integration of a multibody model, rigid and modal bodies: the reference for
the explicit runs.

Scheme (Chung & Hulbert, J. Appl. Mech. 60 (1993) 371) in its Lie-group form on R³ × SO(3) per
body frame, times the vector space of the modal coordinates η (Arnold & Brüls, Multibody Syst.
Dyn. 18 (2007) 185; Brüls & Cardona, J. Comput. Nonlinear Dyn. 5 (2010) 031002). Per step of size h,
with v̇ the true and a the pseudo-acceleration of the free velocity components (v = (ṙ world,
ω body) of every body, see :mod:`.model`, followed by η̇):

    (1 − α_m) a_{n+1} + α_m a_n = (1 − α_f) v̇_{n+1} + α_f v̇_n
    Δq_n = v_n + h (½ − β) a_n + h β a_{n+1}
    q_{n+1} = q_n ∘ exp(h Δq_n)                          (r + h Δq_r,  q ⊗ exp(h Δq_ω / 2),  η + h Δq_η)
    v_{n+1} = v_n + h (1 − γ) a_n + h γ a_{n+1}
    v̇_{n+1} = f(t_{n+1}, q_{n+1}, v_{n+1})              (:mod:`..kernels.implicit`)

with the coefficients of the spectral radius at infinity ρ∞ ∈ [0, 1] (Chung & Hulbert eqs. 25, 17,
20)

    α_m = (2ρ∞ − 1)/(ρ∞ + 1),  α_f = ρ∞/(ρ∞ + 1),  γ = ½ + α_f − α_m,  β = ¼ (γ + ½)².

f is Newton–Euler for rigid bodies. For modal bodies it solves M(η) u̇ = rhs on the integrated
components (the frame's as in ``modal_frame_free``, and all of η̇): the equations of motion of the
explicit scheme (:mod:`..kernels.modal_step`), with the elastic and damping forces −Kη − Dη̇ always
in f — the ``implicit_modes`` option of a modal body concerns the explicit scheme only.

The method is second order in q and v (Arnold & Brüls 2007, Theorem 2) and unconditionally stable
for linear systems; ρ∞ = 1 has no numerical dissipation (for a linear oscillator it is the
trapezoidal rule), smaller ρ∞ damps the unresolved high frequencies (contact rattle, modes above
1/h). Start: a_0 = v̇_0 = f(t_0, q_0, v_0). Held components (``body_free`` = 0, or
``modal_frame_free`` = 0 for a modal body's frame) keep their velocity: v̇ = a = 0, Δq = v.

The unknowns v̇_{n+1} of the free components solve the residual v̇ − f = 0 by modified Newton: a
forward-difference Jacobian (dense, LU-factorised) is kept from step to step and recomputed at
the current iterate when a correction is more than 1 % of the one before (the contraction test of
Hairer & Wanner's RADAU5, *Solving ODEs II*, §IV.8) or a trial state fails; the predictor is
v̇_{n+1} = v̇_n. With h² β' = h² β (1 − α_f)/(1 − α_m) the change of
q_{n+1} per unit change of v̇_{n+1}, an iterate x is accepted when every component of its Newton
correction is below ``tol`` × max(‖x‖∞, ‖v̇_n‖∞, 1 m/s², rad/s² or √kg/s²) or moves the
configuration by less than four units of round-off, 4 ε |q_k| / (h² β') (|q_k| the body's distance
from the origin for translations, 1 for rotations, the body's largest |η_k| for modal coordinates):
below that the residual is round-off noise. The difference step of Jacobian column k is
max(√ε |x_k|, δ_ref / (h² β')), at least δ_ref = 1e-9 m, rad or √kg of configuration change.
"""

from __future__ import annotations

import logging
import math
from collections import namedtuple
from dataclasses import dataclass

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from ..kernels.explicit import record_now
from ..kernels.forces import STATUS_OK
from ..kernels.implicit import fd_jacobian, residual, step_accelerations
from .explicit import DivergenceError, _failure_text
from .model import Model, State, make_record_buffers, make_work
from .recorder import _modal_ranges

__all__ = ["simulate_implicit", "gen_alpha_coefficients", "GenAlphaCoefficients"]

log = logging.getLogger(__name__)

#: α_m, α_f, β, γ of the generalized-α method (dimensionless).
GenAlphaCoefficients = namedtuple("GenAlphaCoefficients", "alpha_m alpha_f beta gamma")

#: Arrays of one step. Generalized velocities and accelerations are flat (n_u,) vectors, n_u =
#: 6 n_b + n_η: the bodies' (n_b, 6) components row by row, then the modal rates η̇. Start of the
#: step: q0 (n_b, 7), e0 = η_n (n_η,), v0, vd0 = v̇_n, a0 = a_n. Trial end state (filled by the
#: residual): vd1 = v̇_{n+1}, a1 = a_{n+1}, dq = Δq_n, q1 (n_b, 7), e1 (n_η,), v1,
#: f1 = f(t_{n+1}, q1, e1, v1). free_idx (n_free,) int64: indices into n_u of the free components;
#: res, res_p (n_free,): residual at x and at a perturbed x.
StepArrays = namedtuple("StepArrays", "free_idx q0 e0 v0 vd0 a0 vd1 a1 dq q1 e1 v1 f1 res res_p")

CONFIG_STEP_REF = 1e-9   # m, rad or √kg: smallest configuration change of a Jacobian difference
ACC_FLOOR = 1.0          # m/s², rad/s², √kg/s²: absolute floor of the Newton tolerance scale
SLOW_RATE = 0.01         # contraction per iteration above which the Jacobian is recomputed
ROUNDOFF_ULPS = 4.0      # configuration round-off units below which a correction is noise


def gen_alpha_coefficients(rho_inf: float) -> GenAlphaCoefficients:
    """Coefficients of the spectral radius at infinity ρ∞ ∈ [0, 1] (Chung & Hulbert 1993)."""
    if not (isinstance(rho_inf, (int, float, np.floating)) and 0.0 <= rho_inf <= 1.0):
        raise ValueError(f"generalized-α: rho_inf must lie in [0, 1], got {rho_inf!r}")
    am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0)
    af = rho_inf / (rho_inf + 1.0)
    gamma = 0.5 + af - am
    return GenAlphaCoefficients(am, af, 0.25 * (gamma + 0.5) ** 2, gamma)


def _free_mask(model: Model) -> np.ndarray:
    """(n_u,) bool: the integrated components of the generalized velocity (rigid, modal frames, η̇)."""
    return np.concatenate([model.free_mask().reshape(-1), np.ones(model.n_modal, dtype=bool)])


def _make_step_arrays(model: Model, state: State) -> StepArrays:
    nb, ne = model.n_bodies, model.n_modal
    free_idx = np.flatnonzero(_free_mask(model)).astype(np.int64)
    z = lambda: np.zeros(6 * nb + ne)  # noqa: E731
    v0 = np.concatenate([np.asarray(state.v, dtype=float).reshape(-1), np.asarray(state.eta_dot, dtype=float)])
    return StepArrays(free_idx=free_idx, q0=np.array(state.q, dtype=float), e0=np.array(state.eta, dtype=float),
                      v0=v0, vd0=z(), a0=z(), vd1=z(), a1=z(), dq=z(), q1=np.zeros((nb, 7)), e1=np.zeros(ne),
                      v1=z(), f1=z(), res=np.zeros(free_idx.size), res_p=np.zeros(free_idx.size))


def _body_view(s: StepArrays, name: str) -> np.ndarray:
    """The (n_b, 6) body part of a generalized vector of ``s``, a view."""
    nb = s.q0.shape[0]
    return getattr(s, name)[:6 * nb].reshape(nb, 6)


def _rate_view(s: StepArrays, name: str) -> np.ndarray:
    """The η̇ (or η̈) part of a generalized vector of ``s``, a view."""
    return getattr(s, name)[6 * s.q0.shape[0]:]


def _config_gain(h: float, c: GenAlphaCoefficients) -> float:
    """h² β': change of q_{n+1} (m, rad) per unit change of v̇_{n+1} (m/s², rad/s²)."""
    return h * h * c.beta * (1.0 - c.alpha_f) / (1.0 - c.alpha_m)


def _roundoff_floor(model: Model, s: StepArrays, gain: float) -> np.ndarray:
    """(n_free,) corrections of v̇_{n+1} that move the configuration by a few round-off units."""
    size = np.ones((s.q0.shape[0], 6))
    size[:, :3] = np.abs(s.q0[:, :3]).max(axis=1, keepdims=True)
    off = model.arrays.modal_off
    eta_size = np.zeros(s.e0.size)
    for o0, o1 in zip(off[:-1], off[1:]):
        eta_size[o0:o1] = np.abs(s.e0[o0:o1]).max(initial=0.0)
    return ROUNDOFF_ULPS * np.finfo(float).eps * np.concatenate([size.reshape(-1), eta_size])[s.free_idx] / gain


@dataclass
class _IterationMatrix:
    """LU factors of the residual Jacobian, reused across iterations and steps, and counters."""

    gain: float
    eps_floor: float
    lu: tuple | None = None
    n_jacobians: int = 0
    n_iterations: int = 0


def _refactor(model, t1, h, c, s, work, x, mat: _IterationMatrix) -> None:
    n = x.size
    jac = np.empty((n, n))
    status, index = fd_jacobian(model.arrays, t1, h, c, s, work, x, mat.eps_floor, jac)
    if status != STATUS_OK:
        raise DivergenceError(_failure_text(model, status, index, t1, work))
    if not np.all(np.isfinite(jac)):
        raise DivergenceError(f"non-finite Jacobian of the generalized-α residual at t = {t1:.6g} s")
    mat.lu = lu_factor(jac, check_finite=False)
    mat.n_jacobians += 1


def _solve_step(model, t1, h, c, s, work, mat: _IterationMatrix, tol, max_iter) -> np.ndarray:
    """Free accelerations v̇_{n+1}; on return the trial arrays of ``s`` and ``work`` hold its end state."""
    x0 = s.vd0[s.free_idx]
    x = x0.copy()
    floor = max(float(np.max(np.abs(x0), initial=0.0)), ACC_FLOOR)
    noise = _roundoff_floor(model, s, mat.gain)
    fresh_here = fresh_step = mat.lu is None
    if fresh_here:
        _refactor(model, t1, h, c, s, work, x, mat)
    prev, scale = math.inf, floor
    for _ in range(max_iter + 1):
        status, index = residual(model.arrays, t1, h, c, s, work, x, s.res)
        ok = status == STATUS_OK and np.all(np.isfinite(s.res))
        if not ok:
            if fresh_step:
                raise DivergenceError(_failure_text(model, status, index, t1, work) if status != STATUS_OK else
                                      f"non-finite accelerations in the Newton iteration at t = {t1:.6g} s")
            x[:] = x0   # a stale matrix led astray: restart from the predictor with a new one
            _refactor(model, t1, h, c, s, work, x, mat)
            fresh_here = fresh_step = True
            prev = math.inf
            continue
        dx = lu_solve(mat.lu, s.res, check_finite=False)
        size = float(np.max(np.abs(dx), initial=0.0))
        scale = max(float(np.max(np.abs(x), initial=0.0)), floor)
        if np.all(np.abs(dx) <= np.maximum(tol * scale, noise)):
            return x
        if size > SLOW_RATE * prev and not fresh_here:
            _refactor(model, t1, h, c, s, work, x, mat)
            fresh_step = True
            dx = lu_solve(mat.lu, s.res, check_finite=False)
            size = float(np.max(np.abs(dx), initial=0.0))
        x -= dx
        mat.n_iterations += 1
        fresh_here, prev = False, size
    raise DivergenceError(
        f"Newton iteration of the generalized-α step did not converge in {max_iter} iterations at "
        f"t = {t1:.6g} s (last correction {prev:.3g}, tolerance {tol * scale:.3g} m/s², rad/s² or √kg/s²): "
        f"reduce timestep_s")


def simulate_implicit(model: Model, state: State, t_end_s: float, timestep_s: float, rho_inf: float = 0.9,
                      record_every: int = 1, tol: float = 1e-10, max_iter: int = 20):
    """Integrate with the generalized-α scheme (module docstring) from ``state`` to ``t_end_s``.

    Parameters
    ----------
    model, state
        The state is advanced in place (to the last completed step if the run fails).
    t_end_s, timestep_s : float, s
        End time and fixed step h; the run makes round((t_end_s − t) / h) steps.
    rho_inf : float
        Spectral radius at infinity ρ∞ ∈ [0, 1]: 1 no numerical dissipation, 0 the most.
    record_every : int
        Store one sample every this many steps (and the start).
    tol : float
        Relative tolerance of the Newton correction of the accelerations.
    max_iter : int
        Newton iterations allowed per step.

    Returns
    -------
    dict of numpy arrays, as :func:`mbd_core.multibody.simulate` kept in memory: t (k,) s,
    q (k, n_b, 7), v (k, n_b, 6), eta and eta_dot (k, n_η), contact outputs fn, delta, slip, ft,
    angle, theta (k, n_c), and body_names, pair_names, pair_kinds, status, timestep_s, every,
    modal_ranges.

    Raises
    ------
    DivergenceError
        Non-finite forces, a penetration beyond a pair's bound, a modal mass matrix that is no
        longer positive definite, or no Newton convergence; the message names the time.
    """
    if not (math.isfinite(t_end_s) and t_end_s > state.t):
        raise ValueError(f"simulate_implicit: t_end_s must be later than the state's time {state.t}, got {t_end_s!r}")
    if not (isinstance(timestep_s, (int, float, np.floating)) and math.isfinite(timestep_s) and timestep_s > 0):
        raise ValueError(f"simulate_implicit: timestep_s must be positive, got {timestep_s!r}")
    if not (isinstance(record_every, int) and record_every >= 1):
        raise ValueError(f"simulate_implicit: record_every must be an integer ≥ 1, got {record_every!r}")
    if not (isinstance(max_iter, int) and max_iter >= 1):
        raise ValueError(f"simulate_implicit: max_iter must be an integer ≥ 1, got {max_iter!r}")
    if not (math.isfinite(tol) and tol > 0):
        raise ValueError(f"simulate_implicit: tol must be positive, got {tol!r}")
    for name in ("eta", "eta_dot"):
        x = np.asarray(getattr(state, name), float)
        if x.shape != (model.n_modal,) or not np.all(np.isfinite(x)):
            raise ValueError(f"simulate_implicit: state.{name} must be {model.n_modal} finite modal coordinates, "
                             f"got shape {x.shape}")
    c = gen_alpha_coefficients(rho_inf)
    h = float(timestep_s)
    a = model.arrays
    work = make_work(model)
    s = _make_step_arrays(model, state)
    v0, ed0 = _body_view(s, "v0"), _rate_view(s, "v0")
    t0 = float(state.t)
    n_total = int(round((t_end_s - t0) / h))
    status, index = step_accelerations(a, t0, s.q0, v0, s.e0, ed0, work, _body_view(s, "vd0"), _rate_view(s, "vd0"))
    if status != STATUS_OK:
        raise DivergenceError(_failure_text(model, status, index, t0, work))
    s.a0[:] = s.vd0
    rec = make_record_buffers(model, n_total // record_every + 1)
    record_now(a, s.q0, v0, s.e0, ed0, work, t0, 0, rec)
    k = 1
    gain = _config_gain(h, c)
    mat = _IterationMatrix(gain=gain, eps_floor=CONFIG_STEP_REF / gain)
    try:
        for step in range(1, n_total + 1):
            t1 = t0 + step * h
            _solve_step(model, t1, h, c, s, work, mat, tol, max_iter)
            for name in ("q", "e", "v", "vd", "a"):
                getattr(s, name + "0")[:] = getattr(s, name + "1")
            state.t = t1
            if step % record_every == 0:
                record_now(a, s.q0, v0, s.e0, ed0, work, t1, k, rec)
                k += 1
    finally:
        state.q[:], state.v[:] = s.q0, v0
        state.eta[:], state.eta_dot[:] = s.e0, ed0
    log.info("generalized-α (ρ∞ = %g, h = %.3g s): %d steps, %d Newton iterations, %d Jacobians", rho_inf, h,
             n_total, mat.n_iterations, mat.n_jacobians)
    out = {f: getattr(rec, f)[:k].copy() for f in rec._fields}
    out.update(body_names=list(model.body_names), pair_names=list(model.pair_names),
               pair_kinds=list(model.pair_kinds), status="complete", timestep_s=h, every=record_every,
               modal_ranges={n: [int(i), int(j)] for n, i, j in _modal_ranges(model)})
    return out
