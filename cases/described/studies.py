"""The studies of a described bearing: the path of ``flexbearing loaddist``, inside a run's folder."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..bearing_rings import with_fidelity
from ..bearing_solver import bearing_solver
from ..config import CaseError
from ..loaddist_command import LoaddistOptions, bearing_description, loaddist_outputs
from ..overrides import StudyEntry, unused_keys
from .case import DescribedCase, RingFidelity
from .estimates import truncation_estimates

__all__ = ["STUDIES", "PREPARE_TABLES", "case_unused_keys", "prepare", "uses_dynamics", "run_study",
           "described_bearing"]


def described_bearing(case: DescribedCase):
    """(name, description) of the case's bearing, its modal rings at the case's ``[rings]`` fidelity."""
    try:
        name, desc = bearing_description(case.bearing.file)
    except ValueError as exc:
        raise CaseError(f"bearing.file: {exc}") from None
    rings = with_fidelity(dict(desc.rings), case.rings.overrides)
    return name, dataclasses.replace(desc, rings=rings)


def _options(case: DescribedCase, folder: str, curve: bool) -> LoaddistOptions:
    """The ``loaddist`` options the case stands for (printing left to the run's report)."""
    life = case.life
    return LoaddistOptions(out=folder, limiting_curve=curve, s0=case.study.s0 if curve else 1.0,
                           p0_limit_MPa=(case.study.p0_limit_MPa or None) if curve else None,
                           rotating_ring=None if life.rotating_ring == "none" else life.rotating_ring,
                           speed_rpm=None if life.rotating_ring == "none" else life.speed_rpm, json=True)


def _figures(summary: dict, out) -> None:
    """Key figures of the loaddist summary into the run's summary and report."""
    cases = summary.get("load_cases", [summary])
    worst = max((r["max_load_N"] for c in cases for r in c["rows"]), default=math.nan)
    s0 = min((c["static_safety"]["s0"] for c in cases if c.get("static_safety")), default=None)
    out.summary.update(largest_element_load_N=worst, s0_min=s0, load_cases=len(cases), rings=summary.get("rings"))
    out.note(f"{len(cases)} load case(s): largest element load {worst:.0f} N" + (f", s0 {s0:.3g}" if s0 else ""))
    ratio = summary.get("limiting_load_curve_modal_over_rigid")
    if ratio and ratio.get("rays_compared"):
        out.summary["limiting_curve_modal_over_rigid_min"] = ratio["min_ratio"]
        out.note(f"limiting load curve with modal rings: {ratio['min_ratio']:.3f} … {ratio['max_ratio']:.3f} of the "
                 "rigid-ring one along its rays")
    for c in cases:
        out.warn(c.get("warnings", ()), f"load case {c.get('case', 1)}")


def _run(curve: bool):
    def run(case: DescribedCase, out, progress=None) -> None:
        name, desc = described_bearing(case)
        if case.bearing.rings == "auto":
            desc = _decide_rings(case, desc, out)
        solver = bearing_solver(desc, rigid=case.bearing.rings == "rigid")
        loads = desc.load_cases
        results = [solver.solve(load) for load in (progress(loads, "load cases") if progress else loads)]
        summary = loaddist_outputs(_options(case, str(out.path("loaddist")), curve), name, desc, results,
                                   desc.time_share, solver)
        _figures(summary, out)
        worst = max(results, key=lambda res: max(float(np.max(r.load_N)) for r in res.rows))
        out.summary["error_estimates"] = truncation_estimates(desc, solver, worst)
    return run


def _decide_rings(case: DescribedCase, desc, out):
    """``bearing.rings = "auto"``: the rings decided (:mod:`.auto`), the decisions in the summary."""
    from .auto import resolve

    desc, decisions = resolve(case, desc)
    out.summary["fidelity_decisions"] = decisions
    for d in decisions:
        out.note(f"{d['body']}: {d['choice']} — {d['reason']}")
    out.warn([d["warning"] for d in decisions if "warning" in d])
    return desc


def _rotation(case: DescribedCase, out, progress=None) -> None:
    from .rotation import run_rotation

    name, desc = described_bearing(case)
    run_rotation(case, desc, out, progress)


_LIFE = "the rating life needs life.rotating_ring"
_QUASI = "read by the quasi-static studies only"
STUDIES = {
    "load-distribution": StudyEntry(run=_run(False), unused={"rotation": "read by the rotation study only"}),
    "limiting-curve": StudyEntry(run=_run(True), sweeps=("s0", "p0_limit_MPa"),
                                 unused={"rotation": "read by the rotation study only"}),
    "rotation": StudyEntry(run=_rotation, unused={"life": _QUASI}),
}


def case_unused_keys(case: DescribedCase) -> dict[str, str]:
    """Every key of ``case`` its study does not read → what does its job."""
    out = unused_keys(case.study.kind, STUDIES, {}, ())
    if case.life.rotating_ring == "none":
        out["life.speed_rpm"] = _LIFE
    if case.study.kind == "rotation" and case.rotation.integrator != "implicit":
        out["rotation.rho_inf"] = 'read by implicit runs only (rotation.integrator = "implicit")'
    if case.bearing.rings == "rigid":
        out.update({f"rings.{f.name}": 'bearing.rings = "rigid" (no modal rings)'
                    for f in dataclasses.fields(RingFidelity)})
    if case.bearing.rings == "auto":
        out.update({f"rings.{f.name}": 'bearing.rings = "auto" chooses the rings\' fidelity; set bearing.rings = '
                    '"file" to choose it yourself' for f in dataclasses.fields(RingFidelity)})
    return out


#: the case tables its modal rings depend on (:func:`prepare`)
PREPARE_TABLES = ("bearing", "rings")


def prepare(case: DescribedCase) -> bool:
    """Mesh and reduce the modal rings of the case's bearing into the model cache (a sweep does this
    once before its points start); False when the rings are rigid or the file makes none modal."""
    from ..bearing_ring_reduction import flexible_rings

    if case.bearing.rings != "file":  # rigid, or decided by auto's pass when the run starts
        return False
    _, desc = described_bearing(case)
    return bool(desc.rings) and bool(flexible_rings(desc.rings, desc.bearing))


def uses_dynamics(case: DescribedCase) -> bool:
    return case.study.kind == "rotation"


def run_study(case: DescribedCase, out, progress=None) -> None:
    STUDIES[case.study.kind].run(case, out, progress)
