"""Roller slices, roller ends and cage pockets on modal bodies (mbd_core.kernels.forces): the force stage
against its numpy twin (tests/reference/multibody.py), work consistency, and two static scenes against
the full FE model.

Synthetic scenes: a modal ring and a modal cage built from clouds of 30 point masses with random mode
shapes (mass-normalised, through cms_reduction.invariants.compute_invariants) and random sample tables
D (m/√kg) and Ω (20 rad/√kg per unit) on the sampled surfaces — a cylinder on three circles across it
(full circle of 24 angles, θ_0 = 0 so that a roller at θ = 0 sits on a sample), a plane on three circles
sampled on the arc 0.5…2.5 rad only (a roller inside it and one beyond it, where the fields are held),
a rib plane on two circles — and on the two walls of each pocket. Rollers are longer than the span of
the circles, so their end slices take the end circle's fields (held in s).

Tolerances, kernel against twin, as in test_kernels_multibody and test_kernels_modal_step: rtol 1e-12;
penetrations 1e-16 m (coordinates of ~0.1 m; a roller end's rim 8 ε ρ/sin(γ/2), 5e-16 m, γ its lean from
the rib, as in test_kernels_multibody); each normal force n K δⁿ⁻¹ × that more, in the floors
of the body forces (with 1e-12 × Σ|terms|), moments (levers < 0.2 m) and modal forces (per unit force
|D| + 0.05 m × |Ω|: levers p − p_s below 5 cm).

Explicit runs (a ball bouncing off a pocket wall of an undamped modal cage, a roller off a modal ring's
raceway) keep the total energy — element, modes and contact — as velocity Verlet does.

Static scenes (references: the full FE model, fem_rings.static_solve, under the same contact forces at
the same points). Ring and cage deflections are compared on circles in the material away from the
loaded contact: right under a concentrated force the FE mesh adds its own local indentation, which the
reduced basis leaves out on purpose (the contact law carries the contact deformation), as in
test_modal_dynamics.
"""

import math

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.spatial.transform import Rotation

from cms_reduction.body import ReducedBody
from cms_reduction.invariants import compute_invariants
from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from cms_reduction.sampling import RacewaySample, sample_points, samples_from_arrays
from fem_rings import MeshSpec, Support, build_model, static_solve
from fem_rings.cages import ball_cage
from fem_rings.nodesets import patch_nodes
from fem_rings.probe import vector_probe_matrix
from fem_rings.profile import rectangle
from fem_rings.solve import point_load
from mbd_core.contact.friction import Coulomb
from mbd_core.contact.line import iso16281_stiffness, slice_stiffness
from mbd_core.kernels import forces as FK
from foundation.materials import ElasticMaterial
from mbd_core.multibody import ContactLaw, Driven, Fixed, ModelBuilder
from mbd_core.multibody.explicit import evaluate_forces, simulate
from mbd_core.multibody.model import make_work
from mbd_core.multibody.statics import static_equilibrium
from tests.reference import multibody as ref

RTOL = 1e-12
ATOL_M = 1e-16
POINT_ATOL_M, NORMAL_ATOL = 1e-12, 1e-12  # contact points (m) and normals against the twin
EPS = np.finfo(float).eps
LEVER_M = 0.05
SEED = 20260517
STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)

# binary-exact geometry of the synthetic ring (m)
R_RACE = 2.0**-4                        # cylinder raceway (roller outside it)
R_ROLLER, L_ROLLER = 2.0**-7, 0.02
CYL_S = (-6e-3, 0.0, 6e-3)              # z of the cylinder's circles: the rollers' end slices lie beyond
Z_PLANE, PLANE_S = -0.02, (0.05, 0.06, 0.07)
Z_RIB, RIB_S = 0.01, (0.064, 0.068)
EDGE_M = 1e-3
RIB_TILT = 0.02                         # rad
N_THETA = 24
DELTA_0 = 2e-5                          # nominal penetration of the rigid geometry, m
ARC = (0.5, 2.5)                        # rad, the plane's sampled arc
# cage pockets
R_POCKET, Z_POCKET, CLEAR = 0.07, 0.03, 2.0**-12
R_BALL = 2.0**-8
POCKET_ANGLES = (0.3, 2.0, 4.0)         # ball (touching a wall), roller (slot), ball (touching the axial side)


# -- synthetic modal bodies ------------------------------------------------------------------------------------
def _cloud_body(rng, freqs_hz, radius, zeta=0.02, n_points=30):
    """A ReducedBody of point masses (0.3 kg in all) near a circle of ``radius``, random mass-normalised modes."""
    n, m = n_points, len(freqs_hz)
    th = 2 * np.pi * np.arange(n) / n + rng.uniform(-0.05, 0.05, n)
    r = radius + rng.uniform(-5e-3, 5e-3, n)
    x = np.column_stack((r * np.cos(th), r * np.sin(th), rng.uniform(-5e-3, 5e-3, n)))
    w = rng.uniform(0.5, 1.5, n) * 0.3 / n
    phi = rng.standard_normal((3 * n, m))
    gram = phi.T @ (np.repeat(w, 3)[:, None] * phi)
    phi = phi @ np.linalg.inv(np.linalg.cholesky(gram)).T
    inv = compute_invariants(sp.diags(w), x, phi)
    return ReducedBody("cloud", x, phi, np.asarray(freqs_hz, float), np.full(m, zeta), False, "hex27",
                       np.zeros((3, n)), np.zeros((27, 0), dtype=np.int64), extras=inv.to_arrays())


def _circles(rng, m, name, coords, point, periodic=True):
    """One RacewaySample per coordinate s: ``point(θ, s)`` on N_THETA angles (full circle, or the arc)."""
    th = 2 * np.pi * np.arange(N_THETA) / N_THETA if periodic else np.linspace(*ARC, N_THETA)
    return [RacewaySample(f"{name}@s{k}", th, np.array([point(t, s) for t in th]),
                          rng.normal(size=(N_THETA, 3, m)), 20.0 * rng.normal(size=(N_THETA, 3, m)), periodic)
            for k, s in enumerate(coords)]


def _e_r(th):
    return np.array([math.cos(th), math.sin(th), 0.0])


def _e_t(th):
    return np.array([-math.sin(th), math.cos(th), 0.0])


def _pocket_centre(th):
    return R_POCKET * _e_r(th) + [0.0, 0.0, Z_POCKET]


def _wall_sample(rng, m):
    """Leading then trailing wall point of every pocket (as cms_reduction.sampling.pocket_contact_points)."""
    half = R_BALL + CLEAR
    pts = np.array([_pocket_centre(a) + sign * half * _e_t(a) for a in POCKET_ANGLES for sign in (1.0, -1.0)])
    n = len(pts)
    return RacewaySample("pockets", np.repeat(POCKET_ANGLES, 2), pts, rng.normal(size=(n, 3, m)),
                         20.0 * rng.normal(size=(n, 3, m)), False)


CYL_ANGLES = (0.0, 1.0, 2 * np.pi - 1e-12, 3.5, 5.0)     # θ = 0 on a sample, the wrap; the last one apart
PLANE_ANGLES = (1.0, 3.0)                                 # inside the arc, beyond it


def _scene(law_slice=None, law_rib=None, law_pocket=None, ring_motion=None, cage_motion=None, freqs=(2e3, 2e4, 8e4)):
    """Modal ring (cylinder raceway, thrust plane, rib) and modal cage (three sampled pockets) with rollers and
    balls on them; the rigid geometry of each contact is DELTA_0 deep (a cylinder roller 10 µm apart)."""
    rng = np.random.default_rng(SEED)
    law_slice = law_slice or ContactLaw(1e9, 10 / 9, 300.0, 1e-6, "impact", Coulomb(0.1, 0.08, 1e-3, 2e-3))
    law_rib = law_rib or ContactLaw(1e10, 1.5, 300.0, 1e-6, "impact", Coulomb(0.1, 0.08, 1e-3, 2e-3))
    law_pocket = law_pocket or ContactLaw(1e8, 1.0, 100.0, 1e-6, "impact", Coulomb(0.1, 0.08, 1e-3, 2e-3))
    m = len(freqs)
    mb = ModelBuilder()
    mb.add_body("rigid", 1.0, (1.0, 2.0, 3.0))               # body and modal indices differ
    ring = mb.add_modal_body("ring", _cloud_body(rng, freqs, R_RACE), motion=ring_motion or Driven(80.0))
    cage = mb.add_modal_body("cage", _cloud_body(rng, [3e3, 3e4], R_POCKET),
                             motion=cage_motion or Driven(-30.0, translation_free=True, tilt_free=True))
    cyl = mb.add_surface(ring, "inner_cylinder", R_RACE, raceway=_circles(
        rng, m, "cyl", CYL_S, lambda t, s: [R_RACE * math.cos(t), R_RACE * math.sin(t), s]))
    plane = mb.add_surface(ring, "plane_up", Z_PLANE, raceway=_circles(
        rng, m, "plane", PLANE_S, lambda t, s: [s * math.cos(t), s * math.sin(t), Z_PLANE], periodic=False))
    rib = mb.add_surface(ring, "plane_down", Z_RIB, raceway=_circles(
        rng, m, "rib", RIB_S, lambda t, s: [s * math.cos(t), s * math.sin(t), Z_RIB]))
    walls = _wall_sample(rng, 2)
    inertia = (1e-6, 1e-6, 2e-7)
    # rollers against the rib lean by RIB_TILT about their radius (a rim point touches, clear of the end face
    # parallel to the rib, where the rigid geometry loses digits), the rim DELTA_0 into the rib
    rho = R_ROLLER - EDGE_M
    half_rib = (Z_RIB + DELTA_0 - EDGE_M - rho * math.sin(RIB_TILT)) / math.cos(RIB_TILT) + EDGE_M
    for k, th in enumerate(CYL_ANGLES):
        gap = -1e-5 if k == len(CYL_ANGLES) - 1 else DELTA_0
        lean = Rotation.from_rotvec(RIB_TILT * _e_r(th) if k in (1, 3) else np.zeros(3))
        roller = mb.add_body(f"roller{k}", 0.01, inertia, position_m=(R_RACE + R_ROLLER - gap) * _e_r(th),
                             orientation=lean.as_quat(scalar_first=True))
        mb.add_roller_raceway(roller, ring, cyl, R_ROLLER, L_ROLLER, law_slice, n_slices=8)
        if k in (1, 3):
            mb.add_roller_rib(roller, ring, rib, R_ROLLER, 2 * half_rib, 1, EDGE_M, law_rib, name=f"roller{k}–rib")
    for k, th in enumerate(PLANE_ANGLES):
        radial = Rotation.align_vectors([_e_r(th)], [[0, 0, 1.0]])[0].as_quat(scalar_first=True)
        roller = mb.add_body(f"thrust{k}", 0.01, inertia, orientation=radial,
                             position_m=0.06 * _e_r(th) + [0, 0, Z_PLANE + R_ROLLER - DELTA_0])
        mb.add_roller_raceway(roller, ring, plane, R_ROLLER, L_ROLLER, law_slice, n_slices=8)
    for k, (th, kind) in enumerate(zip(POCKET_ANGLES, ("cylinder", "slot", "cylinder"))):
        pocket = mb.add_pocket(cage, kind, th, R_POCKET, Z_POCKET, CLEAR, walls=(walls, k))
        offset = (CLEAR + DELTA_0) * (np.array([0.0, 0.0, 1.0]) if k == 2 else _e_t(th))
        if kind == "slot":
            body = mb.add_body(f"pocket_roller{k}", 0.01, inertia, position_m=_pocket_centre(th) + offset)
            mb.add_element_pocket(body, cage, pocket, R_BALL, law_pocket, length_m=L_ROLLER)
        else:
            body = mb.add_body(f"ball{k}", 2e-3, (1.2e-8,) * 3, position_m=_pocket_centre(th) + offset)
            mb.add_element_pocket(body, cage, pocket, R_BALL, law_pocket)
    return mb.finalize()


def _scene_state(model, state, rng, slow, eta_scale=3e-7, jitter=3e-6):
    """Elements moved by ~``jitter`` and slightly turned, random velocities (fast: slip of m/s; slow: in the
    friction law's transition range), the whole scene turned and moved; η with |u| ~ 1 µm, |ψ| ~ 2e-5 rad,
    η̇ with modal surface velocities ~ 5 mm/s."""
    q, v = state.q.copy(), state.v.copy()
    elements = [i for i, n in enumerate(model.body_names) if n not in ("rigid", "ring", "cage")]
    q[elements, :3] += rng.normal(size=(len(elements), 3)) * jitter
    tilt = Rotation.from_rotvec(rng.normal(size=(len(elements), 3)) * 2e-4)
    q[elements, 3:] = (Rotation.from_quat(q[elements, 3:], scalar_first=True) * tilt).as_quat(scalar_first=True)
    scale = [1e-3] * 3 + [0.1] * 3 if slow else [0.1] * 3 + [100.0] * 3
    v[elements] = rng.normal(size=(len(elements), 6)) * scale
    turn, shift = Rotation.random(random_state=rng), rng.normal(size=3) * 0.1
    q[:, :3] = turn.apply(q[:, :3]) + shift
    q[:, 3:] = (turn * Rotation.from_quat(q[:, 3:], scalar_first=True)).as_quat(scalar_first=True)
    v[:, :3] = turn.apply(v[:, :3])
    n = model.n_modal
    return type(state)(state.t, q, v, rng.normal(size=n) * eta_scale, rng.normal(size=n) * 3e-3)


def _forces(model, st):
    w = make_work(model)
    assert FK.compute_forces(model.arrays, st.t, st.q, st.v, st.eta, st.eta_dot, w) == (FK.STATUS_OK, -1)
    return w


def _close(got, want, atol=0.0, rtol=RTOL):
    """|got − want| ≤ atol + rtol |want| elementwise; returns the worst ratio of error to tolerance."""
    got, want = np.asarray(got, float), np.asarray(want, float)
    err = np.abs(got - want) - (atol + rtol * np.abs(want))
    assert got.shape == want.shape and np.all(err <= 0), (
        f"worst excess {err.max():.3g} at {np.unravel_index(np.argmax(err), err.shape)}:\n{got}\n!=\n{want}")
    return float(np.max(np.abs(got - want) / (atol + rtol * np.abs(want) + 1e-300), initial=0.0))


def _compare(model, st):
    """compute_forces against the twin (module docstring for the tolerances)."""
    m = model.arrays
    w = _forces(model, st)
    want = ref.compute_forces(m, st.t, st.q, st.v, st.eta, st.eta_dot)
    slices = np.maximum(np.diff(m.pair_slice_off), 2)          # points per pair (two walls of a slot)
    # a roller end's rim point is found to ρ ε/|u| only, |u| ≥ sin(RIB_TILT/2) the end's lean from the
    # rib plane (test_kernels_multibody, test_roller_end_matches_twin_on_tilted_rollers)
    atol_m = np.where(m.pair_type == FK.ROLLER_RIB,
                      ATOL_M + 8 * EPS * (R_ROLLER - EDGE_M) / math.sin(RIB_TILT / 2), ATOL_M)
    fn_floor = slices * m.pair_n * m.pair_k * np.maximum(want.delta, 0.0) ** (m.pair_n - 1.0) * atol_m
    per_body = np.zeros(model.n_bodies)
    np.add.at(per_body, m.pair_a, fn_floor)
    np.add.at(per_body, m.pair_b, fn_floor)
    worst = [
        _close(w.body_f, want.body_f, atol=(RTOL * want.body_f_scale + per_body)[:, None]),
        _close(w.body_t, want.body_t, atol=(RTOL * want.body_t_scale + 0.2 * per_body)[:, None]),
        _close(w.contact_delta, want.delta, atol=atol_m),
        _close(w.contact_fn, want.fn, atol=fn_floor),
        _close(w.contact_ft, want.ft, atol=m.pair_fric_p[:, 0] * fn_floor),
        _close(w.contact_slip, want.slip, atol=RTOL * np.abs(want.slip).max()),
        _close(w.contact_angle, want.angle, atol=1e-14),
        _close(w.contact_point, want.point, atol=POINT_ATOL_M),
        _close(w.contact_normal, want.normal, atol=NORMAL_ATOL),
        _close(w.energy, [want.energy_contact, want.energy_bushing], atol=atol_m @ want.fn),
    ]
    per_unit = np.abs(m.samp_disp).max() + LEVER_M * np.abs(m.samp_rot).max()
    worst.append(_close(w.modal_f, want.modal_f,
                        atol=RTOL * np.abs(want.modal_f).max() + per_unit * fn_floor.sum()))
    return w, want, max(worst)


# -- (a) the kernel against its twin -------------------------------------------------------------------------
def test_flexible_slices_ribs_and_pockets_match_twin():
    """Penetrations with the surface's deformation, the modal surface velocity in damping and slip, forces
    on both frames and modal forces of roller slices (cylinder, full circle; plane, arc, a roller beyond
    it), roller ends on a rib and elements in pockets of a modal cage (a ball on a wall, one on the axial
    side between the walls, a roller in a slot), on 8 random states; Newton's third law for the frames."""
    model, state = _scene()
    rng = np.random.default_rng(SEED + 1)
    ws, worst = [], 0.0
    for k in range(8):
        st = _scene_state(model, state, rng, slow=k % 2 == 1, jitter=3e-6 if k else 0.0)
        if k == 0:
            st.q[:, 3:] = state.q[:, 3:]         # unturned: a roller exactly on sample 0 and one at the wrap
            st.q[:, :3] = state.q[:, :3]
        w, _, worst_k = _compare(model, st)
        worst = max(worst, worst_k)
        scale = np.sum(w.contact_fn + w.contact_ft)
        assert np.abs(w.body_f.sum(axis=0)).max() < 1e-13 * scale
        assert np.abs(np.sum(np.cross(st.q[:, :3], w.body_f) + w.body_t, axis=0)).max() < 1e-13 * scale * 0.2
        ws.append(w)
    delta = np.array([w.contact_delta for w in ws])
    kinds = np.array(model.pair_kinds)
    for kind in ("roller_raceway", "roller_rib", "element_pocket"):
        assert np.all(np.array([w.contact_fn for w in ws])[:, kinds == kind].sum(axis=1) > 0), kind
    assert np.any(delta <= 0)
    assert np.all(np.array([w.modal_f for w in ws]) != 0.0)
    print(f"worst |kernel − twin| / tolerance {worst:.2g}")


def test_deformation_changes_the_penetration_and_modes_see_the_load():
    """At η = 0 and η̇ = 0 the flexible contacts are the rigid ones (same δ, same forces to round-off); a modal
    surface velocity alone changes slip and damping; a deformation alone changes δ by n·(u + ψ × (p − p_s)):
    for a roller of one slice at θ = 0 and z = 0, on sample 0 of the middle circle (weights 1 and 0 in θ and
    in s), that of sample 0 of the middle circle alone."""
    model, state = _scene()
    m = model.arrays
    rigid = m._replace(race_modal=np.full_like(m.race_modal, -1), pocket_modal=np.full_like(m.pocket_modal, -1))
    st = state.copy()
    w_flex = _forces(model, st)
    w_rigid = make_work(model)
    FK.compute_forces(rigid, st.t, st.q, st.v, st.eta, st.eta_dot, w_rigid)
    np.testing.assert_array_equal(w_flex.contact_delta, w_rigid.contact_delta)
    for name in ("body_f", "body_t", "contact_fn", "contact_slip", "contact_ft"):     # summed in another order
        np.testing.assert_allclose(getattr(w_flex, name), getattr(w_rigid, name), rtol=1e-14, atol=0.0)
    assert np.all(w_flex.modal_f[model.modal_slice("ring")] != 0.0)        # the load goes to the modes
    st_v = st.copy()
    st_v.eta_dot = np.random.default_rng(SEED + 2).normal(size=model.n_modal) * 3e-3
    w_v = _forces(model, st_v)
    loaded = w_flex.contact_fn > 0
    assert np.all(w_v.contact_slip[loaded] != w_flex.contact_slip[loaded])
    # one roller of 1 slice at θ = 0, z = 0: its slice sits on row 0 of the middle circle
    mb = ModelBuilder()
    rng = np.random.default_rng(SEED)
    ring = mb.add_modal_body("ring", _cloud_body(rng, [2e3, 2e4], R_RACE), motion=Fixed())
    circles = _circles(rng, 2, "cyl", CYL_S, lambda t, s: [R_RACE * math.cos(t), R_RACE * math.sin(t), s])
    surf = mb.add_surface(ring, "inner_cylinder", R_RACE, raceway=circles)
    roller = mb.add_body("roller", 0.01, (1e-6, 1e-6, 2e-7), position_m=(R_RACE + R_ROLLER - DELTA_0) * _e_r(0.0))
    mb.add_roller_raceway(roller, ring, surf, R_ROLLER, L_ROLLER, ContactLaw(1e9, 10 / 9), n_slices=1)
    one, st1 = mb.finalize()
    st1.eta = np.array([2e-7, -1e-7])
    w1 = _forces(one, st1)
    row = circles[1]
    n = np.array([1.0, 0.0, 0.0])
    lever = np.array([R_RACE - DELTA_0, 0.0, 0.0]) - row.points_m[0]
    change = n @ (row.displacement[0] @ st1.eta + np.cross(row.rotation[0] @ st1.eta, lever))
    assert w1.contact_delta[0] == pytest.approx(DELTA_0 + change, rel=1e-12, abs=1e-18)
    assert abs(change) > 1e-7


# -- (b) work consistency -------------------------------------------------------------------------------------
def test_contact_forces_and_modal_forces_are_minus_the_gradient_of_the_energy():
    """Frictionless and undamped, frames held, at rest: the modal forces are −∂E/∂η (exactly so by
    construction: weights, normals and contact points do not depend on η — central differences with steps
    of 1e-11 √kg agree to 4e-10 of the largest), and the forces on the elements are
    −∂E/∂x up to the terms the kernel leaves out: the change of n·d (d the surface deformation) with the
    element's place, relative size |∂d/∂p| + |d|/ρ — the deformation's slope between the samples and its
    small rotation (measured 4e-6…1.2e-5 on the rollers), and the normal turning as the element moves, over
    ρ = the distance of a ball's centre from its pocket's axis, about the clearance (9e-4 on the balls).
    An energy change over a random joint step (all elements and η) is −(F·δx + Q·δη) to the same order."""
    law = ContactLaw(1e9, 10 / 9)
    model, state = _scene(law_slice=law, law_rib=ContactLaw(1e10, 1.5), law_pocket=ContactLaw(1e8, 1.0),
                          ring_motion=Fixed(), cage_motion=Fixed())
    m = model.arrays
    rng = np.random.default_rng(SEED + 3)
    base = state.copy()
    base.eta = rng.normal(size=model.n_modal) * 1e-7
    w = _forces(model, base)
    kinds = np.array(model.pair_kinds)
    assert np.all(w.contact_fn[kinds != "roller_raceway"] > 0)
    elements = np.array([i for i, n in enumerate(model.body_names) if n not in ("rigid", "ring", "cage")])

    def energy(d_eta=0.0, dx=None):
        st = base.copy()
        st.eta = st.eta + d_eta
        if dx is not None:
            st.q[elements, :3] += dx
        return _forces(model, st).energy[0]

    e = 1e-11
    grad_eta = np.array([(energy(e * u) - energy(-e * u)) / (2 * e) for u in np.eye(model.n_modal)])
    err_eta = np.abs(w.modal_f + grad_eta).max() / np.abs(w.modal_f).max()
    assert err_eta < 1e-6
    # the terms left out in the element forces: deformation slope between neighbouring samples, rotation,
    # the deformation over the pocket's radius (where the normal turns fastest)
    ring_modes, cage_modes = model.modal_slice("ring"), model.modal_slice("cage")
    k_ring, k_cage = ring_modes.stop - ring_modes.start, cage_modes.stop - cage_modes.start
    d = np.einsum("nck,k->nc", m.samp_disp[:, :, :k_ring], base.eta[ring_modes])     # rows of the ring's surfaces
    slope = 0.0
    for r in range(len(m.race_kind)):
        rows = np.arange(m.race_samp_off[r], m.race_samp_off[r + 1])
        n_c = m.race_circle_off[r + 1] - m.race_circle_off[r]
        grid = rows.reshape(n_c, -1)
        for a_, b_ in ((grid[:, :-1], grid[:, 1:]), (grid[:-1], grid[1:])):
            gap = np.linalg.norm(m.samp_point[a_] - m.samp_point[b_], axis=-1)
            slope = max(slope, (np.linalg.norm(d[a_] - d[b_], axis=-1) / gap).max())
    ring_rows = np.arange(m.race_samp_off[0], m.race_samp_off[-1])
    cage_rows = np.arange(m.pocket_samp.min(), m.pocket_samp.max() + 2)
    d_cage = np.einsum("nck,k->nc", m.samp_disp[cage_rows, :, :k_cage], base.eta[cage_modes])
    rot = max(np.abs(np.einsum("nck,k->nc", m.samp_rot[ring_rows, :, :k_ring], base.eta[ring_modes])).max(),
              np.abs(np.einsum("nck,k->nc", m.samp_rot[cage_rows, :, :k_cage], base.eta[cage_modes])).max())
    bound = slope + rot + np.abs(d_cage).max() / CLEAR
    worst = 0.0
    for j, i in enumerate(elements):
        dx = np.zeros((len(elements), 3))
        grad = []
        for u in np.eye(3):
            dx[j] = 1e-10 * u
            grad.append((energy(dx=dx) - energy(dx=-dx)) / 2e-10)
        if np.linalg.norm(w.body_f[i]) > 0:
            worst = max(worst, np.linalg.norm(w.body_f[i] + np.array(grad)) / np.linalg.norm(w.body_f[i]))
    assert worst < 2 * bound + 1e-5
    step_x = rng.normal(size=(len(elements), 3)) * 1e-10
    step_eta = rng.normal(size=model.n_modal) * 1e-11
    dE = energy(step_eta, step_x) - energy(-step_eta, -step_x)
    work = 2 * (np.sum(w.body_f[elements] * step_x) + w.modal_f @ step_eta)
    scale = 2 * (np.sum(np.abs(w.body_f[elements] * step_x)) + np.abs(w.modal_f) @ np.abs(step_eta))
    assert abs(dE + work) < (2 * bound + 1e-5) * scale
    print(f"|Q + ∂E/∂η| / max|Q| = {err_eta:.2g}; element forces: worst {worst:.2g} of |F| (bound {bound:.2g}); "
          f"joint step: |ΔE + W| / Σ|terms| = {abs(dE + work) / scale:.2g}")


# -- builder -------------------------------------------------------------------------------------------------
def test_builder_refuses_unsampled_contacts_on_modal_bodies_and_mismatched_grids():
    rng = np.random.default_rng(SEED)
    body = _cloud_body(rng, [2e3, 2e4], R_RACE)
    circles = _circles(rng, 2, "cyl", CYL_S, lambda t, s: [R_RACE * math.cos(t), R_RACE * math.sin(t), s])
    law = ContactLaw(1e9, 10 / 9)

    def scene(**surface):
        mb = ModelBuilder()
        ring = mb.add_modal_body("ring", body, motion=Fixed())
        surf = mb.add_surface(ring, "inner_cylinder", R_RACE, **surface)
        roller = mb.add_body("roller", 0.01, (1e-6, 1e-6, 2e-7), position_m=(R_RACE + R_ROLLER, 0, 0))
        mb.add_roller_raceway(roller, ring, surf, R_ROLLER, L_ROLLER, law)
        return mb

    with pytest.raises(ValueError, match="is not sampled; give add_surface"):
        scene().finalize()
    model, _ = scene(raceway=circles[::-1]).finalize()                      # circles sorted by s
    np.testing.assert_allclose(model.arrays.race_circle_s, CYL_S, atol=1e-15)
    np.testing.assert_array_equal(model.arrays.samp_disp[:N_THETA, :, :2], circles[0].displacement)
    odd = RacewaySample("odd", circles[1].theta_rad + 0.01, circles[1].points_m, circles[1].displacement,
                        circles[1].rotation, True)
    with pytest.raises(ValueError, match="same sample angles"):
        scene(raceway=[circles[0], odd])
    with pytest.raises(ValueError, match="distinct coordinates"):
        scene(raceway=circles[:2], raceway_s_m=[0.0, 0.0])
    with pytest.raises(ValueError, match="has no raceway sample 'track'"):
        scene(raceway="track")
    mb = ModelBuilder()
    rings = [mb.add_modal_body(name, body, motion=Fixed()) for name in ("ring", "other")]
    surf = mb.add_surface("ring", "inner_cylinder", R_RACE, raceway=circles)
    roller = mb.add_body("roller", 0.01, (1e-6, 1e-6, 2e-7))
    with pytest.raises(ValueError, match="the sampled surface belongs to body 'ring'"):
        mb.add_roller_raceway(roller, rings[1], surf, R_ROLLER, L_ROLLER, law)
    mb = ModelBuilder()
    cage = mb.add_modal_body("cage", body, motion=Fixed())
    ball = mb.add_body("ball", 1e-3, (1e-8,) * 3)
    p = mb.add_pocket(cage, "cylinder", 0.3, R_POCKET, Z_POCKET, CLEAR)
    mb.add_element_pocket(ball, cage, p, R_BALL, law)
    with pytest.raises(ValueError, match="has no wall samples; give add_pocket"):
        mb.finalize()
    walls = _wall_sample(rng, 2)
    with pytest.raises(ValueError, match="centred .* away from the pocket"):
        mb.add_pocket(cage, "cylinder", 0.3, R_POCKET, Z_POCKET, CLEAR, walls=(walls, 1))
    rigid = ModelBuilder()
    rigid.add_body("ring", 1.0, (1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="is rigid"):
        rigid.add_surface("ring", "inner_cylinder", R_RACE, raceway=circles)
    # rigid models carry empty tables and −1 indices
    mb = ModelBuilder()
    mb.add_body("ring", 1.0, (1.0, 1.0, 1.0), motion=Fixed())
    mb.add_surface("ring", "inner_cylinder", R_RACE)
    mb.add_pocket("ring", "slot", 0.0, R_POCKET, 0.0, CLEAR)
    a = mb.finalize()[0].arrays
    assert a.race_modal.tolist() == [-1] and a.pocket_modal.tolist() == [-1] and a.pocket_samp.tolist() == [-1]
    assert a.race_circle_s.size == 0 and a.samp_theta.size == 0 and a.race_samp_off.tolist() == [0, 0]


# -- (c) a roller on a flexible ring against the full FE model ----------------------------------------------
R_IN, R_OUT, WIDTH = 0.40, 0.45, 0.06
SUPPORTS_DEG = (0.0, 90.0, 180.0, 270.0)


@pytest.fixture(scope="module")
def ring():
    """A steel ring 0.80/0.90 m × 60 mm on 4 patches of its bore: 20 modes + 33 load shapes of the outer
    raceway (n ≤ 16), the raceway sampled on 5 circles across it; the full FE model and its supports."""
    profile, mesh = rectangle("ring", R_IN, R_OUT, 0.0, WIDTH), MeshSpec(0.02, "hex27")
    body = reduced_body(profile, mesh, STEEL, ReductionSpec(
        n_modes=20, interfaces=(InterfaceSpec("inner", SUPPORTS_DEG, 0.03),),
        raceways=(RacewaySpec("outer", 360, n_max=16, n_across=5),)))
    fe = build_model(profile, mesh, STEEL)
    supports = [Support(patch_nodes(fe.ring, "inner", a, 0.03), name=f"patch {a:g}") for a in SUPPORTS_DEG]
    return dict(body=body, fe=fe, supports=supports)


def _circle_error(fe, body, supports, eta, points, forces, circle, th, away):
    """max |u − u_FE| on the circle points (all, and those ``away`` from the contact) / max |u_FE|."""
    res = static_solve(fe, point_load(fe, points, forces), supports)
    u_fe = (vector_probe_matrix(fe.basis(2), circle) @ res.displacement_m.reshape(-1)).reshape(-1, 3)
    u = sample_points(body, "circle", circle, th, True).displacement @ eta
    err = np.linalg.norm(u - u_fe, axis=1) / np.linalg.norm(u_fe, axis=1).max()
    return err.max(), err[away].max()


def test_roller_on_a_flexible_ring_deflects_it_as_the_full_fe_model(ring):
    """A roller 30 × 50 mm (20 slices, ISO/TS 16281 slice stiffness) pressed by 100 kN onto the outer
    raceway between two supports, static equilibrium with the ring's modes: the slices carry the load, and
    the ring deflects as the full FE model under the same 20 slice forces at the slices' contact points —
    on the circle of section centroids, 10° and more from the roller within 2 % (0.86 % measured), and
    within 3 % everywhere (2.5 %; under the roller the FE mesh adds its local indentation)."""
    D, L, n_s, load_N = 0.03, 0.05, 20, 100e3
    th0 = math.radians(30.0)
    b = ModelBuilder()
    r = b.add_modal_body("ring", ring["body"], motion=Fixed())
    surf = b.add_surface(r, "inner_cylinder", R_OUT, raceway="outer")
    roller = b.add_body("roller", 0.3, (2e-4, 2e-4, 3e-5), position_m=(R_OUT + D / 2) * _e_r(th0) + [0, 0, WIDTH / 2],
                        motion=Driven(0.0, translation_free=True))
    b.add_roller_raceway(roller, r, surf, D / 2, L, ContactLaw(slice_stiffness(iso16281_stiffness(L), n_s), 10 / 9),
                         n_slices=n_s)
    b.add_force(roller, -load_N * _e_r(th0))
    model, state = b.finalize()
    assert model.arrays.race_circle_s.size == 5
    eq = static_equilibrium(model, state, fixed_azimuth=[roller]).state
    w = evaluate_forces(model, eq)
    assert w.contact_fn[0] == pytest.approx(load_N, rel=1e-3)       # 3e-13 measured
    # the slice forces on the ring, at the slices' contact points (the twin's contact points)
    points = ref.contact_points(model.arrays, eq.q, eq.v, 0, eq.eta, eq.eta_dot)
    delta = np.array([p[0] for p in points])
    assert np.all(delta > 0) and np.ptp(delta) > 1e-3 * delta.max()     # the ring's deformation shows across
    f = model.arrays.pair_k[0] * delta ** model.arrays.pair_n[0]
    forces = -f[:, None] * np.array([p[1] for p in points])
    assert forces.sum(axis=0) @ _e_r(th0) == pytest.approx(-load_N, rel=1e-3)
    fe = ring["fe"]
    x = fe.nodes_m
    section = np.abs(np.arctan2(x[:, 1], x[:, 0])) < 1e-6
    r_c, z_c = np.hypot(x[section, 0], x[section, 1]).mean(), x[section, 2].mean()
    th = np.linspace(0.0, 2 * math.pi, 360, endpoint=False)
    circle = np.column_stack((r_c * np.cos(th), r_c * np.sin(th), np.full(th.size, z_c)))
    away = np.abs((th - th0 + np.pi) % (2 * np.pi) - np.pi) > math.radians(10.0)
    err_all, err_away = _circle_error(fe, ring["body"], ring["supports"], eq.eta,
                                      np.array([p[2] for p in points]), forces, circle, th, away)
    assert err_away < 0.02
    assert err_all < 0.03
    print(f"slice loads {w.contact_fn[0] / load_N - 1:.2g} off the load; deflection on the centroid circle: "
          f"{err_away:.3%} away from the roller, {err_all:.3%} everywhere")


# -- (d) a ball in a pocket of a flexible cage against the full FE model --------------------------------------
CAGE_D, CAGE_PD, CAGE_CLEAR, CAGE_EXTENT = 0.03, 0.8, 0.5e-3, 0.05
CAGE_SUPPORTS_DEG = (15.0, 105.0, 195.0, 285.0)


def test_ball_pushing_a_pocket_wall_deflects_a_flexible_cage_as_the_full_fe_model():
    """A steel cage ring (0.8 m pitch, 12 pockets for 30 mm balls, 12 × 50 mm section, tet10) held at 4
    patches of its bottom face between pockets, reduced to 60 modes with its pocket walls sampled; a ball
    pushed by 2 kN along the pitch circle into the leading wall of pocket 2: the pocket carries the load, and
    the cage deflects as the full FE model under that force at the contact point — on a circle in the rim
    above the pockets within 2 % (0.84 % measured; 0.56 % 10° and more from the pocket), and at the other
    wall of the same pocket within 2 % (0.19 %; the loaded wall has the FE mesh's local indentation)."""
    profile, pockets = ball_cage("cage", n_balls=12, ball_diameter_m=CAGE_D, pitch_diameter_m=CAGE_PD,
                                 thickness_m=0.012, extent_m=CAGE_EXTENT, pocket_clearance_m=CAGE_CLEAR)
    mesh = MeshSpec(0.008, "tet10")
    body = reduced_body(profile, mesh, STEEL, ReductionSpec(
        n_modes=60, interfaces=(InterfaceSpec("bottom", CAGE_SUPPORTS_DEG, 0.01),)), pockets)
    k, load_N = 2, 2e3
    ang = float(pockets.angles_rad[k])
    b = ModelBuilder()
    cage = b.add_modal_body("cage", body, motion=Fixed())
    pocket = b.add_pocket(cage, "cylinder", ang, CAGE_PD / 2, 0.0, CAGE_CLEAR, walls=k)
    ball = b.add_body("ball", 0.11, (1e-5,) * 3, position_m=CAGE_PD / 2 * _e_r(ang) + CAGE_CLEAR * _e_t(ang))
    b.add_element_pocket(ball, cage, pocket, CAGE_D / 2, ContactLaw(1e8, 1.0))
    b.add_force(ball, load_N * _e_t(ang))
    model, state = b.finalize()
    eq = static_equilibrium(model, state).state
    w = evaluate_forces(model, eq)
    assert w.contact_fn[0] == pytest.approx(load_N, rel=1e-3)         # 7e-14 measured
    (delta, normal, point), = [p[:3] for p in ref.contact_points(model.arrays, eq.q, eq.v, 0, eq.eta, eq.eta_dot)]
    force = -model.arrays.pair_k[0] * delta * normal
    fe = build_model(profile, mesh, STEEL, pockets)
    supports = [Support(patch_nodes(fe.ring, "bottom", a, 0.01), name=f"patch {a:g}") for a in CAGE_SUPPORTS_DEG]
    th = np.linspace(0.0, 2 * math.pi, 360, endpoint=False)
    z_rim = CAGE_EXTENT / 2 - 0.004
    circle = np.column_stack((CAGE_PD / 2 * np.cos(th), CAGE_PD / 2 * np.sin(th), np.full(th.size, z_rim)))
    away = np.abs((th - ang + np.pi) % (2 * np.pi) - np.pi) > math.radians(10.0)
    err_all, err_away = _circle_error(fe, body, supports, eq.eta, point[None], force[None], circle, th, away)
    assert err_all < 0.02
    # the trailing wall of the loaded pocket (the leading one is under the load: FE indentation)
    res = static_solve(fe, point_load(fe, point[None], force[None]), supports)
    walls = samples_from_arrays(body.extras)["pockets"]
    trailing = walls.points_m[2 * k + 1]
    u_fe = vector_probe_matrix(fe.basis(2), trailing[None]) @ res.displacement_m.reshape(-1)
    u = walls.displacement[2 * k + 1] @ eq.eta
    err_wall = np.linalg.norm(u - u_fe) / np.linalg.norm(u_fe)
    assert err_wall < 0.02
    print(f"pocket load {w.contact_fn[0] / load_N - 1:.2g} off; cage deflection: rim circle {err_all:.3%} "
          f"({err_away:.3%} away from the pocket), trailing wall "
          f"{err_wall:.3%}")


# -- (e) a bounce in the explicit loop ----------------------------------------------------------------------------
def _bounce_model(kind):
    """An undamped modal ring or cage (frame held, modes at 3 and 10 kHz, no modal damping, random samples)
    and one element flying into it: a ball into the leading wall of a pocket, 1 µm away at 5 cm/s, or a
    spinning roller onto the cylinder raceway, 2 µm away at 5 cm/s (sliding at 2 cm/s)."""
    rng = np.random.default_rng(SEED + 5)
    mb = ModelBuilder()
    if kind == "pocket":
        cage = mb.add_modal_body("cage", _cloud_body(rng, [3e3, 1e4], R_POCKET, zeta=0.0), motion=Fixed())
        th = POCKET_ANGLES[0]
        pocket = mb.add_pocket(cage, "cylinder", th, R_POCKET, Z_POCKET, CLEAR, walls=(_wall_sample(rng, 2), 0))
        ball = mb.add_body("ball", 2e-3, (1.2e-8,) * 3, position_m=_pocket_centre(th) + (CLEAR - 1e-6) * _e_t(th),
                           velocity_m_s=0.05 * _e_t(th) + [0.0, 0.0, 0.01])
        mb.add_element_pocket(ball, cage, pocket, R_BALL, ContactLaw(1e8, 1.0))
    else:
        ring = mb.add_modal_body("ring", _cloud_body(rng, [3e3, 1e4], R_RACE, zeta=0.0), motion=Fixed())
        circles = _circles(rng, 2, "cyl", CYL_S, lambda t, s: [R_RACE * math.cos(t), R_RACE * math.sin(t), s])
        surf = mb.add_surface(ring, "inner_cylinder", R_RACE, raceway=circles)
        th = 0.7
        roller = mb.add_body("roller", 0.01, (1e-6, 1e-6, 2e-7), position_m=(R_RACE + R_ROLLER + 2e-6) * _e_r(th),
                             velocity_m_s=-0.05 * _e_r(th) + 0.02 * _e_t(th), omega_rad_s=(0.0, 0.0, 5.0))
        mb.add_roller_raceway(roller, ring, surf, R_ROLLER, L_ROLLER, ContactLaw(1e9, 10 / 9), n_slices=8)
    return mb.finalize()


@pytest.mark.parametrize("kind", ["pocket", "raceway"])
def test_a_bounce_on_a_flexible_body_keeps_the_energy(kind):
    """Frictionless, undamped, 6000 explicit steps of 10 ns (the contact's hω ≈ 2e-3, the modes' ≤ 6e-4):
    the element hits the modal body and leaves it, part of its energy left in the body's vibration (4.8 %
    and 1.8 %), and the total — element, modes (½ η̇ᵀ I6 η̇ + ½ Σ ω² η²) and contact — stays within 1e-4
    (2.3e-6 and 1.6e-6 measured; velocity Verlet's energy error is of order (hω)²)."""
    model, state = _bounce_model(kind)
    a = model.arrays
    out = simulate(model, state, 60e-6, timestep_s=1e-8, record_every=50)
    parts = []
    for k in range(len(out["t"])):
        st = type(state)(out["t"][k], out["q"][k], out["v"][k], out["eta"][k], out["eta_dot"][k])
        w = evaluate_forces(model, st)
        v, e, ed = out["v"][k][1], out["eta"][k], out["eta_dot"][k]
        element = 0.5 * a.body_mass[1] * v[:3] @ v[:3] + 0.5 * a.body_inertia[1] @ v[3:] ** 2
        modes = 0.5 * ed @ a.modal_I6[0] @ ed + 0.5 * a.modal_omega2 @ e**2
        parts.append((element, modes, w.energy[0], w.contact_fn[0]))
    element, modes, contact, fn = np.array(parts).T
    total = element + modes + contact
    assert fn.max() > 0 and fn[-1] == 0.0                      # it touched and left
    assert modes[-1] > 0.01 * total[0]
    drift = np.abs(total - total[0]).max() / total[0]
    assert drift < 1e-4
    print(f"{kind}: {modes[-1] / total[0]:.3g} of the energy left in the modes; total within {drift:.2g}")
