"""One dynamic run of the DMA bearing and its friction torque (:mod:`cases.dma.case`).

Model: the inner race held, the outer race driven at its speed about z and free to move along and
across it under the thrust (so it seats on the balls), 24 balls free in six degrees of freedom with
Hertz contacts in both grooves (each its own constant, :func:`mbd_core.contact.hertz.ball_on_groove`),
frictionless Hertz contacts between neighbours, the case's traction at the raceways over the contact
ellipses, and a Stokes drag on every ball. The run starts at the static equilibrium under the thrust
with the balls rolling without slip (:func:`mbd_core.multibody.bearings.set_rolling_velocities`).

Torque of a race: the moment about the bearing axis of every force and moment the balls put on it,
re-evaluated at each recorded sample from the recorded state (:func:`mbd_core.multibody.ring_torque.axial_torques`).
Its mean and ripple are taken over the run after ``analysis.settle_fraction`` of it; its spectrum
and that of ball 0's radial and axial position over the same part (Hann window).

Time-step error (``error_estimates`` in ``summary.json``): a window of 200 steps from the run's end
repeated at h/2 and h/4, the mean race torques over it extrapolated (Richardson,
:func:`mbd_core.multibody.step_error.step_error`).

Reference frequency: the elastic contact frequency of a ball between its two linearised Hertz
contacts, f = sqrt((k_i + k_o)/m)/(2π), k = 1.5·Q/δ at the mean contact load Q.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from foundation.lubricants import LUBRICANT_A
from foundation.materials import ElasticMaterial
from mbd_core.contact.hertz import ball_on_groove, sphere_on_sphere
from mbd_core.multibody import ContactLaw, Driven, Fixed, ModelBuilder, simulate, stable_timestep
from mbd_core.multibody.bearings import add_ball_row, ball_mass_kg, set_rolling_velocities
from mbd_core.multibody.power_losses import PowerLosses, power_losses
from mbd_core.multibody.ring_torque import axial_torques, spectrum_peaks_Hz
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.multibody.step_error import WINDOW_STEPS, step_error
from mbd_core.quasistatic import BallRow

from .case import DmaCase

__all__ = ["TorqueRun", "ball_row", "build", "run_torque", "stokes_drag_N_s_m"]


def ball_row(case: DmaCase) -> BallRow:
    """The bearing as a row with the outer race moving (it carries the thrust)."""
    b = case.bearing
    steel = ElasticMaterial("DMA bearing steel", b.E_Pa, b.poisson, b.density_kg_m3)
    return BallRow("balls", b.n_balls, b.ball_diameter_m, b.pitch_diameter_m, math.radians(b.contact_angle_deg),
                   b.conformity_outer, b.conformity_inner, "outer", axial_sign=1, ball_material=steel,
                   race_material=steel)


def stokes_drag_N_s_m(case: DmaCase) -> float:
    """c = 3π·μ·D: the drag of a ball in the oil at the case's temperature, N·s/m."""
    return 3.0 * math.pi * LUBRICANT_A.dynamic_viscosity_Pa_s(case.operation.temperature_C) * case.bearing.ball_diameter_m


def build(case: DmaCase):
    """(model, state at rest, row bodies, inner, outer) of the case (module docstring)."""
    row = ball_row(case)
    b = ModelBuilder()
    inner = b.add_body("inner race", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    outer = b.add_body("outer race", 1.0, (1e-3, 1e-3, 2e-3),
                       motion=Driven(case.operation.outer_speed_rpm * math.pi / 30.0, translation_free=True))
    rows = add_ball_row(b, row, outer, inner, friction=case.traction.law(), traction_strips=case.traction.strips)
    r = row.ball_diameter_m / 2
    k_ball = sphere_on_sphere(row.ball_diameter_m, row.ball_diameter_m, row.ball_material,
                              row.ball_material).stiffness_N_per_m1p5
    n = len(rows.elements)
    for j, e in enumerate(rows.elements):
        b.add_ball_ball(e, rows.elements[(j + 1) % n], r, r, ContactLaw(k_ball))
        if case.operation.drag:
            b.add_drag(e, stokes_drag_N_s_m(case))
    b.add_force(outer, (0.0, 0.0, case.operation.thrust_N))
    model, state = b.finalize()
    return model, state, rows, inner, outer


@dataclass(frozen=True)
class TorqueRun:
    """Race torques of one run. ``t_s`` (k,) the samples; ``inner_Nm``, ``outer_Nm`` (k,) the torque
    the balls put on each race about +z (the outer race turns about +z); ``ball_radial_m``,
    ``ball_axial_m`` (k,) ball 0's centre; ``settled`` (k,) bool, the part the means are taken over;
    ``ball_load_N`` (Z,) each ball's outer-race contact load averaged over it;
    ``drag_moment_Nm`` the mean moment of the balls' drag about the axis over it (in a steady state
    the race torques balance it: T_inner + T_outer = M_drag); ``step_error`` the time-step error
    estimate of the race torques (module docstring)."""

    t_s: np.ndarray
    inner_Nm: np.ndarray
    outer_Nm: np.ndarray
    ball_radial_m: np.ndarray
    ball_axial_m: np.ndarray
    settled: np.ndarray
    ball_load_N: np.ndarray
    n_balls: int
    contact_load_N: float
    contact_frequency_Hz: float
    drag_per_ball_N: float
    drag_moment_Nm: float
    steps: int
    step_error: dict
    losses: PowerLosses

    def mean_per_ball(self, which: str) -> float:
        return float(np.mean(getattr(self, f"{which}_Nm")[self.settled]) / self.n_balls)

    def ripple_per_ball(self, which: str) -> float:
        """Standard deviation of the race torque per ball over the settled part, N·m."""
        return float(np.std(getattr(self, f"{which}_Nm")[self.settled]) / self.n_balls)

    def summary(self) -> dict:
        out = {"steps": self.steps, "error_estimates": {"time_step": self.step_error},
               "contact_load_N": self.contact_load_N,
               "contact_frequency_Hz": self.contact_frequency_Hz, "drag_per_ball_N": self.drag_per_ball_N,
               "drag_moment_Nm": self.drag_moment_Nm}
        for which in ("inner", "outer"):
            out[f"{which}_race_torque_per_ball_Nm"] = self.mean_per_ball(which)
            out[f"{which}_race_torque_Nm"] = self.mean_per_ball(which) * self.n_balls
            out[f"{which}_race_ripple_per_ball_Nm"] = self.ripple_per_ball(which)
        out["power_losses"] = self.losses.summary()
        dt = self.t_s[1] - self.t_s[0]
        out["ball_motion_peaks_Hz"] = spectrum_peaks_Hz(self.ball_axial_m[self.settled], dt)
        out["inner_torque_peaks_Hz"] = spectrum_peaks_Hz(self.inner_Nm[self.settled], dt)
        return out


def _contact_frequency_Hz(case: DmaCase, row: BallRow, load_N: float) -> float:
    a0 = row.contact_angle_rad
    k = 0.0
    for raceway, f in (("inner", case.bearing.conformity_inner), ("outer", case.bearing.conformity_outer)):
        hertz = ball_on_groove(row.ball_diameter_m, f, row.pitch_diameter_m, a0, raceway, row.ball_material,
                               row.race_material)
        k += 1.5 * load_N / float(hertz.approach_m(load_N))
    m = ball_mass_kg(row.ball_diameter_m, row.ball_material.density_kg_m3)
    return math.sqrt(k / m) / (2.0 * math.pi)


def run_torque(case: DmaCase) -> TorqueRun:
    """The run of the case and its race torques (module docstring)."""
    model, state, rows, inner, outer = build(case)
    start = static_equilibrium(model, state).state
    set_rolling_velocities(model, start, rows.elements, outer, inner)
    step = case.analysis.step_factor * stable_timestep(model, start).timestep_s
    record_every = max(1, int(case.analysis.sample_interval_s / step))
    run = simulate(model, start, case.analysis.duration_s, timestep_s=step, record_every=record_every)
    t, torque = axial_torques(model, run, (inner, outer))
    settled = t >= t[0] + case.analysis.settle_fraction * (t[-1] - t[0])
    e0 = rows.elements[0]
    x = run["q"][:, e0, :3]
    loads = run["fn"][:, list(rows.moving_pairs)][settled]
    row = ball_row(case)
    load = float(loads.mean())
    c = stokes_drag_N_s_m(case) if case.operation.drag else 0.0
    balls_q, balls_v = run["q"][settled][:, list(rows.elements), :3], run["v"][settled][:, list(rows.elements), :3]
    drag = c * float(np.mean(np.linalg.norm(balls_v, axis=2)))
    moment = -c * float(np.mean(np.sum(balls_q[..., 0] * balls_v[..., 1] - balls_q[..., 1] * balls_v[..., 0], axis=1)))
    return TorqueRun(t, torque[:, 0], torque[:, 1], np.hypot(x[:, 0], x[:, 1]), x[:, 2], settled,
                     loads.mean(axis=0), len(rows.elements), load, _contact_frequency_Hz(case, row, load), drag, moment,
                     int(round((t[-1] - t[0]) / step)), _torque_step_error(model, start, step, (inner, outer)),
                     power_losses(model, run, float(t[settled][0])))


def _torque_step_error(model, state, step: float, races) -> dict:
    """The time-step error of the mean race torques over a window from ``state`` (module docstring):
    the larger relative error of the two races, and each race's."""
    def figures(rec):
        _, torque = axial_torques(model, rec, races)
        return {"inner": float(torque[:, 0].mean()), "outer": float(torque[:, 1].mean())}

    est = step_error(model, state, step, figures)
    return {"race_torque": max(e.relative for e in est.values()),
            **{f"{name}_race_torque": e.relative for name, e in est.items()},
            "order": min(e.order for e in est.values()), "window_s": WINDOW_STEPS * step,
            "what": f"relative time-step error of the mean race torques over {WINDOW_STEPS} steps from the run's end, "
                    "repeated at h/2 and h/4 (Richardson)"}
