"""Modal rings and cages of the wind main bearing: reduced bodies and the grids their contacts use.

Each body is meshed and reduced once and cached by its inputs (:func:`cms_reduction.reduced_body`):
the inner ring (42CrMo, floating: free–free modes), the outer ring (42CrMo, held at ``bolts``
patches on its bolt face, 30 mm half-width but at least 0.75 element; fixed-interface modes) and
the three cages (cage steel, free–free modes, pocket walls sampled). Sections and pockets: :mod:`fem_rings.sections`,
:mod:`fem_rings.cages` (the parts of ``flexbearing modes``). No load-mode augmentation: as in the
paper, the rings keep ``n_modes`` normal modes; the contact law carries the local deformation.
Each body carries its stress modes, so the von Mises field of any recorded instant is one product.

Radial-row guide ribs on the inner ring: the section has no ribs, so a rib is a plane at the
roller ends that moves with the ring's material just under the radial raceway (two circles, 2 and
12 mm below it; the fields are held beyond them). Thrust rollers are held along their axis by
the ends of their cage's window pockets, which move with the cage ring beyond them.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from cms_reduction.sampling import sample_points
from fem_rings import MeshSpec
from fem_rings.cages import three_row_cages
from fem_rings.sections import three_row_inner_ring, three_row_outer_ring

from ..parts import CAGE_STEEL, STEEL_42CRMO
from .case import WindCase

__all__ = ["RACEWAYS", "CAGE_KEYS", "ModalBodies", "modal_bodies", "rib_grids", "stress_maps", "peak_stresses"]

log = logging.getLogger(__name__)

#: the raceway segment of each row (same names on both rings' sections)
RACEWAYS = ("radial_raceway", "front_thrust_raceway", "rear_thrust_raceway")
#: the cage of each row in :func:`fem_rings.cages.three_row_cages`
CAGE_KEYS = ("radial", "front_thrust", "rear_thrust")
BOLT_HALF_WIDTH_M = 0.03
#: depths below the radial raceway of the two circles a guide rib moves with, m
RIB_DEPTHS_M = (0.002, 0.012)
#: half the axial distance between the two circles a thrust roller's pocket-end stop moves with, m
CAGE_STOP_HALF_SPAN_M = 0.007


@dataclass(frozen=True)
class ModalBodies:
    """Reduced bodies of a case (None: rigid): inner and outer ring, the cages of the three rows."""

    inner: object | None
    outer: object | None
    cages: tuple


def _raceways(case: WindCase) -> tuple:
    b = case.bodies
    return tuple(RacewaySpec(name, b.n_theta, n_max=-1, n_across=b.n_across) for name in RACEWAYS)


def inner_ring_body(case: WindCase):
    b = case.bodies
    spec = ReductionSpec(n_modes=b.n_modes, raceways=_raceways(case), damping_ratio=b.modal_damping_ratio,
                         stress_modes=True)
    return reduced_body(three_row_inner_ring(), MeshSpec(b.ring_element_size_m, "hex27"), STEEL_42CRMO, spec)


def outer_ring_body(case: WindCase):
    b = case.bodies
    bolts = tuple(360.0 * (k + 0.5) / b.bolts for k in range(b.bolts))
    half_width = max(BOLT_HALF_WIDTH_M, 0.75 * b.ring_element_size_m)  # a patch spans ≥ 2 node columns
    spec = ReductionSpec(n_modes=b.n_modes, interfaces=(InterfaceSpec("bolt_face", bolts, half_width),),
                         raceways=_raceways(case), damping_ratio=b.modal_damping_ratio, stress_modes=True)
    return reduced_body(three_row_outer_ring(), MeshSpec(b.ring_element_size_m, "hex27"), STEEL_42CRMO, spec)


def cage_body(case: WindCase, key: str):
    b = case.bodies
    profile, pockets = three_row_cages()[key]
    spec = ReductionSpec(n_modes=b.n_modes, damping_ratio=b.modal_damping_ratio, stress_modes=True)
    return reduced_body(profile, MeshSpec(b.cage_element_size_m, "tet10"), CAGE_STEEL, spec, pockets)


def modal_bodies(case: WindCase) -> ModalBodies:
    """The bodies the case makes modal (meshed and reduced on first use, then cached)."""
    b = case.bodies
    rings = b.rings == "modal"
    inner = inner_ring_body(case) if rings else None
    outer = outer_ring_body(case) if rings else None
    cages = tuple(cage_body(case, k) for k in CAGE_KEYS) if b.cages == "modal" else (None, None, None)
    for name, body in (("inner ring", inner), ("outer ring", outer), *zip(CAGE_KEYS, cages)):
        if body is not None:
            log.info("%s: %d modes, %.1f … %.1f Hz", name, body.n_modes, body.frequencies_Hz[0], body.frequencies_Hz[-1])
    return ModalBodies(inner, outer, cages)


def rib_grids(body, row, n_theta: int, rib_clearance_m: float) -> tuple:
    """(end +, end −) sampled circles of a row's end guides on a modal body (module docstring), each
    a list of two :class:`cms_reduction.sampling.RacewaySample`: for the radial row the ribs of
    the inner ring, circles under the raceway on the rib planes z0 ± h; for a thrust row the
    pocket ends of its cage, circles in the cage ring 15 mm beyond the stop cylinders R ± h, at
    z0 ± 7 mm (h = L/2 + c/2)."""
    R, D = row.pitch_diameter_m / 2, row.roller_diameter_m
    h = row.roller_length_m / 2 + rib_clearance_m / 2
    th = 2.0 * math.pi * np.arange(n_theta) / n_theta
    c, s = np.cos(th), np.sin(th)
    out = []
    for sign in (1, -1):
        circles = []
        for k, depth in enumerate(RIB_DEPTHS_M):  # k: circle index
            if row.orientation == "radial":
                r, z = R - D / 2 - row.gap_m / 2 - depth, row.axial_position_m + sign * h
            else:  # the stops are the pocket ends: circles in the cage ring beyond them, across its width
                r, z = R + sign * (h + 15e-3), row.axial_position_m + (2 * k - 1) * CAGE_STOP_HALF_SPAN_M
            pts = np.column_stack((r * c, r * s, np.full(n_theta, z)))
            name = f"{row.name} rib {'+' if sign > 0 else '-'}@s{k}"
            circles.append(sample_points(body, name, pts, th, True))
        out.append(circles)
    return tuple(out)


def peak_stresses(sc, rec: dict, after_s: float = 0.0, names: tuple | None = None) -> dict:
    """Per modal body of a run: the recorded instant after ``after_s`` (the start's settling, when
    the modes swing up from zero under the loads) of the largest nodal von Mises stress, from the
    modal coordinates (:func:`cms_reduction.stress_history.worst_time`): name → (body, η of the
    kept samples, that instant); ``names``: only these bodies (None: every modal body)."""
    from cms_reduction.stress_history import worst_time

    reduced = {"inner ring": sc.modal.inner, "outer ring": sc.modal.outer,
               **{f"{row.name} cage": c for row, c in zip(sc.row_defs, sc.modal.cages)}}
    keep = rec["t"] >= after_s
    out = {}
    for name, (first, stop) in rec["modal_ranges"].items():
        if names is not None and name not in names:
            continue
        eta = rec["eta"][keep, first:stop]
        out[name] = (reduced[name], eta, worst_time(reduced[name], rec["t"][keep], eta))
    return out


def stress_maps(sc, rec: dict, folder, after_s: float = 0.0) -> dict:
    """:func:`peak_stresses` with the stress in MPa, its time and an off-screen PNG of the body at
    that instant, ``von_mises_<body>.png`` in ``folder``."""
    from cms_reduction.stress_modes import render_modal_state

    out = {}
    for name, (body, eta, w) in peak_stresses(sc, rec, after_s).items():
        png = f"von_mises_{name.replace(' ', '_')}.png"
        render_modal_state(body, eta[w.index], folder / png,
                           title=f"{name}: von Mises at t = {w.time_s:.3f} s (peak {w.von_mises_Pa / 1e6:.1f} MPa)")
        out[name] = {"peak_von_mises_MPa": w.von_mises_Pa / 1e6, "time_s": w.time_s, "png": png}
    return out
