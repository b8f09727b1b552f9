"""Modal (flexible) rings in the multibody core: conservation and spin of a free modal ring, the static
limit against the full FE model, and a ball rolled around a flexible race.

References: the conservation laws of a free body; the rotating annular disk (S. Timoshenko &
J. N. Goodier, *Theory of Elasticity*, 3rd ed., 1970, §32, plane stress); the full FE model of the
race (K u = f on the DOFs its bolts leave free) under the same ball forces. Ring deflections are
compared on the circle of section centroids: right under a concentrated force the FE mesh adds its own local
indentation, which the reduced basis leaves out on purpose (the Hertz law carries the contact
deformation) — on the centroid circle both see the same structural deflection.
"""

import math

import numpy as np
import pytest

from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from cms_reduction.sampling import interp_index, sample_points, samples_from_arrays
from fem_rings import MeshSpec, Support, build_model
from fem_rings.linalg import factorize_spd
from fem_rings.nodesets import patch_nodes
from fem_rings.probe import vector_probe_matrix
from fem_rings.profile import rectangle
from fem_rings.sections import SlewingSection, slewing_bottom_race
from fem_rings.solve import fixed_dofs, point_load
from mbd_core.contact import ball_on_groove
from foundation.materials import ElasticMaterial
from mbd_core.multibody import ModelBuilder
from mbd_core.multibody.bearings import add_ball_row
from mbd_core.multibody.builder import ContactLaw, Driven, Fixed, Free
from mbd_core.multibody.explicit import evaluate_forces, simulate, stable_timestep
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.quasistatic import BallRow
from tests.reference import modal as ref

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
G = 9.81


# ---------------------------------------------------------------------------- a free modal ring
@pytest.fixture(scope="module")
def free_ring():
    """A 1 m steel ring, 100 × 100 mm section, free–free: 8 modes + its centrifugal stretch shape."""
    return reduced_body(rectangle("ring", 0.45, 0.55, 0.0, 0.1), MeshSpec(0.05, "hex27"), STEEL,
                        ReductionSpec(n_modes=8, centrifugal=True))


def _rotation(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _invariants(a, j=0):
    return (a.modal_mass[j], a.modal_I2[j], a.modal_I3[j], a.modal_I4[j], a.modal_I5[j], a.modal_I6[j],
            a.modal_I7[j], a.modal_I8[j], a.modal_I9[j])


def _momentum_energy(a, q, v, eta, eta_dot):
    """World linear momentum, angular momentum about the world origin and total energy of modal
    body 0 (its frame at the centre of mass), from the numpy twin of M(η): p = M u."""
    R = _rotation(q[3:])
    u = np.concatenate([R.T @ v[:3], v[3:], eta_dot])
    M = ref.mass_matrix(*_invariants(a), eta)
    p = M @ u
    P = R @ p[:3]
    return P, np.cross(q[:3], P) + R @ p[3:6], 0.5 * u @ M @ u + 0.5 * np.sum(a.modal_omega2 * eta**2)


def test_free_modal_ring_conserves_momentum_and_energy(free_ring):
    """Tumbling, translating and vibrating, no loads, 1e5 steps at the automatic step (set by the
    highest mode, hω = 1.6): momenta to round-off; the energy does not drift."""
    rng = np.random.default_rng(60)
    m = free_ring.n_modes
    b = ModelBuilder()
    b.add_modal_body("ring", free_ring, position_m=(0.1, 0.2, 0.3), velocity_m_s=(0.3, -0.2, 0.1),
                     omega_rad_s=(0.5, -0.3, 2.0), motion=Free(), eta=1e-3 * rng.standard_normal(m),
                     eta_dot=0.3 * rng.standard_normal(m))
    model, state = b.finalize()
    a = model.arrays
    h = stable_timestep(model, state).timestep_s
    P0, L0, E0 = _momentum_energy(a, state.q[0], state.v[0], state.eta, state.eta_dot)
    out = simulate(model, state, 1e5 * h, timestep_s=h, record_every=997)
    samples = [_momentum_energy(a, out["q"][k, 0], out["v"][k, 0], out["eta"][k], out["eta_dot"][k])
               for k in range(len(out["t"]))]
    P = np.array([s[0] for s in samples])
    L = np.array([s[1] for s in samples])
    E = np.array([s[2] for s in samples])
    # momentum form of the free frame: exact to round-off by construction (measured 5e-15, 5e-12)
    assert np.abs(P - P0).max() / np.linalg.norm(P0) < 1e-10
    assert np.abs(L - L0).max() / np.linalg.norm(L0) < 1e-10
    # Störmer–Verlet conserves the modified energy E − Σ ½ω²η²(hω/2)² of the modes (exactly for
    # uncoupled linear modes; Hairer, Lubich & Wanner, GNI, §I.5) — it stays within 1e-4 (9e-5
    # measured) and neither it nor the energy drifts (trend over the run 3e-7)
    shadow = E - np.sum(0.5 * a.modal_omega2 * (h * h * a.modal_omega2 / 4) * out["eta"] ** 2, axis=1)
    assert np.abs(shadow - shadow[0]).max() / E0 < 3e-4
    for e in (E, shadow):
        assert abs(np.polyfit(out["t"], e, 1)[0] * out["t"][-1]) / E0 < 1e-4
    # the energy itself oscillates with the top mode (3.4 % at hω = 1.6), bounded
    assert np.abs(E - E0).max() / E0 < 0.1


def test_spinning_ring_keeps_its_centrifugal_stretch(free_ring):
    """Spinning about its axis at 50 rad/s from the static centrifugal solution, the ring stays there
    to round-off; that stretch is the rotating annular disk's (Timoshenko & Goodier §32)."""
    omega = 50.0
    m = free_ring.n_modes
    b = ModelBuilder()
    b.add_modal_body("ring", free_ring, motion=Free())
    a = b.finalize()[0].arrays
    # static modal equilibrium in the rotating frame: ω_k² η_k = ωᵀ G_k(η) ω, ω = Ω e_z
    K = np.diag(a.modal_omega2) - omega**2 * a.modal_I9[0][2, 2].T
    eta_s = np.linalg.solve(K, omega**2 * a.modal_I8[0][2, 2, :m])
    b = ModelBuilder()
    b.add_modal_body("ring", free_ring, omega_rad_s=(0, 0, omega), motion=Free(), eta=eta_s)
    model, state = b.finalize()
    out = simulate(model, state, 0.2, timestep_s=1e-5, record_every=1000)
    assert np.abs(out["eta"] - eta_s).max() <= 1e-12 * np.abs(eta_s).max()
    assert np.abs(out["v"][:, 0, 3:] - [0.0, 0.0, omega]).max() < 1e-12 * omega
    u = free_ring.displacement_m(eta_s)
    x = free_ring.nodes_m
    r = np.hypot(x[:, 0], x[:, 1])
    u_r = (u[:, 0] * x[:, 0] + u[:, 1] * x[:, 1]) / r
    rho, E, nu, r_in, r_out = 7850.0, 200e9, 0.3, 0.45, 0.55
    for radius in (r_in, 0.5, r_out):
        s_r = (3 + nu) / 8 * rho * omega**2 * (r_in**2 + r_out**2 - r_in**2 * r_out**2 / radius**2 - radius**2)
        s_t = (3 + nu) / 8 * rho * omega**2 * (r_in**2 + r_out**2 + r_in**2 * r_out**2 / radius**2
                                               - (1 + 3 * nu) / (3 + nu) * radius**2)
        on = np.abs(r - radius) < 1e-9
        # plane stress vs the 3-D ring of height 0.1 m: 0.03 % measured
        assert u_r[on].mean() == pytest.approx(radius / E * (s_t - nu * s_r), rel=5e-3)
    # undeformed apart from the stretch: every other modal coordinate stays at round-off, and nodes at
    # the same (r, z) move alike (1.1e-5 of the stretch: the revolved mesh's own asymmetry)
    others = np.arange(m) != np.argmax(np.abs(eta_s))
    assert np.abs(out["eta"][:, others]).max() < 1e-10 * np.abs(eta_s).max()  # 4e-12 measured
    keys = np.round(np.column_stack((r, x[:, 2])), 9)
    _, group = np.unique(keys, axis=0, return_inverse=True)
    spread = max(np.ptp(u_r[group.ravel() == k]) for k in range(group.max() + 1))
    assert spread < 1e-4 * np.abs(u_r).max()


# ---------------------------------------------------------------------------- a flexible race
D_BALL, CONFORMITY, ALPHA = 95.25e-3, 0.525, math.radians(60.0)
SUPPORTS_DEG = (45.0, 135.0, 225.0, 315.0)


@pytest.fixture(scope="module")
def race():
    """Bottom race of the 1 m slewing ring, bolted down at 4 patches: 20 modes + 33
    groove load shapes (n ≤ 16), 2 % modal damping; the full FE model, its stiffness on the free
    DOFs factorised once for every static solve of the module, and its centroid circle."""
    profile, mesh = slewing_bottom_race(1.0), MeshSpec(0.04, "hex27", refine={"groove": 0.5})
    groove = SlewingSection().groove("bottom", 1.0)
    body = reduced_body(profile, mesh, STEEL, ReductionSpec(
        n_modes=20, interfaces=(InterfaceSpec("bolt_face", SUPPORTS_DEG, 0.02),),
        raceways=(RacewaySpec("groove", 360, at_rz_m=tuple(groove.contact_point_m), n_max=16),),
        damping_ratio=0.02))
    fe = build_model(profile, mesh, STEEL)
    supports = [Support(patch_nodes(fe.ring, "bolt_face", a, 0.02), name=f"bolt {a:g}") for a in SUPPORTS_DEG]
    free = np.setdiff1d(np.arange(fe.n_dofs), fixed_dofs(supports))
    x = fe.nodes_m
    section = np.abs(np.arctan2(x[:, 1], x[:, 0])) < 1e-6
    r_c, z_c = np.hypot(x[section, 0], x[section, 1]).mean(), x[section, 2].mean()
    th = np.linspace(0.0, 2 * math.pi, 360, endpoint=False)
    circle = np.column_stack((r_c * np.cos(th), r_c * np.sin(th), np.full(th.size, z_c)))
    return dict(body=body, fe=fe, free=free, factor=factorize_spd(fe.K[free][:, free].tocsc()),
                probe=vector_probe_matrix(fe.basis(2), circle),
                modal_probe=sample_points(body, "centroids", circle, th, True).displacement)


def _deflection_error(race, eta, points_m, forces_N):
    """Largest difference of the axial deflection on the centroid circle, reduced model vs full FE
    under the same forces (K u = f on the DOFs the bolts leave free, the factor of the fixture),
    relative to the largest FE deflection."""
    f, free = point_load(race["fe"], points_m, forces_N), race["free"]
    u = np.zeros(race["fe"].n_dofs)
    u[free] = race["factor"].solve(f[free])
    uz_fe = (race["probe"] @ u).reshape(-1, 3)[:, 2]
    uz = (race["modal_probe"] @ eta)[:, 2]
    return np.abs(uz - uz_fe).max() / np.abs(uz_fe).max()


def test_flexible_race_static_limit_matches_the_full_fe_model(race):
    """16 balls pressed by a rigid top race (68.9 t) into the flexible race on 4 bolts: the balls'
    axial loads carry the applied load and the race deflects as the full FE model under them."""
    row = BallRow("balls", 16, D_BALL, 1.0, ALPHA, CONFORMITY, CONFORMITY, "inner", axial_sign=-1,
                  first_azimuth_rad=math.radians(10.0))
    b = ModelBuilder()
    top = b.add_body("top race", 500.0, (100.0, 100.0, 200.0))
    bottom = b.add_modal_body("bottom race", race["body"], motion=Fixed())
    bodies = add_ball_row(b, row, top, bottom, damping_N_s_m=2e4, d_max_m=1e-5, fixed_sample="groove")
    load_N = 68.9e3 * G
    b.add_force(top, (0.0, 0.0, -load_N))
    model, state = b.finalize()
    eq = static_equilibrium(model, state, fixed_azimuth=bodies.elements).state
    fn = evaluate_forces(model, eq).contact_fn[list(bodies.fixed_pairs)]
    # the force of each ball on the race: along the deformed groove normal, at the contact point
    smp = samples_from_arrays(race["body"].extras)["groove"]
    c_rz = np.array([0.5, 0.0]) + (CONFORMITY - 0.5) * D_BALL * np.array([-math.cos(ALPHA), math.sin(ALPHA)])
    points, forces = [], []
    for Q, i in zip(fn, bodies.elements):
        x = eq.q[i, :3]
        th = math.atan2(x[1], x[0]) % (2 * math.pi)
        i0, i1, w0, w1 = interp_index(smp.theta_rad, th, True)
        c = np.array([c_rz[0] * math.cos(th), c_rz[0] * math.sin(th), c_rz[1]])
        p_s = w0 * smp.points_m[i0] + w1 * smp.points_m[i1]
        u = (w0 * smp.displacement[i0] + w1 * smp.displacement[i1]) @ eq.eta
        psi = (w0 * smp.rotation[i0] + w1 * smp.rotation[i1]) @ eq.eta
        n = x - (c + u + np.cross(psi, c - p_s))
        n /= np.linalg.norm(n)
        points.append(x + D_BALL / 2 * n)
        forces.append(Q * n)
    forces = np.array(forces)
    assert forces[:, 2].sum() == pytest.approx(-load_N, rel=1e-3)  # 3e-14 measured
    assert fn.max() / fn.min() > 1.5  # the race bends: loads 33–64 kN (48 kN on rigid races)
    assert _deflection_error(race, eq.eta, np.array(points), forces) < 0.02  # 0.68 % measured


def test_ball_rolled_around_a_flexible_race_carries_its_deflection(race):
    """One ball under a constant 50 kN (57.7 kN along its 60° contact line) goes once round the
    race in 1 s, frictionless, the race's modes integrated implicitly: at 8 angles the race's
    deflection is the full FE model's static response to that ball force there."""
    u = np.array([-math.cos(ALPHA), math.sin(ALPHA)])  # ball centre → fixed groove's curvature centre
    c_f = np.array([0.5, 0.0]) + (CONFORMITY - 0.5) * D_BALL * u
    c_m = np.array([0.5, 0.0]) - (CONFORMITY - 0.5) * D_BALL * u
    k_f = ball_on_groove(D_BALL, CONFORMITY, 1.0, ALPHA, "outer").stiffness_N_per_m1p5
    k_m = ball_on_groove(D_BALL, CONFORMITY, 1.0, ALPHA, "inner").stiffness_N_per_m1p5
    b = ModelBuilder()
    bottom = b.add_modal_body("bottom race", race["body"], motion=Fixed(), implicit_modes=True)
    top = b.add_body("top race", 100.0, (20.0, 20.0, 40.0), motion=Driven(0.0, translation_free=True))
    th0 = math.radians(5.0)
    ball = b.add_body("ball", 3.55, (3.2e-3,) * 3, position_m=(0.5 * math.cos(th0), 0.5 * math.sin(th0), 0.0))
    g_f = b.add_groove(bottom, c_f[0], c_f[1], CONFORMITY * D_BALL, raceway="groove")
    g_m = b.add_groove(top, c_m[0], c_m[1], CONFORMITY * D_BALL)
    b.add_ball_groove(ball, bottom, g_f, D_BALL / 2, ContactLaw(k_f, 1.5, 2e4, 1e-5))
    b.add_ball_groove(ball, top, g_m, D_BALL / 2, ContactLaw(k_m, 1.5, 2e4, 1e-5))
    b.add_bushing(bottom, top, (0.0, 0.0, 0.0), (1e9, 1e9, 0, 0, 0, 0), (2e5, 2e5, 0, 0, 0, 0))
    b.add_force(top, (0.0, 0.0, -50e3))
    model, state = b.finalize()
    start = static_equilibrium(model, state, fixed_azimuth=[ball]).state
    start.v[ball, :3] = math.pi * np.array([-math.sin(th0), math.cos(th0), 0.0])  # 1 turn per second
    out = simulate(model, start, 1.0, record_every=5)
    pos = out["q"][:, ball, :3]
    th = np.unwrap(np.arctan2(pos[:, 1], pos[:, 0]))
    assert th[-1] - th0 > 1.8 * math.pi  # it goes round (slowed a little passing the bolts)
    errors = []
    for k in range(8):
        i = int(np.argmin(np.abs(th - (th0 + math.radians(22.5 + 45.0 * k)))))
        n = np.array([math.cos(ALPHA) * math.cos(th[i]), math.cos(ALPHA) * math.sin(th[i]), -math.sin(ALPHA)])
        force = out["fn"][i, 0] * n
        errors.append(_deflection_error(race, out["eta"][i], (pos[i] + D_BALL / 2 * n)[None], force[None]))
    assert max(errors) < 0.03  # 0.75–1.06 % measured
