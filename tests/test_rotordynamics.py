"""Rotordynamics of 3-D solid rotors reduced to modal bodies, against closed forms and the full model.

References
----------
- Uniform shaft on pinned supports: Timoshenko beam frequency equation for simply supported ends,
  (ρ²I/κG) ω⁴ − (ρA + ρI k² + EIρk²/κG) ω² + EI k⁴ = 0, k = nπ/L (S. Timoshenko, D. H. Young,
  W. Weaver, *Vibration Problems in Engineering*, 4th ed., Wiley 1974, §5.13), shear coefficient of
  a solid circle κ = 6(1 + ν)/(7 + 6ν) (G. R. Cowper, J. Appl. Mech. 33, 1966).
- Disc on a (nearly) massless shaft: the tilt whirl of a rigid disc, I_d ω² ∓ I_p Ω ω − k_θ = 0, so
  ω_f,b = ±(I_p/I_d)Ω/2 + √((I_p Ω/2I_d)² + ω₀²), with ω₀ the tilt frequency at rest and I_p = mR²/2,
  I_d = m(3R² + h²)/12 of a solid cylinder (G. Genta, *Dynamics of Rotating Systems*, Springer 2005,
  §4.5); the translation and the torsion stay at their frequency at rest.
- Rigid rotor on two isotropic radial springs k at z_a, z_b: the cylindrical whirl at √(2k/m),
  unchanged by speed, and the conical whirl I_d ω² ∓ I_p Ω ω − k_θ = 0 with k_θ = k Σ (z_s − z_G)²
  (Genta §3.5).
- Jeffcott rotor with stationary damping: orbit radius ε r²/√((1 − r²)² + (2ζr)²), phase lag
  atan2(2ζr, 1 − r²), ε = U/m, r = Ω/ω_n (Genta §4.4).
- The full FE model's spinning-frame equations, assembled here from its mass matrix directly (not
  through the invariants) and solved by shift-invert on the sparse companion form.
"""

import dataclasses
import math

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem

from fem_rings.assembly import mass_matrix
from fem_rings.mesh import MeshSpec
from fem_rings.model import build_model
from fem_rings.profile import polygon, rectangle
from fem_rings.spinning import centrifugal_geometric_stiffness
from foundation.materials import BEARING_STEEL as STEEL
from mbd_core.rotordynamics import (BearingSpring, campbell, held_dofs, isotropic_bearing, on_bearings, seat_basis,
                                    spinning_body_of_model, statically_determinate_holds, supported_modes,
                                    unbalance_response)

A_SHAFT, R_DISC, H_DISC, L_SHAFT = 0.01, 0.06, 0.03, 0.3
SHAFT_DENSITY_SHARE = 1e-4  # the "massless" shaft of the Jeffcott rotor


def _pinned(model):
    """Lateral DOFs of both end faces held, z at the centre of the bottom face (holds, held DOFs)."""
    x = model.nodes_m
    bot, top = model.node_set("bottom"), model.node_set("top")
    centre = bot[np.argmin(np.hypot(x[bot, 0], x[bot, 1]))]
    holds = [(bot, "xy"), (top, "xy"), ([centre], "z")]
    return holds, held_dofs(len(x), holds)


def _jeffcott(size_m):
    """A steel disc (R 60 mm, h 30 mm) at mid-span of a 300 mm, Ø20 mm shaft of negligible mass,
    pinned at both ends; 12 modes on the supports. (model, held DOFs, frequencies, shapes, body)"""
    z0, z1 = L_SHAFT / 2 - H_DISC / 2, L_SHAFT / 2 + H_DISC / 2
    profile = polygon("jeffcott", [(0, 0), (A_SHAFT, 0), (A_SHAFT, z0), (R_DISC, z0), (R_DISC, z1), (A_SHAFT, z1),
                                   (A_SHAFT, L_SHAFT), (0, L_SHAFT)],
                      ["bottom", "shaft", "disc_left", "disc_rim", "disc_right", "shaft2", "top", "axis"])
    model = build_model(profile, MeshSpec(size_m=size_m, refine={"shaft": 0.5, "shaft2": 0.5}), STEEL,
                        use_cache=False)
    mesh = model.mesh
    zc = mesh.p[2][mesh.t[:4]].mean(axis=0)
    density = np.full(mesh.t.shape[1], STEEL.density_kg_m3 * SHAFT_DENSITY_SHARE)
    density[(zc > z0) & (zc < z1)] = STEEL.density_kg_m3
    M = sum(mass_matrix(skfem.CellBasis(mesh, mesh.elem(), elements=np.flatnonzero(density == rho),
                                        intorder=model.intorder[1]), rho) for rho in np.unique(density))
    model = dataclasses.replace(model, M=M.tocsr())
    holds, held = _pinned(model)
    f, phi = supported_modes(model, holds, 12)
    body = spinning_body_of_model(model, phi, f, held, density)
    return model, held, f, phi, body


@pytest.fixture(scope="module")
def jeffcott():
    return _jeffcott(0.01)


def _disc_inertia():
    m = STEEL.density_kg_m3 * math.pi * R_DISC ** 2 * H_DISC
    return m, m * R_DISC ** 2 / 2, m * (3 * R_DISC ** 2 + H_DISC ** 2) / 12


def test_uniform_shaft_on_pinned_supports_matches_timoshenko():
    R, L = 0.02, 0.4
    model = build_model(rectangle("shaft", 0.0, R, 0.0, L), MeshSpec(size_m=0.01), STEEL, use_cache=False)
    f, _ = supported_modes(model, _pinned(model)[0], 4)
    E, nu, rho = STEEL.E_Pa, STEEL.nu, STEEL.density_kg_m3
    G, A, I = E / (2 * (1 + nu)), math.pi * R * R, math.pi * R ** 4 / 4
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    expected = []
    for n in (1, 2):
        k = n * math.pi / L
        a, b, c = rho * rho * I / (kappa * G), -(rho * A + rho * I * k * k + E * I * rho * k * k / (kappa * G)), E * I * k ** 4
        expected.append(math.sqrt((-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)) / (2 * math.pi))
    # each bending frequency is a pair (x and y); measured 0.04 % and 0.13 % at this mesh
    assert f[0] == pytest.approx(expected[0], rel=0.01) and f[1] == pytest.approx(expected[0], rel=0.01)
    assert f[2] == pytest.approx(expected[1], rel=0.01) and f[3] == pytest.approx(expected[1], rel=0.01)


def test_disc_whirl_forward_and_backward_match_the_gyroscopic_disc(jeffcott):
    _, _, f, _, body = jeffcott
    m, Ip, Id = _disc_inertia()
    speeds = np.array([0.0, 1000.0, 3000.0, 6000.0])  # rad/s (to 57 000 rev/min)
    cd = campbell(body, speeds, 6)
    # at rest: translation pair, torsion, tilt pair, axial; find the tilt pair by its frequency
    f_tilt0 = cd.fixed_Hz[0, 3]
    assert cd.fixed_Hz[0, 4] == pytest.approx(f_tilt0, rel=1e-3)
    w0 = 2 * math.pi * f_tilt0
    for i, W in enumerate(speeds[1:], start=1):
        b = Ip / Id * W / 2
        fwd, bwd = (math.sqrt(b * b + w0 * w0) + b) / (2 * math.pi), (math.sqrt(b * b + w0 * w0) - b) / (2 * math.pi)
        tilt = {w: h for w, h in zip(cd.whirl[i], cd.fixed_Hz[i]) if abs(h - f_tilt0) > 0.05 * f_tilt0 and w != 0}
        assert tilt[1] == pytest.approx(fwd, rel=0.01), (W, tilt, fwd)     # measured ≤ 0.05 %
        assert tilt[-1] == pytest.approx(bwd, rel=0.01), (W, tilt, bwd)
        # the translation pair (one forward, one backward) and the torsion (n = 0) do not move
        trans = sorted(h for w, h in zip(cd.whirl[i], cd.fixed_Hz[i]) if abs(h - cd.fixed_Hz[0, 0]) < 0.01 * h)
        assert len(trans) == 2 and trans == pytest.approx([cd.fixed_Hz[0, 0]] * 2, rel=1e-3)
        standing = cd.fixed_Hz[i][np.round(cd.order[i]) == 0]
        assert np.min(np.abs(standing / cd.fixed_Hz[0, 2] - 1)) < 1e-4
    assert np.all(np.abs(cd.order[1:] - np.round(cd.order[1:])) < 1e-3)


def test_jeffcott_unbalance_response_across_the_critical_speed(jeffcott):
    model, _, f, phi, body = jeffcott
    m, _, _ = _disc_inertia()
    rim = model.node_set("disc_rim")
    wn, zeta, U = 2 * math.pi * f[0], 0.05, 1e-5       # 10 g·mm
    r = np.array([0.5, 0.9, 1.0, 1.1, 1.5, 3.0])
    res = unbalance_response(body, phi, U, rim, rim, r * wn, stationary_damping_per_s=2 * zeta * wn)
    eps = U / m
    radius = eps * r * r / np.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2)
    lag = np.arctan2(2 * zeta * r, 1 - r * r)
    np.testing.assert_allclose(res.radius_m, radius, rtol=0.02)        # measured ≤ 0.35 %
    np.testing.assert_allclose(res.phase_lag_rad, lag, atol=math.radians(2.0))


def _full_spinning_modes(model, held, speed, near_Hz, k=4):
    """Spinning-frame eigenvalues of the full model near ``near_Hz``: M ü + Ω G u̇ + (K + Ω²(K_σ − P)) u = 0
    with G and P assembled from the consistent mass directly."""
    n = model.n_dofs
    free = np.setdiff1d(np.arange(n), held)
    Ms = model.M.tocsr()[0::3, 0::3]
    cross = sp.csr_matrix(([1.0, -1.0], ([1, 0], [0, 1])), shape=(3, 3))   # e_i·(ẑ × e_j)
    inplane = sp.csr_matrix(([1.0, 1.0], ([0, 1], [0, 1])), shape=(3, 3))
    G = 2.0 * sp.kron(Ms, cross.T)      # G[k, l] = 2 ∫ρ e_l·... : Coriolis 2Ω ẑ × u̇ on the left
    P = sp.kron(Ms, inplane)
    Ks, _ = centrifugal_geometric_stiffness(model, held)
    Kt = model.K + speed ** 2 * (Ks - P)
    sub = lambda A: A.tocsr()[free][:, free].tocsc()
    K, M, C = sub(Kt), sub(model.M), sub(speed * G)
    m = len(free)
    sigma = 1j * 2 * math.pi * near_Hz
    # shift-invert of the companion form A z = λ B z, z = (x, λx), A = [[0, I], [−K, −C]], B = diag(I, M),
    # through Q(σ) = σ²M + σC + K: (A − σB)⁻¹(b₁, b₂) = (x, b₁ + σx) with Q(σ) x = −b₂ − (C + σM) b₁
    lu = spla.splu((sigma * sigma * M + sigma * C + K).astype(complex).tocsc(), permc_spec="MMD_AT_PLUS_A")
    CM = (C + sigma * M).astype(complex)

    def apply(z):
        b1, b2 = z[:m], M @ z[m:]
        x = -lu.solve(b2 + CM @ b1)
        return np.concatenate([x, b1 + sigma * x])

    mu = spla.eigs(spla.LinearOperator((2 * m, 2 * m), matvec=apply, dtype=complex), k=k, which="LM",
                   return_eigenvectors=False)      # μ = 1/(λ − σ)
    lam = sigma + 1.0 / mu
    return np.sort(np.abs(lam.imag[lam.imag > 0])) / (2 * math.pi)


def test_reduced_rotor_matches_the_full_model_at_two_speeds():
    model, held, _, _, body = _jeffcott(0.025)   # coarse: the full eigenproblem stays small
    for speed in (2000.0, 6000.0):
        cd = campbell(body, [speed])
        tilt = cd.spinning_Hz[0][np.abs(cd.order[0]) > 0.5]
        for f_red in tilt[2:4]:     # the tilt pair (the two lowest lateral ones are the translation)
            full = _full_spinning_modes(model, held, speed, f_red, k=2)
            assert np.min(np.abs(full - f_red)) / f_red < 1e-3, (speed, f_red, full)


def test_rigid_rotor_on_springs_whirls_as_the_closed_form():
    """A steel cylinder (R 50 mm, L 200 mm: first free bending far above) on two radial springs of
    1 MN/m at 10 mm seats at its ends, reduced by Craig–Bampton at the seats."""
    R, L, k = 0.05, 0.2, 1e6
    profile = polygon("roll", [(0, 0), (R, 0), (R, 0.01), (R, 0.19), (R, L), (0, L)],
                      ["end_a", "seat_a", "outer", "seat_b", "end_b", "axis"])
    model = build_model(profile, MeshSpec(size_m=0.02), STEEL, use_cache=False)
    seats = [model.node_set("seat_a"), model.node_set("seat_b")]
    f, phi = seat_basis(model, seats, 6)
    assert np.sum(f < 1.0) == 6                                # the free rotor's rigid motions
    body = spinning_body_of_model(model, phi, f, statically_determinate_holds(model))
    body = on_bearings(body, phi, model.nodes_m, [(s, BearingSpring(k)) for s in seats])
    m = STEEL.density_kg_m3 * math.pi * R * R * L
    Ip, Id = m * R * R / 2, m * (3 * R * R + L * L) / 12
    z = np.array([model.nodes_m[s, 2].mean() for s in seats])
    k_theta = k * np.sum((z - L / 2) ** 2)
    w_cyl, w0 = math.sqrt(2 * k / m), math.sqrt(k_theta / Id)
    speeds = np.array([500.0, 1500.0, 3000.0])
    cd = campbell(body, speeds, 8)     # the axial and torsional rigid motions, unsupported, stay at 0 Hz
    for i, W in enumerate(speeds):
        b = Ip / Id * W / 2
        expected = {(1, "cyl"): w_cyl, (-1, "cyl"): w_cyl, (1, "con"): b + math.sqrt(b * b + w0 * w0),
                    (-1, "con"): math.sqrt(b * b + w0 * w0) - b}
        got = 2 * math.pi * cd.fixed_Hz[i]
        for (whirl, kind), w in expected.items():
            pick = (cd.whirl[i] == whirl) & (cd.fixed_Hz[i] > 1.0)
            assert np.min(np.abs(got[pick] / w - 1)) < 0.01, (W, whirl, kind, got, w)   # measured ≤ 0.02 %
    # with tilt stiffness and radial–tilt coupling at the seats (mirrored at the second, as a back-to-
    # back pair): against the rigid rotor's fixed-frame equations on (x, y, θx, θy) about its centre,
    # assembled and solved here (seat displacement x + a θy and y − a θx, a = z_s − z_G; gyroscopic
    # coupling I_p Ω between the tilts)
    springs = [BearingSpring(k, 2e3, 2e4), BearingSpring(k, 2e3, 2e4).mirrored()]
    body2 = spinning_body_of_model(model, phi, f, statically_determinate_holds(model))
    body2 = on_bearings(body2, phi, model.nodes_m, list(zip(seats, springs)))
    Kl = np.zeros((4, 4))
    for zs, sp_ in zip(z, springs):
        a = zs - L / 2
        T = np.array([[1, 0, 0, a], [0, 1, -a, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])   # (x, y, θx, θy) → seat
        Kl += T.T @ sp_.matrices()[0] @ T
    Ml = np.diag([m, m, Id, Id])
    for W in speeds:
        Gl = np.zeros((4, 4))
        Gl[2, 3], Gl[3, 2] = Ip * W, -Ip * W
        A = np.block([[np.zeros((4, 4)), np.eye(4)], [-np.linalg.solve(Ml, Kl), -np.linalg.solve(Ml, Gl)]])
        lam = np.linalg.eigvals(A)
        expected = np.sort(lam.imag[lam.imag > 0]) / (2 * math.pi)
        got = campbell(body2, [W], 8).fixed_Hz[0]
        np.testing.assert_allclose(np.sort(got[got > 1.0])[:4], expected, rtol=0.01)   # measured ≤ 0.02 %
    # the isotropic part of a 5 × 5 stiffness: an axially preloaded row is isotropic
    K5 = np.diag([2e7, 2e7, 5e7, 300.0, 300.0])
    K5[0, 4] = K5[4, 0] = 1e4
    K5[1, 3] = K5[3, 1] = -1e4
    spring, left_out = isotropic_bearing(K5)
    assert (spring.k_r_N_m, spring.k_theta_Nm_rad, spring.k_rtheta_N_rad, left_out) == (2e7, 300.0, 1e4, 0.0)
