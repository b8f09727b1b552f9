"""The time-step error estimate (mbd_core.multibody.step_error): Richardson extrapolation from a
window repeated at h/2 and h/4, against the same window run at a step 32 times smaller."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mbd_core.contact.friction import Coulomb
from mbd_core.multibody import Driven, Fixed, ModelBuilder, simulate, stable_timestep, step_error
from mbd_core.multibody.bearings import add_ball_row
from mbd_core.multibody.step_error import ASSUMED_ORDER, richardson
from mbd_core.quasistatic import BallRow


@pytest.mark.parametrize("p", [1.0, 2.0, 3.0])
def test_richardson_recovers_order_and_error_of_a_power_law(p):
    # Reference: y(h) = y* + C h^p exactly; the error of y(h) is C h^p and the order p.
    y_star, c, h = 5.0, 3.0e4, 1e-3
    y = [y_star + c * (h / k) ** p for k in (1, 2, 4)]
    est = richardson(*y)
    assert est.order_observed and est.order == pytest.approx(p, rel=1e-9)
    assert est.error == pytest.approx(c * h ** p, rel=1e-9)
    assert est.relative == pytest.approx(c * h ** p / y[0], rel=1e-9)


def test_richardson_without_a_clean_order_assumes_first_order():
    # Differences of opposite signs: no order to observe; p = 1 gives error = 2 |y_h − y_{h/2}|.
    est = richardson(1.0, 1.0 - 1e-6, 1.0 + 1e-7)
    assert not est.order_observed and est.order == ASSUMED_ORDER
    assert est.error == pytest.approx(2e-6, rel=1e-9)


def _ball_bearing():
    """A 12-ball angular-contact bearing, inner ring turning at 100 rad/s under 2 kN of thrust."""
    row = BallRow("balls", 12, 12e-3, 0.1, math.radians(30), 0.52, 0.52, "inner", axial_sign=1)
    b = ModelBuilder()
    inner = b.add_body("inner ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Driven(100.0, translation_free=True))
    outer = b.add_body("outer ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    friction = Coulomb(0.1, 0.05, 0.05, 0.1)
    added = add_ball_row(b, row, inner, outer, friction=friction, damping_N_s_m=200.0, cage_mass_kg=0.05,
                         pocket_clearance_m=0.2e-3, cage_stiffness_N_per_m=2e6, pocket_friction=friction)
    b.add_force(inner, (0.0, 0.0, 2000.0))
    model, state = b.finalize()
    return model, state, list(added.moving_pairs)


def test_window_estimate_tracks_the_error_against_a_fine_step():
    # Reference: the same window from the same state at h/32 stands for the exact solution; the
    # estimate (from h, h/2, h/4) must lie within a factor 3 of |y_h − y_{h/32}| (issue acceptance:
    # an indicator within a factor 3 of the true error it estimates).
    model, state, pairs = _ball_bearing()
    simulate(model, state, 2e-3, record_every=50)  # settle the start
    h = stable_timestep(model, state).timestep_s

    def largest_ball_load(rec):
        return {"q": float(rec["fn"][:, pairs].max(axis=1).mean())}

    n = 200
    est = step_error(model, state, h, largest_ball_load, n_steps=n)["q"]
    t0 = state.t
    fine = largest_ball_load(simulate(model, state.copy(), t0 + n * h, timestep_s=h / 32, record_every=32))["q"]
    assert state.t == t0  # the window leaves the state alone
    true = abs(est.value - fine)
    assert true > 0.0
    assert 1 / 3 <= est.error / true <= 3, (est, true)


def test_bad_window_arguments_are_refused():
    model, state, _ = _ball_bearing()
    with pytest.raises(ValueError, match="timestep_s must be positive"):
        step_error(model, state, float("nan"), lambda rec: {})
    with pytest.raises(ValueError, match="n_steps must be ≥ 2"):
        step_error(model, state, 1e-6, lambda rec: {}, n_steps=1)
