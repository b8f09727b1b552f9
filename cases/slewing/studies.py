"""The slewing-ring studies (a)–(g) (cases/slewing/README.md): each runs the scenes it needs and writes its figures.

Every study takes the resolved case, a :class:`cases.results.RunOutput` and an optional progress
wrapper, and fills the output's summary (key figures, SI) and report lines. Thesis values quoted
for comparison are from the slewing-ring thesis (README.md, Sources), chapters 3–4 (loads in tonnes-force of 9.81 kN).
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import meshio
import numpy as np

from fem_rings.output import write_vtu

from . import scene
from ..overrides import StudyEntry, unused_keys
from .case import SlewingCase, Study
from .life import plot_subsurface_shear, worst_ball_life
from ..results import plural, share_ylim
from .plots import plot_ball_loads, plot_static, plot_travel
from .auto import CHOSEN_KEYS
from .auto import resolve as resolve_auto
from .quasistatic import analytic_ball_load_N, equilibrium, error_estimates, nominal_ball_load_N, travel

__all__ = ["RUN_KEYS", "STUDIES", "case_unused_keys", "modal_top", "run_study", "runs_of"]

#: a ball counts as unloaded below this share of the nominal ball load
UNLOADED_SHARE = 1e-3


def _bodies(case: SlewingCase) -> scene.Bodies:
    return scene.Bodies(scene.top_body(case), scene.bottom_body(case))


def _fidelity(case: SlewingCase) -> str:
    def one(f, name, modulus=None):
        if f.kind == "rigid":
            return f"{name} rigid"
        if f.kind == "auto":
            return f"{name} chosen per equilibrium (auto), E {modulus or f'{f.E_Pa / 1e9:g} GPa'}"
        return (f"{name} modal ({f.n_modes} modes + groove shapes to harmonic {f.groove_harmonics}, "
                f"E {modulus or f'{f.E_Pa / 1e9:g} GPa'})")
    if "top.E_Pa" in STUDIES[case.study.kind].unused:  # the study sets the modulus itself
        return f"{one(case.top, _top_name(case), 'from study.top_E_Pa')}; {one(case.bottom, 'bottom race')}"
    top = _top_name(case)
    if case.study.kind == "static":  # runs both
        return f"{top} rigid, then {one(replace(case.top, kind='modal'), top)}; {one(case.bottom, 'bottom race')}"
    return f"{one(case.top, top)}; {one(case.bottom, 'bottom race')}"


def _top_name(case: SlewingCase) -> str:
    return "top race + TMR" if case.top.include_tmr else "top race"


def _write_balls_vtu(out, name: str, case: SlewingCase, azimuth_rad, load_N) -> None:
    r = 0.5 * case.geometry.pitch_diameter_m
    pts = np.column_stack((r * np.cos(azimuth_rad), r * np.sin(azimuth_rad), np.zeros_like(azimuth_rad)))
    meshio.Mesh(pts, [("vertex", np.arange(len(pts))[:, None])],
                point_data={"ball_load_N": np.asarray(load_N, float)}).write(out.path(name))


def _write_top_vtu(out, name: str, bodies: scene.Bodies, eta) -> None:
    if bodies.top is not None and len(eta):
        write_vtu(out.path(name), bodies.top.mesh(), {"displacement_m": bodies.top.displacement_m(eta)})


def _distribution_figures(res) -> dict:
    q = res.rows[0].load_N
    return {"max_ball_load_N": float(q.max()), "min_ball_load_N": float(q.min()),
            "unloaded_balls": int(np.sum(q < UNLOADED_SHARE * q.mean())),
            "equilibrium_error": float(res.equilibrium_error)}


# -- (a) static validation ---------------------------------------------------------------------
def study_static(case: SlewingCase, out, progress=None) -> None:
    """Flat races, pure axial dead load: every ball carries the analytic thrust load (Harris §7.2,
    loaded contact angle) — rigid and modal top structure; also against the thesis' W/(Z sin α0)."""
    Q, alpha = analytic_ball_load_N(case)
    Q0 = nominal_ball_load_N(case)
    curves, figures = {}, {}
    for kind in ("rigid", "modal"):
        c = case.with_(top={"kind": kind}, undulation={"scale": 0.0}, thermal={"offset_m": 0.0})
        bodies = _bodies(c)
        res = equilibrium(c, bodies)
        out.warn(res.warnings, f"{kind} top")
        q = res.rows[0].load_N
        curves[kind] = q
        figures[kind] = {"mean_ball_load_N": float(q.mean()), "max_error_vs_analytic": float(np.abs(q / Q - 1).max()),
                         "max_error_vs_nominal_angle": float(np.abs(q / Q0 - 1).max()),
                         "spread": float((q.max() - q.min()) / q.mean()),
                         "axial_sum_over_load": float(res.reaction[2] / c.dead_load_N),
                         "loaded_contact_angle_deg": float(np.degrees(res.rows[0].contact_angle_rad.mean()))}
        out.note(f"{kind:5s} top: mean ball load {q.mean():.0f} N, largest error {100 * figures[kind]['max_error_vs_analytic']:.3f} % "
                 f"against Q = {Q:.0f} N at the loaded angle {math.degrees(alpha):.3f}° "
                 f"({100 * figures[kind]['max_error_vs_nominal_angle']:.2f} % against W/(Z sin α0) = {Q0:.0f} N)")
        _write_balls_vtu(out, f"balls_{kind}.vtu", c, res.rows[0].azimuth_rad, q)
        if kind == "modal":
            _write_top_vtu(out, "top_structure_modal.vtu", bodies, res.modal("top"))
    out.summary.update(analytic_ball_load_N=Q, analytic_contact_angle_deg=math.degrees(alpha), nominal_ball_load_N=Q0,
                       **{f"{k}_top": v for k, v in figures.items()})
    out.write_csv("ball_loads.csv", ["ball", "rigid_load_N", "modal_load_N"],
                  [(i + 1, curves["rigid"][i], curves["modal"][i]) for i in range(len(curves["rigid"]))])
    out.save_figure(plot_static(curves, Q, Q0, case), "ball_loads.png")


# -- (c) undulation ----------------------------------------------------------------------------
def study_undulation(case: SlewingCase, out, progress=None) -> None:
    """Undulated bottom race, ``undulation_scales`` × ``top_E_Pa``: max load, unloaded balls.
    Each pair is a ``single`` equilibrium in its own folder, the spacer run (:func:`_spacer_run`)
    one more (:func:`_single_runs`). With ``kind = "auto"`` each equilibrium decides its races
    (its ``fidelity_decisions``; ``fidelity`` in the table)."""
    s = case.study
    base = case
    items = [(E, h) for E in s.top_E_Pa for h in s.undulation_scales]
    points = [(f"E={E / 1e9:g}GPa_undulation={h:g}", f"E {E / 1e9:g} GPa, undulation ×{h:g}",
               base.with_(top={"E_Pa": E}, undulation={"scale": h},
                          analysis={"type": "quasi_static", "travel_steps": 0})) for E, h in items]
    spacers = [_spacer_run(base)] if s.spacer_run_s > 0.0 else []
    summaries = _single_runs(case, out, points + spacers, progress)  # (the kernels compile meanwhile)
    table, curves = [], {}
    for (E, h), (folder, label, _) in zip(items, points):
        r = summaries[folder]
        out.warn(r.get("warnings", ()), label)
        fig = {k: r[k] for k in ("max_ball_load_N", "min_ball_load_N", "unloaded_balls", "equilibrium_error")}
        curves[(E, h)] = np.asarray(r["ball_load_N"], float)
        decided = "; ".join(d["choice"] for d in r.get("fidelity_decisions", ()))
        table.append({"top_E_Pa": E, "undulation_scale": h, **fig, "error_estimates": r["error_estimates"],
                      "folder": folder, **({"fidelity": decided} if decided else {})})
        out.note(f"E {E / 1e9:7.4g} GPa, undulation ×{h:g}: max ball load {fig['max_ball_load_N']:.0f} N, "
                 f"{plural(fig['unloaded_balls'], 'ball')} unloaded ({folder}/)"
                 + (f"; auto: {decided}" if decided else ""))
    azimuth = np.radians(summaries[points[0][0]]["ball_azimuth_deg"])
    out.summary["cases"] = table
    out.write_csv("ball_loads.csv", ["ball", "azimuth_deg"] + [f"load_E{E / 1e9:g}GPa_x{h:g}_N" for E, h in curves],
                  [(i + 1, math.degrees(azimuth[i]), *(q[i] for q in curves.values())) for i in range(len(azimuth))])
    if spacers:
        _spacer_notes(case, out, summaries[spacers[0][0]])
    figs = {E: plot_ball_loads({h: curves[(E, h)] for h in s.undulation_scales}, azimuth, case,
                               f"top structure E = {E / 1e9:g} GPa") for E in s.top_E_Pa}
    share_ylim(f.axes[0] for f in figs.values())  # the moduli compared on one load scale
    for E, f in figs.items():
        out.save_figure(f, f"ball_loads_E{E / 1e9:g}GPa.png")


def _single_runs(case: SlewingCase, out, points, progress) -> dict[str, dict]:
    """Each ``(folder, label, case)`` of ``points`` run as the ``single`` study into
    ``<results>/<folder>/`` (:func:`cases.sweep.variants.run_variants`: in this process, or on
    Dask with ``flexbearing run --workers/--scheduler``, resumed with ``--resume``); returns
    folder → the run's ``summary.json`` (output units)."""
    from ..sweep.variants import run_variants

    runs = [(folder, replace(c, study=Study(), name=f"{case.name}-{folder.replace('=', '-')}",
                             description=f"{label} of {case.name}"))
            for folder, label, c in points]
    return run_variants(runs, out, progress)


def _spacer_run(case: SlewingCase) -> tuple[str, str, SlewingCase]:
    """The run for the spacer–load ball forces: the undulated ring (×1, from its quasi-static
    equilibrium; rigid top structure, or ``study.spacer_run_top = "modal"`` the case's modal one
    at E = ``top_E_Pa[0]``) turning for ``spacer_run_s``, in the sub-folder ``spacer_run``."""
    modal = case.study.spacer_run_top == "modal"
    top = {"kind": "modal", "E_Pa": case.study.top_E_Pa[0]} if modal else {"kind": "rigid"}
    # (a single run: the undulation study itself takes no rigid top structure)
    return "spacer_run", "spacer run", replace(case, study=Study()).with_(
        top=top, undulation={"scale": 1.0}, analysis={"type": "dynamic_explicit", "duration_s": case.study.spacer_run_s})


def _spacer_notes(case: SlewingCase, out, summary: dict) -> None:
    """The spacer run's key figures (its ``summary.json``) into the study's summary and report."""
    fs = {k: summary[k] for k in ("max_spacer_force_N", "mean_spacer_force_N", "p99_spacer_force_N",
                                  "start_up_excluded_s", "start_up_max_spacer_force_N", "timestep_s") if k in summary}
    modal = case.study.spacer_run_top == "modal"
    what = f"modal top E {case.study.top_E_Pa[0] / 1e9:g} GPa" if modal else "rigid top"
    out.summary["spacer_run"] = {"duration_s": case.study.spacer_run_s, "top": case.study.spacer_run_top, **fs}
    out.warn(summary.get("warnings", ()), "spacer run")
    start = (f"; the first {fs['start_up_excluded_s']:.3g} s left out (start-up, peak "
             f"{fs['start_up_max_spacer_force_N']:.0f} N)" if "start_up_max_spacer_force_N" in fs else "")
    out.note(f"dynamic, {what}, undulation ×1, {case.study.spacer_run_s:g} s: spacer–load ball force "
             f"peak {fs['max_spacer_force_N']:.0f} N (impacts of unloaded balls), 99th percentile "
             f"{fs['p99_spacer_force_N']:.0f} N, mean {fs['mean_spacer_force_N']:.1f} N{start}")


# -- (d) thermal offset and (e) combined -------------------------------------------------------
def _history_csv(prefix: str, offset_m: float, E_Pa: float) -> str:
    return f"{prefix}_ball_history_{offset_m * 1e3:g}mm_E{E_Pa / 1e9:g}GPa.csv"


def _travel_study(case: SlewingCase, out, offsets, stiffness, undulation: float, progress, prefix: str):
    """Travels for every stiffness × offset: rows of key figures and, per case, the history
    (azimuth deg, load N, top rotation deg) of the ball that meets the largest load."""
    a = case.analysis
    steps = a.travel_steps or 144
    rows, histories = [], {}
    for E in stiffness:
        for d in offsets:
            c = case.with_(thermal={"offset_m": d}, undulation={"scale": undulation},
                           top={"E_Pa": E} if case.top.kind == "modal" else {})
            tr = travel(c, _bodies(c), steps, a.travel_revolutions, progress)
            out.warn(tr.warnings, f"{prefix} Δ = {d * 1e3:g} mm, E {E / 1e9:g} GPa")
            k, b = tr.worst
            # the ball that passes the worst place: its whole history
            histories[(E, d)] = (np.degrees(np.mod(tr.ball_azimuth_rad[:, b], 2 * math.pi)), tr.load_N[:, b],
                                 np.degrees(tr.top_rotation_rad))
            rows.append({"top_E_Pa": E, "offset_m": d, "max_ball_load_N": float(tr.load_N.max()),
                         "worst_ball": b + 1, "worst_azimuth_deg": float(np.degrees(tr.ball_azimuth_rad[k, b]) % 360),
                         "worst_top_rotation_deg": float(np.degrees(tr.top_rotation_rad[k])),
                         "min_ball_load_N": float(tr.load_N.min())})
            out.note(f"{prefix} Δ = {d * 1e3:.2f} mm" + (f", E {E / 1e9:g} GPa" if case.top.kind == "modal" else "")
                     + f": worst ball load {tr.load_N.max():.0f} N at ψ = {rows[-1]['worst_azimuth_deg']:.0f}°")
            out.write_csv(_history_csv(prefix, d, E),
                          ["top_rotation_deg", "ball_azimuth_deg", "load_N"],
                          zip(np.degrees(tr.top_rotation_rad), *histories[(E, d)][:2]))
            _write_balls_vtu(out, f"{prefix}_balls_worst_{d * 1e3:g}mm_E{E / 1e9:g}GPa.vtu", c,
                             tr.ball_azimuth_rad[k], tr.load_N[k])
    return rows, histories


def _travel_runs(case: SlewingCase, out, offsets, stiffness, undulation: float, progress, prefix: str):
    """:func:`_travel_study` with every stiffness × offset a ``single`` travel in its own folder
    (:func:`_single_runs`); the ball histories are read back from the folders."""
    modal = case.top.kind == "modal"
    items = [(E, d) for E in stiffness for d in offsets]
    points = [(f"offset={d * 1e3:g}mm" + (f"_E={E / 1e9:g}GPa" if modal else ""), f"{prefix} Δ = {d * 1e3:g} mm",
               case.with_(thermal={"offset_m": d}, undulation={"scale": undulation},
                          analysis={"type": "quasi_static", "travel_steps": case.analysis.travel_steps or 144},
                          top={"E_Pa": E} if modal else {})) for E, d in items]
    summaries = _single_runs(case, out, points, progress)
    rows, histories = [], {}
    for (E, d), (folder, _, c) in zip(items, points):
        r = summaries[folder]
        out.warn(r.get("warnings", ()))  # (each names its offset and modulus)
        rows.append({"top_E_Pa": E, "offset_m": d, "folder": folder,
                     **{k: r["cases"][0][k] for k in ("max_ball_load_N", "worst_ball", "worst_azimuth_deg",
                                                      "worst_top_rotation_deg", "min_ball_load_N")}})
        rotation, azimuth, load = np.loadtxt(Path(out.folder) / folder / _history_csv("travel", d, c.top.E_Pa),
                                             delimiter=",", skiprows=1, ndmin=2).T
        histories[(E, d)] = (azimuth, load, rotation)
        out.note(f"{prefix} Δ = {d * 1e3:.2f} mm" + (f", E {E / 1e9:g} GPa" if modal else "")
                 + f": worst ball load {rows[-1]['max_ball_load_N']:.0f} N at ψ = {rows[-1]['worst_azimuth_deg']:.0f}° "
                 f"({folder}/)")
    return rows, histories


def study_thermal(case: SlewingCase, out, progress=None) -> None:
    """Radial offsets Δ of the top (80–100°, turning with it) and bottom (260–280°) race."""
    rows, hist = _travel_runs(case, out, case.study.offsets_m, (case.top.E_Pa,), 0.0, progress, "thermal")
    out.summary["cases"] = rows
    out.summary["nominal_ball_load_N"] = nominal_ball_load_N(case)
    out.save_figure(plot_travel({f"Δ = {d * 1e3:g} mm": v for (E, d), v in hist.items()}, case,
                                "Load on one ball over a revolution: differential thermal expansion"),
                    "thermal_ball_load.png")


def study_combined(case: SlewingCase, out, progress=None) -> None:
    """Undulation × 1 with the thermal offsets ``combined_offsets_m``, modal top at each ``top_E_Pa``."""
    c = case.with_(top={"kind": "modal"}) if case.top.kind == "rigid" else case
    rows, hist = _travel_runs(c, out, case.study.combined_offsets_m, case.study.top_E_Pa, 1.0, progress, "combined")
    out.summary["cases"] = rows
    label = {(E, d): f"Δ = {d * 1e3:g} mm, E = {E / 1e9:g} GPa" for (E, d) in hist}
    out.save_figure(plot_travel({label[k]: v for k, v in hist.items()}, case,
                                "Worst ball over a revolution: undulation + thermal offset"), "combined_worst_ball.png")


# -- (f) worst ball life -----------------------------------------------------------------------
def study_life(case: SlewingCase, out, progress=None) -> None:
    """Worst ball of the combined case at ``life_offset_m`` (E = last of ``top_E_Pa``): Hertz,
    subsurface shear with the case depth, ISO 281 life and the case-depth corrected life."""
    s = case.study
    c = case.with_(top={"kind": "modal"}) if case.top.kind == "rigid" else case
    rows, hist = _travel_study(c, out, (s.life_offset_m,), (s.top_E_Pa[-1],), 1.0, progress, "combined")
    Q = rows[0]["max_ball_load_N"]
    life = worst_ball_life(Q, pitch_diameter_m=case.geometry.pitch_diameter_m, n_balls=case.geometry.n_balls,
                           axial_load_N=case.dead_load_N, speed_rpm=case.analysis.speed_rpm,
                           case_depth_m=s.case_depth_m)
    out.summary.update(worst_case=rows[0], life=life.to_dict())
    plot_subsurface_shear(life, out.path("subsurface_shear.png"))
    out.save_figure(plot_travel({f"Δ = {s.life_offset_m * 1e3:g} mm, E = {s.top_E_Pa[-1] / 1e9:g} GPa": v
                                 for v in hist.values()}, case, "Worst ball over a revolution"),
                    "worst_ball_history.png")
    out.note(f"worst ball {Q:.0f} N: p0 {life.p0_inner_Pa / 1e6:.0f} MPa (top race), τ_max "
             f"{life.tau_max_inner_Pa / 1e6:.0f} MPa at {life.depth_tau_max_inner_m * 1e3:.2f} mm; required case depth "
             f"{life.required_case_depth_m * 1e3:.1f} mm; A_cd {life.A_cd:.3f} at {s.case_depth_m * 1e3:g} mm")
    out.note(f"ISO 281: C_a {life.C_a_N:.0f} N, L10 {life.L10_nominal_Mrev:.4g} Mrev at the dead load, "
             f"{life.L10_worst_Mrev:.4g} Mrev with the worst ball everywhere, case-depth corrected "
             f"{life.L_cd_Mrev:.4g} Mrev")


# -- (g) full scale ----------------------------------------------------------------------------
def study_full_scale(case: SlewingCase, out, progress=None) -> None:
    """The Ø6.69 m ring with its own stiffness beside the 2 m ring with E = ``top_E_Pa[-1]``
    (the thesis' scaling), both undulated ×1 with a modal top structure."""
    results = {}
    scenes = [("full", scene.REFERENCE_E_PA), ("2m", case.study.top_E_Pa[-1])]
    for variant, E in (progress(scenes, "bearings") if progress else scenes):
        c = case.with_(geometry={"variant": variant}, top={"kind": "modal", "E_Pa": E,
                                                             "element_size_m": None if variant != case.geometry.variant
                                                             else case.top.element_size_m},
                       undulation={"scale": 1.0})
        bodies = _bodies(c)
        res = equilibrium(c, bodies)
        out.warn(res.warnings, variant)
        q = res.rows[0].load_N
        results[variant] = (res.rows[0].azimuth_rad, q, nominal_ball_load_N(c))
        fig = _distribution_figures(res)
        fig.update(top_E_Pa=E, nominal_ball_load_N=nominal_ball_load_N(c), n_balls=c.geometry.n_balls,
                   max_over_nominal=fig["max_ball_load_N"] / nominal_ball_load_N(c),
                   unloaded_share=fig["unloaded_balls"] / c.geometry.n_balls,
                   lowest_frequency_Hz=float(bodies.top.frequencies_Hz[0]), n_nodes=len(bodies.top.nodes_m))
        out.summary[variant] = fig
        out.note(f"{variant:4s} (E {E / 1e9:g} GPa): max ball load {fig['max_ball_load_N']:.0f} N = "
                 f"{fig['max_over_nominal']:.2f} × nominal, {fig['unloaded_balls']} of {plural(c.geometry.n_balls, 'ball')} "
                 "unloaded")
        _write_top_vtu(out, f"top_structure_{variant}.vtu", bodies, res.modal("top"))
        out.write_csv(f"ball_loads_{variant}.csv", ["ball", "azimuth_deg", "load_N"],
                      [(i + 1, math.degrees(res.rows[0].azimuth_rad[i]), q[i]) for i in range(len(q))])
    out.save_figure(plot_ball_loads({v: (az, q / Q) for v, (az, q, Q) in results.items()}, None, case,
                                    "Full scale vs 2 m with reduced stiffness", normalised=True),
                    "full_vs_2m.png")


#: keys of each kind of run; a study that makes no run of a kind does not read its keys
_DYNAMIC_KEYS = ("analysis.speed_rpm", "analysis.duration_s", "analysis.timestep_s", "analysis.record_every",
                 "analysis.spacers", "analysis.rho_inf", "analysis.reference_samples", "contact.damping_ratio", "contact.mu_static",
                 "contact.mu_dynamic", "contact.v_static_m_s", "contact.v_dynamic_m_s", "contact.friction",
                 "contact.implicit_friction", "analysis.implicit_modes")
RUN_KEYS = {
    "dynamic": (dict.fromkeys(_DYNAMIC_KEYS), 'read by dynamic runs only (study.kind = "rotation", or "single" '
                'with analysis.type = "dynamic_explicit")'),
    "travels": (dict.fromkeys(("analysis.travel_steps", "analysis.travel_revolutions")),
                'read by travels only (study.kind = "thermal", "combined", "life", or "single" with travel_steps)'),
}
_TYPE = {"analysis.type": "the study chooses its runs itself"}
_MODAL_TOP = {"top.kind": "the study always takes a modal top structure"}

#: study kind → what runs it and the keys it does not read (:mod:`cases.overrides`)
STUDIES = {
    "single": StudyEntry(None, reads=("analysis.travel_steps",)),
    "static": StudyEntry(study_static, runs=("equilibria",), unused={
        **_TYPE, "top.kind": "the study runs a rigid and a modal top structure",
        "undulation": 'flat races here; study.kind = "undulation" undulates the bottom race',
        "thermal": 'no offset here; study.kind = "thermal" sweeps study.offsets_m'}),
    "rotation": StudyEntry(None, runs=("dynamic",)),
    "undulation": StudyEntry(study_undulation, sweeps=("undulation_scales", "top_E_Pa", "spacer_run_s",
                                                       "spacer_run_top"),
                             runs=("equilibria", "dynamic"), variants=True, unused={
        **_TYPE, "top.E_Pa": "set study.top_E_Pa (the moduli it sweeps)",
        "undulation.scale": "set study.undulation_scales (the scales it sweeps)",
        "analysis.duration_s": "set study.spacer_run_s (the simulated time of its spacer run)"}),
    "thermal": StudyEntry(study_thermal, sweeps=("offsets_m",), runs=("travels",), variants=True, unused={
        **_TYPE, "thermal.offset_m": "set study.offsets_m (the offsets it sweeps)",
        "undulation": 'flat races here; study.kind = "combined" adds the undulation'}),
    "combined": StudyEntry(study_combined, sweeps=("combined_offsets_m", "top_E_Pa"), runs=("travels",),
                           variants=True, unused={
        **_TYPE, **_MODAL_TOP, "top.E_Pa": "set study.top_E_Pa (the moduli it sweeps)",
        "thermal.offset_m": "set study.combined_offsets_m (the offsets it sweeps)",
        "undulation.scale": "the study takes the undulation ×1"}),
    "life": StudyEntry(study_life, sweeps=("life_offset_m", "case_depth_m", "top_E_Pa"), runs=("travels",),
                       reads=("analysis.speed_rpm",), unused={
        **_TYPE, **_MODAL_TOP, "top.E_Pa": "set study.top_E_Pa (its last value is taken)",
        "thermal.offset_m": "set study.life_offset_m", "undulation.scale": "the study takes the undulation ×1"}),
    "full-scale": StudyEntry(study_full_scale, sweeps=("top_E_Pa",), runs=("equilibria",), unused={
        **_TYPE, **_MODAL_TOP,
        "top.E_Pa": "set study.top_E_Pa (its last value is the 2 m ring's; the full ring takes 200 GPa)",
        "undulation.scale": "the study takes the undulation ×1"}),
}


#: fidelity keys of a ring that only a modal ring reads
_MODAL_KEYS = ("n_modes", "groove_harmonics", "E_Pa", "damping_ratio", "element_size_m", "raceway_spread_m",
               "ball_load_shapes", "stress_modes")


def modal_top(case: SlewingCase) -> bool:
    """True when the study makes the top structure modal in some run (it sets ``top.kind``
    itself, or the case asks for it)."""
    return case.top.kind in ("modal", "auto") or "top.kind" in STUDIES[case.study.kind].unused


def _fidelity_unused(case: SlewingCase) -> dict[str, str]:
    """The fidelity keys no run of the case reads: those of a rigid ring, each ring's keys that
    belong to the other one, and the damping ratio the thesis preset replaces."""
    out = {"top.bolts": "only the bottom race is bolted (bottom.bolts)",
           "bottom.include_tmr": "only the top structure carries the TMR (top.include_tmr)"}
    if not modal_top(case):
        out.update({f"top.{k}": 'the top structure is rigid here; set top.kind = "modal"'
                    for k in (*_MODAL_KEYS, "include_tmr")})
    for race in ("top", "bottom"):
        if getattr(case, race).kind == "auto":
            out.update({f"{race}.{k}": f'{race}.kind = "auto" chooses it; set {race}.kind = "modal" to choose it '
                        'yourself' for k in CHOSEN_KEYS})
    if case.contact.preset == "thesis":
        out["contact.damping_ratio"] = "the thesis preset takes the thesis' damping c = K/1000 s"
    if case.bottom.kind == "rigid":
        out.update({f"bottom.{k}": 'the bottom race is rigid here; set bottom.kind = "modal"'
                    for k in (*_MODAL_KEYS, "bolts")})
    return out


def runs_of(case: SlewingCase) -> tuple[str, ...]:
    """The kinds of run (keys of :data:`RUN_KEYS`, and ``equilibria``) the case makes."""
    entry = STUDIES[case.study.kind]
    if case.study.kind == "undulation" and not case.study.spacer_run_s:
        return ("equilibria",)  # no spacer run
    if entry.runs:
        return entry.runs
    if case.analysis.type != "quasi_static":
        return ("dynamic",)
    return ("travels",) if case.analysis.travel_steps else ("equilibria",)


def case_unused_keys(case: SlewingCase) -> dict[str, str]:
    """Every key of ``case`` its study does not read → what does its job."""
    out = {**_fidelity_unused(case), **unused_keys(case.study.kind, STUDIES, RUN_KEYS, runs_of(case))}
    if runs_of(case) != ("dynamic",):  # run_dynamic alone reads them (the undulation study's spacer run does not)
        for race in ("top", "bottom"):
            out.setdefault(f"{race}.stress_modes", 'the stress over time is a result of dynamic runs only '
                           '(study.kind = "rotation", or "single" with a dynamic analysis.type)')
    if "dynamic" in runs_of(case) and case.analysis.type != "dynamic_implicit":
        out.setdefault("analysis.rho_inf", 'read by implicit runs only (analysis.type = "dynamic_implicit")')
    if "dynamic" in runs_of(case) and case.analysis.type == "dynamic_implicit":
        out.setdefault("analysis.implicit_modes", 'the generalized-α integrator takes every mode implicitly; '
                       'read by explicit runs (analysis.type = "dynamic_explicit")')
    top_modal = (case.study.spacer_run_top == "modal" if case.study.kind == "undulation" else modal_top(case))
    if not top_modal and case.bottom.kind == "rigid":
        out.setdefault("analysis.implicit_modes", 'both races of the dynamic run are rigid here: no modes to '
                       'integrate')
    return out


#: the case tables its reduced bodies depend on (:func:`prepare`)
PREPARE_TABLES = ("geometry", "top", "bottom")


def prepare(case: SlewingCase) -> bool:
    """Mesh and reduce the modal top structure and bottom race of ``case`` into the model cache
    (a sweep does this once before its points start); False when both are rigid or left to
    ``auto``, which decides inside the run."""
    top = modal_top(case) and case.top.kind != "auto"  # (a study may make the top modal itself)
    if not (top or case.bottom.kind == "modal"):
        return False
    _bodies(case.with_(top={"kind": "modal" if top else "rigid", "E_Pa": scene.REFERENCE_E_PA},
                       bottom={"E_Pa": scene.REFERENCE_E_PA}))
    return True


def uses_dynamics(case: SlewingCase) -> bool:
    """True when the case runs the explicit dynamics (the numba kernels) at some point."""
    return "dynamic" in runs_of(case)


def run_study(case: SlewingCase, out, progress=None) -> None:
    """Run the study the case names (``single`` with ``quasi_static``: one equilibrium or a travel)."""
    if "auto" in (case.top.kind, case.bottom.kind) and case.study.kind == "single":  # (a study's equilibria decide)
        case, decisions = resolve_auto(case)
        out.summary["fidelity_decisions"] = decisions
        for d in decisions:
            out.note(f"fidelity auto: {d['choice']}, because {d['reason']}")
    out.note(f"modelled: {case.geometry.variant} ring, {plural(case.geometry.n_balls, 'load ball')}, dead load "
             f"{case.dead_load_t:g} t ({case.dead_load_N:.0f} N); {_fidelity(case)}; contact {case.contact.preset}")
    if STUDIES[case.study.kind].run is not None:
        return STUDIES[case.study.kind].run(case, out, progress)
    if runs_of(case) == ("dynamic",):
        from .dynamic import run_dynamic

        return run_dynamic(case, out, progress)
    bodies = _bodies(case)
    if case.analysis.travel_steps:
        rows, hist = _travel_study(case, out, (case.thermal.offset_m,), (case.top.E_Pa,), case.undulation.scale,
                                   progress, "travel")
        out.summary["cases"] = rows
        out.save_figure(plot_travel({"worst ball": v for v in hist.values()}, case, "Worst ball over the run",
                                    thermal=bool(case.thermal.offset_m)),
                        "worst_ball.png")
        return None
    res = equilibrium(case, bodies)
    out.warn(res.warnings)
    out.summary.update(_distribution_figures(res), nominal_ball_load_N=nominal_ball_load_N(case),
                       ball_load_N=res.rows[0].load_N, ball_azimuth_deg=np.degrees(res.rows[0].azimuth_rad),
                       error_estimates=error_estimates(case, bodies, res))
    _write_balls_vtu(out, "balls.vtu", case, res.rows[0].azimuth_rad, res.rows[0].load_N)
    if bodies.top is not None:
        _write_top_vtu(out, "top_structure.vtu", bodies, res.modal("top"))
    out.save_figure(plot_ball_loads({"normal ball load": res.rows[0].load_N}, res.rows[0].azimuth_rad, case, case.name),
                    "ball_loads.png")
    out.note(f"max ball load {res.rows[0].load_N.max():.0f} N")
    return None
