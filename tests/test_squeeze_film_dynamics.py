"""A squeeze-film damper in the multibody model: a journal on a centring spring driven by a rotating
force settles on the circular orbit that the short-damper closed form predicts.

Reference (written here): on a centred circular orbit of radius e = ε c at the forcing speed ω, the
journal's equation of motion in the rotating (radial, tangential) frame is

    −m ω² e = −k e + F_r(ε) + F₀ cos β,      0 = F_t(ε) + F₀ sin β,

with (F_r, F_t) the short π-film forces (Vance 1988, Table 6-1) and β the lead of the force over the
displacement; so F₀² = ((k − m ω²) e − F_r)² + F_t², solved for ε (the root is unique here: the
left side grows monotonically with ε for these parameters).
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from mbd_core.multibody import Driven, Fixed, ModelBuilder, simulate
from mbd_core.multibody.explicit import DivergenceError
from mbd_core.squeeze_film import SqueezeFilmDamper, short_circular_orbit_force_N
from mbd_core.squeeze_film.force_table import tabulate

DAMPER = SqueezeFilmDamper(radius_m=0.02, length_m=0.01, clearance_m=1e-4, viscosity_Pa_s=0.01)
MASS_KG, K_N_M, OMEGA_RAD_S, F0_N = 0.2, 1e6, 1000.0, 44.0


def _model(force_N=F0_N, table=None, static_N=0.0):
    b = ModelBuilder()
    b.add_body("housing", 1.0, (1e-3,) * 3, motion=Fixed())
    b.add_body("journal", MASS_KG, (1e-5,) * 3, motion=Driven(0.0, translation_free=True))
    b.add_bushing("housing", "journal", (0, 0, 0), (K_N_M, K_N_M, 0, 0, 0, 0))
    b.add_squeeze_film("journal", "housing", table or tabulate(DAMPER, "short"))
    t = np.linspace(0.0, 0.1, 1601)      # 100 knots per forcing period: spline error ≈ 1e-7
    loads = np.zeros((t.size, 6))
    loads[:, 0], loads[:, 1] = force_N * np.cos(OMEGA_RAD_S * t), force_N * np.sin(OMEGA_RAD_S * t)
    b.add_load_history("journal", t, loads)
    b.add_force("journal", (static_N, 0.0, 0.0))
    return b.finalize()


def _predicted_orbit():
    c = DAMPER.clearance_m

    def residual(eps):
        fr, ft = short_circular_orbit_force_N(DAMPER, eps, OMEGA_RAD_S)
        return math.hypot((K_N_M - MASS_KG * OMEGA_RAD_S**2) * eps * c - fr, ft) - F0_N

    eps = brentq(residual, 1e-6, 0.9, xtol=1e-12)
    fr, ft = short_circular_orbit_force_N(DAMPER, eps, OMEGA_RAD_S)
    return eps, math.atan2(-ft, (K_N_M - MASS_KG * OMEGA_RAD_S**2) * eps * c - fr)


def test_forced_circular_orbit_matches_short_damper_closed_form():
    model, state = _model()
    run = simulate(model, state, 0.1, record_every=20)
    t, xy = run["t"], run["q"][:, 1, :2]
    late = t > 0.06                                      # settled: the film's decay time m/c ≈ 0.5 ms
    radius = np.linalg.norm(xy[late], axis=1) / DAMPER.clearance_m
    lead = np.angle(np.exp(1j * OMEGA_RAD_S * t[late]) / (xy[late, 0] + 1j * xy[late, 1]))
    eps, beta = _predicted_orbit()
    assert 0.3 < eps < 0.5
    # table interpolation (≤ 0.5 %) and the explicit step: 1 % on the radius, 0.01 rad on the lead
    assert np.all(np.abs(radius / eps - 1.0) < 0.01), (radius.min(), radius.max(), eps)
    assert np.all(np.abs(lead - beta) < 0.01), (lead.min(), lead.max(), beta)


def test_journal_beyond_the_table_stops_with_the_damper_named():
    # a steady force the spring cannot hold within the clearance (1 mm against 0.1 mm) drives the journal
    # to the table's end
    model, state = _model(static_N=1000.0)
    with pytest.raises(DivergenceError, match="squeeze-film damper 'journal–housing film'"):
        simulate(model, state, 0.02, record_every=20)


def test_bad_damper_input_names_the_field():
    b = ModelBuilder()
    b.add_body("housing", 1.0, (1e-3,) * 3, motion=Fixed())
    b.add_body("journal", MASS_KG, (1e-5,) * 3, position_m=(2e-4, 0, 0))
    with pytest.raises(ValueError, match="starts at ε = 2"):
        b.add_squeeze_film("journal", "housing", tabulate(DAMPER, "short", n_eps=5, n_psi=8))
    with pytest.raises(TypeError, match="FilmForceTable"):
        b.add_squeeze_film("journal", "housing", DAMPER)
    with pytest.raises(ValueError, match="axis"):
        b.add_squeeze_film("journal", "housing", tabulate(DAMPER, "short", n_eps=5, n_psi=8),
                           bore_center_m=(2e-4, 0, 0), axis=(0, 0, 0))
