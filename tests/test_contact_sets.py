"""Contact sets of a load distribution: loads, pressures and ellipses per contact, against Hertz theory.

References: the approaches of a ball's two Hertz contacts add up to the ball's approach in the
load distribution (contacts in series, Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed.,
ch. 7); a line contact's p0 = sqrt(q·E'/(2π·R·l)) (Johnson, *Contact Mechanics*, 1985, eq. 4.45
with p0 = 2q/(π·b·l)).
"""

import math

import numpy as np

from foundation.materials import BEARING_STEEL, effective_modulus_Pa
from mbd_core.contact.hertz import ball_on_groove
from mbd_core.quasistatic import BallRow, Bearing, RingLoad, RollerRow, solve_load_distribution
from mbd_core.quasistatic.contacts import contact_sets, groove_truncated


def _ball_bearing():
    row = BallRow("acbb", 20, 12e-3, 80e-3, math.radians(40.0), 0.52, 0.53, moving_raceway="inner", axial_sign=1)
    return Bearing("acbb", (row,)), row


def test_ball_contact_approaches_add_up_to_the_ball_approach():
    bearing, row = _ball_bearing()
    dist = solve_load_distribution(bearing, RingLoad(Fx_N=800.0, Fz_N=3000.0))
    sets = contact_sets(bearing, dist)
    assert [s.raceway for s in sets] == ["inner", "outer"]
    res = dist.rows[0]
    delta = np.zeros(row.n_balls)
    for s, f in zip(sets, (row.conformity_moving, row.conformity_fixed)):
        c = ball_on_groove(row.ball_diameter_m, f, row.pitch_diameter_m, row.contact_angle_rad, s.raceway)
        delta += c.approach_m(s.load_N)
        np.testing.assert_array_equal(s.load_N, res.load_N)
    loaded = res.load_N > 0
    assert loaded.sum() >= 3
    # contacts in series: δ_inner + δ_outer = δ of the ball (rel. 1e-9, the solver's rounding)
    np.testing.assert_allclose(delta[loaded], res.approach_m[loaded], rtol=1e-9)
    # the inner (more curved) contact is the smaller and the more highly loaded
    assert np.all(sets[0].max_pressure_Pa[loaded] > sets[1].max_pressure_Pa[loaded])
    assert np.all(sets[0].semi_major_m >= sets[0].semi_minor_m)
    assert not sets[0].max_pressure_Pa[~loaded].any()


def test_roller_contact_pressure_is_the_line_contact_closed_form():
    row = RollerRow("crb", 16, 10e-3, 10e-3, 70e-3, "radial", n_slices=10)
    bearing = Bearing("crb", (row,))
    dist = solve_load_distribution(bearing, RingLoad(Fx_N=5000.0))
    sets = contact_sets(bearing, dist)
    q = dist.rows[0].slice_load_N.max(axis=1)
    l = row.roller_length_m / row.n_slices
    Ep = effective_modulus_Pa(BEARING_STEEL, BEARING_STEEL)
    for s, R in zip(sets, (1 / (2 / 10e-3 + 2 / 60e-3), 1 / (2 / 10e-3 - 2 / 80e-3))):
        expected = np.sqrt(q * Ep / (2 * math.pi * R * l))  # Johnson eq. 4.45
        np.testing.assert_allclose(s.max_pressure_Pa, expected, rtol=1e-12)
    assert sets[0].max_pressure_Pa.max() > sets[1].max_pressure_Pa.max()  # convex inner raceway


def test_truncation_flags_the_ellipse_beyond_the_groove_edge():
    # ellipse half-angle a/(f·D) = 0.1 rad about α; edge at 90°
    a = np.array([0.1, 0.1, 0.1]) * 0.53 * 0.02
    alpha = np.array([math.pi / 2 - 0.2, math.pi / 2 - 0.05, 0.05])
    np.testing.assert_array_equal(groove_truncated(a, 0.53 * 0.02, alpha, 0.0, math.pi / 2), [False, True, True])
