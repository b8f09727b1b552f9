"""Modal-body kernels (mbd_core.kernels.modal) against their numpy twin on seeded random invariants and
corner states, and against the mechanics of a free FE ring: kinetic energy of the nodal velocities,
power balance of the quadratic-velocity vector and Kirchhoff's equations in body axes."""

import numpy as np
import pytest

from cms_reduction.invariants import compute_invariants
from fem_rings import MeshSpec, build_model, modal_analysis
from fem_rings.profile import rectangle
from mbd_core.kernels.modal import modal_mass_matrix, modal_velocity_terms
from foundation.materials import ElasticMaterial
from tests.reference import modal as ref

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
PROFILE = rectangle("ring", 0.95, 1.05, -0.05, 0.05)
# Body-frame origin off the ring centre, so the first moment S and the off-centre inertia are large.
ORIGIN_M = np.array([0.3, -0.2, 0.1])


def _random_invariants(rng, m):
    """Invariant-shaped arrays. Only the symmetries that make M(η) symmetric are imposed (I6, I7
    symmetric, I9_ijkl = I9_jilk); I3, I4, I5, I8 are fully random so an index swap shows."""
    I7 = rng.standard_normal((3, 3))
    I6 = rng.standard_normal((m, m))
    I9 = rng.standard_normal((3, 3, m, m))
    return (
        rng.uniform(0.5, 2.0), rng.standard_normal(3), rng.standard_normal((3, m)),
        rng.standard_normal((3, m)), rng.standard_normal((3, m, m)), I6 + I6.T, I7 + I7.T,
        rng.standard_normal((3, 3, m)), I9 + I9.transpose(1, 0, 3, 2),
    )


def _kernel(args, eta, v=None, omega=None, eta_dot=None):
    n = 6 + len(eta)
    M = modal_mass_matrix(*args, eta, np.full((n, n), np.nan))
    if v is None:
        return M
    return M, modal_velocity_terms(*args, eta, v, omega, eta_dot, np.full(n, np.nan))


def _assert_close(actual, desired):
    # rtol 1e-12; the absolute floor covers entries that cancel to ~0 (sums of O(max) terms).
    np.testing.assert_allclose(actual, desired, rtol=1e-12, atol=1e-13 * np.abs(desired).max())


@pytest.mark.parametrize("m", [1, 2, 5])
def test_kernels_match_numpy_twin_on_random_invariants(m):
    rng = np.random.default_rng(8100 + m)
    for trial in range(20):
        args = _random_invariants(rng, m)
        eta, eta_dot = rng.standard_normal(m), rng.standard_normal(m)
        v, omega = rng.standard_normal(3), rng.standard_normal(3)
        eta *= rng.choice([1e-3, 1.0, 30.0])
        M, h = _kernel(args, eta, v, omega, eta_dot)
        _assert_close(M, ref.mass_matrix(*args, eta))
        _assert_close(h, ref.velocity_terms(*args, eta, v, omega, eta_dot))
        np.testing.assert_array_equal(M, M.T)


def test_kernels_match_numpy_twin_at_corner_states():
    rng = np.random.default_rng(8200)
    m = 4
    args = _random_invariants(rng, m)
    mass, I2, I3, I4, I5, I6, I7 = args[:7]
    zero3, zerom = np.zeros(3), np.zeros(m)
    eta, eta_dot = rng.standard_normal(m), rng.standard_normal(m)
    v, omega = rng.standard_normal(3), rng.standard_normal(3)
    cases = [
        (zerom, v, omega, eta_dot), (eta, v, omega, zerom), (zerom, v, omega, zerom),
        (eta, v, zero3, eta_dot), (eta, zero3, omega, zerom), (zerom, zero3, zero3, zerom),
    ]
    for e, vv, w, ed in cases:
        M, h = _kernel(args, e, vv, w, ed)
        _assert_close(M, ref.mass_matrix(*args, e))
        np.testing.assert_allclose(h, ref.velocity_terms(*args, e, vv, w, ed), rtol=1e-12,
                                   atol=1e-13 * (1.0 + np.abs(h).max()))
    # Exact structure: at η = 0 the blocks are the invariants themselves ...
    M = _kernel(args, zerom)
    np.testing.assert_array_equal(M[3:6, 3:6], I7)
    np.testing.assert_array_equal(M[3:6, 6:], I4)
    np.testing.assert_array_equal(M[:3, 6:], I3)
    np.testing.assert_array_equal(M[6:, 6:], I6)
    np.testing.assert_array_equal(M[:3, :3], mass * np.eye(3))
    np.testing.assert_array_equal(M[3:6, :3], ref.skew(I2))
    # ... and every term of h carries ω, so h = 0 without rotation whatever v, η, η̇.
    _, h = _kernel(args, eta, v, zero3, eta_dot)
    np.testing.assert_array_equal(h, 0.0)


@pytest.fixture(scope="module")
def ring():
    """Free hex27 ring R = 1 m, 100 × 100 mm section, 16 layers; all 12 modes (6 rigid), so I3 and
    I4 do not vanish; invariants about ORIGIN_M."""
    model = build_model(PROFILE, MeshSpec(0.05, "hex27", n_theta=16), STEEL, use_cache=False)
    modes = modal_analysis(model, 12)
    nodes = model.nodes_m - ORIGIN_M
    inv = compute_invariants(model.M, nodes, modes.shapes)
    args = (inv.I1,) + tuple(np.ascontiguousarray(a) for a in
                             (inv.I2, inv.I3, inv.I4, inv.I5, inv.I6, inv.I7, inv.I8, inv.I9))
    return model.M, nodes, modes.shapes, args


def _states(ring, n, seed):
    """Random (v, ω, η, η̇): v, ω ~ 1 m/s, 1 rad/s (the ring radius is 1 m); η with a peak nodal
    displacement of 50 mm, so the η-dependent terms of M matter at 1e-10; η̇ with a peak nodal
    velocity of 1 m/s."""
    _, _, phi, _ = ring
    rng = np.random.default_rng(seed)
    for _ in range(n):
        eta, eta_dot = rng.standard_normal((2, phi.shape[1]))
        eta *= 0.05 / np.abs(phi @ eta).max()
        eta_dot *= 1.0 / np.abs(phi @ eta_dot).max()
        yield rng.standard_normal(3), rng.standard_normal(3), eta, eta_dot


def _mass_rate(args, eta, eta_dot, delta=1.0):
    """Ṁ = Σ_k ∂M/∂η_k η̇_k as the central difference (M(η + δη̇) − M(η − δη̇))/2δ. M is quadratic in
    η, so the difference is exact up to rounding, ~ eps |M| / δ; δ = 1 keeps that at 1e-16 |M|."""
    return (_kernel(args, eta + delta * eta_dot) - _kernel(args, eta - delta * eta_dot)) / (2 * delta)


def test_kinetic_energy_equals_fe_kinetic_energy(ring):
    # Reference: T = ½ ṗᵀ M_FE ṗ of the nodal body-frame velocities ṗ = v + ω × (x̄ + Φη) + Φη̇,
    # exact for the FE fields (ω × u is pointwise linear in u). Equal quadratic forms for all u
    # mean equal matrices, so M(η) = Bᵀ M_FE B with B = ∂ṗ/∂u is checked too.
    M_fe, x, phi, args = ring
    n = len(x)
    worst = 0.0
    for v, omega, eta, eta_dot in _states(ring, 10, 8300):
        u = np.concatenate([v, omega, eta_dot])
        pos = x + (phi @ eta).reshape(n, 3)
        pdot = (v + np.cross(omega, pos) + (phi @ eta_dot).reshape(n, 3)).ravel()
        t_fe = 0.5 * pdot @ (M_fe @ pdot)
        M = _kernel(args, eta)
        t = 0.5 * u @ M @ u
        assert t == pytest.approx(t_fe, rel=1e-10)
        worst = max(worst, abs(t - t_fe) / t_fe)
        B = np.zeros((3 * n, 6 + len(eta)))
        for c in range(3):
            B[c::3, c] = 1.0
        B[0::3, 4], B[0::3, 5] = pos[:, 2], -pos[:, 1]           # ω × p = −p̃ ω
        B[1::3, 3], B[1::3, 5] = -pos[:, 2], pos[:, 0]
        B[2::3, 3], B[2::3, 4] = pos[:, 1], -pos[:, 0]
        B[:, 6:] = phi
        np.testing.assert_allclose(M, B.T @ (M_fe @ B), rtol=0, atol=1e-10 * np.abs(M).max())
    print(f"max relative kinetic-energy error {worst:.1e}")


def test_power_of_velocity_terms_balances_mass_matrix_rate(ring):
    # Free body: M u̇ + h = 0 and dT/dt = 0 with T = ½ uᵀ M u, so uᵀ h = ½ uᵀ Ṁ u. Both sides are
    # sums of O(|u|² |M|-sized) terms that partly cancel (the S̃ terms of h_v and h_ω cancel exactly);
    # tolerance 1e-10 of Σ|u_i||h_i|, well above rounding and the exact-for-quadratics difference.
    _, _, _, args = ring
    worst = 0.0
    for v, omega, eta, eta_dot in _states(ring, 10, 8400):
        u = np.concatenate([v, omega, eta_dot])
        _, h = _kernel(args, eta, v, omega, eta_dot)
        power, rate = u @ h, 0.5 * u @ _mass_rate(args, eta, eta_dot) @ u
        scale = np.abs(u) @ np.abs(h)
        assert abs(power - rate) <= 1e-10 * scale
        assert abs(rate) > 1e-6 * scale        # the balance is not 0 = 0, by 4 orders of magnitude
        worst = max(worst, abs(power - rate) / scale)
    print(f"max |uᵀh − ½uᵀṀu| / Σ|u||h| = {worst:.1e}")


def test_velocity_terms_follow_kirchhoff_equations(ring):
    # The power balance cannot see power-free (gyroscopic) terms such as ω̃Jω or the I5 term of h_η.
    # Kirchhoff's equations of T(η, u) in body axes give all of h from M alone (Lamb, Hydrodynamics,
    # §124; Schwertassek & Wallrapp 1999): with p = M u = (p_v, p_ω, p_η),
    #   h = Ṁ u + (ω × p_v, ω × p_ω + v × p_v, −∂T/∂η),   ∂T/∂η_k = ½ uᵀ (∂M/∂η_k) u,
    # ∂M/∂η_k by the same exact-for-quadratics central difference.
    _, _, _, args = ring
    worst = 0.0
    for v, omega, eta, eta_dot in _states(ring, 6, 8500):
        m = len(eta)
        u = np.concatenate([v, omega, eta_dot])
        M, h = _kernel(args, eta, v, omega, eta_dot)
        p = M @ u
        dT = np.array([0.5 * u @ _mass_rate(args, eta, e) @ u for e in np.eye(m)])
        kirchhoff = _mass_rate(args, eta, eta_dot) @ u + np.concatenate(
            [np.cross(omega, p[:3]), np.cross(omega, p[3:6]) + np.cross(v, p[:3]), -dT])
        np.testing.assert_allclose(h, kirchhoff, rtol=0, atol=1e-10 * np.abs(h).max())
        worst = max(worst, np.abs(h - kirchhoff).max() / np.abs(h).max())
    print(f"max |h − Kirchhoff| / max|h| = {worst:.1e}")
