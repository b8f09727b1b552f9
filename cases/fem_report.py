"""Free–free (or supported) modes of a built-in ring part: table, result folder, pictures."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from fem_rings import MeshSpec, build_model, modal_analysis
from fem_rings.model import FEModel
from fem_rings.output import displacement_magnitude, write_vtu
from fem_rings.render import render_png
from fem_rings.solve import Modes, classify_ring_mode

from .mesh_budget import check_model_size
from .parts import RingPart
from .outdir import atomic_folder
from .report import format_table
from .results import output_units

__all__ = ["part_modes", "modes_table", "write_modes", "shape_at_amplitude", "MODE_AMPLITUDE_M"]


def part_modes(part: RingPart, n_modes: int, size_m: float | None = None, element: str | None = None,
               use_cache: bool = True, keys: tuple[str, str] = ("size_m", "n_modes")) -> tuple[FEModel, Modes, dict]:
    """Mesh, assemble and solve the lowest free–free modes of a part; returns (model, modes, summary).

    The model's size is estimated first (:func:`cases.mesh_budget.check_model_size`): a ValueError
    naming ``keys`` (element size, mode count) refuses a mesh that cannot give ``n_modes`` modes
    or would not fit in memory."""
    profile, pockets = part.make()
    spec = MeshSpec(size_m or part.default_size_m, element or part.default_element, solid=part.solid)
    size_text = f"{spec.size_m * 1e3:g}" if keys[0].endswith("-mm") else None
    check_model_size(profile, spec.size_m, n_modes, *keys, size_text=size_text, n_rigid=0)
    model = build_model(profile, spec, part.material, pockets, use_cache=use_cache)
    modes = modal_analysis(model, n_modes)
    ex = np.zeros(model.n_dofs)
    ex[0::3] = 1.0
    rows = []
    for k, (f, rigid) in enumerate(zip(modes.frequencies_Hz, modes.rigid)):
        family, n = ("rigid", 0) if rigid else classify_ring_mode(model.nodes_m, modes.shapes[:, k])
        rows.append({"mode": k + 1, "frequency_Hz": float(f), "family": family, "waves": n})
    summary = {
        "part": part.name,
        "description": part.description,
        "material": {"name": part.material.name, "E_Pa": part.material.E_Pa, "nu": part.material.nu,
                     "density_kg_m3": part.material.density_kg_m3},
        "element": spec.element,
        "element_size_m": spec.size_m,
        "dofs": model.n_dofs,
        "mass_kg": float(ex @ model.M @ ex),
        "mass_of_section_kg": (None if pockets or part.solid else
                               profile.revolved_properties(part.material.density_kg_m3)["mass_kg"]),
        "n_rigid_modes": modes.n_rigid,
        "factorisation": modes.backend,
        "timings_s": model.timings_s,
        "modes": rows,
    }
    return model, modes, summary


def modes_table(summary: dict) -> str:
    head = (f"{summary['description']}: {summary['element']}, {summary['dofs']} DOF, "
            f"mass {summary['mass_kg']:.1f} kg, {summary['n_rigid_modes']} rigid-body modes")
    rows = [(r["mode"], f"{r['frequency_Hz']:.3f}", r["family"], r["waves"] if r["family"] != "rigid" else "")
            for r in summary["modes"]]
    return head + "\n" + format_table(rows, ("mode", "f Hz", "family", "waves n"))


#: largest nodal displacement a mode shape is drawn at (a mode's own amplitude is arbitrary), m
MODE_AMPLITUDE_M = 1e-3


def shape_at_amplitude(shape, amplitude_m: float = MODE_AMPLITUDE_M) -> np.ndarray:
    """A mode shape (n, 3) (mass-normalised, m/√kg) scaled so its largest nodal displacement
    magnitude is ``amplitude_m``: a physical displacement field, m."""
    shape = np.asarray(shape, dtype=float)
    return shape * (amplitude_m / float(displacement_magnitude(shape).max()))


def write_modes(model: FEModel, modes: Modes, summary: dict, out_dir: str | os.PathLike, n_pictures: int = 2) -> Path:
    """summary.json (output units, :data:`cases.results.OUTPUT_UNITS`), modes.vtu (all mode shapes as
    point data, mass-normalised) and PNGs of the first elastic modes, each scaled to a largest
    displacement of ``MODE_AMPLITUDE_M`` and coloured by its displacement in mm."""
    with atomic_folder(out_dir, str(summary.get("part", ""))) as tmp:
        shapes = {f"mode_{k + 1:02d}_{f:.2f}Hz": modes.shapes[:, k].reshape(-1, 3)
                  for k, f in enumerate(modes.frequencies_Hz)}
        write_vtu(tmp / "modes.vtu", model.mesh, shapes)
        elastic = np.flatnonzero(~modes.rigid)[:n_pictures]
        for k in elastic:
            u = shape_at_amplitude(modes.shapes[:, k].reshape(-1, 3))
            render_png(tmp / f"mode_{k + 1:02d}.png", model.mesh, displacement_magnitude(u), scale=1e3,
                       label="displacement", unit="mm", displacement_m=u,
                       title=f"{summary['part']}: mode {k + 1}, {modes.frequencies_Hz[k]:.2f} Hz, "
                             f"scaled to a largest displacement of {MODE_AMPLITUDE_M * 1e3:g} mm")
        (tmp / "summary.json").write_text(json.dumps(output_units(summary), indent=1))
    return Path(out_dir)
