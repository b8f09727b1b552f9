"""The studies of a turbocharger case (:mod:`.case`): one run at the operating point, a run-up over
speed, and the damper's land length and clearance."""

from __future__ import annotations

import dataclasses
import math

from mbd_core.multibody import DivergenceError, StepTooLargeError, stable_timestep

from ..config import CaseError
from ..integrate import integrate
from ..overrides import StudyEntry, unused_keys
from ..ring_torque_report import write_power_losses
from .analysis import RunFigures, analyse
from .case import TurbochargerCase
from .plots import (plot_ball_loads, plot_cage, plot_damper, plot_damper_sweep, plot_orbits, plot_over_speed,
                    plot_spectrum, plot_waterfall)
from .scene import build_scene, with_speed

__all__ = ["STUDIES", "case_unused_keys", "run_study", "uses_dynamics", "simulate_case"]


#: share of the start's stable step a run takes first; a run whose loads outgrow it (the friction law's
#: slope sets the limit, and it falls as the load grows) runs again at half the step, at most STEP_RETRIES times
STEP_MARGIN = 0.7
STEP_RETRIES = 3


def _key_of(message: str) -> str:
    """The case key a stopped run points at."""
    if "squeeze-film damper" in message:
        return "damper.clearance_m"
    if "pocket" in message:
        return "bearings.pocket_clearance_m"
    if "penetration" in message:          # a ball contact beyond its bound: a load the row cannot carry
        return "operation.unbalance_g_mm"
    return "operation.speed_rpm"


def simulate_case(case: TurbochargerCase, speed_rpm: float | None = None, progress=None) -> tuple[object, RunFigures]:
    """Build the scene at ``speed_rpm`` (default the case's), run it and analyse the run; a run that
    stops (a damper at the end of its table, a contact beyond its bound) raises :class:`CaseError`
    naming the key to change."""
    scene = build_scene(case, speed_rpm)
    margin = STEP_MARGIN
    for attempt in range(STEP_RETRIES + 1):
        try:
            # one step for the whole run: evenly spaced samples for the spectra
            h = margin * stable_timestep(scene.model, scene.state).timestep_s
            every = max(1, int(round(case.run.sample_s / h)))
            rec = integrate(scene.model, scene.state.copy(), case.run.duration_s, every, progress, chunks=20,
                            timestep_s=h)
            break
        except StepTooLargeError as exc:
            if attempt == STEP_RETRIES:   # the friction law's slope sets the step of these runs
                raise CaseError(f"bearings.friction: the run at {scene.speed_rad_s * 30 / math.pi:.0f} rev/min "
                                f"outgrew {2 ** STEP_RETRIES} times a smaller step than the start's: {exc}") from None
            margin *= 0.5          # the loads grew: the same run at half the step
        except DivergenceError as exc:
            speed = scene.speed_rad_s * 30 / math.pi
            raise CaseError(f"{_key_of(str(exc))}: the run at {speed:.0f} rev/min stopped: {exc}") from None
    return scene, analyse(case, scene, rec)


def _title(case: TurbochargerCase, speed_rpm: float) -> str:
    op = case.operation
    return (f"{case.name}: {speed_rpm:.0f} rev/min, {op.unbalance_g_mm:g} g·mm at the {op.unbalance_at}, "
            f"preload {case.bearings.preload_N:g} N")


def _run(case: TurbochargerCase, out, progress=None) -> None:
    scene, run = simulate_case(case, progress=progress)
    title = _title(case, case.operation.speed_rpm)
    out.save_figure(plot_ball_loads(run, title), "ball_loads.png")
    out.save_figure(plot_orbits(run, case.damper.clearance_m, title), "orbits.png")
    out.save_figure(plot_damper(run, title), "dampers.png")
    out.save_figure(plot_spectrum(run, title), "spectrum.png")
    out.save_figure(plot_cage(run, case.bearings.pocket_clearance_m, title), "cage.png")
    write_power_losses(run.losses, out, title)
    stations = list(run.orbits_m)
    header = ["t_s"] + [f"{n.replace(' ', '_')}_{c}_m" for n in stations for c in "xy"] + \
        ["turbine_damper_eps", "compressor_damper_eps", "turbine_housing_force_x_N", "turbine_housing_force_y_N",
         "compressor_housing_force_x_N", "compressor_housing_force_y_N", "turbine_row_min_inner_load_N",
         "compressor_row_min_inner_load_N", "cage_whirl_x_m", "cage_whirl_y_m"]
    cols = [run.t_s] + [run.orbits_m[n][:, c] for n in stations for c in (0, 1)] + \
        [run.eccentricity[:, 0], run.eccentricity[:, 1], run.housing_N[:, 0, 0], run.housing_N[:, 0, 1],
         run.housing_N[:, 1, 0], run.housing_N[:, 1, 1], run.inner_loads_N[0].min(axis=1),
         run.inner_loads_N[1].min(axis=1), run.cage_whirl_m[:, 0], run.cage_whirl_m[:, 1]]
    out.write_csv("time_series.csv", header, zip(*cols))
    k = scene.quasi[0].stiffness
    names = ("x", "y", "z", "theta_x", "theta_y")
    out.write_csv("row_stiffness.csv", ("row_of_load",) + names, [(n,) + tuple(r) for n, r in zip(names, k)])
    s = run.summary
    out.summary.update(s, row_stiffness_5x5=k.tolist())
    out.note(f"turbine-side row: inner loads {s['inner_load_min_N'][0]:.1f} … {s['inner_load_max_N'][0]:.1f} N, "
             f"unloaded {100 * s['inner_unloaded_share'][0]:.1f} % of the time; compressor-side row "
             f"{s['inner_load_min_N'][1]:.1f} … {s['inner_load_max_N'][1]:.1f} N, "
             f"unloaded {100 * s['inner_unloaded_share'][1]:.1f} %")
    out.note("orbit radius " + ", ".join(f"{n} {r:.1f} µm" for n, r in s["orbit_radius_um"].items())
             + f"; dampers ε ≤ {max(s['damper_max_eccentricity']):.2f}, into the housing ≤ "
             f"{max(s['housing_force_amplitude_N']):.0f} N; step {s['timestep_s']:.3g} s")
    _validity(out, s)


#: land length over diameter beyond which the short-damper closed form is refused as the film model
#: without a warning: against the grid solver at ε = 0.4 (circular whirl) it overestimates the film's
#: tangential and radial force by 3.5 % and 8 % at L/D = 0.23, 14 % and 27 % at L/D = 0.5
SHORT_DAMPER_MAX_L_D = 0.3


def _damper_validity(out, case: TurbochargerCase) -> None:
    d = case.damper
    ratio = d.length_m / (2.0 * d.journal_radius_m)
    if d.method == "short" and ratio > SHORT_DAMPER_MAX_L_D:
        out.warn([f"damper L/D = {ratio:.2f} > {SHORT_DAMPER_MAX_L_D}: the short-damper closed form overestimates "
                  "the film force there (14 % tangential, 27 % radial at L/D = 0.5); set damper.method = \"grid\""])


def _validity(out, s: dict) -> None:
    if max(s["damper_max_eccentricity"]) > 0.6:
        out.warn([f"damper eccentricity up to {max(s['damper_max_eccentricity']):.2f}: the film force is far from "
                  "linear there (and the tables end at damper.max_eccentricity_ratio)"])


def _point(out, case: TurbochargerCase, label: str) -> RunFigures | None:
    """One run of a sweep; a run that stops is reported (a warning naming the point and the cause) and
    left out, so that the rest of the sweep still runs."""
    try:
        return simulate_case(case)[1]
    except CaseError as exc:
        out.warn([f"{label}: {exc}"])
        return None


def _run_up(case: TurbochargerCase, out, progress=None) -> None:
    speeds = case.study.speeds_rpm
    rows, radius, min_load, runs = [], {}, [], []
    for n in (progress(speeds, "speeds") if progress else speeds):
        run = _point(out, with_speed(case, n), f"{n:.0f} rev/min")
        if run is None:
            continue
        runs.append(run)
        s = run.summary
        for name, r in s["orbit_radius_um"].items():
            radius.setdefault(name, []).append(r)
        min_load.append(s["inner_load_min_N"])
        rows.append((n, *s["orbit_radius_um"].values(), *s["damper_max_eccentricity"],
                     *s["housing_force_amplitude_N"], *s["inner_load_min_N"], *s["inner_unloaded_share"],
                     s["timestep_s"]))
        _validity(out, s)
    if not rows:
        raise CaseError("study.speeds_rpm: the run stopped at every speed (see the warnings)")
    speeds = [r[0] for r in rows]
    names = [n.replace(" ", "_") for n in radius]
    out.write_csv("run_up.csv", ["speed_rpm"] + [f"{n}_orbit_radius_um" for n in names] +
                  ["turbine_damper_max_eps", "compressor_damper_max_eps", "turbine_housing_force_N",
                   "compressor_housing_force_N", "turbine_row_min_inner_load_N", "compressor_row_min_inner_load_N",
                   "turbine_row_unloaded_share", "compressor_row_unloaded_share", "timestep_s"], rows)
    op = case.operation
    out.save_figure(plot_over_speed(list(speeds), radius, min_load,
                                    f"{case.name}: {op.unbalance_g_mm:g} g·mm at the {op.unbalance_at}, preload "
                                    f"{case.bearings.preload_N:g} N, steady runs"), "run_up.png")
    out.save_figure(plot_waterfall(speeds, runs, case.name), "waterfall.png")
    out.summary.update(points=[dict(speed_rpm=r[0], orbit_radius_um=dict(zip(radius, r[1:5])),
                                    damper_max_eccentricity=list(r[5:7]), housing_force_amplitude_N=list(r[7:9]),
                                    inner_load_min_N=list(r[9:11]), inner_unloaded_share=list(r[11:13]),
                                    timestep_s=r[13]) for r in rows])
    out.note(f"{len(rows)} speeds: the step the stable-step guard picked "
             + ", ".join(f"{r[0]:.0f} rev/min {r[13]:.3g} s" for r in rows))


def _damper(case: TurbochargerCase, out, progress=None) -> None:
    lengths, clearances = case.study.damper_lengths_m, case.study.damper_clearances_m
    grid = [(c, L) for c in clearances for L in lengths]
    force, radius, rows = {}, {}, []
    for c, L in (progress(grid, "dampers") if progress else grid):
        variant = dataclasses.replace(case, damper=dataclasses.replace(case.damper, clearance_m=c, length_m=L))
        run = _point(out, variant, f"L = {L * 1e3:g} mm, c = {c * 1e6:g} µm")
        if run is None:
            force.setdefault(c, []).append(math.nan)
            radius.setdefault(c, []).append(math.nan)
            rows.append((L, c, math.nan, math.nan, math.nan, math.nan))
            continue
        s = run.summary
        f = max(s["housing_force_amplitude_N"])
        r = s["orbit_radius_um"]["turbine bearing"]
        force.setdefault(c, []).append(f)
        radius.setdefault(c, []).append(r)
        rows.append((L, c, f, r, max(s["damper_max_eccentricity"]), min(s["inner_load_min_N"])))
        _validity(out, s)
    out.write_csv("damper_sweep.csv", ("length_m", "clearance_m", "housing_force_max_N", "turbine_bearing_orbit_um",
                                       "damper_max_eps", "min_inner_load_N"), rows)
    out.save_figure(plot_damper_sweep(lengths, clearances, [force[c] for c in clearances],
                                      [radius[c] for c in clearances],
                                      f"{case.name}: {case.operation.speed_rpm:.0f} rev/min, damper land and clearance"),
                    "damper_sweep.png")
    out.summary.update(points=[dict(zip(("length_m", "clearance_m", "housing_force_max_N", "turbine_bearing_orbit_um",
                                         "damper_max_eps", "min_inner_load_N"), r)) for r in rows])
    ran = [r for r in rows if math.isfinite(r[2])]
    if not ran:
        raise CaseError("study.damper_clearances_m: every damper of the sweep stopped (see the warnings)")
    best = min(ran, key=lambda r: r[2])
    out.note(f"{len(ran)} of {len(rows)} dampers ran: least force into the housing {best[2]:.0f} N at "
             f"L = {best[0] * 1e3:g} mm, c = {best[1] * 1e6:g} µm")


STUDIES = {
    "run": StudyEntry(run=_run),
    "run-up": StudyEntry(run=_run_up, sweeps=("speeds_rpm",), unused={"operation.speed_rpm": "set study.speeds_rpm"}),
    "damper": StudyEntry(run=_damper, sweeps=("damper_lengths_m", "damper_clearances_m"),
                         unused={"damper.length_m": "set study.damper_lengths_m",
                                 "damper.clearance_m": "set study.damper_clearances_m"}),
}


def case_unused_keys(case: TurbochargerCase) -> dict[str, str]:
    """Every key of ``case`` its study does not read → what does its job."""
    out = unused_keys(case.study.kind, STUDIES, {}, ())
    if case.operation.unbalance_g_mm == 0.0:
        out["operation.unbalance_at"] = "read only with operation.unbalance_g_mm > 0"
    if case.defect.race == "none":
        out.update({f"defect.{k}": "read only with defect.race = 'inner' or 'outer'"
                    for k in ("length_m", "depth_m", "angle_deg")})
    return out


def uses_dynamics(case: TurbochargerCase) -> bool:
    return True


def run_study(case: TurbochargerCase, out, progress=None) -> None:
    lengths = case.study.damper_lengths_m if case.study.kind == "damper" else (case.damper.length_m,)
    for length in lengths:
        _damper_validity(out, dataclasses.replace(case, damper=dataclasses.replace(case.damper, length_m=length)))
    STUDIES[case.study.kind].run(case, out, progress)
    out.summary["integrator"] = {"kind": "explicit, at the automatic stable step"}
