"""Flexible-raceway interpolation kernels against their numpy twins in cms_reduction.sampling, on
seeded random tables and corner angles, and the work consistency of the force projection."""

import math

import numpy as np
import pytest

from cms_reduction import sampling as ref
from mbd_core.kernels.raceway import add_modal_force, interp_index, raceway_field

RNG = np.random.default_rng(611)
N, M = 36, 7


def _grid(periodic, start=0.0):
    if periodic:
        return start + 2 * math.pi * np.arange(N) / N
    return np.sort(RNG.uniform(0.3, 2.5, N))


CORNERS = [0.0, 2 * math.pi - 1e-15, 2 * math.pi, -1e-12, math.pi, 7 * math.pi, -3.0]


@pytest.mark.parametrize("periodic,start", [(True, 0.0), (True, 0.05), (False, 0.0)])
def test_interp_index_matches_the_numpy_version(periodic, start):
    grid = _grid(periodic, start)
    thetas = np.concatenate([RNG.uniform(-7, 14, 300), CORNERS, grid, grid[[0, -1]] + [-1e-9, 1e-9]])
    for th in thetas:
        i0, i1, w0, w1 = interp_index(grid, th, periodic)
        j0, j1, v0, v1 = ref.interp_index(grid, th, periodic)
        assert (i0, i1) == (j0, j1)
        assert w0 == pytest.approx(v0, rel=1e-12, abs=1e-15)
        assert w1 == pytest.approx(v1, rel=1e-12, abs=1e-15)
        assert w0 + w1 == pytest.approx(1.0, abs=1e-15) and -1e-15 <= w1 <= 1 + 1e-15


@pytest.mark.parametrize("periodic", [True, False])
def test_field_and_modal_force_match_the_numpy_version_and_do_the_same_work(periodic):
    grid = _grid(periodic)
    table = RNG.normal(size=(N, 3, M)) * 1e-4
    for th in np.concatenate([RNG.uniform(-1, 7, 200), CORNERS]):
        eta = RNG.normal(size=M) * RNG.choice([1e-6, 1.0, 1e3])
        f = RNG.normal(size=3) * 1e4
        i0, i1, w0, w1 = interp_index(grid, th, periodic)
        u = np.array(raceway_field(table, i0, i1, w0, w1, eta))
        np.testing.assert_allclose(u, ref.raceway_displacement(table, i0, i1, w0, w1, eta), rtol=1e-12,
                                   atol=1e-14 * np.abs(table).max() * np.abs(eta).sum())
        out = np.zeros(M)
        add_modal_force(table, i0, i1, w0, w1, f[0], f[1], f[2], out)
        q = ref.raceway_modal_force(table, i0, i1, w0, w1, f)
        np.testing.assert_allclose(out, q, rtol=1e-12, atol=1e-14 * np.abs(table).max() * np.abs(f).sum())
        # the projection is work-consistent: f·u(η) = Q·η (sampling module docstring)
        assert f @ u == pytest.approx(out @ eta, rel=1e-10, abs=1e-12 * np.abs(f).sum() * np.abs(u).sum())
    # accumulation: two forces add
    out = np.ones(M)
    add_modal_force(table, 0, 1, 0.25, 0.75, 1.0, 2.0, 3.0, out)
    np.testing.assert_allclose(out, 1.0 + ref.raceway_modal_force(table, 0, 1, 0.25, 0.75, np.array([1.0, 2, 3])),
                               rtol=1e-12)
