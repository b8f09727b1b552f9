"""The fidelity ladder of a described bearing, beside its case schema: the ``[rings]`` keys that trade
speed for accuracy in the quasi-static load distribution of a bearing file with modal rings.

Knobs (keys of :class:`.case.DescribedCase`, cheap → expensive):

- ``bearing.rings``: rigid, file (the file's ``[rings.X]`` tables make those rings modal);
- ``rings.n_modes``: fixed-interface normal modes per ring, 5 … 80;
- ``rings.raceway_harmonics``: raceway load shapes cos nθ, sin nθ up to this n, 0 … 32;
- ``rings.element_size_factor``: each ring's element size times 1, 0.7, 0.5 (never coarser than the
  file's: a coarser mesh can leave a bolt's washer patch too few nodes to hold the ring);
- ``rings.element_load_shapes``: off, on (the static shapes of the element forces at their places,
  spread over a raceway patch of 0.3 × the element diameter; with them the equilibrium is the
  finite-element solution of the rings under the element forces). Not offered when a row is a
  four-point or crossed roller row (cases/bearings/README.md).

Combined rungs: ``auto`` (``bearing.rings = "auto"``: each ring rigid or modal as its cheap pass
decides, :mod:`.auto`), cheap and fine modal rings, and element load shapes with 10 modes.

Reference: 80 modes, harmonics to 32, the finest mesh (0.5×) and, where offered, the element load
shapes: the most accurate model of the rings the project builds on this machine. The quick ladder
keeps every ring's mesh as the file gives it, and measures modes, load shapes and element shapes
there against a reference on that mesh (40 modes, harmonics to 16).

Scene: the load case of the file whose largest element load under rigid rings is the largest (the
most demanding one; the file's only load when it has one), solved quasi-statically. Each rung also
gives its own estimate of its modal truncation error (:mod:`.estimates`), which the ladder compares
with its true error.
"""

from __future__ import annotations

import dataclasses
import tomllib
from pathlib import Path

import numpy as np

from fem_rings.cache import file_digest
from foundation.materials import BEARING_STEEL
from mbd_core.contact.subsurface import subsurface_shear
from mbd_core.quasistatic.contacts import contact_sets

from ..bearing_ring_reduction import two_sided
from ..bearing_solver import bearing_solver
from ..fidelity import Knob, Ladder, Outcome, case_tables
from .auto import most_loaded_case, refused_reason
from .auto import resolve as resolve_auto
from .case import DescribedCase
from .estimates import truncation_estimates
from .studies import described_bearing

__all__ = ["ladder", "scene", "measure", "rung_case", "describe", "rung_overrides", "element_columns", "cache_inputs",
           "LOADS_FILE"]

#: the mesh of every quick rung, as a factor of each ring's element size in the file
QUICK_SIZE_FACTOR = 1.0
#: element sizes of the mesh knob, as factors of each ring's element size in the file
SIZE_FACTORS = (1.0, 0.7, 0.5)
#: an element counts as unloaded below this share of the mean load
UNLOADED_SHARE = 1e-3
#: the file of ``flexbearing tradeoff`` that holds every rung's element loads
LOADS_FILE = "element_loads.csv"


def _shapes_offered(desc) -> bool:
    return not any(two_sided(r) for r in desc.bearing.rows)


def _description(case: DescribedCase):
    """The case's bearing with its rings at the file's fidelity (the knobs are the ladder's)."""
    return described_bearing(dataclasses.replace(case, rings=type(case.rings)()))[1]


def ladder(case: DescribedCase, quick: bool = False) -> Ladder:
    """The ladder of the case's bearing file (module docstring); ValueError when the file has no
    modal rings (nothing to trade)."""
    desc = _description(case)
    if not desc.rings:
        raise ValueError("tradeoff: the bearing file gives no [rings.X] tables: its rings are rigid, and a rigid-ring "
                         "load distribution has no fidelity to trade (cases/bearings/README.md: modal rings)")
    shapes = _shapes_offered(desc)
    kind = Knob("bearing.rings", ("rigid", "file"), "rings")
    modes = Knob("rings.n_modes", (5, 20) if quick else (5, 10, 20, 40, 80), "normal modes", float, "normal modes n")
    harmonics = Knob("rings.raceway_harmonics", (0, 8) if quick else (0, 4, 8, 16, 32),
                     "raceway load shapes up to harmonic", lambda n: n + 1.0, "highest harmonic + 1")
    sizes = (QUICK_SIZE_FACTOR,) if quick else SIZE_FACTORS
    mesh = Knob("rings.element_size_factor", sizes, "element size (× the file's)", lambda f: 1.0 / f,
                "1 / element size factor")
    knobs = [kind, modes, harmonics, mesh]
    base = {"bearing.rings": "file", "rings.n_modes": 20, "rings.raceway_harmonics": 8,
            "rings.element_size_factor": QUICK_SIZE_FACTOR if quick else SIZE_FACTORS[0]}
    if shapes:
        knobs.append(Knob("rings.element_load_shapes", (False, True), "element load shapes"))
        base["rings.element_load_shapes"] = False
    on = {"rings.element_load_shapes": True} if shapes else {}
    text = "one quasi-static equilibrium: " + describe_scene(case, desc)
    if quick:
        reference = {"rings.n_modes": 40, "rings.raceway_harmonics": 16, **on}
        return Ladder(tuple(knobs), base, reference, primary="max_load", primary_label="largest element load",
                      scene=text)
    reference = {"rings.n_modes": 80, "rings.raceway_harmonics": 32, "rings.element_size_factor": SIZE_FACTORS[-1], **on}
    combined = {"auto": {"bearing.rings": "auto"}, "cheap": {"rings.n_modes": 10, "rings.raceway_harmonics": 4},
                "fine": {"rings.n_modes": 40, "rings.raceway_harmonics": 16, "rings.element_size_factor": SIZE_FACTORS[1]}}
    if shapes:
        combined.update({"shapes-cheap": {**on, "rings.n_modes": 10},
                         "shapes-fine": {**on, "rings.n_modes": 10, "rings.element_size_factor": SIZE_FACTORS[1]}})
    return Ladder(tuple(knobs), base, reference, combined, primary="max_load", primary_label="largest element load",
                  scene=text)


def _scene_load(desc) -> tuple[int, object]:
    """(index, load) of the load case with the largest rigid-ring element load."""
    k, _ = most_loaded_case(desc)
    return k, desc.load_cases[k]


def describe_scene(case: DescribedCase, desc=None) -> str:
    desc = desc or _description(case)
    k, _ = _scene_load(desc)
    which = f"load case {k + 1} of {len(desc.load_cases)} (the most loaded)" if len(desc.load_cases) > 1 else "its load"
    return f"{desc.name} ({case.bearing.file}), {which}"


def scene(case: DescribedCase) -> DescribedCase:
    """The study the ladder measures: the load distribution (the limiting curve is many of them)."""
    return case.with_(study={"kind": "load-distribution"})


def _tau_max_Pa(desc, dist) -> float:
    """Peak subsurface shear under the contact of largest Hertz pressure (rings of bearing steel's ν)."""
    best = max(((float(np.max(s.max_pressure_Pa)), s) for s in contact_sets(desc.bearing, dist)), key=lambda x: x[0])
    p0, s = best
    if not p0 > 0.0:
        return 0.0
    i = int(np.argmax(s.max_pressure_Pa))
    return subsurface_shear(p0, float(s.semi_major_m[i]), float(s.semi_minor_m[i]), BEARING_STEEL.nu).tau_max_Pa


def measure(case: DescribedCase) -> Outcome:
    """Element loads, contact angles and peak shear of the scene at the case's fidelity (``auto``: the
    rings as its pass decides them)."""
    _, desc = described_bearing(case)
    _, load = _scene_load(desc)
    if case.bearing.rings == "auto":
        desc = resolve_auto(case, desc)[0]
    solver = bearing_solver(desc, rigid=case.bearing.rings == "rigid")
    dist = solver.solve(load)
    loads = np.concatenate([np.asarray(r.load_N, float) for r in dist.rows])
    angles = np.concatenate([np.asarray(r.contact_angle_rad, float) for r in dist.rows])
    est = truncation_estimates(desc, solver, dist)["modal_truncation"]
    return Outcome(loads, angles, _tau_max_Pa(desc, dist), unloaded_share=UNLOADED_SHARE,
                   estimates={"estimated_error": None if est is None else est["max_load"]})


def element_columns(case: DescribedCase, n: int) -> tuple[list[str], list[tuple]]:
    """The columns that name the ``n`` elements in :data:`LOADS_FILE`: row and element number."""
    desc = _description(case)
    labels = [(row.name, k + 1) for row in desc.bearing.rows for k in range(row.n_elements)]
    return ["row", "element"], labels[:n]


def _settings_used(settings: dict) -> dict:
    """A rigid or ``auto`` rung sets no ``rings.*`` key (the case refuses them there)."""
    if settings.get("bearing.rings") in ("rigid", "auto"):
        return {"bearing.rings": settings["bearing.rings"]}
    return dict(settings)


def rung_case(case: DescribedCase, settings: dict) -> DescribedCase:
    """``case``'s scene with the rung's knob values (dotted keys → values)."""
    return scene(case).with_(**case_tables(_settings_used(settings)))


def describe(settings: dict) -> str:
    """A rung in words, as a user would set it."""
    if settings.get("bearing.rings") == "rigid":
        return "rigid rings"
    if settings.get("bearing.rings") == "auto":
        return "auto (each ring rigid or modal as its cheap pass decides)"
    shapes = "element load shapes + " if settings.get("rings.element_load_shapes") else ""
    return (f"modal rings: {shapes}{settings['rings.n_modes']} modes, raceway load shapes to harmonic "
            f"{settings['rings.raceway_harmonics']}, element size × {settings['rings.element_size_factor']:g}")


def rung_overrides(case: DescribedCase, settings: dict) -> dict | None:
    """The table overrides that run ``case`` at a rung's fidelity (its own study kept); None for the
    ``auto`` rung when the case's study is not one ``auto`` decides for."""
    used = _settings_used(settings)
    if used.get("bearing.rings") == "auto" and refused_reason(case):
        return None
    tables = case_tables(used)
    if used.get("bearing.rings") in ("rigid", "auto"):
        tables["rings"] = {f.name: f.default for f in dataclasses.fields(type(case.rings))}
    return tables


def _digest(path: Path) -> str:
    try:
        return file_digest(path)
    except OSError:
        return "unreadable"


def cache_inputs(case: DescribedCase) -> list[str]:
    """SHA-256 of the bearing file and of every file it names (a DXF section, a STEP solid, a load
    CSV), so that a cached ladder is not reused after one of them changed."""
    desc = _description(case)
    source = Path(desc.source)
    out = [_digest(source)]
    for m in desc.rings.values():
        if m.solid is not None:
            out.append(m.solid.sha256)
        if m.keys.dxf_file:
            out.append(_digest(source.parent / m.keys.dxf_file))
    try:
        load = tomllib.loads(source.read_text()).get("load", {})
    except (OSError, ValueError):
        load = {}
    for key, value in sorted(load.items()) if isinstance(load, dict) else ():
        if key.endswith("_csv") and isinstance(value, str):
            out.append(_digest(source.parent / value))
    return out
