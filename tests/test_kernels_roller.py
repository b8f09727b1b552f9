"""Roller slice kernel against its numpy twin and simple geometric cases (aligned, tilted, crowned)."""

import math

import numpy as np
import pytest

from mbd_core.kernels import roller_slices as RS
from tests.reference.roller_slices import roller_slices as twin

RNG = np.random.default_rng(11)
D, L, N_S = 55e-3, 55e-3, 20          # radial row of the 12 MW bearing


def _kernel(center, axis, drop, raceway, value):
    n = len(drop)
    d, q, nn = np.empty(n), np.empty((n, 3)), np.empty((n, 3))
    RS.roller_slices(center, axis, L, D / 2, drop, raceway, value, d, q, nn)
    return d, q, nn


@pytest.mark.parametrize("raceway,value", [(RS.RACEWAY_INNER_CYLINDER, 0.954),
                                           (RS.RACEWAY_OUTER_CYLINDER, 1.0091),
                                           (RS.RACEWAY_PLANE_UP, -0.03), (RS.RACEWAY_PLANE_DOWN, 0.03)])
def test_matches_twin_on_random_tilted_and_skewed_rollers(raceway, value):
    for _ in range(50):
        th = RNG.uniform(0, 2 * np.pi)
        radial = raceway in (RS.RACEWAY_INNER_CYLINDER, RS.RACEWAY_OUTER_CYLINDER)
        base_axis = np.array([0, 0, 1.0]) if radial else np.array([math.cos(th), math.sin(th), 0])
        axis = base_axis + RNG.normal(size=3) * 0.01            # small tilt and skew
        axis /= np.linalg.norm(axis)
        r = 0.9815 if radial else 1.091
        center = np.array([r * math.cos(th), r * math.sin(th), 0.0]) + RNG.normal(size=3) * 1e-4
        drop = RNG.uniform(0, 2e-5, N_S)
        for a, b in zip(_kernel(center, axis, drop, raceway, value), twin(center, axis, L, D / 2, drop, raceway, value)):
            assert a == pytest.approx(b, rel=1e-12, abs=1e-15)


def test_aligned_roller_penetrates_uniformly_and_tilt_makes_it_linear():
    # Aligned roller on the inner raceway R = 0.954 m, centre at r = R + D/2 − δ0: every slice δ0.
    d0 = 20e-6
    c = np.array([0.954 + D / 2 - d0, 0.0, 0.0])
    d, q, n = _kernel(c, np.array([0, 0, 1.0]), np.zeros(N_S), RS.RACEWAY_INNER_CYLINDER, 0.954)
    assert d == pytest.approx(np.full(N_S, d0), abs=1e-15)
    assert n == pytest.approx(np.tile([1.0, 0, 0], (N_S, 1)))
    # tilt by γ in the radial plane (about the tangential axis): δ_k = δ0 + γ s_k to first order
    g = 1e-4
    axis = np.array([math.sin(g), 0.0, math.cos(g)])
    d, _, _ = _kernel(c, axis, np.zeros(N_S), RS.RACEWAY_INNER_CYLINDER, 0.954)
    s = -L / 2 + (np.arange(N_S) + 0.5) * L / N_S
    assert d == pytest.approx(d0 - g * s, abs=1e-9)
    # a crown drop reduces the penetration slice by slice
    drop = 5e-6 * (2 * s / L) ** 2
    dc, _, _ = _kernel(c, np.array([0, 0, 1.0]), drop, RS.RACEWAY_INNER_CYLINDER, 0.954)
    assert dc == pytest.approx(d0 - drop, abs=1e-15)


def test_thrust_roller_on_plane():
    # Roller axis radial at θ = 30°, resting on the plane z = −0.03 (facing +z): δ = Z − (z_c − D/2).
    th = math.radians(30)
    c = np.array([1.091 * math.cos(th), 1.091 * math.sin(th), -0.03 + D / 2 - 15e-6])
    d, q, n = _kernel(c, np.array([math.cos(th), math.sin(th), 0.0]), np.zeros(N_S), RS.RACEWAY_PLANE_UP, -0.03)
    assert d == pytest.approx(np.full(N_S, 15e-6), abs=1e-15)
    assert q[:, 2] == pytest.approx(np.full(N_S, -0.03 - 15e-6), abs=1e-15)
