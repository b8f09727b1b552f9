"""The studies of the DMA bearing (:mod:`cases.dma.case`): a torque run, the report's traction
models side by side, torque over speed."""

from __future__ import annotations


from ..overrides import StudyEntry, unused_keys
from ..ring_torque_report import write_power_losses
from .case import DmaCase
from .plots import plot_models, plot_speed, plot_spectrum, plot_torque
from .torque import run_torque

__all__ = ["STUDIES", "REPORT_TORQUE_PER_BALL_NM", "TRACTION_MODELS", "case_unused_keys", "run_study",
           "uses_dynamics"]

#: the report's traction sets (its Models I–III), as [traction] tables
TRACTION_MODELS = {
    "κ = 1·u": {"model": "linear", "B": 1.0},
    "κ = 0.015": {"model": "constant", "A": 0.015},
    "κ = 0.03": {"model": "constant", "A": 0.030},
    "κ = 0.03 − 1·u": {"model": "falling", "A": 0.030, "B": 1.0},
}
#: the report's mean race torques per ball at 267 N and 60 rev/min, N·m (its Figs. 9 and 18; the
#: κ = 0.03 − 1·u run "close to the one with κ = 0.030", no figure given)
REPORT_TORQUE_PER_BALL_NM = {"κ = 1·u": {"inner": 3.6e-4, "outer": 4.7e-4}, "κ = 0.015": {"inner": 1.65e-3},
                             "κ = 0.03": {"inner": 2.11e-3}}


def _torque_outputs(case: DmaCase, out, run, prefix: str = "") -> dict:
    """The files and key figures of one torque run (``prefix`` names them within a study)."""
    title = (f"DMA bearing, {case.operation.thrust_N:g} N, {case.operation.outer_speed_rpm:g} rev/min, "
             f"{case.traction.label}, {case.traction.strips} strips")
    out.save_figure(plot_torque(run, title), f"{prefix}torque.png")
    out.save_figure(plot_spectrum(run, title), f"{prefix}spectrum.png")
    out.write_csv(f"{prefix}torque.csv", ("t_s", "inner_race_torque_Nm", "outer_race_torque_Nm", "settled"),
                  zip(run.t_s, run.inner_Nm, run.outer_Nm, run.settled.astype(int)))
    write_power_losses(run.losses, out, title, f"{prefix}power_losses", case.traction.label if prefix else "")
    return run.summary()


def _torque(case: DmaCase, out, progress=None) -> None:
    run = run_torque(case)
    figures = _torque_outputs(case, out, run)
    out.summary.update(traction=case.traction.label, **figures)
    out.note(f"torque per ball: inner race {figures['inner_race_torque_per_ball_Nm']:.3g} N·m, outer race "
             f"{figures['outer_race_torque_per_ball_Nm']:.3g} N·m ({case.traction.label}, settled part)")
    out.note(f"ball motion spectrum peaks: {', '.join(f'{f / 1e3:.2f}' for f in figures['ball_motion_peaks_Hz'])} kHz "
             f"(Hertz contact frequency {figures['contact_frequency_Hz'] / 1e3:.2f} kHz)")


def _models(case: DmaCase, out, progress=None) -> None:
    labels = list(TRACTION_MODELS)
    rows, inner, outer = [], [], []
    for label in (progress(labels, "traction models") if progress else labels):
        variant = case.with_(traction=TRACTION_MODELS[label])
        run = run_torque(variant)
        slug = variant.traction.model + ("" if variant.traction.model == "linear" else f"_{variant.traction.A:g}")
        figures = _torque_outputs(variant, out, run, f"{slug}_")
        inner.append(figures["inner_race_torque_per_ball_Nm"])
        outer.append(figures["outer_race_torque_per_ball_Nm"])
        ref = REPORT_TORQUE_PER_BALL_NM.get(label, {})
        rows.append((label, inner[-1], outer[-1], ref.get("inner", float("nan")), ref.get("outer", float("nan"))))
        out.summary.setdefault("models", []).append({"traction": label, **figures})
        out.note(f"{label}: torque per ball inner {inner[-1]:.3g} N·m, outer {outer[-1]:.3g} N·m"
                 + (f" (report: inner {ref['inner']:.3g})" if "inner" in ref else ""))
    out.write_csv("traction_models.csv", ("traction", "inner_race_torque_per_ball_Nm", "outer_race_torque_per_ball_Nm",
                                          "report_inner_per_ball_Nm", "report_outer_per_ball_Nm"), rows)
    out.save_figure(plot_models(labels, inner, outer, REPORT_TORQUE_PER_BALL_NM,
                                f"DMA bearing, {case.operation.thrust_N:g} N, {case.operation.outer_speed_rpm:g} "
                                "rev/min: mean race torque per ball"), "traction_models.png")


def _speed(case: DmaCase, out, progress=None) -> None:
    speeds, loads = case.study.speeds_rpm, case.study.loads_N
    points = [(load, speed) for load in loads for speed in speeds]
    torques = {(load, which): [] for load in loads for which in ("inner", "outer")}
    rows = []
    for load, speed in (progress(points, "load and speed points") if progress else points):
        variant = case.with_(operation={"thrust_N": load, "outer_speed_rpm": speed})
        figures = run_torque(variant).summary()
        for which in ("inner", "outer"):
            torques[(load, which)].append(figures[f"{which}_race_torque_Nm"])
        rows.append((load, speed, figures["inner_race_torque_Nm"], figures["outer_race_torque_Nm"],
                     figures["drag_per_ball_N"]))
        out.summary.setdefault("points", []).append({"thrust_N": load, "outer_speed_rpm": speed, **figures})
    out.write_csv("torque_speed.csv", ("thrust_N", "outer_speed_rpm", "inner_race_torque_Nm", "outer_race_torque_Nm",
                                       "drag_per_ball_N"), rows)
    out.save_figure(plot_speed(list(speeds), torques, f"DMA bearing torque over speed, {case.traction.label}"),
                    "torque_speed.png")
    out.note(f"{len(points)} points: bearing torque on the inner race "
             f"{min(abs(r[2]) for r in rows):.3g} … {max(abs(r[2]) for r in rows):.3g} N·m")


STUDIES = {
    "torque": StudyEntry(run=_torque, unused={"study.speeds_rpm": "read by the speed study only",
                                              "study.loads_N": "read by the speed study only"}),
    "traction-models": StudyEntry(run=_models, unused={
        "traction.model": "the traction-models study runs each of the report's models",
        "traction.A": "the traction-models study runs each of the report's models",
        "traction.B": "the traction-models study runs each of the report's models",
        "study.speeds_rpm": "read by the speed study only", "study.loads_N": "read by the speed study only"}),
    "speed": StudyEntry(run=_speed, unused={"operation.thrust_N": "set study.loads_N",
                                            "operation.outer_speed_rpm": "set study.speeds_rpm"}),
}


def case_unused_keys(case: DmaCase) -> dict[str, str]:
    """Every key of ``case`` its study does not read → what does its job."""
    out = unused_keys(case.study.kind, STUDIES, {}, ())
    traction = case.traction
    if traction.model == "linear":
        out.update({"traction.A": "read by the constant and falling models", "traction.blend_m_s": "read by the "
                    "constant and falling models"})
    else:
        out["traction.B"] = "read by the linear and falling models"
    if case.study.kind == "traction-models":
        out.pop("traction.blend_m_s", None)
    return out


def uses_dynamics(case: DmaCase) -> bool:
    return True


def run_study(case: DmaCase, out, progress=None) -> None:
    STUDIES[case.study.kind].run(case, out, progress)


