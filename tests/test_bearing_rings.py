"""Modal rings of bearing description files ([rings.inner] / [rings.outer]).

References: the gothic-arch geometry of a four-point row (Amasorrain et al., Mech. Mach. Theory 38,
2003: each diagonal's groove arc of radius f·D about a curvature centre (f − ½)·D beyond the ball
centre), integrated here independently of the profile code; the rigid-ring load distribution
(:func:`mbd_core.quasistatic.solve_load_distribution`) as the limit of very stiff rings; a central
finite difference of the flexible displacement–load relation for the condensed stiffness matrix.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from cases.bearing_file import loads_bearing
from cases.bearing_solver import bearing_solver
from cases.config import CaseError
from cms_reduction.body import with_stiffness_scaled
from mbd_core.quasistatic import RingLoad, solve_load_distribution
from mbd_core.quasistatic.flexible import FlexibleRing, build_flexible_model
from mbd_core.quasistatic.flexible_solve import solve_flexible_load_distribution

D, DM, F, ALPHA, SHOULDER = 0.025, 0.5, 0.53, 45.0, 70.0

SMALL = f"""
[bearing]
name = "four-point test bearing"
moving_ring = "inner"

[[rows]]
type = "four_point"
name = "balls"
count = 40
ball_diameter_m = {D}
pitch_diameter_m = {DM}
contact_angle_deg = {ALPHA}
shoulder_angle_deg = {SHOULDER}
conformity_inner = {F}
conformity_outer = {F}

[rings.inner]
inner_diameter_m = 0.42
z_min_m = -0.03
z_max_m = 0.03
n_modes = 12
raceway_harmonics = 4
element_size_m = 0.03
[rings.inner.bolts]
count = 12
pitch_diameter_m = 0.44
face = "top"

[rings.outer]
outer_diameter_m = 0.58
z_min_m = -0.03
z_max_m = 0.03
n_modes = 12
raceway_harmonics = 4
element_size_m = 0.03
clamped_face = "bottom"

[load]
Fx_N = 5.0e3
Fz_N = -2.0e4
My_Nm = 2.0e3
"""


@pytest.fixture(scope="module")
def desc():
    return loads_bearing(SMALL)


@pytest.fixture(scope="module")
def solver(desc):
    return bearing_solver(desc)


def _land_radius(ring: str) -> float:
    """Independent: the groove arc of diagonal +α on the inner ring, centre at
    b + (f − ½)D·(cos α, sin α), reaches the shoulder angle at r = b_r − (f·D·cos θ_s − (f − ½)·D·cos α)."""
    lever = F * D * math.cos(math.radians(SHOULDER)) - (F - 0.5) * D * math.cos(math.radians(ALPHA))
    return 0.5 * DM - lever if ring == "inner" else 0.5 * DM + lever


def _groove_area(ring: str) -> float:
    """Area cut from the box by the gothic arch: ∫ |r_land − r_arc(z)| dz over both arcs (quadrature)."""
    R = F * D
    c_r = 0.5 * DM + (1 if ring == "inner" else -1) * (F - 0.5) * D * math.cos(math.radians(ALPHA))
    c_z = (F - 0.5) * D * math.sin(math.radians(ALPHA))  # centre of the arc below the mid-plane
    z_sh = c_z - R * math.sin(math.radians(SHOULDER))
    side = -1 if ring == "inner" else 1

    def depth(z):
        return abs(c_r + side * math.sqrt(R * R - (z - c_z) ** 2) - _land_radius(ring))

    return 2.0 * quad(depth, z_sh, 0.0, epsabs=1e-14, epsrel=1e-12)[0]


@pytest.mark.parametrize("ring, r_far", [("inner", 0.21), ("outer", 0.29)])
def test_box_section_has_the_gothic_arch_of_the_row(desc, ring, r_far):
    prof = desc.rings[ring].profile
    r0, r1, z0, z1 = prof.bounds_m
    land = r1 if ring == "inner" else r0
    assert land == pytest.approx(_land_radius(ring), rel=1e-12, abs=1e-12)
    box = abs(land - r_far) * 0.06
    # area of the section = box − groove (quadrature to 1e-12), the profile integrates its arcs exactly
    assert prof.area_m2 == pytest.approx(box - _groove_area(ring), rel=1e-9)
    # the raceway sample sits at the arch apex: on the mid-plane, f·D from both curvature centres
    apex = np.asarray(desc.rings[ring].places["balls"].point_rz_m)
    assert apex[1] == pytest.approx(0.0, abs=1e-15)
    side = 1 if ring == "inner" else -1
    for s in (1, -1):
        c = np.array([0.5 * DM + side * (F - 0.5) * D * math.cos(math.radians(ALPHA)),
                      s * (F - 0.5) * D * math.sin(math.radians(ALPHA))])
        assert np.linalg.norm(apex - c) == pytest.approx(F * D, rel=1e-12)


def check_equilibrium_and_condensed_stiffness(desc, solver) -> None:
    """Residual ≤ 1e-9 relative; the stiffness matrix symmetric and the inverse of a central
    difference of the displacement–load relation to 1e-5 (acceptance of the bearing files)."""
    load = desc.default_load
    dist = solver.solve(load)
    assert dist.equilibrium_error <= 1e-9
    K = dist.stiffness
    assert np.max(np.abs(K - K.T)) <= 1e-9 * np.max(np.abs(K))
    base = load.as_array()
    scale = np.array([2.0, 2.0, 2.0, 0.2, 0.2])  # truncation O(h²): 1e-5 needs h ≲ 10 N here
    C = np.zeros((5, 5))
    for j in range(5):
        h = np.zeros(5)
        h[j] = scale[j]
        qp = solver.solve(RingLoad(*(base + h))).displacement
        qm = solver.solve(RingLoad(*(base - h))).displacement
        C[:, j] = (qp - qm) / (2.0 * scale[j])
    assert np.max(np.abs(K @ C - np.eye(5))) <= 1e-5


def test_modal_rings_equilibrium_and_condensed_stiffness(desc, solver):
    assert solver.flexible and {r.name for r in solver.rings} == {"inner", "outer"}
    check_equilibrium_and_condensed_stiffness(desc, solver)


def test_very_stiff_modal_rings_give_the_rigid_ring_loads(desc, solver):
    """E × 10⁶: the ring bending vanishes (∝ 1/E), so ball loads approach the rigid-ring ones;
    left: the raceway's own deflection at 10⁻⁶ of the soft ring's, far below 1e-4 of the loads."""
    stiff = tuple(FlexibleRing(r.name, with_stiffness_scaled(r.body, 1e6), r.ring, dict(r.raceways)) for r in solver.rings)
    model = build_flexible_model(desc.bearing, stiff)
    load = desc.default_load
    flex = solve_flexible_load_distribution(model, load)
    rigid = solve_load_distribution(desc.bearing, load)
    qf, qr = flex.rows[0].contact_load_N, rigid.rows[0].contact_load_N
    assert np.max(np.abs(qf - qr)) <= 1e-4 * qr.max()
    # and soft rings (E / 100) do change the loads: the test would see a coupling that does nothing
    # (the real rings of this small bearing are too stiff to tell: their bending moves Q_max ~0.1 %)
    soft = tuple(FlexibleRing(r.name, with_stiffness_scaled(r.body, 1e-2), r.ring, dict(r.raceways)) for r in solver.rings)
    q_soft = solve_flexible_load_distribution(build_flexible_model(desc.bearing, soft), load).rows[0].contact_load_N
    assert np.max(np.abs(q_soft - qr)) >= 1e-2 * qr.max()


def test_bolt_patches_are_washer_discs(desc):
    """Independent: the top-face nodes within the washer radius of a bolt point, in Cartesian x, y."""
    from cases.bearing_rings import ring_mesh_spec
    from fem_rings.model import build_model
    from fem_rings.nodesets import patch_nodes

    m = desc.rings["inner"]
    ring = build_model(m.profile, ring_mesh_spec(m), m.material).ring
    bolts = m.keys.bolts
    radius = 0.25 * math.pi * bolts.pitch_diameter_m / bolts.count  # default washer: half the bolt spacing
    theta = 360.0 * 0.5 / bolts.count
    got = patch_nodes(ring, "top", theta, radius, at_radius_m=0.5 * bolts.pitch_diameter_m)
    nodes = ring.node_sets["top"]
    x, y = ring.mesh.doflocs[0, nodes], ring.mesh.doflocs[1, nodes]
    bx, by = 0.5 * bolts.pitch_diameter_m * math.cos(math.radians(theta)), 0.5 * bolts.pitch_diameter_m * math.sin(math.radians(theta))
    d = np.hypot(x - bx, y - by)
    assert set(got) >= set(nodes[d <= radius]) and set(got) <= set(nodes[d <= radius * (1 + 1e-6) + 1e-6 * ring.size_m])
    assert 0 < len(got) < len(nodes) / bolts.count


@pytest.mark.parametrize("change, message", [
    (("inner_diameter_m = 0.42\n", ""), "rings.inner.inner_diameter_m: missing key"),
    (("outer_diameter_m = 0.58\n", "outer_diameter_m = 0.58\ninner_diameter_m = 0.5\n"),
     "rings.outer.inner_diameter_m: the raceways put this face at"),
    (('face = "top"', 'face = "flange"'), "rings.inner.bolts.face: the section has no face 'flange'"),
    (('clamped_face = "bottom"', 'clamped_face = "raceway balls"'), "rings.outer.clamped_face: 'raceway balls' carries a raceway"),
    (('clamped_face = "bottom"', ''), "rings.outer.bolts: give the ring's support"),
    (("n_modes = 12\nraceway_harmonics = 4\nelement_size_m = 0.03\nclamped", "n_modes = 0\nclamped"),
     "rings.outer.n_modes: must lie in 1"),
    (("[rings.inner]", "[rings.middle]\n[rings.inner]"), "rings.middle: unknown ring"),
    (("element_size_m = 0.03\n[rings.inner.bolts]", "element_size_m = 0.0005\n[rings.inner.bolts]"),
     "rings.inner.element_size_m = 0.0005 would give"),
])
def test_bad_ring_tables_name_the_key(change, message):
    text = SMALL.replace(*change, 1)
    assert text != SMALL
    with pytest.raises(CaseError) as err:
        loads_bearing(text)
    assert str(err.value).startswith(message), str(err.value)


def test_profile_section_must_carry_the_raceway():
    profile = """
[rings.outer]
section = "profile"
clamped_face = "bottom"
segments = [
  { kind = "line", start_m = [0.27, -0.03], end_m = [0.29, -0.03], name = "bottom" },
  { kind = "line", start_m = [0.29, -0.03], end_m = [0.29, 0.03], name = "outer" },
  { kind = "line", start_m = [0.29, 0.03], end_m = [0.27, 0.03], name = "top" },
  { kind = "line", start_m = [0.27, 0.03], end_m = [0.27, -0.03], name = "bore" },
]
"""
    text = SMALL[:SMALL.index("[rings.outer]")] + profile + SMALL[SMALL.index("[load]"):]
    with pytest.raises(CaseError) as err:
        loads_bearing(text)
    assert str(err.value).startswith("rings.outer.segments: no segment passes through the raceway of row 'balls'")


def _write_dxf(profile, path, drop_last: bool = False) -> None:
    """The profile as LINE and ARC entities (mm), each on the layer of its segment's name."""
    import ezdxf

    from fem_rings.profile import Arc

    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 4  # mm
    msp = doc.modelspace()
    segs = profile.segments[:-1] if drop_last else profile.segments
    for seg in segs:
        layer = seg.name.replace(" ", "_")
        if isinstance(seg, Arc):
            c = np.asarray(seg.center)
            a0 = math.degrees(math.atan2(seg.start[1] - c[1], seg.start[0] - c[0]))
            a1 = math.degrees(math.atan2(seg.end[1] - c[1], seg.end[0] - c[0]))
            if not seg.ccw:
                a0, a1 = a1, a0
            msp.add_arc(tuple(1e3 * c), 1e3 * seg.radius_m, a0, a1, dxfattribs={"layer": layer})
        else:
            msp.add_line(tuple(1e3 * np.asarray(seg.start)), tuple(1e3 * np.asarray(seg.end)), dxfattribs={"layer": layer})
    doc.saveas(path)


def test_dxf_section_of_a_ring(desc, tmp_path):
    """The outer ring's box section drawn in a DXF (mm) and read back as its section: same area, the
    raceway found on the groove layer; an open drawing stops at the key before any meshing."""
    _write_dxf(desc.rings["outer"].profile, tmp_path / "outer.dxf")
    dxf = """
[rings.outer]
section = "dxf"
dxf_file = "outer.dxf"
clamped_face = "bottom"
"""
    text = SMALL[:SMALL.index("[rings.outer]")] + dxf + SMALL[SMALL.index("[load]"):]
    (tmp_path / "b.toml").write_text(text)
    from cases.bearing_file import read_bearing_file

    ring = read_bearing_file(tmp_path / "b.toml").rings["outer"]
    assert ring.profile.area_m2 == pytest.approx(desc.rings["outer"].profile.area_m2, rel=1e-9)
    assert ring.raceways == {"balls": "raceway_balls"}
    _write_dxf(desc.rings["outer"].profile, tmp_path / "outer.dxf", drop_last=True)
    with pytest.raises(CaseError) as err:
        read_bearing_file(tmp_path / "b.toml")
    assert str(err.value).startswith("rings.outer.dxf_file: ") and "outer.dxf" in str(err.value)


def test_modes_of_a_described_ring_against_thin_ring_theory(tmp_path, capsys):
    """`flexbearing modes FILE --ring outer`: the lowest in-plane bending pair (n = 2) against the
    inextensional thin-ring frequency ω_n = n(n² − 1)/√(n² + 1)·√(EI/(ρAR⁴)) (Hoppe 1871; Love,
    *Mathematical Theory of Elasticity*, §293), with A, the centroid radius R and I = ∫(r − R)² dA
    of the section integrated here from its outline (Green's theorem). Tolerance 3 %: the theory
    neglects shear and rotary inertia, O((h/R)²) ≈ 1 % for this section (h/R ≈ 0.11)."""
    import json

    from cases.cli import main

    path = tmp_path / "b.toml"
    path.write_text(SMALL)
    assert main(["modes", str(path), "--ring", "outer", "--modes", "10", "--json"]) in (0, None)
    out = json.loads(capsys.readouterr().out)
    f_in = [m["frequency_Hz"] for m in out["modes"] if m["family"] == "in" and m["waves"] == 2]
    prof = loads_bearing(SMALL).rings["outer"].profile
    pts = prof.polyline(4000)[0]
    r, z = pts[:, 0], pts[:, 1]
    rn, zn = np.roll(r, -1), np.roll(z, -1)
    cr = r * zn - rn * z
    A = 0.5 * cr.sum()
    R = ((r + rn) * cr).sum() / 6.0 / A
    I = ((r * r + r * rn + rn * rn) * cr).sum() / 12.0 - A * R * R
    E, rho = 207e9, 7850.0  # bearing_steel
    f2 = 6.0 / math.sqrt(5.0) * math.sqrt(E * I / (rho * A * R**4)) / (2.0 * math.pi)
    assert f_in and f_in[0] == pytest.approx(f2, rel=0.03)


def test_load_steps_reach_the_same_equilibrium(desc, solver):
    """The load applied in 8 steps (the fallback where Newton from the rigid-ring start fails) ends
    in the equilibrium of the direct solve: displacement and modal coordinates to 1e-9 relative."""
    load = RingLoad(Fx_N=2.0e4, Fz_N=-3.0e5, My_Nm=-1.5e4)
    direct = solve_flexible_load_distribution(solver.model, load)
    stepped = solve_flexible_load_distribution(solver.model, load, load_steps=8)
    assert stepped.equilibrium_error <= 1e-9
    assert np.max(np.abs(stepped.displacement - direct.displacement)) <= 1e-9 * np.max(np.abs(direct.displacement))
    for a, b in zip(stepped.modal_coordinates, direct.modal_coordinates):
        assert np.max(np.abs(a - b)) <= 1e-9 * np.max(np.abs(b))



def test_a_washer_too_small_for_the_mesh_names_its_key():
    """A 1 mm washer on 30 mm elements holds no node (or nodes on a line): one line naming the key."""
    text = SMALL.replace('face = "top"', 'face = "top"\nwasher_diameter_m = 0.001', 1)
    with pytest.raises(CaseError) as err:
        bearing_solver(loads_bearing(text))
    assert str(err.value).startswith("rings.inner.bolts.washer_diameter_m: the support cannot be built on this mesh")


ANGULAR = SMALL.replace('type = "four_point"', 'type = "angular_contact"\nloaded_direction = "-z"').replace(
    f"shoulder_angle_deg = {SHOULDER}\n", "")


def _with_ring_keys(text: str, rings=("inner", "outer"), **keys) -> str:
    """``text`` with ``keys`` replacing or added to the [rings.X] tables of ``rings`` (TOML values as text)."""
    for ring in rings:
        head = f"[rings.{ring}]\n"
        start = text.index(head) + len(head)
        end = text.index("[", start)
        lines = [ln for ln in text[start:end].splitlines() if ln.split("=")[0].strip() not in keys]
        lines += [f"{k} = {v}" for k, v in keys.items()]
        text = text[:start] + "\n".join(lines) + "\n" + text[end:]
    return text


def _soft_largest_load(text: str) -> float:
    """Largest ball load of the default load with both rings at E / 100 (their bending then moves
    the loads by several per cent, see test_very_stiff_modal_rings_give_the_rigid_ring_loads)."""
    d = loads_bearing(text)
    rings = tuple(FlexibleRing(r.name, with_stiffness_scaled(r.body, 1e-2), r.ring, dict(r.raceways))
                  for r in bearing_solver(d).rings)
    return float(solve_flexible_load_distribution(build_flexible_model(d.bearing, rings), d.default_load)
                 .rows[0].load_N.max())


def test_element_load_shapes_make_the_ring_basis_hold_the_static_response():
    # Reference: Ritz. With the static shapes of radial and axial forces at every ball (spread over
    # a 4 mm patch of the groove; 0.3·D, the default, reaches past this shallow groove's edge) in the basis, the static response to the ball forces lies in it whatever modes
    # and harmonics are added, so 4 modes with none agree with 12 modes and harmonics to 4, within
    # 1e-3 (measured 3.4e-4: the solver samples the raceway as a patch average on its θ
    # grid, while the shapes spread each force over the patch and ±spread along the circumference, so
    # the force it applies is not exactly the load of a shape; the slewing ladder: 0.07 %); without
    # those shapes 4 modes miss part of the ring's flexibility (more than 1 %).
    # Only the inner ring's basis changes (the outer ring is the same, and reduced once).
    inner = ("inner",)
    shapes = dict(element_load_shapes="true", raceway_spread_m="0.004")
    lean = _soft_largest_load(_with_ring_keys(ANGULAR, inner, n_modes=4, raceway_harmonics=0, **shapes))
    rich = _soft_largest_load(_with_ring_keys(ANGULAR, inner, **shapes))
    plain = _soft_largest_load(_with_ring_keys(ANGULAR, inner, n_modes=4, raceway_harmonics=0, raceway_spread_m="0.004"))
    assert lean == pytest.approx(rich, rel=1e-3)
    assert abs(plain - rich) > 1e-2 * rich, (plain, rich)


@pytest.mark.parametrize("text, keys, message", [
    (ANGULAR, {"raceway_spread_m": "-0.001"}, "rings.inner.raceway_spread_m: must be ≥ 0"),
    (ANGULAR, {"element_load_shapes": "true", "raceway_spread_m": "0.0"},
     "rings.inner.raceway_spread_m: element_load_shapes need"),
    (ANGULAR, {"raceway_spread_m": "0.02"}, "rings.inner.raceway_spread_m: raceway"),
    (SMALL, {"element_load_shapes": "true"}, "rings.inner.element_load_shapes: not for the four-point row"),
])
def test_bad_patch_keys_name_the_key(text, keys, message):
    with pytest.raises(CaseError, match=message.replace(".", r"\.")):
        bearing_solver(loads_bearing(_with_ring_keys(text, **keys)))
