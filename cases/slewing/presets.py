"""The named sub-cases of the slewing ring (studies (a)–(g)) and their quick variants.

``--quick`` keeps the question and shrinks the work: coarser ring meshes and fewer modes, fewer
positions or a shorter simulated time. The quick case is a case like any other (its resolved
TOML is saved with the run), and the tests run it.
"""

from __future__ import annotations

from ..config import from_mapping
from ..quick import quick_variant
from .case import REDUCED_E_PA, SlewingCase

__all__ = ["PRESETS", "preset", "quick"]

_MODAL = {"kind": "modal"}
#: the dynamic runs with a modal top structure report its stress over time (:mod:`.dynamic_stress`)
_MODAL_STRESS = {"kind": "modal", "stress_modes": True}
#: top structure mesh of (c), the README's first command: 0.1 m instead of the 2 m ring's 0.07 m
#: keeps a cold run within minutes on the default install (cholespy); the case's max ball loads
#: stay within 1.5 % of the 0.07 m mesh's and its unloaded-ball counts are the same (case README)
UNDULATION_TOP_ELEMENT_SIZE_M = 0.1

_PRESET_TABLES = {
    "slewing-static": dict(
        name="slewing-static", description="(a) full-scale ring under its dead load, flat races: load per ball "
        "against Q = W/(Z sin α), rigid and modal top structure (top race + TMR)",
        study={"kind": "static"}, geometry={"variant": "full"}),
    "slewing-rotation": dict(
        name="slewing-rotation", description="(b) 1 m ring, flat races, the top race turning at 6.55 r/min with "
        "friction and spacer balls (explicit dynamics): the load per ball stays uniform",
        study={"kind": "rotation"}, geometry={"variant": "1m"},
        analysis={"type": "dynamic_explicit", "duration_s": 4.6}),
    "slewing-undulation": dict(
        name="slewing-undulation", description="(c) 2 m ring, undulated bottom race ×0.5/×1/×1.5, top structure "
        "with E = 200 GPa and the thesis' reduced 1.5975 GPa, its fidelity chosen per equilibrium (auto): max ball "
        "load, unloaded balls",
        study={"kind": "undulation"}, top={"kind": "auto", "element_size_m": UNDULATION_TOP_ELEMENT_SIZE_M}),
    "slewing-thermal": dict(
        name="slewing-thermal", description="(d) 2 m ring, rigid races, radial offset Δ = 0.3/0.4/0.5 mm of the "
        "top race over 80–100° and the bottom race over 260–280°: load on a ball over one revolution",
        study={"kind": "thermal"}, analysis={"travel_steps": 288}),
    "slewing-combined": dict(
        name="slewing-combined", description="(e) 2 m ring, undulation ×1 and Δ = 0.4/1.11 mm, modal top "
        "structure at both moduli: worst ball load over one revolution",
        study={"kind": "combined"}, top=_MODAL, analysis={"travel_steps": 288}),
    "slewing-life": dict(
        name="slewing-life", description="(f) worst ball of (e) at Δ = 0.4 mm with the reduced stiffness: Hertz "
        "pressure, subsurface shear and case depth, ISO 281 and case-depth corrected life",
        study={"kind": "life"}, top=_MODAL, analysis={"travel_steps": 288}),
    "slewing-full-scale": dict(
        name="slewing-full-scale", description="(g) the Ø6.69 m ring with a modal top structure (top race + "
        "TMR, E = 200 GPa) under the undulation, beside the 2 m ring with E = 1.5975 GPa",
        study={"kind": "full-scale", "top_E_Pa": (200e9, REDUCED_E_PA)}, top=_MODAL),
    # the studies run dynamically with a modal top structure, each compared with the quasi-static
    # solution at the run's positions (analysis.reference_samples)
    "slewing-rotation-modal": dict(
        name="slewing-rotation-modal", description="(b) dynamic with a modal top structure (top race + TMR): the "
        "1 m ring turning at 6.55 r/min with friction and spacer balls, against the rigid top's uniform load",
        study={"kind": "rotation"}, geometry={"variant": "1m"}, top=_MODAL_STRESS,
        analysis={"type": "dynamic_explicit", "duration_s": 4.6}),
    "slewing-spacers-modal": dict(
        name="slewing-spacers-modal", description="(c) dynamic with a modal top structure: the 2 m ring, bottom race "
        "undulated ×1, turning for 1 s: ball loads against the quasi-static ones, spacer–load ball forces "
        "(thesis ≤ 625 N)",
        study={"kind": "rotation"}, geometry={"variant": "2m"}, undulation={"scale": 1.0},
        top={**_MODAL_STRESS, "element_size_m": UNDULATION_TOP_ELEMENT_SIZE_M},
        analysis={"type": "dynamic_explicit", "duration_s": 1.0}),
    "slewing-thermal-modal": dict(
        name="slewing-thermal-modal", description="(d) dynamic with a modal top structure: the 2 m ring with the "
        "thermal offset Δ = 0.4 mm (top race 80–100°, turning with it; bottom race 260–280°), turning for 1 s",
        study={"kind": "rotation"}, geometry={"variant": "2m"}, thermal={"offset_m": 0.4e-3},
        top={**_MODAL_STRESS, "element_size_m": UNDULATION_TOP_ELEMENT_SIZE_M},
        analysis={"type": "dynamic_explicit", "duration_s": 1.0}),
    "slewing-combined-modal": dict(
        name="slewing-combined-modal", description="(e) dynamic with a modal top structure at the reduced modulus "
        "1.5975 GPa: the 2 m ring undulated ×1 with Δ = 0.4 mm, turning for 1 s",
        study={"kind": "rotation"}, geometry={"variant": "2m"}, undulation={"scale": 1.0},
        thermal={"offset_m": 0.4e-3},
        top={**_MODAL_STRESS, "element_size_m": UNDULATION_TOP_ELEMENT_SIZE_M, "E_Pa": REDUCED_E_PA},
        analysis={"type": "dynamic_explicit", "duration_s": 1.0}),
    "slewing-full-scale-turning": dict(
        name="slewing-full-scale-turning", description="(g) dynamic: the Ø6.69 m ring (116 load + 116 spacer balls) "
        "with a modal top structure (top race + TMR, E = 200 GPa), bottom race undulated ×1, turning one revolution "
        "of the top race at 6.55 r/min: ball loads and spacer forces over time against the quasi-static ones",
        study={"kind": "rotation"}, geometry={"variant": "full"}, undulation={"scale": 1.0}, top=_MODAL_STRESS,
        analysis={"type": "dynamic_explicit", "duration_s": 60.0 / 6.55, "record_every": 100,
                  "reference_samples": 24}),
}

PRESETS = {name: from_mapping(SlewingCase, tables) for name, tables in _PRESET_TABLES.items()}

_QUICK = {
    "static": dict(geometry={"variant": "1m"}, top={"element_size_m": 0.1, "n_modes": 12, "groove_harmonics": 8}),
    "rotation": dict(analysis={"duration_s": 0.4, "record_every": 10}),
    "undulation": dict(top={"element_size_m": 0.12, "n_modes": 12, "groove_harmonics": 8},
                       study={"spacer_run_s": 0.05}),
    "thermal": dict(study={"offsets_m": (0.5e-3,)}, analysis={"travel_steps": 144}),
    "combined": dict(top={"element_size_m": 0.12, "n_modes": 12, "groove_harmonics": 8},
                     study={"combined_offsets_m": (0.4e-3,), "top_E_Pa": (REDUCED_E_PA,)},
                     analysis={"travel_steps": 72}),
    "life": dict(top={"element_size_m": 0.12, "n_modes": 12, "groove_harmonics": 8}, analysis={"travel_steps": 72}),
    "full-scale": dict(top={"element_size_m": 0.3, "n_modes": 12, "groove_harmonics": 8}),
    "single": {},
}
#: ``single``: a coarser modal ring (a rigid one has nothing to coarsen, and its case.toml would
#: carry keys no run reads)
_QUICK_MODAL = {"element_size_m": 0.12, "n_modes": 12, "groove_harmonics": 8}
#: the same on the full-scale ring (as the full-scale study's quick variant)
_QUICK_MODAL_FULL = {**_QUICK_MODAL, "element_size_m": 0.3}
#: ``single``: the shorter run of the kind the case makes (a quick equilibrium stays one, and a
#: quasi-static case keeps no dynamic-only key its saved case.toml would have to refuse)
_QUICK_SINGLE_ANALYSIS = {"dynamic": {"duration_s": 0.4}, "travels": {"travel_steps": 36}, "equilibria": {}}


def preset(name: str) -> SlewingCase:
    if name not in PRESETS:
        raise KeyError(name)
    return PRESETS[name]


def quick(case: SlewingCase) -> SlewingCase:
    """The reduced variant of ``case`` that ``--quick`` runs (:func:`cases.quick.quick_variant`)."""
    from .studies import runs_of

    tables = dict(_QUICK[case.study.kind])
    if case.top.kind == "auto" and "top" in tables:  # auto chooses the modal keys; only the mesh is coarsened
        tables["top"] = {k: v for k, v in tables["top"].items() if k == "element_size_m"}
    modal = [k for k in ("top", "bottom") if getattr(case, k).kind == "modal"]
    if case.study.kind == "rotation" and modal:  # coarser modal rings
        tables.update({k: _QUICK_MODAL_FULL if case.geometry.variant == "full" else _QUICK_MODAL for k in modal})
    if case.study.kind == "single":
        tables["analysis"] = _QUICK_SINGLE_ANALYSIS[runs_of(case)[0]]
        tables.update({k: _QUICK_MODAL for k in ("top", "bottom") if getattr(case, k).kind == "modal"})
    return quick_variant(case, {t: v for t, v in tables.items() if v})
