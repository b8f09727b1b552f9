"""Shared tolerances and comparisons of the multibody kernel tests against their numpy twins
(tests/test_kernels_multibody.py, tests/test_kernels_elements.py; tolerances explained there)."""

import numpy as np
from scipy.spatial.transform import Rotation

RTOL = 1e-12
ATOL_M = 1e-16                            # absolute floor on penetrations and points, m
POINT_ATOL_M, NORMAL_ATOL = 1e-12, 1e-12  # contact points (m) and normals against the twin
SEED = 20260311


def close(got, want, rtol=RTOL, atol=0.0):
    """|got − want| ≤ atol + rtol |want| elementwise (atol may be an array broadcast against want)."""
    got, want = np.asarray(got, float), np.asarray(want, float)
    err = np.abs(got - want) - (atol + rtol * np.abs(want))
    assert got.shape == want.shape and np.all(err <= 0), (
        f"worst excess {err.max():.3g} at {np.unravel_index(np.argmax(err), err.shape)}:\n{got}\n!=\n{want}")


def close_scaled(got, want, rtol=RTOL):
    """rtol on each entry plus a floor of rtol × the largest |entry| (sums of terms of both signs)."""
    want = np.asarray(want, float)
    np.testing.assert_allclose(got, want, rtol=rtol, atol=rtol * max(np.max(np.abs(want)), 1e-300))


def random_quat(rng):
    return Rotation.random(random_state=rng).as_quat(scalar_first=True)
