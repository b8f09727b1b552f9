"""Where a bearing's friction power goes: the power each family of internal forces dissipates over a
recorded run, beside the power the drives put in.

The force stage is evaluated again at recorded samples (as :mod:`.ring_torque` does) on copies of the
model that keep one family of forces. The power of a set of forces at a state is

    P = Σ_i (F_i · v_i + M_i · ω_i) + Σ_k f_k · η̇_k,

F_i and M_i the force and moment on body i about its centre (world), v_i its centre's velocity, ω_i
its angular velocity (world), f_k the generalized force on modal coordinate k. A family's loss is
−P of its dissipative part:

- **friction** of a group of contacts: the group evaluated as built, less the group without friction;
- **normal damping** of a group: the group without friction, less the same without damping (the
  Hertz spring alone, which stores energy and gives it back: its mean power over a long window is
  −ΔU/T, listed as ``elastic exchange``, not as a loss);
- **drag** of the fluid around the elements (all of it dissipative);
- **bushing damping** of each pair of bodies a set of bushings joins (bushings less their springs) and
  **squeeze-film dampers**;
- **modal damping** of the modal bodies, Σ 2ζω η̇² (the implicit modes' added damping of unresolved
  modes, a numerical device, is not counted).

The contact groups are a pair kind and the body its elements touch: each ring's raceway or groove,
each cage's pockets, and the elements among themselves.

The drives' power is what holds the prescribed velocity components: P_in = −Σ Q_j v_j over the held
components j (a ring driven about its axis: −T·Ω, T the elements' torque on it). The external loads
on free components (thrust, gravity of rigid bodies, load histories, unbalances, on a modal body's
modes too) add P_ext = Σ Q_ext,j v_j. Energy balance: over
a window, mean(P_in + P_ext) = Σ mean(losses) + ΔE/T, E the kinetic and elastic energy of the model
(for rigid bodies, whose held components turn at a constant speed about a principal axis of an
axisymmetric body; checked when every body is rigid, ``balance_residual_W``).

The mean of a loss over the samples approximates its time mean the better the denser the samples are
against its fluctuation; losses do not change sign, so a few hundred samples of a steady run suffice.
With implicit friction the integrator applies a damper frozen at each force evaluation, which the
re-evaluated friction only approximates.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial.transform import Rotation

from ..kernels.explicit import kinetic_energy
from .explicit import evaluate_forces
from .model import Model, State
from .ring_torque import internal_model

__all__ = ["PowerLosses", "contact_groups", "power_losses", "pair_subset"]

#: how a pair kind reads in a loss's name
_KIND_LABEL = {"ball_groove": "groove", "ball_ball": "element–element contacts", "roller_raceway": "raceway",
               "roller_rib": "rib", "element_pocket": "pockets"}


@dataclasses.dataclass(frozen=True)
class PowerLosses:
    """Mean powers over the samples a breakdown was taken at, W.

    ``losses``: name → mean dissipated power (≥ 0 up to the re-evaluation's sampling); ``input_W``
    the drives' mean power and ``input_error_W`` its standard error (the samples' standard deviation
    over √n: a torque whose ripple dwarfs its mean gives a drive power known only to this);
    ``external_W`` the external loads' mean power on free components; ``elastic_exchange_W`` name →
    mean power the contact springs took in (→ 0 on a long steady window); ``stored_W`` ΔE/T, the
    rate at which the model's kinetic and elastic energy grew over the window, and
    ``balance_residual_W`` mean(P_in + P_ext) − Σ losses − ΔE/T, both when every body is rigid (else
    None); ``samples`` how many states the means are over."""

    losses: dict
    input_W: float
    input_error_W: float
    external_W: float
    elastic_exchange_W: dict
    stored_W: float | None
    balance_residual_W: float | None
    samples: int

    @property
    def total_W(self) -> float:
        return float(sum(self.losses.values()))

    def shares(self) -> dict:
        """Each loss as a share of their sum (empty when nothing dissipates)."""
        total = self.total_W
        return {k: v / total for k, v in self.losses.items()} if total > 0.0 else {}

    def summary(self) -> dict:
        out = {"losses_W": dict(self.losses), "shares": self.shares(), "total_loss_W": self.total_W,
               "input_W": self.input_W, "input_error_W": self.input_error_W, "external_W": self.external_W,
               "elastic_exchange_W": dict(self.elastic_exchange_W), "samples": self.samples}
        if self.balance_residual_W is not None:
            out["stored_W"] = self.stored_W
            out["balance_residual_W"] = self.balance_residual_W
        return out


def pair_subset(model: Model, keep) -> Model:
    """The model with only the contact pairs ``keep`` (indices, ascending), everything else as it is."""
    a = model.arrays
    keep = np.asarray(keep, dtype=np.int64)
    counts = np.diff(a.pair_slice_off)[keep]
    drops = [a.slice_drop[a.pair_slice_off[c]:a.pair_slice_off[c + 1]] for c in keep]
    fields = {name: np.ascontiguousarray(getattr(a, name)[keep]) for name in a._fields
              if name.startswith("pair_") and name != "pair_slice_off"}
    fields["pair_slice_off"] = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    fields["slice_drop"] = np.concatenate(drops) if drops else np.zeros(0)
    return dataclasses.replace(model, arrays=a._replace(**fields), pair_names=tuple(model.pair_names[c] for c in keep),
                               pair_kinds=tuple(model.pair_kinds[c] for c in keep))


def contact_groups(model: Model) -> dict:
    """name → pair indices: one group per pair kind and the body the elements touch (a ring's raceway
    or groove, a cage's pockets); contacts between elements are one group."""
    a = model.arrays
    groups: dict = {}
    for c, kind in enumerate(model.pair_kinds):
        label = _KIND_LABEL.get(kind, kind)
        name = label if kind == "ball_ball" else f"{model.body_names[int(a.pair_b[c])]} {label}"
        groups.setdefault(name, []).append(c)
    return {k: np.array(v, dtype=np.int64) for k, v in groups.items()}


def _bushing_groups(model: Model) -> dict:
    """name → bushing indices: one group per pair of bodies a bushing joins ("<a>–<b> bushing damping")."""
    a = model.arrays
    groups: dict = {}
    for j, (i, k) in enumerate(zip(a.bush_a, a.bush_b)):
        groups.setdefault(f"{model.body_names[int(i)]}–{model.body_names[int(k)]} bushing damping", []).append(j)
    return {k: np.array(v, dtype=np.int64) for k, v in groups.items()}


def _bushing_subset(model: Model, keep) -> Model:
    """The model with only the bushings ``keep``."""
    a = model.arrays
    fields = {name: np.ascontiguousarray(getattr(a, name)[keep]) for name in a._fields if name.startswith("bush_")}
    return dataclasses.replace(model, arrays=a._replace(**fields))


def _only_contacts(model: Model, keep, friction: bool, damping: bool) -> Model:
    """The internal model with the pairs ``keep`` only, no drag, bushings or dampers; without friction
    or normal damping when asked."""
    sub = pair_subset(_none_else(model), keep)
    a = sub.arrays
    if not friction:
        a = a._replace(pair_fric=np.zeros_like(a.pair_fric), pair_fric_p=np.zeros_like(a.pair_fric_p),
                       pair_strips=np.zeros_like(a.pair_strips))
    if not damping:
        a = a._replace(pair_c=np.zeros_like(a.pair_c))
    return dataclasses.replace(sub, arrays=a)


def _none_else(model: Model, drag=False, bushings=False, dampers=False) -> Model:
    """The internal model (no external loads) keeping only the asked families besides the contacts."""
    inner = internal_model(model)
    a = inner.arrays
    empty = np.zeros(0, dtype=np.int64)
    fields = {}
    if not drag:
        fields["drag_body"] = empty
    if not bushings:
        fields["bush_a"] = empty
    if not dampers:
        fields["sfd_a"] = empty
    return dataclasses.replace(inner, arrays=a._replace(**fields))


def _energy(model: Model, state: State, work) -> float:
    """Kinetic energy of the rigid bodies and the contacts' and bushings' elastic energy, J."""
    w = evaluate_forces(model, state, work)
    return float(kinetic_energy(model.arrays.body_mass, model.arrays.body_inertia, state.v) + w.energy[0] + w.energy[1])


def _family_models(model: Model, groups: dict) -> tuple[dict, dict]:
    """The models that keep one family each: per contact group (as built, without friction, without
    friction and damping); per other family (as built[, its springs alone])."""
    variants = {name: tuple(_only_contacts(model, keep, f, d) for f, d in ((True, True), (False, True), (False, False)))
                for name, keep in groups.items()}
    none = np.zeros(0, dtype=np.int64)
    extra = {}
    if model.arrays.drag_body.size:
        extra["drag"] = (pair_subset(_none_else(model, drag=True), none),)
    for name, keep in _bushing_groups(model).items():
        bush = _bushing_subset(pair_subset(_none_else(model, bushings=True), none), keep)
        springs = dataclasses.replace(bush, arrays=bush.arrays._replace(bush_c=np.zeros_like(bush.arrays.bush_c)))
        extra[name] = (bush, springs)
    if model.arrays.sfd_a.size:
        extra["squeeze-film dampers"] = (pair_subset(_none_else(model, dampers=True), none),)
    return variants, extra


def power_losses(model: Model, run: dict, t_from_s: float = -np.inf, max_samples: int = 400) -> PowerLosses:
    """The loss breakdown (module docstring) over the recorded samples with t ≥ ``t_from_s`` (about
    ``max_samples`` of them, evenly picked)."""
    t = np.asarray(run["t"])
    window = np.flatnonzero(t >= t_from_s)
    if window.size < 2:
        raise ValueError(f"power_losses: fewer than two recorded samples after t = {t_from_s} s")
    picks = window[::max(1, int(np.ceil(window.size / max_samples)))]
    a = model.arrays
    n_eta = model.n_modal
    groups = contact_groups(model)
    variants, extra = _family_models(model, groups)
    internal = internal_model(model)
    works = {id(m): None for v in (*variants.values(), *extra.values()) for m in v}
    free = model.free_mask()
    held = ~free
    loss_sum = {name: 0.0 for name in [*(f"{g} friction" for g in groups), *(f"{g} damping" for g in groups), *extra]}
    if n_eta:
        loss_sum["modal damping"] = 0.0
    elastic_sum = {g: 0.0 for g in groups}
    p_in = np.zeros(picks.size)
    p_ext = 0.0
    work_full = work_int = None
    for row, k in enumerate(picks):
        state = State(float(t[k]), run["q"][k].copy(), run["v"][k].copy(),
                      run["eta"][k].copy() if n_eta else np.zeros(0), run["eta_dot"][k].copy() if n_eta else np.zeros(0))
        rot = Rotation.from_quat(state.q[:, 3:], scalar_first=True)
        omega = rot.apply(state.v[:, 3:])       # world angular velocities

        def power(m):
            works[id(m)] = work = evaluate_forces(m, state, works[id(m)])
            return _power_of(work, state, omega)

        for g, (full, no_fric, spring) in variants.items():
            pf, pn, pe = power(full), power(no_fric), power(spring)
            loss_sum[f"{g} friction"] -= pf - pn
            loss_sum[f"{g} damping"] -= pn - pe
            elastic_sum[g] += pe
        for name, ms in extra.items():
            spring = power(ms[1]) if len(ms) > 1 else 0.0
            loss_sum[name] -= power(ms[0]) - spring
        if n_eta:
            loss_sum["modal damping"] += float(np.sum(a.modal_damp * state.eta_dot ** 2))
        work_full = evaluate_forces(model, state, work_full)
        q_full = _generalized_of(work_full, rot)
        work_int = evaluate_forces(internal, state, work_int)
        q_int = _generalized_of(work_int, rot)
        p_in[row] = -float(np.sum((q_int * state.v)[held]))
        p_ext += float(np.sum(((q_full - q_int) * state.v)[free]))
        if n_eta:   # loads that reach the modes too (an unbalance on a modal rotor)
            p_ext += float((work_full.modal_f - work_int.modal_f) @ state.eta_dot)
    n = picks.size
    losses = {k: v / n for k, v in loss_sum.items()}
    stored = residual = None
    if not np.any(a.body_modal >= 0):
        ends = []
        for k in (picks[0], picks[-1]):
            state = State(float(t[k]), run["q"][k].copy(), run["v"][k].copy())
            ends.append(_energy(internal, state, None))
        stored = (ends[1] - ends[0]) / float(t[picks[-1]] - t[picks[0]])
        residual = float(p_in.mean()) + p_ext / n - sum(losses.values()) - stored
    error = float(p_in.std(ddof=1) / np.sqrt(n)) if n > 1 else float("inf")
    return PowerLosses(losses, float(p_in.mean()), error, p_ext / n, {g: v / n for g, v in elastic_sum.items()}, stored,
                       residual, int(n))


def _power_of(work, state: State, omega_world: np.ndarray) -> float:
    """P = Σ F·v + M·ω + f·η̇ of the forces in ``work`` (module docstring), W."""
    p = float(np.sum(work.body_f * state.v[:, :3]) + np.sum(work.body_t * omega_world))
    if state.eta_dot.size:
        p += float(work.modal_f @ state.eta_dot)
    return p


def _generalized_of(work, rot: Rotation) -> np.ndarray:
    """(n_b, 6) the forces in ``work`` on each body's components: world force, moment in the body frame
    (the frame of ω; ``rot`` the bodies' orientations)."""
    return np.hstack([work.body_f, rot.inv().apply(work.body_t)])
