"""The slewing ring's fidelity ladder, beside its case schema: which keys trade speed for accuracy,
the quasi-static scene the ladder measures, and what a rung computes.

Knobs (keys of :class:`.case.BodyFidelity` of the top structure, cheap → expensive):

- ``top.kind``: rigid, modal;
- ``top.n_modes``: free–free normal modes kept, 5 … 80;
- ``top.groove_harmonics``: raceway load shapes (inertia relief) up to this harmonic, −1 (none) … 32;
- ``top.element_size_m``: 1.4×, 1×, 0.7× the variant's default element size (hex27);
- ``top.raceway_spread_m``: 0 (the groove sampled on the contact line) or s = 0.3·D, the groove
  region a ball spans (sampled and loaded over a patch of that size,
  :func:`fem_rings.nodesets.raceway_patch`);
- ``top.ball_load_shapes``: with it, the static shapes of radial and axial ball forces at the balls'
  places (on the same patch), so that the equilibrium is the finite-element solution of the top
  structure under the ball forces.

Why a patch of the groove and not the contact ellipse: the Hertz approach already holds the
deformation near the contact, so the ring's part is its deflection under the ball taken over the
groove region, as FE load-distribution models of slewing bearings do with rigid links from the
groove centre to the raceway surface (Daidié, Chaib & Ghosn, J. Mech. Design 130 (2008) 082601).
Measured on the ladder's scene: with a patch of the contact ellipse's size (a = 9.9 mm) the
largest load still moved by 1.0 % and 3.9 % from 98 to 70 to 49 mm elements; with a patch larger
than the elements it converges with the mesh.

Reference: ball load shapes on the contact patch, 80 modes, load shapes to harmonic 32, the finest
mesh: the finite-element model of the top structure under the Hertz ball forces (each spread over
its contact patch), at the most the machine affords. Combined rungs show its own convergence in the
mesh, and the cheaper models a user would pick.

Scene: one quasi-static equilibrium of the case (the balls at their first azimuths). A study that
sweeps values gives its most demanding single scene: the undulation ×1 (or its largest scale) on
the ring of the last ``study.top_E_Pa`` (the softest in the thesis' studies), with the study's
first thermal offset where it has one. Dynamic studies have no ladder yet.
"""

from __future__ import annotations

import numpy as np

from foundation.materials import BEARING_STEEL
from mbd_core.contact import ball_on_groove
from mbd_core.contact.subsurface import subsurface_shear

from ..fidelity import Knob, Ladder, Outcome, case_tables
from . import scene as scene_mod
from .case import SlewingCase
from .quasistatic import equilibrium, error_estimates
from .studies import UNLOADED_SHARE

__all__ = ["ladder", "scene", "measure", "rung_case", "describe", "rung_overrides", "element_columns", "LOADS_FILE"]

#: element sizes of the mesh knob, as factors of the variant's default
MESH_FACTORS = (1.4, 1.0, 0.7)
#: element size of the quick ladder, as a factor of the variant's default: every rung of the quick
#: ladder and its reference share this mesh, so it measures the modal knobs (modes, load shapes,
#: ball shapes) in minutes on the default install; its errors are against a reference on the same mesh
QUICK_MESH_FACTOR = 2.0


def _sizes(case: SlewingCase) -> tuple[float, ...]:
    h = scene_mod.DEFAULT_ELEMENT_SIZE_M[case.geometry.variant]
    return tuple(round(f * h, 4) for f in MESH_FACTORS)


def ladder(case: SlewingCase, quick: bool = False) -> Ladder:
    """The ladder of ``case``'s variant (``quick``: a short one on a mesh twice as coarse as the
    default — rigid, 5 or 20 modes, with or without load shapes, with ball load shapes — against the
    ball load shapes with 40 modes on that mesh)."""
    coarse, default, fine = _sizes(case)
    a = scene_mod.groove_patch_m(case)
    patch = Knob("top.raceway_spread_m", (0.0,) if quick else (0.0, a), "raceway patch (m)")
    balls = Knob("top.ball_load_shapes", (False, True), "ball load shapes", implies={True: {"top.raceway_spread_m": a}})
    modes = Knob("top.n_modes", (5, 20) if quick else (5, 10, 20, 40, 80), "normal modes", float, "normal modes n")
    shapes = Knob("top.groove_harmonics", (-1, 16) if quick else (-1, 4, 8, 16, 32),
                  "groove load shapes up to harmonic", lambda n: n + 2.0,
                  "highest harmonic + 2 (none: 1)")
    kind = Knob("top.kind", ("rigid", "modal"), "top structure")
    scene_text = "one quasi-static equilibrium: " + describe_scene(case)
    if quick:
        quick_h = round(QUICK_MESH_FACTOR * scene_mod.DEFAULT_ELEMENT_SIZE_M[case.geometry.variant], 4)
        mesh = Knob("top.element_size_m", (quick_h,), "element size (m)", lambda h: 1.0 / h, "1 / element size (1/m)")
        base = {"top.kind": "modal", "top.n_modes": 20, "top.groove_harmonics": 16, "top.element_size_m": quick_h,
                "top.raceway_spread_m": 0.0, "top.ball_load_shapes": False}
        reference = {"top.n_modes": 40, "top.raceway_spread_m": a, "top.ball_load_shapes": True}
        return Ladder((kind, modes, shapes, mesh, patch, balls), base, reference, primary="max_load",
                      primary_label="largest ball load", scene=scene_text)
    mesh = Knob("top.element_size_m", (coarse, default, fine), "element size (m)", lambda h: 1.0 / h, "1 / element size (1/m)")
    base = {"top.kind": "modal", "top.n_modes": 20, "top.groove_harmonics": 16, "top.element_size_m": default,
            "top.raceway_spread_m": 0.0, "top.ball_load_shapes": False}
    on_patch = {"top.raceway_spread_m": a, "top.ball_load_shapes": True}
    combined = {"coarse": {"top.n_modes": 10, "top.groove_harmonics": 8, "top.element_size_m": coarse},
                "fine": {"top.n_modes": 40, "top.groove_harmonics": 32, "top.element_size_m": default},
                "balls-coarse": {**on_patch, "top.element_size_m": coarse},
                "balls-fine": {**on_patch, "top.n_modes": 40, "top.groove_harmonics": 32},
                "reference-mesh-coarse": {**on_patch, "top.n_modes": 80, "top.groove_harmonics": 32,
                                          "top.element_size_m": coarse},
                "reference-mesh-default": {**on_patch, "top.n_modes": 80, "top.groove_harmonics": 32}}
    reference = {**on_patch, "top.n_modes": 80, "top.groove_harmonics": 32, "top.element_size_m": fine}
    return Ladder((kind, modes, shapes, mesh, patch, balls), base, reference, combined, primary="max_load",
                  primary_label="largest ball load", scene=scene_text)


def _scene_values(case: SlewingCase) -> dict:
    """The case tables that make the study's single scene."""
    s, kind = case.study, case.study.kind
    if kind == "rotation" or (kind == "single" and case.analysis.type != "quasi_static"):
        raise ValueError("tradeoff: the slewing ring has a ladder for quasi-static scenes only; this case runs "
                         "the dynamics (analysis.type or study.kind = rotation)")
    scale = 1.0 if 1.0 in s.undulation_scales else max(s.undulation_scales)
    E = s.top_E_Pa[-1]
    return {
        "single": {},
        "static": {"undulation": {"scale": 0.0}, "thermal": {"offset_m": 0.0}},
        "undulation": {"undulation": {"scale": scale}, "top": {"E_Pa": E}},
        "thermal": {"undulation": {"scale": 0.0}, "thermal": {"offset_m": s.offsets_m[0]}},
        "combined": {"undulation": {"scale": 1.0}, "thermal": {"offset_m": s.combined_offsets_m[0]},
                     "top": {"E_Pa": E}},
        "life": {"undulation": {"scale": 1.0}, "thermal": {"offset_m": s.life_offset_m}, "top": {"E_Pa": E}},
        "full-scale": {"undulation": {"scale": 1.0}, "top": {"E_Pa": E}},
    }[kind]


def scene(case: SlewingCase) -> SlewingCase:
    """The single quasi-static equilibrium the ladder measures (module docstring)."""
    values = _scene_values(case)
    return case.with_(study={"kind": "single"}, analysis={"type": "quasi_static", "travel_steps": 0}, **values)


def describe_scene(case: SlewingCase) -> str:
    c = scene(case)
    return (f"{c.geometry.variant} ring, undulation ×{c.undulation.scale:g}, thermal offset "
            f"{1e3 * c.thermal.offset_m:g} mm, top structure E = {c.top.E_Pa / 1e9:g} GPa")


def _tau_max_Pa(case: SlewingCase, load_N: float, alpha_rad: float) -> float:
    """Peak subsurface shear under ``load_N`` at the more stressed of the two grooves (Hertz, then
    the subsurface field of :func:`mbd_core.contact.subsurface.subsurface_shear`)."""
    g = case.geometry
    out = 0.0
    for raceway in ("inner", "outer"):
        c = ball_on_groove(g.ball_diameter_m, g.conformity, g.pitch_diameter_m, alpha_rad, raceway,
                           BEARING_STEEL, BEARING_STEEL)
        a, b = (float(x) for x in c.semi_axes_m(load_N))
        out = max(out, subsurface_shear(float(c.max_pressure_Pa(load_N)), a, b, BEARING_STEEL.nu).tau_max_Pa)
    return out


def measure(case: SlewingCase) -> Outcome:
    """Ball loads, contact angles and peak shear of the scene at the case's fidelity (``auto``:
    its decision's, the cheap pass included)."""
    c = scene(case)
    if "auto" in (c.top.kind, c.bottom.kind):
        from .auto import resolve

        c = resolve(c)[0]
    bodies = scene_mod.Bodies(scene_mod.top_body(c), scene_mod.bottom_body(c))
    res = equilibrium(c, bodies)
    row = res.rows[0]
    k = int(np.argmax(row.load_N))
    tau = _tau_max_Pa(c, float(row.load_N[k]), float(row.contact_angle_rad[k]))
    est = error_estimates(c, bodies, res)["modal_truncation"]
    return Outcome(np.asarray(row.load_N, float), np.asarray(row.contact_angle_rad, float), tau,
                   unloaded_share=UNLOADED_SHARE,
                   estimates={"estimated_error": None if est is None else est["max_load"]})


#: the file of ``flexbearing tradeoff`` that holds every rung's element loads
LOADS_FILE = "ball_loads.csv"


def element_columns(case: SlewingCase, n: int) -> tuple[list[str], list[tuple]]:
    """The columns that name the ``n`` balls in :data:`LOADS_FILE`: number, azimuth from the first."""
    return ["element", "azimuth_from_first_deg"], [(i + 1, 360.0 * i / n) for i in range(n)]


def rung_case(case: SlewingCase, settings: dict) -> SlewingCase:
    """``case``'s scene with the rung's knob values (dotted keys → values)."""
    return scene(case).with_(**case_tables(settings))


def describe(settings: dict) -> str:
    """A rung in words, as a user would set it."""
    if settings.get("top.kind") == "rigid":
        return "rigid top structure"
    spread = settings.get("top.raceway_spread_m", 0.0)
    where = f"on a {1e3 * spread:g} mm patch" if spread else "on the contact line"
    balls = "ball load shapes + " if settings.get("top.ball_load_shapes") else ""
    return (f"modal top structure: {balls}{settings['top.n_modes']} modes, load shapes to harmonic "
            f"{settings['top.groove_harmonics']}, element {1e3 * settings['top.element_size_m']:g} mm, {where}")



def rung_overrides(case: SlewingCase, settings: dict) -> dict | None:
    """The table overrides that run ``case`` at a rung's fidelity (its own study kept), or None when
    its study fixes a knob to another value (a study that makes the top structure modal, or the
    undulation study, cannot run a rigid rung)."""
    from .studies import case_unused_keys, modal_top

    kind = settings["top.kind"]
    study_sets_kind = "top.kind" in case_unused_keys(case)
    if study_sets_kind and kind != ("modal" if modal_top(case) else case.top.kind):
        return None
    if kind == "rigid" and case.study.kind == "undulation":  # it compares moduli of a bending top structure
        return None
    top = {} if study_sets_kind else {"kind": kind}
    if kind == "modal":
        top.update({key.split(".")[1]: v for key, v in settings.items() if key != "top.kind"})
    return {"top": top}
