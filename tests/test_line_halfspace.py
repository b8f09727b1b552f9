"""Tests of the half-space coupled roller slices in ``mbd_core.contact.line_halfspace``.

References used below:

* Johnson, *Contact Mechanics* (1985): Hertz sphere on a plane (§4.2: a² = R δ,
  P = (4/3) E* R^½ δ^(3/2), p0 = 3P/(2πa²), E* = E'/2); Love's uniformly loaded rectangle (eq. 3.25).
* ``tests/reference/halfspace_grid.py``: an independent contact solver on a grid of uniformly
  loaded rectangles of the half-space (no slices, no assumed pressure shape), checked here first
  against Hertz.
* Sharp-edged punch on a half-space: the pressure near a straight edge grows as r^(−½)
  (Johnson §5.2), so the mean pressure on an end slice of width w grows as w^(−½).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mbd_core.contact.line_halfspace import (
    coupled_slice_loads,
    coupled_slices_under_load,
    strip_influence,
)
from mbd_core.quasistatic.rows import roller_drop_m
from tests.reference.halfspace_grid import grid_contact, rectangle_influence

E_EFF_PA = 2.26e11  # steel on steel, E = 207 GPa, ν = 0.29 (BEARING_STEEL): E' = 2/(2(1 − ν²)/E) = E/(1 − ν²)
ROLLER_RADIUS_M = 8e-3  # Ø16 mm roller on a flat raceway: R = 8 mm across
LENGTH_M = 16e-3


def _slice_centres(n):
    return (np.arange(n) + 0.5) / n * LENGTH_M - LENGTH_M / 2


def test_grid_reference_reproduces_hertz_sphere():
    """The grid reference itself: a sphere on a plane within 0.1 % of Hertz (load and peak)."""
    R, delta = 0.01, 5e-6
    a = math.sqrt(R * delta)
    P = 4.0 / 3.0 * (E_EFF_PA / 2) * math.sqrt(R) * delta**1.5
    edges = np.linspace(-1.3 * a, 1.3 * a, 42)
    c = 0.5 * (edges[1:] + edges[:-1])
    X, Y = np.meshgrid(c, c, indexing="ij")
    p = grid_contact(edges, edges, (X**2 + Y**2) / (2 * R), delta, E_EFF_PA)
    assert p.sum() * (edges[1] - edges[0]) ** 2 == pytest.approx(P, rel=1e-3)
    assert p.max() == pytest.approx(3 * P / (2 * math.pi * a * a), rel=1e-3)


@pytest.mark.parametrize("m", [0, 1, 3])
@pytest.mark.parametrize("beta", [0.05, 1.0, 20.0])
def test_strip_influence_vs_love_rectangles(m, beta):
    """I(m, β) equals the semi-elliptical strip summed from 4000 uniform Love rectangles to 1e-4.

    Strip of width 1 (x ∈ [−½, ½]) and half-width β: the band between t_k and t_{k+1} (t = y/β)
    carries sqrt(1 − t²) at its centre; I is the centre-line approach at x = m divided by β
    (the t-integral's dy = β dt) — the rectangles' error is O(N^−1.5) at the strip's borders.
    """
    t = np.linspace(-1.0, 1.0, 4001)
    tc = 0.5 * (t[1:] + t[:-1])
    bands = rectangle_influence(float(m), 0.0, -0.5, 0.5, beta * t[:-1], beta * t[1:])
    reference = np.sum(np.sqrt(1.0 - tc**2) * bands) / beta
    assert strip_influence(m, beta) == pytest.approx(reference, rel=1e-4)


def _grid_slices(n, sub, gap_fn, delta, half_width_m, n_y=40):
    """Slice loads (n,) N and centre-line pressure (n·sub,) Pa of the grid reference."""
    ex = np.linspace(-LENGTH_M / 2, LENGTH_M / 2, n * sub + 1)
    ey = np.linspace(-1.3 * half_width_m, 1.3 * half_width_m, n_y + 1)
    X, Y = np.meshgrid(0.5 * (ex[1:] + ex[:-1]), 0.5 * (ey[1:] + ey[:-1]), indexing="ij")
    p = grid_contact(ex, ey, gap_fn(X) + Y**2 / (2 * ROLLER_RADIUS_M), delta, E_EFF_PA)
    loads = (p * (ex[1] - ex[0]) * (ey[1] - ey[0])).reshape(n, sub, -1).sum(axis=(1, 2))
    centre = 0.5 * (p[:, n_y // 2 - 1] + p[:, n_y // 2])
    return loads, centre


@pytest.fixture(scope="module")
def crowned():
    """A crowned roller (10 µm parabolic drop at the ends) loaded along its whole length."""
    n, crown, delta = 16, 10e-6, 12e-6

    def gap(x):
        return crown * (2 * x / LENGTH_M) ** 2

    s = coupled_slice_loads(delta - gap(_slice_centres(n)), LENGTH_M, ROLLER_RADIUS_M, E_EFF_PA)
    loads, centre = _grid_slices(n, 4, gap, delta, s.half_width_m.max())
    return s, loads, centre


def test_crowned_roller_slices_match_the_half_space_grid(crowned):
    """Slice loads within 2 % of the largest slice load of the grid reference (acceptance), the
    total within 1 %, the middle slice's peak pressure within 2 % (measured: 0.42 %, 0.13 %, 0.07 %)."""
    s, loads, centre = crowned
    assert np.max(np.abs(s.load_N - loads)) < 0.02 * loads.max()
    assert s.total_load_N == pytest.approx(loads.sum(), rel=0.01)
    # grid pressure on the centre line, averaged over the middle slice's cells
    n = s.load_N.size
    assert s.peak_pressure_Pa[n // 2] == pytest.approx(centre[4 * (n // 2): 4 * (n // 2) + 4].mean(), rel=0.02)


def test_straight_roller_edge_stress_against_the_grid():
    """A straight roller: the end slices carry more than the middle (edge stress), as on the grid.

    Both discretisations are short of the r^(−½) singularity at the ends, so the end/middle load
    ratio is compared within 10 % (measured at 16 slices: 1.38 coupled slices, 1.47 grid of 96
    cells along the roller); the uncoupled ISO slices load the roller evenly (ratio 1).
    """
    n, delta = 16, 6e-6
    s = coupled_slice_loads(np.full(n, delta), LENGTH_M, ROLLER_RADIUS_M, E_EFF_PA)
    loads, _ = _grid_slices(n, 6, np.zeros_like, delta, s.half_width_m.max())
    ratio, ratio_grid = s.load_N[0] / s.load_N[n // 2], loads[0] / loads[n // 2]
    assert ratio > 1.3
    assert ratio == pytest.approx(ratio_grid, rel=0.10)
    assert s.load_N == pytest.approx(s.load_N[::-1], rel=1e-9)  # symmetric
    assert s.total_load_N == pytest.approx(loads.sum(), rel=0.02)


def test_straight_roller_edge_pressure_grows_towards_the_singularity():
    """End-slice pressure over slice count 10 → 80: it grows at each halving of the slice width,
    by a ratio that rises towards the r^(−½) singularity's √2 (measured 1.07, 1.10, 1.15); the
    middle pressure settles (changes 0.10 %, 0.05 %, 0.04 %)."""
    p_end, p_mid = [], []
    for n in (10, 20, 40, 80):
        s = coupled_slice_loads(np.full(n, 6e-6), LENGTH_M, ROLLER_RADIUS_M, E_EFF_PA)
        p_end.append(s.peak_pressure_Pa[0])
        p_mid.append(s.peak_pressure_Pa[n // 2])
    ratios = np.array(p_end[1:]) / np.array(p_end[:-1])
    assert np.all(np.diff(ratios) > 0.0) and np.all(ratios > 1.0) and np.all(ratios < math.sqrt(2))
    assert np.all(np.abs(np.diff(p_mid)) / p_mid[-1] < 2e-3)


def test_logarithmic_roller_converges_with_slice_count():
    """ISO/TS 16281 logarithmic profile (relief 0.00035·D) under 3 kN: approach and peak pressure
    converge as the slices are refined 10 → 20 → 40 (observed order ≥ 3 on both; measured
    8.645, 8.717, 8.723 µm and 1144.2, 1149.0, 1149.3 MPa). The ends stay unloaded."""
    out = []
    for n in (10, 20, 40):
        drop = roller_drop_m(_slice_centres(n), LENGTH_M, "logarithmic", 0.0, 0.00035 * 16e-3)
        s, delta = coupled_slices_under_load(3000.0, drop, LENGTH_M, ROLLER_RADIUS_M, E_EFF_PA)
        assert s.total_load_N == pytest.approx(3000.0, rel=1e-8)
        out.append((delta, s.peak_pressure_Pa.max()))
    for j in (0, 1):
        a, b, c = (o[j] for o in out)
        assert math.log2(abs((b - a) / (c - b))) > 3.0
    assert s.load_N[0] < 0.1 * s.load_N.max()


def test_unloaded_and_bad_input():
    zero = coupled_slice_loads(np.full(8, -1e-6), LENGTH_M, ROLLER_RADIUS_M, E_EFF_PA)
    assert zero.total_load_N == 0.0
    with pytest.raises(ValueError, match="interference_m must be"):
        coupled_slice_loads(np.array([1e-6, np.nan]), LENGTH_M, ROLLER_RADIUS_M, E_EFF_PA)
    with pytest.raises(ValueError, match="length_m"):
        coupled_slice_loads(np.full(4, 1e-6), -1.0, ROLLER_RADIUS_M, E_EFF_PA)


def test_influence_table_interpolates_the_quadrature():
    """The spline over ln β that the fixed point uses, against the quadrature at random points: 1e-7
    (measured 1.3e-8)."""
    from mbd_core.contact.line_halfspace import influence_table

    rng = np.random.default_rng(7)
    beta = np.exp(rng.uniform(math.log(1e-3), math.log(1e3), 300))
    m = rng.integers(0, 24, 300)
    got = influence_table(24)(np.log(beta))[m, np.arange(300)]
    assert np.max(np.abs(got / strip_influence(m, beta) - 1.0)) < 1e-7
