"""Tests of the parametric ring and cage sections in ``fem_rings.sections``.

References used below:

* Groove geometry (Harris & Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed., ch. 2):
  groove radius f·D; the curvature centre lies (f − ½)·D from the ball centre on the contact line.
* Circular segment of radius R and central angle θ: area R²(θ − sin θ)/2, centroid
  4R·sin³(θ/2) / (3(θ − sin θ)) from the circle centre; chord height R(1 − cos(θ/2)).
* Pappus–Guldinus: volume of revolution = 2π · area · centroid radius.
* Slewing-ring thesis (README.md, Sources; static validation): top race weight 31 817 N = 3.25 t at Ø6.69 m,
  4767.66 N = 0.486 t for the Ø1 m model.
* Wind main-bearing paper (Pang et al., Lubricants 12 (2024) 252, Table 2): inner ring
  2271 + 1700 kg, outer ring 3055 kg, thrust cage 90.2 kg, radial cage 70 kg.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from fem_rings.profile import Line, ProfileError
from fem_rings.cages import CagePockets, ball_cage, three_row_cages
from fem_rings.sections import (
    BallGroove,
    SlewingSection,
    ThreeRowGeometry,
    ball_groove_arc,
    grooved_ring,
    slewing_bottom_race,
    slewing_top_race,
    slewing_tmr,
    three_row_inner_ring,
    three_row_outer_ring,
)

STEEL_KG_M3 = 7850.0
D, F, ALPHA = 95.25e-3, 0.525, 60.0  # the slewing ring's balls, conformity, contact angle


# -- helpers --------------------------------------------------------------------------------------------
def _boundary(profile, n_per_arc=128):
    pts, _ = profile.polyline(n_per_arc)
    return pts


def _inside(poly, pts):
    """Even-odd point-in-polygon, (m,) bool; points on the boundary are undefined."""
    a, b = poly, np.roll(poly, -1, axis=0)
    x, y = pts[:, 0:1], pts[:, 1:2]
    crosses = (a[:, 1] > y) != (b[:, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return np.count_nonzero(crosses & (x < xc), axis=1) % 2 == 1


def _edges_meet(p, q):
    """Whether any edge of closed polyline p meets (crosses or touches) any edge of q."""
    a, b = p[:, None, :], np.roll(p, -1, axis=0)[:, None, :]
    c, d = q[None, :, :], np.roll(q, -1, axis=0)[None, :, :]
    r, s, cp = b - a, d - c, c - a
    den = r[..., 0] * s[..., 1] - r[..., 1] * s[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (cp[..., 0] * s[..., 1] - cp[..., 1] * s[..., 0]) / den
        u = (cp[..., 0] * r[..., 1] - cp[..., 1] * r[..., 0]) / den
    return bool(np.any((den != 0) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)))


def _disjoint(p, q):
    """Two simple closed polylines bound disjoint regions: no edges meet, no vertex inside the other."""
    return not (_edges_meet(p, q) or _inside(q, p).any() or _inside(p, q).any())


def _box(r0, r1, z0, z1, shrink=1e-7):
    return np.array([(r0 + shrink, z0 + shrink), (r1 - shrink, z0 + shrink),
                     (r1 - shrink, z1 - shrink), (r0 + shrink, z1 - shrink)])


def _segments(profile, name):
    return [s for s in profile.segments if s.name == name]


def _segment_area(R, depth):
    theta = 2.0 * math.acos((R - depth) / R)
    return 0.5 * R**2 * (theta - math.sin(theta)), theta


# -- ball grooves ---------------------------------------------------------------------------------------
def _bottom_groove(depth=0.030):
    return BallGroove(D, F, ALPHA, (3.345, 0.0), (1, -1), depth, "top")


def test_groove_arc_radius_contact_point_and_depth():
    g = _bottom_groove()
    arc, (lo, hi) = ball_groove_arc(g)
    R = F * D
    assert arc.radius_m == pytest.approx(R, rel=1e-14)
    assert arc.name == "groove" and arc.start == lo and arc.end == hi
    c, p = np.asarray(arc.center), g.contact_point_m
    # curvature centre (f − ½)·D from the ball centre, against the contact direction (Harris)
    n = np.array([math.cos(math.radians(ALPHA)), -math.sin(math.radians(ALPHA))])
    assert np.allclose(c, np.array([3.345, 0.0]) - (F - 0.5) * D * n, atol=1e-15)
    assert abs(np.linalg.norm(p - c) - R) < 1e-12
    assert math.degrees(math.atan2(-p[1], p[0] - 3.345)) == pytest.approx(ALPHA, abs=1e-9)
    # contact point between the edges: its angle about c lies inside the arc's sweep
    a_lo, a_hi, a_p = (math.atan2(q[1] - c[1], q[0] - c[0]) for q in (lo, hi, p))
    assert min(a_lo, a_hi) < a_p < max(a_lo, a_hi)
    # depth from the face (edge points' z) to the lowest point of the arc
    zs = arc.points(np.linspace(0, 1, 20001))[:, 1]
    assert lo[1] == hi[1] == g.face_position_m
    assert g.face_position_m - zs.min() == pytest.approx(0.030, abs=1e-9)
    assert g.face_position_m - g.deepest_point_m[1] == pytest.approx(0.030, abs=1e-15)


def test_groove_arc_name_override_and_sweep_below_half_circle():
    arc, _ = ball_groove_arc(_bottom_groove(), name="raceway")
    assert arc.name == "raceway"
    _, theta = _segment_area(F * D, 0.030)
    assert arc.sweep_rad == pytest.approx(theta, rel=1e-12) and arc.sweep_rad < math.pi


def test_top_face_groove_area_and_mass_against_circular_segment():
    g = _bottom_groove()
    zf = g.face_position_m
    prof = grooved_ring("race", 3.235, 3.455, zf - 0.1, zf, [g])
    seg, _ = _segment_area(F * D, 0.030)
    assert prof.area_m2 == pytest.approx(0.22 * 0.1 - seg, rel=1e-12)
    # Pappus: the segment is symmetric about r = c_r
    rc = g.curvature_center_m[0]
    vol = 2 * math.pi * (0.22 * 0.1 * 3.345 - seg * rc)
    assert prof.revolved_properties(STEEL_KG_M3)["mass_kg"] == pytest.approx(STEEL_KG_M3 * vol, rel=1e-12)


def test_cylindrical_face_groove_mass_against_pappus():
    # radial ball groove (α = 0) in the outer face r = 0.45 m of an inner ring
    Db, f, depth = 0.020, 0.52, 0.003
    R = f * Db
    b_r = 0.45 + (R - depth) - (f - 0.5) * Db
    g = BallGroove(Db, f, 0.0, (b_r, 0.0), (-1, 1), depth, "outer", name="raceway")
    assert g.face_position_m == pytest.approx(0.45, abs=1e-15)
    prof = grooved_ring("inner ring", 0.40, 0.45, -0.02, 0.02, [g], {"inner": "bore"})
    seg, theta = _segment_area(R, depth)
    r_seg = g.curvature_center_m[0] - 4 * R * math.sin(theta / 2) ** 3 / (3 * (theta - math.sin(theta)))
    vol = 2 * math.pi * (0.05 * 0.04 * 0.425 - seg * r_seg)
    assert prof.area_m2 == pytest.approx(0.05 * 0.04 - seg, rel=1e-12)
    assert prof.revolved_properties(STEEL_KG_M3)["mass_kg"] == pytest.approx(STEEL_KG_M3 * vol, rel=1e-12)
    assert set(prof.names) == {"bottom", "outer", "raceway", "top", "bore"}
    assert len(_segments(prof, "outer")) == 2


def test_two_grooves_on_one_face():
    Db, f, depth = 0.020, 0.53, 0.004
    gs = [BallGroove(Db, f, 45.0, (r, 0.0), (1, -1), depth, "top", name=f"groove{i}")
          for i, r in enumerate((0.50, 0.55))]
    zf = gs[0].face_position_m
    prof = grooved_ring("double", 0.46, 0.60, zf - 0.05, zf, gs)
    seg, _ = _segment_area(f * Db, depth)
    assert prof.area_m2 == pytest.approx(0.14 * 0.05 - 2 * seg, rel=1e-12)
    assert len(_segments(prof, "top")) == 3


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(groove_depth_m=0.06), "groove_depth_m.*180°"),  # deeper than f·D
        (dict(groove_depth_m=0.005), "contact point outside the groove: increase groove_depth_m"),
        (dict(groove_depth_m=0.0), "groove_depth_m"),
        (dict(conformity=0.5), "conformity"),
        (dict(ball_diameter_m=-1.0), "ball_diameter_m"),
        (dict(contact_angle_deg=95.0), "contact_angle_deg"),
        (dict(contact_signs=(1, 1)), "contact_signs"),
        (dict(contact_signs=(1, 0)), "contact_signs"),
        (dict(face="side"), "face"),
    ],
)
def test_groove_rejects_bad_input_naming_the_parameter(kwargs, match):
    with pytest.raises(ValueError, match=match):
        dataclasses.replace(_bottom_groove(), **kwargs)


def test_grooved_ring_rejects_misplaced_grooves():
    g = _bottom_groove()
    zf = g.face_position_m
    with pytest.raises(ValueError, match="z_max_m"):
        grooved_ring("race", 3.235, 3.455, zf - 0.1, zf + 0.001, [g])
    with pytest.raises(ValueError, match="widen the face"):
        grooved_ring("race", 3.30, 3.455, zf - 0.1, zf, [g])
    with pytest.raises(ValueError, match="face_names"):
        grooved_ring("race", 3.235, 3.455, zf - 0.1, zf, [g], {"front": "x"})
    with pytest.raises(ProfileError, match="r_out_m"):
        grooved_ring("race", 3.5, 3.455, zf - 0.1, zf, [g])


# -- slewing ring ---------------------------------------------------------------------------------------
def test_slewing_races_gap_names_and_groove_margin():
    bottom, top, tmr = slewing_bottom_race(), slewing_top_race(), slewing_tmr()
    # face z of the bottom race: c_z − f·D + depth, c_z = (f − ½)·D·sin α; point-symmetric top race
    R, cz = F * D, (F - 0.5) * D * math.sin(math.radians(ALPHA))
    gap = 2.0 * (R - 0.030 - cz)
    assert bottom.bounds_m[3] == pytest.approx(-gap / 2, abs=1e-12)
    assert top.bounds_m[2] - bottom.bounds_m[3] == pytest.approx(gap, abs=1e-12)
    assert gap == pytest.approx(0.035888, abs=1e-6) and gap > 0.0
    assert _disjoint(_boundary(bottom), _boundary(top))
    assert tmr.bounds_m[2] == pytest.approx(top.bounds_m[3], abs=1e-15)  # TMR sits on the top race
    assert set(bottom.names) == {"bolt_face", "outer", "top", "groove", "bore"}
    assert set(top.names) == {"bottom", "groove", "outer", "bolt_face", "bore"}
    assert set(tmr.names) == {"race_face", "outer", "load_face", "bore"}
    assert _segments(bottom, "bolt_face")[0].start[1] == pytest.approx(bottom.bounds_m[2], abs=1e-15)
    assert _segments(tmr, "race_face")[0].start[1] == pytest.approx(_segments(top, "bolt_face")[0].start[1], abs=1e-15)
    # arc reaches ≥ 10° beyond the contact point for nominal and loaded contact angles (60–65°)
    for race in ("bottom", "top"):
        g = SlewingSection().groove(race, 6.69)
        for alpha in (55.0, 60.0, 65.0):
            assert g.edge_margin_deg(alpha) >= 10.0
        assert g.edge_margin_deg(60.0) == pytest.approx(math.degrees(math.acos((R - 0.030) / R)) - 30.0, abs=1e-9)


def test_slewing_ball_stays_outside_the_races():
    # ball shrunk by 1 µm: the sampled groove's chords cut 0.13 µm into the groove circle
    ang = np.linspace(0.0, 2 * math.pi, 2001)
    ball = np.column_stack((3.345 + (0.5 * D - 1e-6) * np.cos(ang), (0.5 * D - 1e-6) * np.sin(ang)))
    for prof in (slewing_bottom_race(), slewing_top_race()):
        groove = _segments(prof, "groove")[0]
        dist = np.linalg.norm(ball - np.asarray(groove.center), axis=1)
        assert dist.max() <= groove.radius_m + 1e-12  # ball inside the groove circle
        assert not _inside(_boundary(prof, 512), ball).any()


@pytest.mark.parametrize("pitch_m, mass_t", [(6.69, 3.25), (1.0, 0.486)])
def test_slewing_top_race_weight_matches_thesis(pitch_m, mass_t):
    m = slewing_top_race(pitch_m).revolved_properties(STEEL_KG_M3)["mass_kg"]
    assert m == pytest.approx(mass_t * 1000.0, rel=0.02)


def test_slewing_section_rejects_bad_input():
    with pytest.raises(ValueError, match="race_height_m"):
        SlewingSection(race_height_m=0.02)
    with pytest.raises(ValueError, match="tmr_width_m"):
        slewing_tmr(0.4)
    with pytest.raises(ValueError, match="pitch_diameter_m"):
        slewing_bottom_race(-1.0)
    with pytest.raises(ValueError, match="race_width_m"):
        slewing_top_race(section=SlewingSection(race_width_m=0.08))


# -- three-row roller bearing ---------------------------------------------------------------------------
GEOM = ThreeRowGeometry()


@pytest.mark.parametrize("ring, paper_kg", [(three_row_inner_ring, 2271.0 + 1700.0), (three_row_outer_ring, 3055.0)])
def test_three_row_ring_masses_match_paper(ring, paper_kg):
    assert ring(GEOM).revolved_properties(STEEL_KG_M3)["mass_kg"] == pytest.approx(paper_kg, rel=0.01)


def _line_span(profile, name):
    segs = _segments(profile, name)
    assert len(segs) == 1 and isinstance(segs[0], Line)
    return np.array([segs[0].start, segs[0].end])


def test_three_row_raceways_at_roller_positions():
    inner, outer = three_row_inner_ring(GEOM), three_row_outer_ring(GEOM)
    # radial row: pitch radius 0.9815 m ∓ 0.0275 m, 0.10 mm clearance on the nose tip
    ri, ro = _line_span(inner, "radial_raceway"), _line_span(outer, "radial_raceway")
    assert np.allclose(ri[:, 0], 0.9815 - 0.0275, atol=1e-15) and np.allclose(ro[:, 0], 0.9815 + 0.0275 + 0.10e-3, atol=1e-15)
    assert np.allclose(np.sort(ri[:, 1]), [-0.0275, 0.0275], atol=1e-15)
    assert np.allclose(np.sort(ro[:, 1]), [-0.0275, 0.0275], atol=1e-15)
    # thrust rows: roller centres z = ∓0.09 m, ± 0.030 m, 0.085 mm clearance on the nose
    for row, zc, s in (("front", -0.09, -1.0), ("rear", 0.09, 1.0)):
        fi, fo = _line_span(inner, f"{row}_thrust_raceway"), _line_span(outer, f"{row}_thrust_raceway")
        assert np.allclose(fi[:, 1], zc + s * 0.030, atol=1e-15)
        assert np.allclose(fo[:, 1], zc - s * (0.030 + 0.085e-3), atol=1e-15)
        for span in (fi, fo):
            assert np.allclose(np.sort(span[:, 0]), [1.091 - 0.030, 1.091 + 0.030], atol=1e-15)
    assert {"bore", "bolt_face", "rear_face", "flange_outer"} <= set(inner.names)
    assert {"front_face", "outer", "bolt_face", "nose_tip"} <= set(outer.names)
    assert _segments(inner, "bolt_face")[0].start[1] == -0.225 and _segments(outer, "bolt_face")[0].start[1] == 0.225
    assert inner.bounds_m[0] == pytest.approx(0.855) and outer.bounds_m[1] == pytest.approx(1.251)


def test_three_row_rings_rollers_and_cages_do_not_overlap():
    inner, outer = _boundary(three_row_inner_ring(GEOM)), _boundary(three_row_outer_ring(GEOM))
    assert _disjoint(inner, outer)
    rollers = [_box(*GEOM.radial_box_m), _box(*GEOM.thrust_box_m("front")), _box(*GEOM.thrust_box_m("rear"))]
    cages = [_boundary(p) for p, _ in three_row_cages(GEOM).values()]
    for body in rollers + cages:
        assert _disjoint(body, inner) and _disjoint(body, outer)
    # roller rectangles fill the gap between their raceways up to the clearance
    z_nose = GEOM.nose_z_m
    assert z_nose[0] - GEOM.thrust_box_m("front")[3] == pytest.approx(0.085e-3, abs=1e-15)
    assert GEOM.thrust_box_m("rear")[2] - z_nose[1] == pytest.approx(0.085e-3, abs=1e-15)


def test_three_row_cages_pockets_and_masses():
    cages = three_row_cages(GEOM)
    for key, (n, d, paper_kg) in {"radial": (98, 0.055, 70.0), "front_thrust": (94, 0.060, 90.2),
                                  "rear_thrust": (94, 0.060, 90.2)}.items():
        ring, pockets = cages[key]
        assert pockets.n_pockets == n and pockets.width_m == pytest.approx(d + 1e-3, abs=1e-15)
        r0, r1, z0, z1 = ring.bounds_m
        if pockets.axis == "radial":  # pocket: strip |y| ≤ a of the annulus r0..r1 (area 2∫√(r²−y²)dy), × h
            a = pockets.width_m / 2
            half = [a * math.sqrt(r * r - a * a) + r * r * math.asin(a / r) for r in (r0, r1)]
            v_pocket = (half[1] - half[0]) * pockets.height_m
        else:
            v_pocket = pockets.width_m * pockets.height_m * (z1 - z0)
        mass = ring.revolved_properties(STEEL_KG_M3)["mass_kg"] - STEEL_KG_M3 * n * v_pocket
        assert mass == pytest.approx(paper_kg, rel=0.05)
    # cage rings stay between the raceways of their rows
    r0, r1, _, _ = cages["radial"][0].bounds_m
    assert GEOM.radial_box_m[0] < r0 and r1 < GEOM.radial_outer_raceway_r_m
    _, _, z0, z1 = cages["front_thrust"][0].bounds_m
    assert GEOM.thrust_box_m("front")[2] < z0 and z1 < GEOM.nose_z_m[0]


def test_three_row_geometry_rejects_inconsistent_dimensions():
    with pytest.raises(ValueError, match="flange_diameter_m"):
        ThreeRowGeometry(flange_diameter_m=2.2)
    with pytest.raises(ValueError, match="outer_ring_z_m"):
        ThreeRowGeometry(outer_ring_z_m=(-0.05, 0.225))
    with pytest.raises(ValueError, match="bore_diameter_m"):
        ThreeRowGeometry(bore_diameter_m=1.95)


# -- cages ----------------------------------------------------------------------------------------------
def test_cage_pockets_overlap_names_n_pockets():
    # chord between neighbours 2R·sin(π/n) must exceed the pocket width: 0.1 m on R = 1 m fits n ≤ 62
    CagePockets(62, "cylinder", "radial", 1.0, radius_m=0.05)
    with pytest.raises(ValueError, match="n_pockets"):
        CagePockets(63, "cylinder", "radial", 1.0, radius_m=0.05)
    with pytest.raises(ValueError, match="n_pockets"):
        CagePockets(63, "box", "axial", 1.0, width_m=0.1, height_m=0.05)
    with pytest.raises(ValueError, match="width_m"):
        CagePockets(10, "box", "axial", 1.0, height_m=0.05)
    with pytest.raises(ValueError, match="axis"):
        CagePockets(10, "box", "tangential", 1.0, width_m=0.05, height_m=0.05)
    p = CagePockets(4, "box", "axial", 1.0, width_m=0.1, height_m=0.1, angle_offset_deg=45.0)
    assert np.allclose(np.degrees(p.angles_rad), [45.0, 135.0, 225.0, 315.0], atol=1e-12)


def test_ball_cage_ring_and_pockets():
    ring, pockets = ball_cage("ball cage", n_balls=20, ball_diameter_m=0.02, pitch_diameter_m=0.5,
                              thickness_m=0.008, extent_m=0.03)
    assert pockets.radius_m == pytest.approx(0.0105, abs=1e-15) and pockets.shape == "cylinder"
    assert pockets.pitch_radius_m == 0.25 and pockets.axis == "radial"
    assert ring.bounds_m == pytest.approx((0.246, 0.254, -0.015, 0.015), abs=1e-12)
    with pytest.raises(ValueError, match="extent_m"):
        ball_cage("c", n_balls=20, ball_diameter_m=0.02, pitch_diameter_m=0.5, thickness_m=0.008, extent_m=0.02)
    with pytest.raises(ValueError, match="thickness_m"):
        ball_cage("c", n_balls=20, ball_diameter_m=0.02, pitch_diameter_m=0.5, thickness_m=0.03, extent_m=0.03)
    with pytest.raises(ValueError, match="n_pockets"):
        ball_cage("c", n_balls=80, ball_diameter_m=0.02, pitch_diameter_m=0.5, thickness_m=0.008, extent_m=0.03)
