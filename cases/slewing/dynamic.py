"""Dynamic runs of the slewing ring: the top race turning on its balls (explicit integration).

Scene (thesis §3.1): the bottom race fixed (rigid, or modal bolted at its patches); the top
structure spinning at the case speed about the axis, free to sink and tilt, loaded by gravity
(its mass is the dead load, :mod:`.case`); load balls in both grooves with Hertz contacts,
friction and damping; spacer balls in the bottom groove between them (touching the bottom race
and their two neighbours only), which keep the balls apart instead of a cage.

Start: the flexible quasi-static equilibrium (:func:`.quasistatic.equilibrium`, Newton with the
balls condensed: milliseconds) mapped onto the scene — the top structure's displacement and modal
coordinates, each ball on its loaded contact line (:func:`state_from_quasistatic`) — and, with
modal bodies, polished by the multibody static equilibrium from there with every ball held at its
azimuth (:func:`mbd_core.multibody.statics.static_equilibrium`); then the no-slip rolling
velocities of the load balls (:func:`mbd_core.multibody.bearings.set_rolling_velocities`) and of
the spacers (orbit speed of the load balls, rolling on the bottom race).

Contact damping: ``damping_ratio`` × the critical damping 2√(k m) of a load ball on the
linearised Hertz stiffness k = 1.5 K δ^0.5 of one contact at the nominal load (``thesis``
preset: its c = K/1000 s, i.e. 2.58 MN·s/m).
"""

from __future__ import annotations

import logging
import math

import numpy as np

from mbd_core.contact import ball_on_groove
from mbd_core.contact.hertz import sphere_on_sphere
from foundation.materials import BEARING_STEEL
from mbd_core.multibody import ModelBuilder, StepTooLargeError, largest_load_step_error
from mbd_core.multibody.bearings import (_rotate_back, add_ball_row, ball_mass_kg, orbit_rad_s,
                                         set_rolling_velocities)
from mbd_core.multibody.builder import ContactLaw, Driven, Fixed
from mbd_core.multibody.statics import static_equilibrium

from ..config import CaseError
from ..integrate import IMPLICIT_STEP_FACTOR, integrate, integrate_implicit
from ..ring_torque_report import write_ring_torque
from . import scene
from .case import THESIS_CONTACT_DAMPING_N_S_PER_M, THESIS_CONTACT_STIFFNESS_N_PER_M1P5, SlewingCase
from .quasistatic import analytic_ball_load_N
from .dynamic_reference import compare_with_quasistatic, plot_comparison
from .dynamic_stress import write_race_stresses

__all__ = ["DynamicScene", "build_scene", "state_from_quasistatic", "start_state", "run_dynamic", "ball_columns", "spacer_columns",
           "start_up_window", "spacer_force_figures"]

log = logging.getLogger(__name__)

#: share of a run at its start (the transient from the start state) left out of the key figures and plots
START_UP_SHARE = 0.1
#: penetration over which the IMPACT damping ramps in (well below the 0.1 mm Hertz approach)
D_MAX_M = 1e-6


class DynamicScene:
    """The model and the indices a run reads back: bodies and contact pairs."""

    def __init__(self, model, state, top, bottom, balls, spacers, ball_pairs_top, ball_pairs_bottom, spacer_pairs):
        self.model, self.state, self.top, self.bottom = model, state, top, bottom
        self.balls, self.spacers = balls, spacers
        self.ball_pairs_top, self.ball_pairs_bottom, self.spacer_pairs = ball_pairs_top, ball_pairs_bottom, spacer_pairs


def _tables(case: SlewingCase):
    th = 2.0 * math.pi * np.arange(scene.N_THETA) / scene.N_THETA
    h = scene.undulation_m(case.undulation, th) if case.undulation.scale else None
    dr_bottom = scene.thermal_offset_m(case, "bottom", th) if case.thermal.offset_m else None
    dr_top = scene.thermal_offset_m(case, "top", th) if case.thermal.offset_m else None
    return (None, dr_top), (h, dr_bottom)


def _damping(case: SlewingCase, k_contact: float) -> float:
    if case.contact.preset == "thesis":
        return THESIS_CONTACT_DAMPING_N_S_PER_M
    Q, _ = analytic_ball_load_N(case)
    delta = (Q / k_contact) ** (2.0 / 3.0)
    k_lin = 1.5 * k_contact * math.sqrt(delta)
    m = ball_mass_kg(case.geometry.ball_diameter_m, BEARING_STEEL.density_kg_m3)
    return case.contact.damping_ratio * 2.0 * math.sqrt(k_lin * m)


def build_scene(case: SlewingCase, bodies: scene.Bodies) -> DynamicScene:
    """The multibody model of the case at rest, before the static equilibrium."""
    g = case.geometry
    row = scene.ball_row(case)
    omega = case.analysis.speed_rpm * 2.0 * math.pi / 60.0
    b = ModelBuilder(gravity_m_s2=(0.0, 0.0, -case.load.gravity_m_s2), implicit_friction=case.contact.implicit_friction)
    drive = Driven(omega, translation_free=True, tilt_free=True)
    R = 0.5 * g.pitch_diameter_m
    if bodies.top is None:
        m = 1000.0 * case.dead_load_t
        top = b.add_body("top structure", m, (0.5 * m * R * R, 0.5 * m * R * R, m * R * R), motion=drive,
                         omega_rad_s=(0.0, 0.0, omega))
    else:
        top = b.add_modal_body("top structure", bodies.top, motion=drive, omega_rad_s=(0.0, 0.0, omega),
                               implicit_modes=case.analysis.implicit_modes)
    if bodies.bottom is None:
        bottom = b.add_body("bottom race", 1000.0, (1e3, 1e3, 2e3), motion=Fixed())
    else:
        bottom = b.add_modal_body("bottom race", bodies.bottom, motion=Fixed(), implicit_modes=case.analysis.implicit_modes)
    moving_tab, fixed_tab = _tables(case)
    k = ball_on_groove(g.ball_diameter_m, g.conformity, g.pitch_diameter_m, row.contact_angle_rad, "inner",
                       BEARING_STEEL, BEARING_STEEL).stiffness_N_per_m1p5
    c = _damping(case, k if row.stiffness_N_per_m1p5 is None else row.stiffness_N_per_m1p5 * 2.0**1.5)
    friction = case.contact.friction_law()
    rb = add_ball_row(b, row, top, bottom, friction=friction, damping_N_s_m=c, d_max_m=D_MAX_M,
                      moving_sample="groove" if bodies.top is not None else None,
                      fixed_sample="groove" if bodies.bottom is not None else None,
                      moving_groove_m=moving_tab, fixed_groove_m=fixed_tab)
    spacers, spacer_pairs = [], []
    if case.analysis.spacers:
        spacers, spacer_pairs = _add_spacers(b, case, row, bottom, rb.elements, fixed_tab,
                                             "groove" if bodies.bottom is not None else None, c, friction)
    model, state = b.finalize()
    return DynamicScene(model, state, top, bottom, rb.elements, spacers, rb.moving_pairs, rb.fixed_pairs, spacer_pairs)


def _bottom_groove_centre_rz(case: SlewingCase) -> np.ndarray:
    """(r, z) of the bottom groove's curvature centre, m: the ball centre + (f D − D/2) u, u the
    unit vector towards the top-race contact at α0 (as in :func:`add_ball_row`)."""
    g = case.geometry
    a0 = math.radians(g.contact_angle_deg)
    u = np.array([-math.cos(a0), math.sin(a0)])
    return np.array([0.5 * g.pitch_diameter_m, 0.0]) + (g.conformity * g.ball_diameter_m - g.ball_diameter_m / 2) * u


def _add_spacers(b, case: SlewingCase, row, bottom, balls, fixed_tab, sample, damping: float, friction):
    """Spacer balls at the bottom of the bottom groove, half-way between the load balls."""
    g = case.geometry
    D, d = g.ball_diameter_m, g.spacer_m
    c_f = _bottom_groove_centre_rz(case)
    groove = b.add_groove(bottom, c_f[0], c_f[1], g.conformity * D, *(fixed_tab or (None, None)), raceway=sample)
    r_centre, z_centre = c_f[0], c_f[1] - (g.conformity * D - d / 2)
    k_groove = ball_on_groove(d, g.conformity * D / d, g.pitch_diameter_m, 0.5 * math.pi, "outer",
                              BEARING_STEEL, BEARING_STEEL).stiffness_N_per_m1p5
    k_ball = sphere_on_sphere(D, d).stiffness_N_per_m1p5
    m = ball_mass_kg(d, BEARING_STEEL.density_kg_m3)
    law_groove = ContactLaw(k_groove, 1.5, damping, D_MAX_M, friction=friction)
    law_ball = ContactLaw(k_ball, 1.5, damping, D_MAX_M, friction=friction)
    n = len(balls)
    spacers, pairs = [], []
    for j in range(n):
        psi = row.first_azimuth_rad + 2.0 * math.pi * (j + 0.5) / n
        s = b.add_body(f"spacer {j}", m, (0.1 * m * d * d,) * 3,
                       position_m=(r_centre * math.cos(psi), r_centre * math.sin(psi), z_centre))
        b.add_ball_groove(s, bottom, groove, d / 2, law_groove, name=f"spacer {j}–bottom")
        pairs.append(b.add_ball_ball(balls[j], s, D / 2, d / 2, law_ball, name=f"ball {j}–spacer {j}"))
        pairs.append(b.add_ball_ball(balls[(j + 1) % n], s, D / 2, d / 2, law_ball, name=f"ball {(j + 1) % n}–spacer {j}"))
        spacers.append(s)
    return spacers, pairs


def state_from_quasistatic(sc: DynamicScene, case: SlewingCase, bodies: scene.Bodies | None = None):
    """The scene placed at the (flexible) quasi-static equilibrium (:func:`.quasistatic.equilibrium`).

    The top structure takes the solution's displacement (x, y, z, θx, θy) and, when modal, its modal
    coordinates η (the same reduced body, so the same coordinates); a modal bottom race its own η.
    Ball i sits on its loaded contact line at ψ_i, at f·D − D/2 + δ_f,i from the bottom groove's
    (offset, and with a modal bottom race displaced) curvature centre, δ_f,i = (Q_i / K_f)^(2/3)
    its share of the approach (Hertz, bottom contact); spacers sit on the (undulated) groove
    bottom. Exact for the contacts the quasi-static model has with a rigid top; with modal bodies
    the multibody grooves interpolate the same raceway samples their own way (measured 5e-5 of the
    largest load on the 2 m ring), and the balls' and spacers' weights are not in it.
    """
    from mbd_core.multibody.builder import quat_from_axis_angle

    from .quasistatic import equilibrium

    bodies = bodies or scene.Bodies(None, None)
    res = equilibrium(case, bodies)
    g = case.geometry
    D, f = g.ball_diameter_m, g.conformity
    a0 = math.radians(g.contact_angle_deg)
    k_f = ball_on_groove(D, f, g.pitch_diameter_m, a0, "outer", BEARING_STEEL, BEARING_STEEL).stiffness_N_per_m1p5
    if case.contact.preset == "thesis":
        k_f = THESIS_CONTACT_STIFFNESS_N_PER_M1P5
    state = sc.state
    x, y, z, tx, ty = res.displacement
    state.q[sc.top, :3] = (x, y, z)
    angle = math.hypot(tx, ty)
    if angle > 0.0:
        state.q[sc.top, 3:] = quat_from_axis_angle((tx / angle, ty / angle, 0.0), angle)
    a = sc.model.arrays
    for name, body in (("top", sc.top), ("bottom", sc.model.body("bottom race"))):
        if name in res.ring_names:
            o = a.modal_off[int(np.flatnonzero(a.modal_body == body)[0])]
            eta = res.modal(name)
            state.eta[o:o + eta.size] = eta
    c0 = _bottom_groove_centre_rz(case)
    r = res.rows[0]
    h = scene.undulation_m(case.undulation, r.azimuth_rad)
    dr = scene.thermal_offset_m(case, "bottom", r.azimuth_rad)
    moved = np.zeros((len(sc.balls), 3))
    if "bottom" in res.ring_names:
        moved = res.raceway_deflection("bottom", r.name).groove_centre_displacement_m
    for i, b in enumerate(sc.balls):
        psi, al = r.azimuth_rad[i], (r.contact_angle_rad[i] if r.load_N[i] > 0 else a0)
        d_f = (r.load_N[i] / k_f) ** (2.0 / 3.0)
        rc = c0[0] + dr[i] - (f * D - D / 2 + d_f) * -math.cos(al)
        zc = c0[1] + h[i] - (f * D - D / 2 + d_f) * math.sin(al)
        state.q[b, :3] = (rc * math.cos(psi), rc * math.sin(psi), zc) + moved[i]
    for s in sc.spacers:
        psi = math.atan2(state.q[s, 1], state.q[s, 0])
        state.q[s, 2] += float(scene.undulation_m(case.undulation, psi))
        rs = math.hypot(state.q[s, 0], state.q[s, 1]) + float(scene.thermal_offset_m(case, "bottom", psi))
        state.q[s, :2] = (rs * math.cos(psi), rs * math.sin(psi))
    return state


def start_state(sc: DynamicScene, case: SlewingCase, bodies: scene.Bodies | None = None):
    """The start of a run: the quasi-static equilibrium mapped onto the scene
    (:func:`state_from_quasistatic`); with modal bodies polished by the multibody static
    equilibrium from there (balls and spacers held at their azimuths), which then takes seconds
    instead of the minutes a start from rest needs. Then the rolling velocities."""
    spin = sc.state.v[sc.top, 3:].copy()
    state = state_from_quasistatic(sc, case, bodies)
    if sc.model.n_modal:
        state = static_equilibrium(sc.model, state, fixed_azimuth=list(sc.balls) + list(sc.spacers)).state
    state.v[sc.top, 3:] = spin  # the drive's spin
    set_rolling_velocities(sc.model, state, sc.balls, sc.top, sc.model.body("bottom race"))
    if sc.spacers:
        a = sc.model.arrays
        w_orbit = np.mean([np.cross(state.q[i, :3], state.v[i, :3])[2] / np.dot(state.q[i, :2], state.q[i, :2])
                           for i in sc.balls])
        for s in sc.spacers:
            v = w_orbit * np.cross([0.0, 0.0, 1.0], state.q[s, :3])
            r_s = a.pair_radius[int(np.flatnonzero(a.pair_a == s)[0])]
            state.v[s, :3] = v
            # rolling on the groove bottom below it: ω × (−r_s ẑ) = −v
            state.v[s, 3:] = _rotate_back(state.q[s, 3:], np.cross([0.0, 0.0, 1.0], v) / r_s)
    return state


def start_up_window(t_s: np.ndarray) -> tuple[float, np.ndarray]:
    """(time the key figures start from, mask of the samples from then on): the first
    ``START_UP_SHARE`` of the run, the transient from the start state, is left out of the
    summary and of the plots alike."""
    t_s = np.asarray(t_s)
    start_s = float(t_s[0] + START_UP_SHARE * (t_s[-1] - t_s[0]))
    return start_s, t_s >= start_s


def spacer_force_figures(forces_N: np.ndarray) -> dict:
    """Peak, mean and 99th percentile of (samples, contacts) spacer–load ball forces, N."""
    return {"max_spacer_force_N": float(forces_N.max()), "mean_spacer_force_N": float(forces_N.mean()),
            "p99_spacer_force_N": float(np.percentile(forces_N, 99.0))}


def ball_columns(n_balls: int) -> list[str]:
    """CSV columns of the load balls' loads, numbered 1…Z as in the plots."""
    return [f"ball_{i + 1}_N" for i in range(n_balls)]


def spacer_columns(n_balls: int) -> list[str]:
    """CSV columns of the spacer contacts, numbered 1…Z like the balls: for spacer j, its
    contact with ball j, then with ball j + 1 (the order of :func:`_add_spacers`)."""
    return [f"ball_{(j + k) % n_balls + 1}_spacer_{j + 1}_N" for j in range(n_balls) for k in (0, 1)]


def _integrate_implicit(sc: DynamicScene, state, a) -> dict:
    """The run with the implicit generalized-α integrator (:func:`cases.integrate.integrate_implicit`)."""
    return integrate_implicit(sc.model, state, a.duration_s, a.record_every, a.rho_inf, a.timestep_s)


#: a dynamic run must record at least this many samples (its figures, the start-up window and the
#: quasi-static comparison need them)
MIN_SAMPLES = 20
#: pieces of an explicit run (:func:`cases.integrate.integrate`); each records from its own start
PIECES = 40


def check_samples(sc: DynamicScene, state, a) -> None:
    """Refuse a run that would record fewer than :data:`MIN_SAMPLES` samples (``analysis.record_every``
    too large for the step and the duration), naming the key and the largest value that works."""
    from mbd_core.multibody import stable_timestep

    implicit = a.type == "dynamic_implicit"
    h = a.timestep_s or (IMPLICIT_STEP_FACTOR if implicit else 1.0) * stable_timestep(sc.model, state).timestep_s
    steps = a.duration_s / h
    per_piece, pieces = (steps, 1) if implicit else (steps / PIECES, PIECES)
    if 1 + pieces * int(per_piece // a.record_every) < MIN_SAMPLES:
        best = max(1, int(per_piece // math.ceil((MIN_SAMPLES - 1) / pieces)))
        raise CaseError(f"analysis.record_every = {a.record_every}: the run of {a.duration_s:g} s at the step "
                        f"{h:.3g} s would record fewer than {MIN_SAMPLES} samples; use at most {best}")


def run_dynamic(case: SlewingCase, out, progress=None) -> None:
    """Run the dynamic scene, write its series, figures and key figures."""
    from .plots import plot_dynamic
    from .studies import _write_balls_vtu, _write_top_vtu

    bodies = scene.Bodies(scene.top_body(case), scene.bottom_body(case))
    sc = build_scene(case, bodies)
    state = start_state(sc, case, bodies)
    a = case.analysis
    check_samples(sc, state, a)
    implicit = a.type == "dynamic_implicit"
    if implicit:
        run = _integrate_implicit(sc, state, a)
    else:
        try:
            run = integrate(sc.model, state, a.duration_s, a.record_every, progress, chunks=PIECES,
                            timestep_s=a.timestep_s)
        except StepTooLargeError as exc:
            raise CaseError(f"analysis.timestep_s = {a.timestep_s:g} s: {exc}") from None
    t = run["t"]
    q = run["fn"][:, list(sc.ball_pairs_top)]
    settled_from_s, settled = start_up_window(t)
    spread = (q.max(axis=1) - q.min(axis=1)) / q.mean(axis=1)
    Q, alpha = analytic_ball_load_N(case)
    w_top = case.analysis.speed_rpm * 2.0 * math.pi / 60.0
    orbit = orbit_rad_s(run["q"][:, list(sc.balls), :3], run["v"][:, list(sc.balls), :3]).mean(axis=1)
    fig = {"timestep_s": run["timestep_s"], "steps": int(round(a.duration_s / run["timestep_s"])),
           "max_ball_load_N": float(q[settled].max()), "min_ball_load_N": float(q[settled].min()),
           "mean_ball_load_N": float(q[settled].mean()), "analytic_ball_load_N": Q,
           "max_load_spread": float(spread[settled].max()),
           "ball_orbit_over_kinematic": float(orbit[settled].mean() / (scene.orbit_ratio(case) * w_top))}
    if sc.spacer_pairs:
        fs = run["fn"][:, list(sc.spacer_pairs)]
        fig.update(spacer_force_figures(fs[settled]))
        if (~settled).any():  # reported apart: the start's impacts, not the rolling ring's
            fig["start_up_max_spacer_force_N"] = float(fs[~settled].max())
    out.summary.update(fig)
    out.summary["start_up_excluded_s"] = float(settled_from_s - t[0])
    step = None if implicit else largest_load_step_error(sc.model, state, run["timestep_s"], sc.ball_pairs_top)
    out.summary["error_estimates"] = {"time_step": step}
    out.summary["integrator"] = ({"kind": "generalized-alpha (implicit)", "rho_inf": a.rho_inf} if implicit
                                 else {"kind": "explicit (velocity Verlet)"})
    cmp = compare_with_quasistatic(case, bodies, run, sc.top, sc.balls, sc.ball_pairs_top, settled,
                                   a.reference_samples, progress)
    if cmp is not None:
        out.summary["quasistatic_comparison"] = {k: v for k, v in cmp.items() if not k.endswith("_load_N")}
        out.note(f"against the quasi-static equilibrium at {len(cmp['time_s'])} positions, each ball where the run has "
                 f"it: largest deviation {100 * cmp['max_deviation']:.2f} % of the largest load, "
                 f"{100 * cmp['max_deviation_loaded']:.2f} % of its own load for balls above "
                 f"{100 * cmp['loaded_share']:.0f} % of the largest (balls up to {cmp['max_ball_offset_deg']:.3f}° from "
                 f"even spacing; against the evenly spaced row {100 * cmp['even_spacing_deviation']:.2f} % / "
                 f"{100 * cmp['even_spacing_deviation_loaded']:.2f} %)")
        if cmp["samples_at_even_spacing"]:
            out.warn([f"{cmp['samples_at_even_spacing']} compared samples had a ball half a spacing or more off its "
                      "place; there the reference row is evenly spaced"], "quasi-static comparison")
        out.write_csv("quasistatic_comparison.csv", ["t_s", "top_rotation_deg", "ball", "run_load_N",
                                                     "quasistatic_load_N"],
                      ([t, ang, j + 1, g, w] for t, ang, gs, ws in zip(cmp["time_s"], cmp["top_rotation_deg"],
                                                                       cmp["run_load_N"], cmp["quasistatic_load_N"])
                       for j, (g, w) in enumerate(zip(gs, ws))))
        out.save_figure(plot_comparison(cmp, case), "quasistatic_comparison.png")
    write_ring_torque(sc.model, run, {"top": sc.top, "bottom": sc.bottom}, settled_from_s, out,
                      f"{case.name}: torque of the balls{' and spacers' if sc.spacer_pairs else ''} on the races "
                      "about the axis", friction=case.contact.friction_law())
    write_race_stresses(out, case, bodies, run, settled)
    out.write_timeseries(sc.model, run, case=case.name, study=case.study.kind)
    out.write_csv("ball_loads_time.csv", ["t_s"] + ball_columns(q.shape[1]),
                  (np.concatenate([[ti], qi]) for ti, qi in zip(t, q)))
    if sc.spacer_pairs:
        out.write_csv("spacer_forces_time.csv", ["t_s"] + spacer_columns(len(sc.balls)),
                      (np.concatenate([[ti], fi]) for ti, fi in zip(t, fs)))
    az = np.arctan2(run["q"][-1, list(sc.balls), 1], run["q"][-1, list(sc.balls), 0])
    _write_balls_vtu(out, "balls_end.vtu", case, az, q[-1])
    if bodies.top is not None:
        lo, hi = run["modal_ranges"]["top structure"]
        _write_top_vtu(out, "top_structure_end.vtu", bodies, run["eta"][-1, lo:hi])
    out.save_figure(plot_dynamic(t, q, fs if sc.spacer_pairs else None, Q, case, settled_from_s),
                    "ball_loads_time.png")
    out.note(f"{'implicit' if implicit else 'explicit'} step {run['timestep_s']:.3g} s, {fig['steps']} steps; "
             f"after the first "
             f"{settled_from_s - t[0]:.3g} s: ball load {q[settled].min():.0f}–"
             f"{q[settled].max():.0f} N (analytic {Q:.0f} N), largest spread "
             f"{100 * fig['max_load_spread']:.2f} %; ball orbit speed {fig['ball_orbit_over_kinematic']:.4f} × kinematic"
             + (f"; spacer–load ball force ≤ {fig['max_spacer_force_N']:.1f} N" if sc.spacer_pairs else ""))
    if step is not None:
        out.note(f"time-step error of the largest ball load (Richardson, h/2 and h/4 over {1e3 * step['window_s']:.2g} "
                 f"ms from the end): {100 * step['max_load']:.2g} %")
    else:
        out.note(f"implicit generalized-α run, ρ∞ = {a.rho_inf:g} (its step is not estimated: the Richardson window "
                 "repeats explicit steps)")
