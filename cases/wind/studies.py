"""The studies of the wind main bearing; each fills a :class:`cases.results.RunOutput`.

Paper values quoted for comparison are from Pang et al., *Lubricants* 12 (2024) 252:
Table 4 (roller speeds), §4.3.1 (driving speed) and §4.3.2 (friction).
"""

from __future__ import annotations

import csv
import math
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from mbd_core.quasistatic import Bearing, solve_load_distribution

from ..loaddist_plots import plot_element_loads
from ..overrides import StudyEntry, unused_keys
from . import dynamic, plots
from .bodies import modal_bodies, stress_maps
from .case import Study, WindCase
from .scene import inner_ring_load, load_history, rows
from .spectrum import load_cases, write_csv

__all__ = ["STUDIES", "case_unused_keys", "run_study"]

#: paper Table 4: theoretical roller speeds (r/min) and the rigid / rigid–flexible errors
PAPER_ROLLER_ERRORS = {"radial": (0.0083, 0.0028), "rear thrust": (0.0070, 0.0042), "front thrust": (0.0079, 0.0021)}


def _spectrum_files(case: WindCase, out) -> None:
    t, f = load_history(case)
    write_csv(out.path("load_history.csv"), t, f)
    _, share = load_cases()
    if case.loads.source == "synthetic":
        plots.spectrum_figure(t, f, share, out.path("load_spectrum.png"))


def study_load_case(case: WindCase, out, progress=None) -> None:
    """Quasi-static load distribution (rigid rings) under load case ``loads.case_index`` of the
    synthetic spectrum (× ``loads.scale``) and the inner ring's weight: the load of every roller
    of each row, the largest and the loaded rollers per row, the equilibrium residual."""
    from ..sweep.variants import inside_study

    loads, share = load_cases()
    k = case.loads.case_index
    res = solve_load_distribution(Bearing("three-row roller", rows(case)), inner_ring_load(loads[k] * case.loads.scale))
    out.warn(res.warnings, f"load case {k + 1}")
    out.write_csv("roller_loads.csv", ["row", "roller", "azimuth_deg", "load_N"],
                  [(r.name, i + 1, math.degrees(r.azimuth_rad[i]) % 360.0, r.load_N[i])
                   for r in res.rows for i in range(len(r.load_N))])
    if not inside_study():  # (the static study draws its load cases together)
        plot_element_loads([res], out.path("roller_loads.png"))
    out.summary.update(load_case=k + 1, time_share=float(share[k]), equilibrium_error=float(res.equilibrium_error),
                       max_roller_load_N={r.name: float(r.load_N.max()) for r in res.rows},
                       loaded_rollers={r.name: int(np.sum(r.load_N > 0)) for r in res.rows})
    for r in res.rows:
        out.note(f"load case {k + 1}, {r.name:12s}: largest roller load {r.load_N.max():9.0f} N, "
                 f"{int(np.sum(r.load_N > 0))} of {len(r.load_N)} rollers loaded")


def _roller_loads(path: Path) -> dict:
    """Row name → (azimuth deg, load N) of every roller, from a load case's ``roller_loads.csv``."""
    with open(path, newline="", encoding="utf-8") as fh:
        table = list(csv.DictReader(fh))
    rows: dict = {}
    for r in table:
        psi, q = rows.setdefault(r["row"], ([], []))
        psi.append(float(r["azimuth_deg"]))
        q.append(float(r["load_N"]))
    return rows


def study_static(case: WindCase, out, progress=None) -> None:
    """:func:`study_load_case` under each of the 32 load cases, each a run in its own folder
    ``load_case=NN/`` (:func:`cases.sweep.variants.run_variants`: in this process, or on Dask with
    ``flexbearing run --workers/--scheduler``): largest roller load and loaded rollers per row
    over the spectrum (``max_roller_loads.png``), every roller's load under each load case
    (``roller_loads.png``); the equilibrium residual."""
    from ..sweep.variants import run_variants

    _, share = load_cases()
    runs = [(f"load_case={k + 1:02d}",
             replace(case, study=Study(kind="load-case"), loads=replace(case.loads, case_index=k),
                     name=f"{case.name}-load-case-{k + 1}", description=f"load case {k + 1} of {case.name}"))
            for k in range(len(share))]
    done = run_variants(runs, out, progress)
    summaries = [done[name] for name, _ in runs]
    for r in summaries:
        out.warn(r.get("warnings", ()))  # (each names its load case)
    per_row = {n: [(r["max_roller_load_N"][n], r["loaded_rollers"][n]) for r in summaries]
               for n in summaries[0]["max_roller_load_N"]}
    out.write_csv("max_roller_loads.csv", ["case", "time_share", *[f"{n.replace(' ', '_')}_max_load_N" for n in per_row]],
                  [(k + 1, share[k], *[per_row[n][k][0] for n in per_row]) for k in range(len(share))])
    out.save_figure(plots.max_loads_figure(per_row, share), "max_roller_loads.png")
    out.save_figure(plots.load_cases_figure([_roller_loads(Path(out.folder) / name / "roller_loads.csv")
                                             for name, _ in runs]), "roller_loads.png")
    _spectrum_files(case, out)
    out.summary.update(equilibrium_error_max=max(r["equilibrium_error"] for r in summaries),
                       max_roller_load_N={n: max(v[0] for v in vals) for n, vals in per_row.items()})
    for n, vals in per_row.items():
        out.note(f"{n:12s}: largest roller load {max(v[0] for v in vals):9.0f} N over the {len(share)} load cases "
                 "(each in load_case=NN/)")


def _one_run(case: WindCase, progress=None, out=None, label: str = "") -> tuple[dict, object, dict]:
    """One dynamic run and its figures; with ``out``, its raw time series in ``timeseries[_label].nc``."""
    t0 = time.perf_counter()
    sc, rec = dynamic.run(case, progress)
    figures = {"speeds": dynamic.roller_speeds(case, sc, rec), "cages": dynamic.cage_speeds(case, sc, rec),
               "equilibrium": dynamic.equilibrium_error(case, sc, rec),
               "cage_forces": dynamic.cage_forces(case, sc, rec), "timestep_s": rec["timestep_s"],
               "error_estimates": {"time_step": dynamic.step_error(sc, rec["timestep_s"]),
                                   "slices": dynamic.slice_error(case, sc.modal)},
               "wall_time_s": time.perf_counter() - t0}
    if out is not None:
        _ring_torque(case, out, sc, rec, label)
        out.write_timeseries(sc.model, rec, f"timeseries_{label}.nc" if label else "timeseries.nc", case=case.name,
                             study=case.study.kind, **({"variant": label} if label else {}))
    return figures, sc, rec


def _ring_torque(case: WindCase, out, sc, rec: dict, label: str = "") -> dict:
    """The friction torque of the rollers, cages and drag on both rings about the shaft axis
    (:func:`cases.ring_torque_report.write_ring_torque`), after the settling time."""
    from ..ring_torque_report import write_ring_torque

    title = (f"{case.name}{' (' + label + ')' if label else ''}: torque of the rollers and cages on the rings "
             f"about the shaft axis, {case.analysis.speed_rpm:g} r/min")
    return write_ring_torque(sc.model, rec, {"inner": sc.inner, "outer": sc.outer}, case.analysis.settle_s, out,
                             title, friction=case.contact.friction_law(), label=label)


def _speed_notes(out, fig: dict, label: str = "") -> None:
    for name, s in fig["speeds"].items():
        out.note(f"{label}{name:12s}: loaded rollers {s['loaded_mean_rpm']:.2f} r/min against {s['kinematic_rpm']:.2f} "
                 f"({100 * s['loaded_error']:+.2f} %), roller {s['one_roller']} {s['one_roller_mean_rpm']:.1f} r/min "
                 f"(±{s['one_roller_fluctuation_rpm']:.1f}); cage {100 * fig['cages'][name]['error']:+.2f} %; "
                 f"paper (rigid/flexible) {100 * PAPER_ROLLER_ERRORS[name][0]:.2f} / {100 * PAPER_ROLLER_ERRORS[name][1]:.2f} %")
    e = fig["equilibrium"]
    out.note(f"{label}inner ring equilibrium: force {100 * e['force_error']:.3f} %, moment {100 * e['moment_error']:.3f} % "
             f"of the load; {fig['wall_time_s']:.0f} s wall")
    step = fig["error_estimates"]["time_step"]
    out.note(f"{label}time-step error of the largest roller load (Richardson, h/2 and h/4 over "
             f"{1e3 * step['window_s']:.2g} ms): {100 * step['max_load']:.2g} %")
    slices = fig["error_estimates"]["slices"]
    if slices is not None:
        out.note(f"{label}slicing error of the largest roller load (quasi-static, 2× and 4× the slices): "
                 f"{100 * slices['max_load']:.2g} %")


def study_speeds(case: WindCase, out, progress=None) -> None:
    """Roller and cage speeds against rolling kinematics, with the inner ring's equilibrium."""
    fig, sc, rec = _one_run(case, progress, out)
    _spectrum_files(case, out)
    out.save_figure(plots.roller_speed_figure(case, sc, rec), "roller_speeds.png")
    if case.bodies.any_modal:
        _stress(case, out, fig, sc, rec)
    out.summary.update(fig)
    _speed_notes(out, fig)


def _stress(case: WindCase, out, fig: dict, sc, rec) -> None:
    fig["stress"] = stress_maps(sc, rec, out.folder, after_s=case.analysis.settle_s)
    for name, v in fig["stress"].items():
        out.note(f"{name:18s}: peak von Mises {v['peak_von_mises_MPa']:.1f} MPa at t = {v['time_s']:.3f} s")


def study_rigid_flexible(case: WindCase, out, progress=None) -> None:
    """The speeds study with rigid bodies and with modal rings and cages; the ratio of the two
    models' roller speed errors (paper Table 4: 1.67–3.76), for the loaded rollers and for the
    watched roller over the whole run (loaded and unloaded zones, as the paper's one roller)."""
    figs, runs = {}, {}
    # the modal bodies first (cached on disk): meshed and reduced while the kernels compile in the
    # background for the rigid run (mbd_core.multibody.warmup)
    modal_bodies(case.with_(bodies={"rings": "modal", "cages": "modal"}))
    for label, kind in (("rigid", "rigid"), ("flexible", "modal")):
        c = case.with_(bodies={"rings": kind, "cages": kind})
        fig, sc, rec = _one_run(c, progress, out, label)
        runs[label] = (c, sc, rec)
        _speed_notes(out, fig, f"{label:8s} ")
        figs[label] = fig
        if kind == "modal":
            _stress(case, out, fig, sc, rec)
    for label, f in plots.roller_speed_figures(runs).items():  # one y scale per row for both
        out.save_figure(f, f"roller_speeds_{label}.png")
    _spectrum_files(case, out)
    def ratio(key: str) -> dict:
        return {n: abs(figs["rigid"]["speeds"][n][key]) / max(abs(figs["flexible"]["speeds"][n][key]), 1e-12)
                for n in figs["rigid"]["speeds"]}

    loaded, one = ratio("loaded_error"), ratio("one_roller_error")
    out.summary.update(figs, error_ratio_rigid_over_flexible=loaded, one_roller_error_ratio_rigid_over_flexible=one)
    for label, r in (("loaded rollers", loaded), ("one roller over the run", one)):
        out.note(f"roller speed error, rigid over flexible, {label}: " + ", ".join(f"{n} {v:.2f}" for n, v in r.items())
                 + " (paper 1.67–3.76)")


def _sweep(case: WindCase, out, variants, label: str, progress=None) -> dict:
    """Each ``(key, folder name, case)`` of ``variants`` run as the ``speeds`` study into its own
    folder (:func:`cases.sweep.variants.run_variants`: in this process, or on Dask with
    ``flexbearing run --workers/--scheduler``); returns key → the variant's figures."""
    from ..sweep.variants import run_variants

    runs = [(folder, replace(c, study=Study(), name=f"{case.name}-{folder}",
                             description=f"{label} {key} of {case.name}")) for key, folder, c in variants]
    summaries = run_variants(runs, out, progress)
    results = {}
    for key, folder, _ in variants:
        fig = results[key] = summaries[folder]
        cf = fig["cage_forces"]
        out.note(f"{label} {key}: mean roller–cage force radial {cf['radial']['mean_N']:.1f} N, front "
                 f"{cf['front thrust']['mean_N']:.1f} N, rear {cf['rear thrust']['mean_N']:.1f} N; peak "
                 f"{max(v['peak_N'] for v in cf.values()):.0f} N; inner ring torque "
                 f"{fig['ring_torque']['inner_ring_Nm']:.1f} N·m (run in {folder}/)")
    return results


def study_driving_speed(case: WindCase, out, progress=None) -> None:
    """Cage and raceway forces at each driving speed; front/rear thrust cage force ratio (paper 1.19–1.59)."""
    variants = [(s, f"speed={s:g}rpm", case.with_(analysis={"speed_rpm": s})) for s in case.study.speeds_rpm]
    res = _sweep(case, out, variants, "speed (r/min)", progress)
    ratio = {s: r["cage_forces"]["front thrust"]["mean_N"] / r["cage_forces"]["rear thrust"]["mean_N"] for s, r in res.items()}
    out.summary.update(by_speed_rpm={str(s): r["cage_forces"] for s, r in res.items()},
                       ring_torque_by_speed_rpm={str(s): r["ring_torque"] for s, r in res.items()},
                       front_rear_cage_force_ratio={str(s): v for s, v in ratio.items()})
    out.save_figure(plots.sweep_figure(res, "driving speed, r/min"), "cage_forces_vs_speed.png")
    out.note("front/rear thrust cage force ratio: " + ", ".join(f"{s:g} r/min {v:.2f}" for s, v in ratio.items()))


def study_friction(case: WindCase, out, progress=None) -> None:
    """Cage forces for each (μ_dynamic, μ_static); drop from the highest to the lowest friction (paper 50–76 %)."""
    variants = [(f"{md:g}/{ms:g}", f"friction={md:g}_{ms:g}", case.with_(contact={"mu_dynamic": md, "mu_static": ms}))
                for md, ms in case.study.friction_sets]
    res = _sweep(case, out, variants, "friction μd/μs", progress)
    keys = list(res)
    hi = max(keys, key=lambda k: float(k.split("/")[0]))
    lo = min(keys, key=lambda k: float(k.split("/")[0]))
    drop = {n: 1.0 - res[lo]["cage_forces"][n]["mean_N"] / res[hi]["cage_forces"][n]["mean_N"] for n in res[hi]["cage_forces"]}
    out.summary.update(by_friction={k: r["cage_forces"] for k, r in res.items()}, cage_force_drop=drop,
                       ring_torque_by_friction={k: r["ring_torque"] for k, r in res.items()})
    out.save_figure(plots.sweep_figure(res, "friction μd/μs"), "cage_forces_vs_friction.png")
    out.note("drop of the mean cage force from μd " + f"{hi} to {lo}: " + ", ".join(f"{n} {100 * v:.0f} %" for n, v in drop.items()))


#: study kind → what runs it and the keys it does not read (:mod:`cases.overrides`); every
#: study but ``static`` makes one kind of run, the dynamic one
_QUASI_STATIC_UNUSED = {
    "bodies": "the study is quasi-static with rigid rings",
    "contact": "the study is quasi-static (no damping, friction or cage pockets)",
    "analysis": "the study is quasi-static",
    **{f"rollers.{k}": "a quasi-static load distribution has no roller ends or cage pockets"
       for k in ("rib_clearance_m", "thrust_end_radius_m", "pocket_clearance_m")},
    **{f"loads.{k}": "the study solves load cases of the synthetic spectrum (loads.scale applies)"
       for k in ("source", "csv_path", "spectrum_duration_s", "include_torque")},
}
_STATIC_UNUSED = {**_QUASI_STATIC_UNUSED,
                  "loads.case_index": "the static study solves each of the 32 load cases of the synthetic spectrum"}
STUDIES = {
    "static": StudyEntry(study_static, runs=("equilibria",), variants=True, unused=_STATIC_UNUSED),
    "load-case": StudyEntry(study_load_case, runs=("equilibria",), unused=_QUASI_STATIC_UNUSED),
    "speeds": StudyEntry(study_speeds, runs=("dynamic",)),
    "rigid-flexible": StudyEntry(study_rigid_flexible, runs=("dynamic",), unused={
        "bodies.rings": "the study runs rigid and modal rings", "bodies.cages": "the study runs rigid and modal cages"}),
    "driving-speed": StudyEntry(study_driving_speed, sweeps=("speeds_rpm",), runs=("dynamic",), variants=True, unused={
        "analysis.speed_rpm": "set study.speeds_rpm (the speeds it sweeps)"}),
    "friction": StudyEntry(study_friction, sweeps=("friction_sets",), runs=("dynamic",), variants=True, unused={
        "contact.mu_dynamic": "set study.friction_sets (the (μ_dynamic, μ_static) pairs it sweeps)",
        "contact.mu_static": "set study.friction_sets (the (μ_dynamic, μ_static) pairs it sweeps)"}),
}


_RING_KEYS = ("ring_element_size_m", "bolts", "n_theta", "n_across")


def _fidelity_unused(case: WindCase) -> dict[str, str]:
    """The ``bodies`` keys of rigid rings or cages and the damping ratio the Adams preset replaces."""
    b, out = case.bodies, {}
    if case.study.kind != "rigid-flexible":  # (it runs both)
        if b.rings == "rigid":
            out.update({f"bodies.{k}": 'the rings are rigid here; set bodies.rings = "modal"' for k in _RING_KEYS})
        if b.cages != "modal":
            out["bodies.cage_element_size_m"] = ('bodies.cages = "auto" keeps the cages rigid' if b.cages == "auto"
                                                 else 'the cages are rigid here; set bodies.cages = "modal"')
        if b.rings == "auto":
            out["bodies.n_modes"] = 'bodies.rings = "auto" chooses it'
        elif not b.any_modal:
            out.update({f"bodies.{k}": 'rings and cages are rigid here; set bodies.rings or bodies.cages = "modal"'
                        for k in ("n_modes", "modal_damping_ratio")})
    if case.contact.preset == "adams":
        out["contact.damping_ratio"] = "the adams preset takes the paper's damping c = 70 N·s/mm"
    return out


def case_unused_keys(case: WindCase) -> dict[str, str]:
    """Every key of ``case`` its study does not read → what does its job."""
    return {**_fidelity_unused(case), **unused_keys(case.study.kind, STUDIES, {}, STUDIES[case.study.kind].runs)}


#: the case table its modal bodies depend on (:func:`prepare`)
PREPARE_TABLES = ("bodies",)


def prepare(case: WindCase) -> bool:
    """Mesh and reduce the modal rings and cages of a dynamic ``case`` into the model cache (a
    sweep does this once before its points start); False when there are none to build (rigid,
    ``auto``, or the quasi-static study)."""
    if not uses_dynamics(case):
        return False
    if case.study.kind == "rigid-flexible":
        case = case.with_(bodies={"rings": "modal", "cages": "modal"})
    if "modal" not in (case.bodies.rings, case.bodies.cages):
        return False
    modal_bodies(case)
    return True


def uses_dynamics(case: WindCase) -> bool:
    """True when the case runs the explicit dynamics (the numba kernels) at some point."""
    return "dynamic" in STUDIES[case.study.kind].runs


def run_study(case: WindCase, out, progress=None) -> None:
    if "auto" in (case.bodies.rings, case.bodies.cages):
        from .auto import resolve

        case, decisions = resolve(case)
        out.summary["fidelity_decisions"] = decisions
        for d in decisions:
            out.note(f"fidelity auto: {d['choice']}, because {d['reason']}")
    STUDIES[case.study.kind].run(case, out, progress)
