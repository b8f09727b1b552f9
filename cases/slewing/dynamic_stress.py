"""The races' stress over a dynamic run, from their modal coordinates.

A race reduced with ``stress_modes`` (:class:`.case.BodyFidelity`) carries the nodal stress σ_j of
each of its modes, so the stress at every recorded sample is the superposition Σ_j η_j(t) σ_j
(:mod:`cms_reduction.stress_history`): exact for the linear-elastic finite-element model of the race
within its modal basis, mechanical loads only (the thermal study's offsets move the grooves, they
put no thermal strain into the ring).

The dead load. The model carries it as the top structure's weight (its density raised ×k so that
its weight is the dead load W, :mod:`.scene`), which loads every element of the ring; the real
structure carries its own weight W/k and the plug's (1 − 1/k)·W as a pressure on the seat (the
TMR's top face, ``load_face``; the race's ``bolt_face`` without TMR). The difference of the two is
a self-equilibrated load Δf = (1 − 1/k)·(seat pressure of W − the body force of W), fixed in the
structure's frame (gravity stays along its axis to the tilts' µrad). Linear elasticity makes the
stress of the real loading the model's plus the static stress of Δf, so that stress (one
finite-element solve of the free structure held at six DOFs whose reactions are zero,
:func:`fem_rings.spinning.statically_determinate_holds`; cached) is added at every instant. The
inertia of the run keeps the model's mass distribution (at ≤ 6.55 r/min the ring's inertia forces
are negligible, :mod:`.quasistatic`), and Δf, being axisymmetric, moves the groove evenly round
the ring and by little: on the 2 m ring under 140 t, at most 0.4 µm radially and 0.9 µm axially
near the groove (rigid motion of the holds included) against a Hertz approach of about 0.1 mm, so
the ball loads do not see it.

Two regions are reported apart. The ball forces reach a modal race as loads on its groove's contact
line (the raceway load shapes), whose nodal stress right at the line grows as the mesh is refined
(a line load on an elastic body has unbounded stress under it); the real stress there is the
field of each ball's own force, which decays over about a ball diameter (Boussinesq) and which
the smooth load shapes do not hold, and at the contact the Hertz stress of study (f). So the
*ring* stress is the largest nodal von Mises stress of the nodes farther than the groove zone
from the groove surface, one ball diameter or one element size, whichever is larger (the bending,
twisting and hoop stress of the race and the structure, and the dead load's path); the *groove*
stress, of the nodes within it, is given for completeness with that caveat.

Per race, after the start-up window: the peak of each over time, where the ring peak sits (radius,
height, azimuth in the race's own frame), the von Mises stress over time at that node (the cycle a
material point of the turning race goes through as the loads travel round it: what a fatigue
assessment needs), a CSV of the three histories, a plot, and the race at the instant of its ring
peak (PNG, and a VTU with displacement and von Mises stress for ParaView).
"""

from __future__ import annotations

import math

import numpy as np

from .case import SlewingCase

__all__ = ["RACES", "groove_zone_m", "groove_distance_m", "race_stress_histories", "write_race_stresses"]

#: race key of the case → the name of its modal body in the scene
RACES = {"top": "top structure", "bottom": "bottom race"}


def groove_zone_m(case: SlewingCase, body) -> float:
    """Depth of the groove zone (module docstring): max(ball diameter, the body's element size), m."""
    return max(case.geometry.ball_diameter_m, float(body.metadata["element_size_m"]))


def groove_distance_m(case: SlewingCase, race: str, nodes_m: np.ndarray) -> np.ndarray:
    """Distance of each node (N, 3) from the surface of the race's groove (the circle of radius f·D
    about the groove's curvature centre in the section), m."""
    groove = case.geometry.section().groove(race, case.geometry.pitch_diameter_m)
    rc, zc = groove.curvature_center_m
    r = np.hypot(nodes_m[:, 0], nodes_m[:, 1])
    return np.abs(np.hypot(r - rc, nodes_m[:, 2] - zc) - groove.radius_m)


#: version of the dead-load correction's cache entries (bump when its arithmetic changes)
SEAT_CORRECTION_VERSION = 1
#: the correction's holds must carry no load: largest reaction allowed, relative to the dead load
HOLD_REACTION_TOLERANCE = 1e-6


def seat_face(case: SlewingCase) -> str:
    """The facet set of the top structure the plug rests on."""
    return "load_face" if case.top.include_tmr else "bolt_face"


def seat_correction_loads_N(model, seat: str, gravity_m_s2: float) -> np.ndarray:
    """Δf (3N,) N of the module docstring for an FE model whose density carries the dead load W:
    (1 − 1/k)·(W as a uniform pressure on ``seat`` − the body force M g), k = ρ_model / ρ_steel."""
    from fem_rings.solve import surface_load

    from .scene import DENSITY_KG_M3

    g = np.zeros(model.n_dofs)
    g[2::3] = -gravity_m_s2
    body = model.M @ g                     # the weight, N: its z components sum to −W
    weight_N = -float(body[2::3].sum())
    facets = model.ring.facet_sets[seat]
    area = float(-surface_load(model, facets, (0.0, 0.0, -1.0))[2::3].sum())  # unit pressure → area
    seat_load = surface_load(model, facets, (0.0, 0.0, -weight_N / area))
    share = 1.0 - DENSITY_KG_M3 / model.material.density_kg_m3
    return share * (seat_load - body)


def seat_correction_Pa(case: SlewingCase) -> np.ndarray:
    """(N, 6) Voigt stress, Pa, of the dead load moved from the top structure's body onto its seat
    (module docstring), on the nodes of :func:`.scene.top_body`; cached by the model's inputs."""
    from fem_rings import build_model
    from fem_rings.cache import input_hash, load_arrays, save_arrays
    from fem_rings.solve import Support, static_solve
    from fem_rings.spinning import statically_determinate_holds
    from fem_rings.stress import nodal_stress_Pa

    from .scene import top_model_inputs

    inputs = top_model_inputs(case)
    seat, g = seat_face(case), case.load.gravity_m_s2
    key = input_hash("slewing-seat-stress", SEAT_CORRECTION_VERSION, *inputs, seat, g)
    stored = load_arrays("slewing-seat-stress", key)
    if stored is not None:
        return stored["stress_Pa"]
    model = build_model(*inputs)
    f = seat_correction_loads_N(model, seat, g)
    holds = statically_determinate_holds(model)
    supports = [Support(np.array([d // 3]), (int(d % 3),), f"hold {k}") for k, d in enumerate(holds)]
    res = static_solve(model, f, supports)
    reaction = float(np.abs(res.reaction_N).max())
    if reaction > HOLD_REACTION_TOLERANCE * case.dead_load_N:
        raise RuntimeError(f"the dead-load seat correction is not self-equilibrated: {reaction:.3g} N at its holds")
    stress = nodal_stress_Pa(model, res.u)
    save_arrays("slewing-seat-stress", key, {"stress_Pa": stress})
    return stress


def race_stress_histories(case: SlewingCase, race: str, body, eta_t: np.ndarray) -> dict:
    """``ring`` and ``groove`` :class:`cms_reduction.stress_history.PeakHistory` of a race over the
    samples of ``eta_t`` (n_t, m), the depth of the groove zone that separates them, m, and the constant stress
    added to the modal one (``offset_Pa``: the top structure's seat correction; None for the bottom race)."""
    from cms_reduction.stress_history import peak_von_mises_history

    size = groove_zone_m(case, body)
    near = groove_distance_m(case, race, np.asarray(body.nodes_m)) < size
    offset = seat_correction_Pa(case) if race == "top" else None
    return {"ring": peak_von_mises_history(body, eta_t, nodes=np.flatnonzero(~near), offset_Pa=offset),
            "groove": peak_von_mises_history(body, eta_t, nodes=np.flatnonzero(near), offset_Pa=offset),
            "groove_zone_m": size, "offset_Pa": offset}


def _stress_Pa(body, eta: np.ndarray, offset) -> np.ndarray:
    """Nodal stress (N, 6) Pa of one instant: modal plus the constant offset."""
    from cms_reduction.stress_modes import modal_stress_Pa

    s = modal_stress_Pa(body, eta)
    return s if offset is None else s + offset


def write_race_stresses(out, case: SlewingCase, bodies, run: dict, settled: np.ndarray) -> None:
    """Summary entries, CSV, plot, PNG and VTU of every race with stress modes (module docstring)."""
    from fem_rings.output import write_vtu
    from fem_rings.render import render_png
    from fem_rings.stress import von_mises_Pa

    from .plots import plot_race_stress

    t = np.asarray(run["t"])
    histories = {}
    for race, name in RACES.items():
        body = getattr(bodies, race)
        if body is None or "stress_modes" not in body.extras:
            continue
        lo, hi = run["modal_ranges"][name]
        eta = np.asarray(run["eta"])[:, lo:hi]
        h = race_stress_histories(case, race, body, eta)
        histories[name] = h
        ring, groove, offset = h["ring"], h["groove"], h["offset_Pa"]
        k = int(np.flatnonzero(settled)[np.argmax(ring.von_mises_Pa[settled])])
        n = int(ring.node[k])
        x, y, z = np.asarray(body.nodes_m)[n]
        # the stress cycle of that material point as the loads travel round the turning race
        at_node = eta @ np.asarray(body.extras["stress_modes"])[n].T
        h["at_peak_node"] = von_mises_Pa(at_node if offset is None else at_node + offset[n])
        slug = name.replace(" ", "_")
        out.summary.setdefault("race_stress", {})[name] = {
            "ring_peak_von_mises_Pa": float(ring.von_mises_Pa[k]), "time_s": float(t[k]),
            "ring_peak_radius_m": float(math.hypot(x, y)), "ring_peak_height_m": float(z),
            "ring_peak_azimuth_rad": float(math.atan2(y, x)),
            "ring_von_mises_range_Pa": [float(ring.von_mises_Pa[settled].min()), float(ring.von_mises_Pa[settled].max())],
            "peak_node_von_mises_range_Pa": [float(h["at_peak_node"][settled].min()),
                                             float(h["at_peak_node"][settled].max())],
            "groove_peak_von_mises_Pa": float(groove.von_mises_Pa[settled].max()),
            "groove_zone_m": h["groove_zone_m"],
            "dead_load": ("on the seat (" + seat_face(case) + "): the model's body force moved there by a static "
                          "correction" if offset is not None else "not carried by this race's body"),
            "what": "largest nodal von Mises stress after the start-up: 'ring' beyond groove_zone_m (a ball diameter "
                    "or an element, the larger) "
                    "from the groove surface; 'groove' within it, where the ball forces' line loads make it "
                    "mesh-dependent (the contact stress is Hertz', study life)"}
        out.write_csv(f"{slug}_stress_time.csv", ["t_s", "ring_von_mises_Pa", "ring_node", "ring_radius_m",
                                                  "ring_height_m", "ring_azimuth_rad", "groove_von_mises_Pa",
                                                  "peak_node_von_mises_Pa"],
                      ([ti, s, m, math.hypot(*body.nodes_m[m][:2]), body.nodes_m[m][2],
                        math.atan2(body.nodes_m[m][1], body.nodes_m[m][0]), g, p]
                       for ti, s, m, g, p in zip(t, ring.von_mises_Pa, ring.node, groove.von_mises_Pa,
                                                 h["at_peak_node"])))
        vm = von_mises_Pa(_stress_Pa(body, eta[k], offset))
        u = body.displacement_m(eta[k])
        write_vtu(out.path(f"{slug}_ring_peak.vtu"), body.mesh(), {"displacement_m": u, "von_mises_Pa": vm})
        render_png(out.path(f"{slug}_ring_peak.png"), body.mesh(), vm, label="von Mises", unit="MPa", scale=1e-6,
                   displacement_m=u,
                   title=f"{name}: von Mises at t = {t[k]:.3f} s (ring peak {ring.von_mises_Pa[k] / 1e6:.1f} MPa)")
        out.note(f"{name} stress (von Mises, after the start-up): ring {ring.von_mises_Pa[settled].min() / 1e6:.1f}–"
                 f"{ring.von_mises_Pa[k] / 1e6:.1f} MPa, peak at t = {t[k]:.3f} s, r = {math.hypot(x, y):.3f} m, "
                 f"z = {z:.3f} m, {math.degrees(math.atan2(y, x)):.1f}° in its frame (there "
                 f"{h['at_peak_node'][settled].min() / 1e6:.1f}–{h['at_peak_node'][settled].max() / 1e6:.1f} MPa over "
                 f"the run); within {1e3 * h['groove_zone_m']:.0f} mm of the groove up to "
                 f"{groove.von_mises_Pa[settled].max() / 1e6:.1f} MPa (ball forces as line loads: mesh-dependent)")
    if histories:
        settled_from_s = float(t[np.flatnonzero(settled)[0]])
        out.save_figure(plot_race_stress(t, histories, case, settled_from_s), "race_stress_time.png")
