"""Where a bearing's drive power goes (:mod:`mbd_core.multibody.power_losses`).

References:
- energy balance of the multibody model: over a window, the drives' and external loads' mean power
  equals the mean dissipation plus the change of kinetic and elastic energy over the window (the
  recorded states' own energies, an independent sum);
- the drives' power of a ring turning at Ω about the axis is −T·Ω, T the elements' torque on it
  (:func:`mbd_core.multibody.ring_torque.axial_torques`, moments about the axis);
- the power of a Stokes drag c·v on a body moving at v is c·|v|² (computed here from the recorded
  velocities);
- sliding friction of constant coefficient A at slip speed u under the normal force F_n dissipates
  A·F_n·u (Coulomb); a race turning at Ω under a ball at rest slips at u = Ω·ρ at a contact point ρ
  from the axis, across the meridian plane that holds the contact normal.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from cases.dma.presets import PRESETS
from cases.dma.torque import build, stokes_drag_N_s_m
from mbd_core.multibody import evaluate_forces, simulate, stable_timestep
from mbd_core.multibody.bearings import set_rolling_velocities
from mbd_core.multibody.power_losses import contact_groups, pair_subset, power_losses
from mbd_core.multibody.ring_torque import axial_torques, internal_model
from mbd_core.multibody.statics import static_equilibrium

SETTLED_FROM_S = 0.008


def _dma(**traction):
    case = PRESETS["dma-torque"].with_(study={"kind": "torque"}, traction=traction or {"model": "linear"})
    model, state, rows, inner, outer = build(case)
    start = static_equilibrium(model, state).state
    return case, model, start, rows, inner, outer


@pytest.fixture(scope="module")
def ehd_run():
    case, model, start, rows, inner, outer = _dma()
    set_rolling_velocities(model, start, rows.elements, outer, inner)
    step = stable_timestep(model, start).timestep_s
    run = simulate(model, start, 0.02, timestep_s=step, record_every=max(1, int(2e-5 / step)))
    return case, model, run, rows, inner, outer


def test_drive_power_balances_the_losses_and_the_energy_change(ehd_run):
    """The DMA bearing at 267 N, 60 rev/min, κ = 1·u over its settled part: drives + loads − losses −
    ΔE/T within 1e-4 of the drive power (measured 5.5e-6); the drive power is −T_outer·Ω to 1e-9."""
    case, model, run, rows, inner, outer = ehd_run
    losses = power_losses(model, run, SETTLED_FROM_S)
    assert abs(losses.balance_residual_W) < 1e-4 * losses.input_W
    t, torque = axial_torques(model, run, (inner, outer))
    picks = np.flatnonzero(np.asarray(run["t"]) >= SETTLED_FROM_S)[::int(np.ceil(np.sum(t >= SETTLED_FROM_S) / 400))]
    omega = case.operation.outer_speed_rpm * math.pi / 30.0
    assert losses.samples == picks.size
    assert losses.input_W == pytest.approx(-omega * torque[picks, 1].mean(), rel=1e-9)


def test_drag_loss_is_c_v_squared_and_dominates_as_in_the_report(ehd_run):
    """Drag power Σ c|v|² from the recorded ball velocities to 1e-12; the report's torque with
    κ = 1·u comes "mostly from the drag": its share of the losses exceeds 95 % (measured 99.6 %)."""
    case, model, run, rows, inner, outer = ehd_run
    losses = power_losses(model, run, SETTLED_FROM_S)
    t = np.asarray(run["t"])
    picks = np.flatnonzero(t >= SETTLED_FROM_S)
    picks = picks[::int(np.ceil(picks.size / 400))]
    v = np.asarray(run["v"])[picks][:, list(rows.elements), :3]
    expected = stokes_drag_N_s_m(case) * float(np.mean(np.sum(v**2, axis=(1, 2))))
    assert losses.losses["drag"] == pytest.approx(expected, rel=1e-12)
    assert losses.shares()["drag"] > 0.95
    assert sum(losses.shares().values()) == pytest.approx(1.0, rel=1e-12)
    # both grooves take traction losses, the balls do not touch each other
    assert losses.losses["outer race groove friction"] > 0 and losses.losses["inner race groove friction"] > 0
    assert losses.losses["element–element contacts friction"] == 0.0


def test_sliding_friction_loss_is_coefficient_load_and_slip_speed():
    """Balls at rest on their loaded contact lines, the outer race turning at Ω, constant traction
    A = 0.03 at the contact centre: the outer groove's friction dissipates Σ A·F_n·Ω·ρ to 1e-9, the
    inner groove (no slip) and the normal damping nothing, and the drive's power equals the losses."""
    A = 0.03
    case, model, start, rows, inner, outer = _dma(model="constant", A=A, strips=0)
    omega = case.operation.outer_speed_rpm * math.pi / 30.0
    start.v[:] = 0.0
    start.v[outer, 5] = omega
    run = {"t": np.array([0.0, 1e-6]), "q": np.array([start.q, start.q]), "v": np.array([start.v, start.v])}
    losses = power_losses(model, run)
    work = evaluate_forces(model, start)
    outer_pairs = contact_groups(model)["outer race groove"]
    rho = np.hypot(work.contact_point[outer_pairs, 0], work.contact_point[outer_pairs, 1])
    expected = float(np.sum(A * work.contact_fn[outer_pairs] * omega * rho))
    assert expected > 0
    assert losses.losses["outer race groove friction"] == pytest.approx(expected, rel=1e-9)
    assert abs(losses.losses["inner race groove friction"]) < 1e-12 * expected
    assert abs(losses.losses["outer race groove damping"]) < 1e-12 * expected
    assert losses.input_W == pytest.approx(losses.total_W, rel=1e-9)
    assert abs(losses.balance_residual_W) < 1e-9 * expected


def test_a_pair_subset_keeps_the_forces_of_its_pairs():
    """The model cut to one group's pairs gives those pairs' forces exactly: the groups' subsets (no
    drag, no external loads) add up to the whole model's contact forces and moments to round-off."""
    case, model, start, rows, inner, outer = _dma(model="constant", A=0.03)
    start.v[outer, 5] = 1.0  # slipping contacts: friction forces and strip moments
    internal = internal_model(model)
    bare = dataclasses.replace(internal, arrays=internal.arrays._replace(drag_body=np.zeros(0, dtype=np.int64)))
    whole = evaluate_forces(bare, start)
    whole_f, whole_t = whole.body_f.copy(), whole.body_t.copy()
    groups = contact_groups(model).values()
    assert sum(len(g) for g in groups) == model.n_pairs
    parts = [evaluate_forces(pair_subset(bare, keep), start) for keep in groups]
    parts_f, parts_t = sum(w.body_f.copy() for w in parts), sum(w.body_t.copy() for w in parts)
    assert np.allclose(parts_f, whole_f, rtol=0, atol=1e-12 * np.abs(whole_f).max())
    assert np.allclose(parts_t, whole_t, rtol=0, atol=1e-12 * np.abs(whole_t).max())
