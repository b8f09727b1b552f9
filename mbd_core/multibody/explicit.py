"""Explicit dynamic runs: the stable time step, the chunked run loop, and its errors.

The time step is limited by

* the contacts of each body, linearised at ``load_factor`` × their present load (at least the
  largest external force, so a run that starts unloaded is not underestimated): k = n F/δ at
  F = K δⁿ; the contacts of one body add up to the Gershgorin bound of the largest eigenvalue
  of M⁻¹K, ω_i² = Σ k (1 + [other body free]) / m_i, and likewise the damping; for velocity Verlet with damping ratio ζ the limit is h < (2/ω)(√(1 + ζ²) − ζ)
  (Belytschko, Liu & Moran, *Nonlinear Finite Elements for Continua and Structures*, §6.3);
* friction: below the transition speed the friction force acts as a damper of slope
  c = F·max dμ/du on the tangential effective mass m_t (translation plus rotation of the element
  about its centre, 1/m_t = 1/m + r²/I), and an explicit damper needs h < 2 m_t / c. Bodies that
  integrate their friction implicitly (``implicit_friction``) leave m_t; a pair with only such
  bodies does not limit the step. F is
  ``load_factor`` × the larger of the present load and, for raceway contacts, the external load
  shared by all pairs of that kind (1 % of that share for cage and rib contacts). Laws with
  μ(0⁺) > 0 (DREB falling, Kragelskii with D > 0) have no bounded slope and are not counted;
* bushings: as contacts, with their linear stiffness and damping.

The smallest limit times ``safety`` is the automatic step; a larger requested step is refused with
the contact that sets the limit. During the run a non-finite force, a penetration beyond a pair's
bound or a kinetic-energy runaway stops the run with :class:`DivergenceError` naming the contact or
body and the time; the record folder then says "failed" and holds only the samples before it.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..kernels.explicit import record_now, run_explicit, total_kinetic_energy
from ..kernels.forces import (STATUS_ENERGY, STATUS_MODAL, STATUS_NONFINITE, STATUS_OK, STATUS_PENETRATION,
                              STATUS_SQUEEZE_FILM, compute_forces)
from ..kernels.laws import friction_coefficient, friction_slope
from ..kernels.modal import modal_mass_matrix
from .model import RECORDED_CONTACT_FIELDS, Model, State, make_record_buffers, make_work
from .recorder import RunRecord, _modal_ranges, read_run, recorded_timestep_s

__all__ = ["StepLimit", "stable_timestep", "simulate", "SimulationError", "StepTooLargeError", "DivergenceError",
           "evaluate_forces"]

log = logging.getLogger(__name__)


class SimulationError(RuntimeError):
    """A run could not be done as asked."""


class StepTooLargeError(SimulationError):
    """The requested time step exceeds the explicit stability limit."""


class DivergenceError(SimulationError):
    """A run diverged; the message names the cause, the contact or body, and the time."""


@dataclass(frozen=True)
class StepLimit:
    """Stable explicit step: ``timestep_s`` (= safety × limit) and what sets the limit."""

    limit_s: float
    timestep_s: float
    reason: str


def evaluate_forces(model: Model, state: State, work=None):
    """Forces and contact outputs at a state (raises on a non-finite force); returns the work arrays."""
    work = make_work(model) if work is None else work
    status, index = compute_forces(model.arrays, state.t, state.q, state.v, state.eta, state.eta_dot, work)
    if status != STATUS_OK:
        raise DivergenceError(_failure_text(model, status, index, state.t, work))
    return work


def _external_force_scale(model: Model) -> float:
    a = model.arrays
    free = a.body_free[:, :3].any(axis=1)
    f = np.linalg.norm(a.body_force[:, :3], axis=1)[free]
    scale = float(f.max()) if f.size else 0.0
    if a.knot_coef.size:
        scale = max(scale, float(np.abs(a.knot_coef[:, 3, :3]).max()) * math.sqrt(3))
    return scale


def _friction_slope(code: int, p: np.ndarray) -> float:
    """max over slip speeds of dμ/du and μ/u; inf for laws with μ(0⁺) > 0 (no bounded slope)."""
    u = np.geomspace(1e-9, 20.0, 1500)
    mu = np.array([friction_coefficient(code, x, p[0], p[1], p[2], p[3]) for x in u])
    if mu[0] > 1e-3 * max(mu.max(), 1e-300):
        return math.inf
    slope = np.array([friction_slope(code, x, p[0], p[1], p[2], p[3]) for x in u])
    return float(max(np.max(mu / u), np.max(np.abs(slope))))


def stable_timestep(model: Model, state: State, load_factor: float = 3.0, safety: float = 0.8) -> StepLimit:
    """Stable explicit step for this model at this state (see the module docstring)."""
    a = model.arrays
    work = evaluate_forces(model, state)
    free_t = a.body_free[:, :3].any(axis=1)
    inv_m = np.where(free_t, 1.0 / a.body_mass, 0.0)
    f_floor = _external_force_scale(model)
    best = (math.inf, "no contact or bushing limits the step")
    # contacts in parallel on one body add up (Gershgorin row sums of M⁻¹K and M⁻¹C)
    k_sum = np.zeros(model.n_bodies)
    c_sum = np.zeros(model.n_bodies)
    stiffest = np.full(model.n_bodies, -1)
    k_lin_of = np.zeros(model.n_pairs)
    fric_cache: dict[tuple, float] = {}
    kind_count = np.bincount(a.pair_type, minlength=5)
    for c in range(model.n_pairs):
        ia, ib = a.pair_a[c], a.pair_b[c]
        w_inv = inv_m[ia] + inv_m[ib]
        if w_inv == 0.0:
            continue
        n_s = max(int(a.pair_slice_off[c + 1] - a.pair_slice_off[c]), 1)
        k_total, n = a.pair_k[c] * n_s, a.pair_n[c]
        f_ref = load_factor * max(work.contact_fn[c], f_floor, 1.0)
        delta = (f_ref / k_total) ** (1.0 / n)
        k_lin = n * f_ref / delta
        k_lin_of[c] = k_lin
        c_damp = a.pair_c[c] if a.pair_law[c] == 0 else a.pair_c[c] * f_ref
        both = 2.0 if inv_m[ia] > 0.0 and inv_m[ib] > 0.0 else 1.0
        for i in (ia, ib):
            if inv_m[i] > 0.0:
                k_sum[i] += k_lin * both * inv_m[i]
                c_sum[i] += c_damp * both * inv_m[i]
                if stiffest[i] < 0 or k_lin > k_lin_of[stiffest[i]]:
                    stiffest[i] = c
        if not np.any(a.pair_fric_p[c]):
            continue
        key = (int(a.pair_fric[c]), tuple(a.pair_fric_p[c]))
        if key not in fric_cache:
            fric_cache[key] = _friction_slope(key[0], a.pair_fric_p[c])
        slope = fric_cache[key]
        if not math.isfinite(slope) or slope == 0.0:
            continue  # no bounded slope, or no friction at all (μ = 0: frictionless)
        # friction acts at the load the contact carries: raceway contacts may carry a share of the
        # external load from the start, cage and rib contacts only what they carry now
        share = f_floor / max(kind_count[a.pair_type[c]], 1)
        if a.pair_type[c] not in (0, 2):
            share *= 0.01
        f_ref = load_factor * max(work.contact_fn[c], share, 1.0)
        r = a.pair_radius[c]
        # bodies with implicit friction do not limit the step (mbd_core.kernels.explicit)
        inv_mt = 0.0 if a.body_fric_implicit[ia] else (
            inv_m[ia] + (r * r / a.body_inertia[ia].min() if a.body_free[ia, 3:].any() else 0.0))
        inv_mt += 0.0 if a.body_fric_implicit[ib] else inv_m[ib]
        if inv_mt == 0.0:
            continue
        h_f = 2.0 / (inv_mt * slope * f_ref)
        if h_f < best[0]:
            best = (h_f, f"friction at contact {model.pair_names[c]!r} (slope dμ/du up to {slope:.3g} s/m at "
                         f"{f_ref:.3g} N on a tangential effective mass {1.0 / inv_mt:.3g} kg)")
    for j, i in enumerate(a.drag_body):     # drag damps the centre's motion (its linear part)
        c_sum[i] += a.drag_c[j, 0] * inv_m[i]
    for j in range(a.sfd_a.shape[0]):
        # a film is a damper: explicit damping is stable for h < 2/(c·(1/m_a + 1/m_b)), c its largest
        # coefficient |F|/|V| (at the table's end, where it is stiffest)
        o1 = a.sfd_table_off[j + 1]
        n_psi = a.sfd_table_size[j, 1]
        c_film = float(np.linalg.norm(a.sfd_table[o1 - n_psi:o1], axis=1).max()) / (1.0 - a.sfd_eps_max[j] ** 2) ** 2
        w_inv = inv_m[a.sfd_a[j]] + inv_m[a.sfd_b[j]]
        if c_film * w_inv > 0.0 and 2.0 / (c_film * w_inv) < best[0]:
            best = (2.0 / (c_film * w_inv), f"squeeze-film damper {model.damper_names[j]!r} (damping up to "
                                            f"{c_film:.3g} N·s/m at ε = {a.sfd_eps_max[j]:g})")
    for i in np.flatnonzero(k_sum > 0):
        omega = math.sqrt(k_sum[i])
        zeta = c_sum[i] / (2.0 * omega)
        h = 2.0 / omega * (math.sqrt(1.0 + zeta * zeta) - zeta)
        if h < best[0]:
            c = stiffest[i]
            best = (h, f"the contacts of body {model.body_names[i]!r} (stiffest: {model.pair_names[c]!r}, "
                       f"linearised stiffness {k_lin_of[c]:.3g} N/m at {load_factor:g}× its load; "
                       f"body mass {a.body_mass[i]:.3g} kg, damping ratio {zeta:.2g})")
    for j in range(a.bush_a.shape[0]):
        w_inv = inv_m[a.bush_a[j]] + inv_m[a.bush_b[j]]
        k = a.bush_k[j, :3].max()
        if w_inv == 0.0 or k == 0.0:
            continue
        omega = math.sqrt(k * w_inv)
        zeta = a.bush_c[j, :3].max() * math.sqrt(w_inv / k) / 2.0
        h = 2.0 / omega * (math.sqrt(1.0 + zeta * zeta) - zeta)
        if h < best[0]:
            best = (h, f"bushing {j} (stiffness {k:.3g} N/m)")
    h_modal, why = _modal_limit(model, state, work, k_lin_of)
    if h_modal < best[0]:
        best = (h_modal, why)
    return StepLimit(best[0], safety * best[0], best[1])


def _modal_limit(model: Model, state: State, work, k_lin_of: np.ndarray) -> tuple[float, str]:
    """Step limit of each modal body: the largest generalized eigenvalue of (K, M) over its integrated
    components u_f = (free frame components, η̇), M = M(η)_ff (:func:`mbd_core.kernels.modal.modal_mass_matrix`,
    the frame–mode coupling included), K = diag(0, K_η) (K_η only for explicit modes) + Σ_c 2 k_c J_cᵀJ_c
    over its contacts, J_c the displacement of contact c's point per unit u_f (frame translation,
    rotation about the frame origin, raceway displacement table D at the contact's angle), k_c the
    contact's linearised stiffness (factor 2: the element on the other side is free too, as in the
    contacts' Gershgorin bound)."""
    a = model.arrays
    best = (math.inf, "")
    for j, i in enumerate(a.modal_body):
        o0, o1 = int(a.modal_off[j]), int(a.modal_off[j + 1])
        mj = o1 - o0
        sel = np.concatenate([np.flatnonzero(a.modal_frame_free[j]), 6 + np.arange(mj)])
        n_frame = sel.size - mj
        inv = [np.ascontiguousarray(x) for x in (a.modal_I2[j], a.modal_I3[j, :, :mj], a.modal_I4[j, :, :mj],
                                                 a.modal_I5[j, :, :mj, :mj], a.modal_I6[j, :mj, :mj], a.modal_I7[j],
                                                 a.modal_I8[j, :, :, :mj], a.modal_I9[j, :, :, :mj, :mj])]
        M = modal_mass_matrix(float(a.modal_mass[j]), *inv, np.ascontiguousarray(state.eta[o0:o1]),
                              np.zeros((6 + mj, 6 + mj)))[np.ix_(sel, sel)]
        K = np.zeros((sel.size, sel.size))
        if not a.modal_implicit[j]:
            K[n_frame:, n_frame:] = np.diag(a.modal_omega2[o0:o1])
        R = _rotation_matrix(state.q[i, 3:])
        for c in np.flatnonzero((a.pair_b == i) | (a.pair_a == i)):
            other = a.pair_a[c] if a.pair_b[c] == i else a.pair_b[c]
            r = R.T @ (state.q[other, :3] - state.q[i, :3])  # the contact near the other body's centre
            J = np.zeros((3, 6 + mj))
            J[:, :3] = np.eye(3)
            J[:, 3:6] = -_skew(r)
            g = a.pair_geom[c]
            if a.pair_type[c] == 0 and a.groove_modal[g] == j:
                s0, s1 = a.groove_samp_off[g], a.groove_samp_off[g + 1]
                th = a.samp_theta[s0:s1]
                k = int(np.argmin(np.abs(np.angle(np.exp(1j * (th - work.contact_theta[c]))))))
                J[:, 6:] = a.samp_disp[s0 + k, :, :mj]
            J = J[:, sel]
            K += 2.0 * k_lin_of[c] * J.T @ J
        if sel.size == 0:
            continue
        lam = float(scipy.linalg.eigh(K, M, eigvals_only=True)[-1])
        if lam <= 0.0:
            continue
        zeta = float(np.max(a.modal_damp[o0:o1] / (2.0 * np.sqrt(np.maximum(a.modal_omega2[o0:o1], 1e-300)))))
        zeta = 0.0 if a.modal_implicit[j] else min(zeta, 1.0)
        h = 2.0 / math.sqrt(lam) * (math.sqrt(1.0 + zeta * zeta) - zeta)
        if h < best[0]:
            f_max = 0.0 if a.modal_implicit[j] else math.sqrt(a.modal_omega2[o1 - 1]) / (2 * math.pi)
            best = (h, f"modal body {model.body_names[i]!r} (highest kept mode {f_max:.4g} Hz; with its frame's free "
                       f"components and the contacts on it: {math.sqrt(lam) / (2 * math.pi):.4g} Hz"
                       + ("; implicit modes: contacts only" if a.modal_implicit[j] else "") + ")")
    return best


def _rotation_matrix(q) -> np.ndarray:
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _skew(a) -> np.ndarray:
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _failure_text(model: Model, status: int, index: int, t: float, work) -> str:
    if status == STATUS_PENETRATION:
        name = model.pair_names[index]
        return (f"penetration {work.contact_delta[index]:.3g} m at contact {name!r} beyond its bound "
                f"{model.arrays.pair_delta_max[index]:.3g} m at t = {t:.6g} s (time step too large for the "
                f"contact stiffness, or a load the bearing cannot carry)")
    if status == STATUS_NONFINITE:
        if index < model.n_pairs:
            return f"non-finite force at contact {model.pair_names[index]!r} at t = {t:.6g} s"
        return f"non-finite force on body {model.body_names[index - model.n_pairs]!r} at t = {t:.6g} s"
    if status == STATUS_ENERGY:
        return f"kinetic energy ran away (beyond the limit) at t ≈ {t:.6g} s: the run is unstable"
    if status == STATUS_SQUEEZE_FILM:
        return (f"the journal of squeeze-film damper {model.damper_names[index]!r} reached the end of its force "
                f"table (ε = {model.arrays.sfd_eps_max[index]:g} of the clearance) at t = {t:.6g} s: the race rides "
                "on the housing; raise the clearance or the damper length, or lower the load")
    if status == STATUS_MODAL:
        return (f"the mass matrix of a modal body is no longer positive definite at t ≈ {t:.6g} s (modal "
                "coordinates beyond the small-deformation range): the run is unstable")
    return f"run failed with status {status} at t = {t:.6g} s"


def simulate(model: Model, state: State, t_end_s: float, timestep_s: float | None = None, record_every: int = 10,
             folder=None, resume: bool = False, chunk_samples: int = 500, energy_limit_J: float | None = None,
             allow_unstable: bool = False, skip_open_contacts: bool = True):
    """Integrate with the explicit scheme from ``state`` to ``t_end_s``.

    Parameters
    ----------
    model, state
        The state is advanced in place.
    timestep_s : float or None
        None: the automatic stable step. A larger step than the stable limit is refused
        (:class:`StepTooLargeError`) unless ``allow_unstable``.
    record_every : int
        Store one sample every this many steps (and the start).
    folder : path or None
        Write the record there in chunks, with a checkpoint after each (see :mod:`.recorder`);
        None keeps the samples in memory only.
    resume : bool
        Continue the run recorded in ``folder`` from its checkpoint (``state`` is then ignored; the
        time step and ``record_every`` must be those of the record, None takes the recorded step).
    skip_open_contacts : bool
        On the steps that are not recorded, a contact on a modal body's sampled surface whose
        rigid-geometry gap exceeds the bound of the surface's motion is taken as open without forming
        its deformation (:mod:`mbd_core.kernels.forces`): the same forces, fewer modal sums where many
        contacts are open (unloaded rollers, cage pockets). False forms every contact on every step.

    Returns
    -------
    dict of numpy arrays (see :func:`mbd_core.multibody.recorder.read_run`), and
    ``surface_contacts_skipped``: of the sampled-surface contacts checked on the steps that may skip,
    the fraction skipped as open (0 without modal bodies).
    """
    if not (math.isfinite(t_end_s) and t_end_s > state.t):
        raise ValueError(f"simulate: t_end_s must be later than the state's time {state.t}, got {t_end_s!r}")
    if not (isinstance(record_every, int) and record_every >= 1):
        raise ValueError(f"simulate: record_every must be an integer ≥ 1, got {record_every!r}")
    a = model.arrays
    work = make_work(model)
    work.flex_skip[0] = int(bool(skip_open_contacts))
    if resume:
        if folder is None:
            raise ValueError("simulate: resume needs the record folder")
        if timestep_s is None:
            timestep_s = recorded_timestep_s(folder)
        rec_file = RunRecord(folder, model, timestep_s, record_every, t_end_s, resume=True)
        ck = rec_file.load_checkpoint()
        t_origin, step = float(ck["t_origin"]), int(ck["step"])
        state.q[:], state.v[:] = ck["q"], ck["v"]
        state.eta, state.eta_dot = ck["eta"].copy(), ck["eta_dot"].copy()
        work.body_f[:], work.body_t[:], work.modal_f[:] = ck["body_f"], ck["body_t"], ck["modal_f"]
        if "fric_c" in ck:  # (checkpoints written before implicit friction existed lack them: zero there)
            work.fric_c[:], work.fric_v[:] = ck["fric_c"], ck["fric_v"]
        for f in RECORDED_CONTACT_FIELDS:
            if f in ck:  # (checkpoints written before points and normals were recorded lack them: zero there)
                getattr(work, f"contact_{f}")[:] = ck[f]
        h = timestep_s
        state.t = t_origin + step * h
        if t_end_s < state.t:
            raise ValueError(f"simulate: t_end_s = {t_end_s!r} s is before the checkpoint's time {state.t!r} s "
                             f"in {folder}; a resume can only run on")
        if energy_limit_J is None and "energy_limit_J" in ck:
            energy_limit_J = float(ck["energy_limit_J"])  # the original run's limit
    else:
        limit = stable_timestep(model, state)
        h = limit.timestep_s if timestep_s is None else float(timestep_s)
        if not (math.isfinite(h) and h > 0):
            raise ValueError(f"simulate: timestep_s must be positive, got {timestep_s!r}")
        if h > limit.limit_s and not allow_unstable:
            raise StepTooLargeError(
                f"time step {h:.3g} s exceeds the explicit stability limit {limit.limit_s:.3g} s set by "
                f"{limit.reason}; use at most {limit.timestep_s:.3g} s")
        log.info("explicit step %.3g s (limit %.3g s from %s)", h, limit.limit_s, limit.reason)
        t_origin, step = float(state.t), 0
        _check_modal_state(model, state)
        status, index = compute_forces(a, state.t, state.q, state.v, state.eta, state.eta_dot, work)
        if status != STATUS_OK:
            raise DivergenceError(_failure_text(model, status, index, state.t, work))
        rec_file = RunRecord(folder, model, h, record_every, t_end_s) if folder is not None else None
    n_total = int(round((t_end_s - t_origin) / h))
    e_limit = energy_limit_J if energy_limit_J is not None else 1e3 * max(
        total_kinetic_energy(a, state.q, state.v, state.eta, state.eta_dot, work), 10.0)
    rec = make_record_buffers(model, chunk_samples)
    in_memory: list[dict] = []

    def store(k):
        if k == 0:
            return
        if rec_file is not None:
            rec_file.write_chunk(rec, k)
        else:
            in_memory.append({f: getattr(rec, f)[:k].copy() for f in rec._fields})

    if step == 0:
        record_now(a, state.q, state.v, state.eta, state.eta_dot, work, state.t, 0, rec)
        store(1)
    while step < n_total:
        n_run = min(chunk_samples * record_every, n_total - step)
        status, index, done, k = run_explicit(a, state.q, state.v, state.eta, state.eta_dot, work, t_origin, step,
                                              n_run, h, record_every, rec, e_limit)
        step += done
        state.t = t_origin + step * h
        store(k)
        if status != STATUS_OK:
            text = _failure_text(model, status, index, t_origin + (step + 1) * h, work)
            if rec_file is not None:
                rec_file.finish(f"failed: {text}")
            raise DivergenceError(text)
        if rec_file is not None:
            rec_file.write_checkpoint(t_origin, step, state, work, e_limit)
    checked, skipped = work.flex_bound[:, 2].sum(), work.flex_bound[:, 3].sum()
    if checked:
        log.info("surface contacts: %d of %d checks skipped as open beyond the surfaces' motion bound",
                 skipped, checked)
    if rec_file is not None:
        rec_file.finish("complete")
        out = read_run(folder)
    else:
        out = {f: np.concatenate([c[f] for c in in_memory]) for f in rec._fields}
        out.update(body_names=list(model.body_names), pair_names=list(model.pair_names),
                   pair_kinds=list(model.pair_kinds), status="complete", timestep_s=h, every=record_every,
                   modal_ranges={n: [int(i), int(j)] for n, i, j in _modal_ranges(model)})
    out["surface_contacts_skipped"] = float(skipped / checked) if checked else 0.0
    return out


def _check_modal_state(model: Model, state: State) -> None:
    n = model.n_modal
    for name in ("eta", "eta_dot"):
        x = np.asarray(getattr(state, name), float)
        if x.shape != (n,) or not np.all(np.isfinite(x)):
            raise ValueError(f"simulate: state.{name} must be {n} finite modal coordinates, got shape {x.shape}")
