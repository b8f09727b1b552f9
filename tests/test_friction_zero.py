"""Coulomb(0, 0) is frictionless: it divided by zero in the explicit step limit (dμ/du = 0; a
RuntimeWarning and an infinite friction step, an error wherever floating-point errors raise)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mbd_core.contact.friction import Coulomb, DrebLinear
from mbd_core.multibody import Driven, Fixed, ModelBuilder, stable_timestep
from mbd_core.multibody.bearings import add_ball_row
from mbd_core.quasistatic import BallRow


def _model(friction):
    row = BallRow("balls", 12, 12e-3, 0.1, math.radians(30), 0.52, 0.52, "inner", axial_sign=1)
    b = ModelBuilder()
    inner = b.add_body("inner ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Driven(100.0, translation_free=True))
    outer = b.add_body("outer ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    add_ball_row(b, row, inner, outer, friction=friction, damping_N_s_m=200.0, cage_mass_kg=0.05,
                 pocket_clearance_m=0.2e-3, cage_stiffness_N_per_m=2e6, pocket_friction=friction)
    b.add_force(inner, (0.0, 0.0, 2000.0))
    return b.finalize()


@pytest.mark.parametrize("zero", [Coulomb(0.0, 0.0), DrebLinear(0.0)])
def test_zero_friction_step_equals_frictionless(zero):
    """Reference: the same model without a friction law. μ ≡ 0 must give the identical stable step."""
    with np.errstate(divide="raise", invalid="raise"):
        ref = stable_timestep(*_model(None))
        got = stable_timestep(*_model(zero))
    assert got.timestep_s == ref.timestep_s
    assert got.reason == ref.reason
