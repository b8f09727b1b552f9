"""Rigid-rotation kernels against their numpy twin and the invariants of the free rigid body."""

import math

import numpy as np
import pytest

from mbd_core.kernels.rigid import free_rotation_step, quat_rotate
from tests.reference.rigid_rotation import free_rotation_step as twin_step
from tests.reference.rigid_rotation import quat_to_matrix

RNG = np.random.default_rng(7)
INERTIA = np.array([1.0, 2.5, 4.0])   # kg·m², an asymmetric top (unstable middle axis)


def _random_quat():
    q = RNG.normal(size=4)
    return q / np.linalg.norm(q)


def test_quat_rotate_matches_rotation_matrix():
    for _ in range(50):
        q, v, out = _random_quat(), RNG.normal(size=3), np.empty(3)
        quat_rotate(q, v, out)
        assert out == pytest.approx(quat_to_matrix(q) @ v, rel=1e-12, abs=1e-14)


def test_step_matches_twin_including_corner_states():
    states = [(_random_quat(), RNG.normal(size=3) * 10, RNG.uniform(1e-4, 0.1)) for _ in range(40)]
    states += [(np.array([1.0, 0, 0, 0]), np.zeros(3), 1e-3),             # at rest
               (np.array([1.0, 0, 0, 0]), np.array([0, 0, 5.0]), 1e-3),   # spin about a principal axis
               (np.array([0.0, 0, 0, 1.0]), np.array([1e-12, 3.0, 0]), 0.2)]
    for q0, pi0, h in states:
        q, pi = q0.copy(), pi0.copy()
        free_rotation_step(q, pi, INERTIA, h)
        R, p = twin_step(quat_to_matrix(q0), pi0, INERTIA, h)
        assert quat_to_matrix(q) == pytest.approx(R, rel=1e-12, abs=1e-13)
        assert pi == pytest.approx(p, rel=1e-12, abs=1e-13)


def _run(q, pi, h, n):
    energies, L = [], []
    for _ in range(n):
        free_rotation_step(q, pi, INERTIA, h)
        energies.append(0.5 * np.sum(pi**2 / INERTIA))
        L.append(quat_to_matrix(q) @ pi)
    return np.array(energies), np.array(L)


def test_free_asymmetric_top_conserves_momentum_and_energy_without_drift():
    # Invariants of the torque-free body (Euler): inertial angular momentum exactly, |π| exactly,
    # energy to a bounded O(h²) error that does not grow (symplectic splitting). 1e5 steps near
    # the unstable middle axis, ω ≈ 2 rad/s, h = 1 ms.
    q = np.array([1.0, 0.0, 0.0, 0.0])
    pi = np.array([0.05, 5.0, 0.05])
    E0, L0 = 0.5 * np.sum(pi**2 / INERTIA), pi.copy()
    E, L = _run(q, pi, 1e-3, 100_000)
    assert np.max(np.abs(L - L0)) < 1e-10 * np.linalg.norm(L0)
    assert abs(np.linalg.norm(pi) - np.linalg.norm(L0)) < 1e-12 * np.linalg.norm(L0)
    dev = np.abs(E / E0 - 1)
    assert dev.max() < 1e-4
    assert dev[-10_000:].max() < 2 * dev[:10_000].max() + 1e-12     # no drift
    assert abs(np.linalg.norm(q) - 1) < 1e-14


def test_second_order_convergence_under_step_halving():
    # Trajectory at T = 1 s with h, h/2, h/4: the error of the orientation against a fine
    # reference (h/64) falls by 4 per halving (second order).
    def attitude(h):
        q = np.array([1.0, 0.0, 0.0, 0.0])
        pi = np.array([0.4, 3.0, 1.0])
        for _ in range(int(round(1.0 / h))):
            free_rotation_step(q, pi, INERTIA, h)
        return quat_to_matrix(q)

    ref = attitude(1e-2 / 64)
    errs = [np.linalg.norm(attitude(1e-2 / 2**k) - ref) for k in range(3)]
    rates = [math.log2(errs[k] / errs[k + 1]) for k in range(2)]
    assert all(1.9 < r < 2.1 for r in rates), rates
