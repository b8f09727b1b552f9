"""Fluid drag on a body's centre (``ModelBuilder.add_drag``).

Reference: a body of mass m under a constant force F and linear drag c (Stokes, F_d = −c·v)
moves at v(t) = (F/c)(1 − e^(−c t/m)) from rest (the linear first-order ODE m v̇ = F − c v).
With quadratic drag c₂ alone the terminal speed is sqrt(F/c₂) and v(t) = v_T·tanh(t·sqrt(F c₂)/m).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mbd_core.multibody import Free, ModelBuilder, simulate


@pytest.mark.parametrize("linear, quadratic", [(0.8, 0.0), (0.0, 0.5)])
def test_speed_under_constant_force_and_drag(linear, quadratic):
    mass, force = 0.2, 1.5
    b = ModelBuilder()
    body = b.add_body("ball", mass, (1e-5,) * 3, motion=Free())
    b.add_force(body, (force, 0.0, 0.0))
    b.add_drag(body, linear, quadratic)
    model, state = b.finalize()
    run = simulate(model, state, 1.0, timestep_s=1e-4, record_every=100)
    t, v = run["t"], run["v"][:, 0, 0]
    if quadratic == 0.0:
        want = force / linear * (1.0 - np.exp(-linear * t / mass))
    else:
        want = math.sqrt(force / quadratic) * np.tanh(t * math.sqrt(force * quadratic) / mass)
    assert np.max(np.abs(v - want)) < 1e-3 * np.max(want)   # first-order accurate in h = 1e-4 s


def test_bad_drag_names_the_field():
    b = ModelBuilder()
    body = b.add_body("ball", 0.2, (1e-5,) * 3)
    with pytest.raises(ValueError, match="linear_N_s_m"):
        b.add_drag(body, -1.0)
