"""A dynamic run of the slewing ring with a modal top structure starts at its flexible equilibrium.

The 2 m ring, undulated bottom race ×1, modal top structure (the quick mesh of study (c): 0.12 m,
12 modes, raceway load shapes to harmonic 8). Reference: the flexible quasi-static solution
(:func:`cases.slewing.quasistatic.equilibrium`: Newton on the top's displacement and modal
coordinates with the balls condensed, an independent solver of the same reduced body and
undulation), at the start and, during the run, at the top's angle and the balls' phase of each
compared sample.
"""

import math
import time

import numpy as np
import pytest

from cases.integrate import integrate
from cases.slewing import scene
from cases.slewing.dynamic import build_scene, start_state, state_from_quasistatic
from cases.slewing.presets import PRESETS
from cases.slewing.quasistatic import equilibrium
from mbd_core.multibody import evaluate_forces


@pytest.fixture(scope="module")
def modal_scene():
    case = PRESETS["slewing-rotation"].with_(
        geometry={"variant": "2m"}, undulation={"scale": 1.0},
        top={"kind": "modal", "n_modes": 12, "groove_harmonics": 8, "element_size_m": 0.12})
    bodies = scene.Bodies(scene.top_body(case), scene.bottom_body(case))
    return case, bodies


def _at_rest(sc, state):
    still = state.copy()
    still.v[:] = 0.0
    still.eta_dot[:] = 0.0
    return evaluate_forces(sc.model, still).contact_fn[list(sc.ball_pairs_top)]


def test_the_start_is_the_flexible_equilibrium(modal_scene):
    case, bodies = modal_scene
    reference = equilibrium(case, bodies).rows[0].load_N
    sc = build_scene(case, bodies)
    mapped = _at_rest(sc, state_from_quasistatic(sc, case, bodies).copy())
    # the mapping alone: the multibody groove interpolates the same raceway samples its own way;
    # measured 5.1e-5 of the largest load
    assert np.abs(mapped - reference).max() < 5e-4 * reference.max()
    sc = build_scene(case, bodies)
    t0 = time.perf_counter()
    start = start_state(sc, case, bodies)
    took_s = time.perf_counter() - t0
    polished = _at_rest(sc, start)
    # polished by the multibody static equilibrium: 1.9e-4 of the largest load, the balls' own
    # weight (34 N, 1.8e-4 of 185 kN) that the quasi-static model leaves out; tolerance 5e-4
    assert np.abs(polished - reference).max() < 5e-4 * reference.max()
    # from rest it took 33 s (133 585 force evaluations); from the mapped state 6 s, and 2.9 s
    # (14 556 evaluations) since the search stops where the forces left stall.
    # Not a timing test: a generous bound that a search from rest would not meet
    assert took_s < 25.0


def test_a_run_from_it_follows_the_flexible_quasistatic_loads(modal_scene):
    case, bodies = modal_scene
    sc = build_scene(case, bodies)
    run = integrate(sc.model, start_state(sc, case, bodies), 0.02, 200)
    pairs, balls = list(sc.ball_pairs_top), list(sc.balls)
    worst = 0.0
    for k in np.linspace(0, len(run["t"]) - 1, 3).astype(int):
        q = run["q"][k]
        top_rad = 2.0 * math.atan2(q[sc.top, 6], q[sc.top, 3])
        psi = np.arctan2(q[balls, 1], q[balls, 0]) - 2.0 * math.pi * np.arange(len(balls)) / len(balls)
        phase = math.atan2(np.sin(psi).mean(), np.cos(psi).mean())
        ref = equilibrium(case, bodies, top_rotation_rad=top_rad, ball_phase_rad=phase).rows[0].load_N
        worst = max(worst, np.abs(run["fn"][k, pairs] - ref).max() / ref.max())
    # no start-up shock: within 0.5 % of the largest load at every compared sample (the issue's
    # bound over 0.2 s; measured 0.05 % here, 0.31 % at 0.2 s in a longer run)
    assert worst < 0.005, worst
