"""Named sub-cases of the wind main bearing (its studies) and their quick variants.

``--quick`` keeps the question and shrinks the work: 0.3 s simulated at 5 slices per roller with
one load case held (the first 0.1 s excluded from the averages), two speeds or friction sets.
"""

from __future__ import annotations

from ..config import from_mapping
from ..quick import quick_variant
from .case import WindCase

__all__ = ["PRESETS", "preset", "quick"]

#: the paper's friction transition speeds (μ_static at 10 mm/s, μ_dynamic from 100 mm/s on): the
#: cage forces depend on them (at the default 0.3/0.6 m/s the friction below 0.3 m/s of slip is
#: weak, and the cage forces hardly change with μ); the sweeps and the Adams preset use them
_PAPER_TRANSITION = {"v_static_m_s": 0.01, "v_dynamic_m_s": 0.1}

_PRESET_TABLES = {
    "wind-static": dict(
        name="wind-static", description="12 MW main bearing: quasi-static roller loads of the three rows under "
        "each of the 32 synthetic load cases (rigid rings)", study={"kind": "static"}),
    "wind-load-case": dict(
        name="wind-load-case", description="12 MW main bearing: quasi-static load of every roller of the three "
        "rows under load case 19 of the synthetic spectrum (rigid rings)", study={"kind": "load-case"}),
    "wind-speeds": dict(
        name="wind-speeds", description="12 MW main bearing, rigid rings, 30 r/min, 8 s of the load spectrum: "
        "roller and cage speeds against rolling kinematics, inner-ring equilibrium", study={"kind": "speeds"}),
    "wind-speeds-adams": dict(
        name="wind-speeds-adams", description="12 MW main bearing as wind-speeds with the paper's Adams contact "
        "settings (K = 1e5 N/mm^1.5, n = 1.5, c = 70 N·s/mm, d_max = 0.1 mm, friction transition 10/100 mm/s)",
        contact={"preset": "adams", **_PAPER_TRANSITION}, study={"kind": "speeds"}),
    "wind-rigid-flexible": dict(
        name="wind-rigid-flexible", description="12 MW main bearing, 30 r/min, 8 s of the load spectrum with rigid "
        "and with modal rings and cages (20 modes each): roller speed errors of both models and their ratio",
        study={"kind": "rigid-flexible"}),
    "wind-driving-speed": dict(
        name="wind-driving-speed", description="12 MW main bearing at 20/25/30 r/min: roller–cage forces of "
        "each row, front/rear thrust cage ratio (friction transition 10/100 mm/s)", contact=_PAPER_TRANSITION,
        study={"kind": "driving-speed"}),
    "wind-friction": dict(
        name="wind-friction", description="12 MW main bearing at 30 r/min with (μd, μs) = (0.025, 0.05) … (0.1, "
        "0.2): roller–cage forces of each row (friction transition 10/100 mm/s)", contact=_PAPER_TRANSITION,
        study={"kind": "friction"}),
}

PRESETS = {name: from_mapping(WindCase, tables) for name, tables in _PRESET_TABLES.items()}

_DYNAMIC_QUICK = dict(rollers={"n_slices": 5}, loads={"source": "constant"},
                      analysis={"duration_s": 0.3, "settle_s": 0.1, "record_every": 100})
_QUICK = {
    "static": {},
    "load-case": {},
    "speeds": _DYNAMIC_QUICK,
    "rigid-flexible": {**_DYNAMIC_QUICK, "analysis": {"duration_s": 0.1, "settle_s": 0.05, "record_every": 100},
                       "bodies": {"n_modes": 8, "bolts": 24, "ring_element_size_m": 0.18, "cage_element_size_m": 0.05}},
    "driving-speed": {**_DYNAMIC_QUICK, "study": {"speeds_rpm": (20.0, 30.0)}},
    "friction": {**_DYNAMIC_QUICK, "study": {"friction_sets": ((0.025, 0.05), (0.1, 0.2))}},
}


def preset(name: str) -> WindCase:
    if name not in PRESETS:
        raise KeyError(name)
    return PRESETS[name]


def quick(case: WindCase) -> WindCase:
    """The reduced variant of ``case`` that ``--quick`` runs (:func:`cases.quick.quick_variant`)."""
    return quick_variant(case, _QUICK[case.study.kind])
