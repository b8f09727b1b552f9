"""Ring cross-sections read from DXF drawings (fem_rings.dxf_section).

The drawings are written here with ezdxf; areas and first moments of area are checked against
closed forms computed in this file independently of the profile's Gauss–Green quadrature: the
shoelace formula for the polygon of the segment end points plus, for each arc, the signed circular
segment between arc and chord, area ρ²/2 (θ − sin θ) with its centroid 4ρ sin³(θ/2) / (3(θ − sin θ))
from the centre along the bisector (e.g. Gieck, Engineering Formulas, section B, "circular segment").
"""

import math
import random

import ezdxf
import pytest

from fem_rings import sections
from fem_rings.dxf_section import profile_from_dxf
from fem_rings.profile import Arc, Line, ProfileError

# Tolerance 1e-9 relative: the drawing stores coordinates and angles as doubles; the only error is
# the rounding of cos/sin of the arc angles (~1e-16) and the profile's 24-point Gauss rule on arcs.
REL = 1e-9


# -- independent reference: polygon + circular segments --------------------------------------------

def _segment_area_and_moment(p, q, c, ccw):
    """Signed area between an arc and its chord and its first moment ∫∫ r dA (>0 when ccw)."""
    rho = math.dist(p, c)
    a0, a1 = math.atan2(p[1] - c[1], p[0] - c[0]), math.atan2(q[1] - c[1], q[0] - c[0])
    th = ((a1 - a0) if ccw else (a0 - a1)) % (2 * math.pi)
    area = rho * rho / 2 * (th - math.sin(th))
    d = 4 * rho * math.sin(th / 2) ** 3 / (3 * (th - math.sin(th)))
    mid = a0 + (th / 2 if ccw else -th / 2)
    r_c = c[0] + d * math.cos(mid)
    sign = 1.0 if ccw else -1.0
    return sign * area, sign * area * r_c


def reference_area_and_moment(chain):
    """Area and ∫∫ r dA of a closed chain [(p, q, centre or None, ccw)], positive counter-clockwise."""
    area = moment = 0.0
    for p, q, c, ccw in chain:
        cross = p[0] * q[1] - q[0] * p[1]
        area += cross / 2
        moment += (p[0] + q[0]) * cross / 6
        if c is not None:
            a, m = _segment_area_and_moment(p, q, c, ccw)
            area, moment = area + a, moment + m
    return area, moment


def profile_area_and_moment(profile):
    # ∫∫ r dA = V / (2π) (Pappus), V from the revolved mass at unit density
    return profile.area_m2, profile.revolved_properties(1.0)["mass_kg"] / (2 * math.pi)


def _deg(p, c):
    return math.degrees(math.atan2(p[1] - c[1], p[0] - c[0]))


def add_arc(msp, p, q, c, ccw, layer):
    """DXF ARC from p to q about c (DXF arcs run counter-clockwise from start to end angle)."""
    lo, hi = (p, q) if ccw else (q, p)
    msp.add_arc(c, math.dist(p, c), _deg(lo, c), _deg(hi, c), dxfattribs={"layer": layer})


def write(tmp_path, build, name="section.dxf", insunits=4):
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = insunits  # 4: mm (ezdxf's new drawings say 6, metres)
    build(doc.modelspace())
    path = tmp_path / name
    doc.saveas(path)
    return path


# -- a rectangle with a gothic-arch groove on the outer face -------------------------------------

Ri, Ro, H, ZC = 400.0, 450.0, 60.0, 30.0          # mm
RHO, E, RC = 10.0, 1.0, Ro + 2.0                    # groove radius, centre offset, centre radius, mm


def gothic_chain():
    """The section, counter-clockwise, in mm: [(p, q, centre or None, ccw, layer)]."""
    zf = math.sqrt(RHO**2 - (RC - Ro) ** 2)          # face points at ZC ± (zf − E)
    lo_face, hi_face = (Ro, ZC + E - zf), (Ro, ZC - E + zf)
    bottom = (RC - math.sqrt(RHO**2 - E**2), ZC)     # where the two arcs meet
    return [
        ((Ri, 0.0), (Ro, 0.0), None, True, "bottom"),
        ((Ro, 0.0), lo_face, None, True, "outer"),
        (lo_face, bottom, (RC, ZC + E), False, "groove"),  # lower flank, centre above the groove axis
        (bottom, hi_face, (RC, ZC - E), False, "groove"),
        (hi_face, (Ro, H), None, True, "outer"),
        ((Ro, H), (Ri, H), None, True, "top"),
        ((Ri, H), (Ri, 0.0), None, True, "0"),
    ]


def draw_chain(msp, chain, reverse_some=False):
    for k, (p, q, c, ccw, layer) in enumerate(chain):
        if reverse_some and k % 2:
            p, q, ccw = q, p, not ccw  # the same curve drawn the other way
        if c is None:
            msp.add_line(p, q, dxfattribs={"layer": layer})
        else:
            add_arc(msp, p, q, c, ccw, layer)


@pytest.mark.parametrize("reverse_some", [False, True])
def test_gothic_groove_section_area_moment_and_names(tmp_path, reverse_some):
    chain = gothic_chain()
    path = write(tmp_path, lambda msp: draw_chain(msp, chain, reverse_some))
    prof = profile_from_dxf(path, name="inner ring", unit="mm")
    ref_area, ref_moment = reference_area_and_moment(
        [(tuple(x * 1e-3 for x in p), tuple(x * 1e-3 for x in q), c and tuple(x * 1e-3 for x in c), ccw)
         for p, q, c, ccw, _ in chain])
    area, moment = profile_area_and_moment(prof)
    assert area == pytest.approx(ref_area, rel=REL)
    assert moment == pytest.approx(ref_moment, rel=REL)
    assert sorted(prof.names) == ["bottom", "face", "groove", "outer", "top"]   # layer 0 → "face"
    arcs = [s for s in prof.segments if isinstance(s, Arc)]
    assert [s.name for s in arcs] == ["groove", "groove"]
    assert all(s.radius_m == pytest.approx(RHO * 1e-3, rel=REL) for s in arcs)
    # the groove bottom lies inside the material: both arcs run clockwise in the ccw section
    assert not any(s.ccw for s in arcs)
    # layer_names=False names every segment "face"
    assert profile_from_dxf(path, name="x", layer_names=False).names == ("face",)


def test_drawing_in_metres_and_insunits(tmp_path):
    chain = [(tuple(x * 1e-3 for x in p), tuple(x * 1e-3 for x in q), c and tuple(x * 1e-3 for x in c), ccw, ly)
             for p, q, c, ccw, ly in gothic_chain()]
    in_m = write(tmp_path, lambda msp: draw_chain(msp, chain), "m.dxf", insunits=6)
    in_mm = write(tmp_path, lambda msp: draw_chain(msp, gothic_chain()), "mm.dxf", insunits=4)
    a_m = profile_from_dxf(in_m, name="m", unit="m").area_m2
    assert profile_from_dxf(in_m, name="m", unit="file").area_m2 == a_m
    assert profile_from_dxf(in_mm, name="mm", unit="file").area_m2 == pytest.approx(a_m, rel=REL)
    with pytest.raises(ProfileError, match=r"m\.dxf: unit='mm' disagrees with the drawing's \$INSUNITS = 6 \(m\)"):
        profile_from_dxf(in_m, name="m", unit="mm")
    no_header = write(tmp_path, lambda msp: draw_chain(msp, gothic_chain()), "plain.dxf", insunits=0)
    with pytest.raises(ProfileError, match=r"plain\.dxf: \$INSUNITS is not set"):
        profile_from_dxf(no_header, name="p", unit="file")
    with pytest.raises(ProfileError, match="unit must be"):
        profile_from_dxf(no_header, name="p", unit="inch")


# -- polylines with bulges -------------------------------------------------------------------------

def _bulge_centre(p, q, b):
    """Centre of the bulge arc, found as the circumcentre of p, q and the arc midpoint.

    The arc midpoint lies at the sagitta s = b·c/2 from the chord midpoint, to the right of the
    chord direction for b > 0 (DXF Reference: bulge = tan(θ/4), positive counter-clockwise).
    """
    c = math.dist(p, q)
    ux, uy = (q[0] - p[0]) / c, (q[1] - p[1]) / c
    s = b * c / 2
    m = ((p[0] + q[0]) / 2 + uy * s, (p[1] + q[1]) / 2 - ux * s)
    (ax, ay), (bx, by), (cx, cy) = p, q, m
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    x = ((ax**2 + ay**2) * (by - cy) + (bx**2 + by**2) * (cy - ay) + (cx**2 + cy**2) * (ay - by)) / d
    y = ((ax**2 + ay**2) * (cx - bx) + (bx**2 + by**2) * (ax - cx) + (cx**2 + cy**2) * (bx - ax)) / d
    return (x, y)


def _bulge_chain(points):
    out = []
    for k, (x, y, b) in enumerate(points):
        q = points[(k + 1) % len(points)][:2]
        out.append(((x, y), q, None if b == 0 else _bulge_centre((x, y), q, b), b > 0))
    return out


BULGED = [(100.0, 0.0, 0.0), (200.0, 0.0, 0.5), (200.0, 50.0, -0.25), (100.0, 50.0, 0.0)]  # mm, ccw
MAJOR = [(100.0, 0.0, 2.0), (140.0, 0.0, 0.0)]  # an arc of 4·atan 2 = 253° closed by its chord


@pytest.mark.parametrize("points,polyline2d", [(BULGED, False), (BULGED, True), (MAJOR, True)])
def test_polyline_with_bulges(tmp_path, points, polyline2d):
    def build(msp):
        if polyline2d:
            msp.add_polyline2d([(x, y, 0, 0, b) for x, y, b in points], format="xyseb", close=True,
                               dxfattribs={"layer": "skin"})
        else:
            msp.add_lwpolyline(points, format="xyb", close=True, dxfattribs={"layer": "skin"})
    prof = profile_from_dxf(write(tmp_path, build), name="bulged", unit="mm")
    ref = reference_area_and_moment([(tuple(v * 1e-3 for v in p), tuple(v * 1e-3 for v in q),
                                      c and tuple(v * 1e-3 for v in c), ccw) for p, q, c, ccw in _bulge_chain(points)])
    area, moment = profile_area_and_moment(prof)
    assert area == pytest.approx(ref[0], rel=REL)
    assert moment == pytest.approx(ref[1], rel=REL)
    assert prof.names == ("skin",)
    if points is MAJOR:  # the 253° arc is split into two arcs of at most a half circle
        arcs = [s for s in prof.segments if isinstance(s, Arc)]
        assert len(arcs) == 2
        assert sum(s.sweep_rad for s in arcs) == pytest.approx(4 * math.atan(2.0), rel=REL)


def test_arc_with_downward_extrusion_is_mirrored(tmp_path):
    # Half disc r ∈ [100, 140] mm on the axis z = 0, its arc stored in a mirrored object coordinate
    # system (extrusion −z, as some CAD programs write): object x = −drawing x (arbitrary axis
    # algorithm), and the arc runs counter-clockwise about −z.
    def build(msp):
        msp.add_line((100, 0), (140, 0))
        # drawing arc from (140, 0) to (100, 0) about (120, 0) ccw through (120, 20): in object
        # coordinates centre (−120, 0), from angle 180° − 0° to 180° − 180° about −z
        msp.add_arc((-120, 0), 20, 0, 180, dxfattribs={"extrusion": (0, 0, -1)})
    prof = profile_from_dxf(write(tmp_path, build), name="half disc", unit="mm")
    # reference: half disc of radius a = 20 mm at r = 120 mm: A = πa²/2, ∫∫ r dA = A·120 mm
    a = 0.020
    assert prof.area_m2 == pytest.approx(math.pi * a * a / 2, rel=REL)
    assert profile_area_and_moment(prof)[1] == pytest.approx(math.pi * a * a / 2 * 0.120, rel=REL)
    assert prof.bounds_m[3] == pytest.approx(0.020, rel=1e-6)   # the arc is above z = 0


# -- round trip ------------------------------------------------------------------------------------

def write_profile(profile, path, seed=0):
    """Profile → DXF: one LINE or ARC per segment on the layer of its name, shuffled, some reversed."""
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 6  # m
    msp = doc.modelspace()
    segs = list(profile.segments)
    rng = random.Random(seed)
    rng.shuffle(segs)
    for k, s in enumerate(segs):
        if k % 3 == 1:
            s = s.reversed()
        layer = "0" if s.name == "face" else s.name
        if isinstance(s, Line):
            msp.add_line(s.start, s.end, dxfattribs={"layer": layer})
        else:
            add_arc(msp, s.start, s.end, s.center, s.ccw, layer)
    doc.saveas(path)


@pytest.mark.parametrize("make", [
    lambda: sections.slewing_bottom_race(2.0),
    lambda: sections.three_row_outer_ring(),
])
def test_round_trip_gives_the_same_segments(tmp_path, make):
    prof = make()
    path = tmp_path / "rt.dxf"
    write_profile(prof, path)
    back = profile_from_dxf(path, name=prof.name, unit="m")
    assert len(back.segments) == len(prof.segments)
    # same cyclic chain: rotate to the segment that starts where the original's first one does
    tol = 1e-9 * prof.size_m
    k0 = next(k for k, s in enumerate(back.segments) if math.dist(s.start, prof.segments[0].start) < tol)
    for k, s in enumerate(prof.segments):
        b = back.segments[(k0 + k) % len(back.segments)]
        assert type(b) is type(s) and b.name == s.name
        assert math.dist(b.start, s.start) < tol and math.dist(b.end, s.end) < tol
        if isinstance(s, Arc):
            assert b.ccw == s.ccw and math.dist(b.center, s.center) < tol


# -- errors name the file and the place ------------------------------------------------------------

def rect(msp, x0=100, x1=150, y0=0, y1=40, layer="0"):
    pts = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    for k in range(4):
        msp.add_line(pts[k], pts[(k + 1) % 4], dxfattribs={"layer": layer})


def test_unreadable_and_empty_files(tmp_path):
    junk = tmp_path / "junk.dxf"
    junk.write_text("this is not a drawing\n")
    with pytest.raises(ProfileError, match=r"junk\.dxf: not a DXF file"):
        profile_from_dxf(junk, name="x")
    with pytest.raises(ProfileError, match=r"missing\.dxf: no such file"):
        profile_from_dxf(tmp_path / "missing.dxf", name="x")
    only_text = write(tmp_path, lambda msp: msp.add_text("hello"), "text.dxf")
    with pytest.raises(ProfileError, match=r"text\.dxf: no LINE, ARC or polyline in model space \(found 1 TEXT\)"):
        profile_from_dxf(only_text, name="x")


def test_open_section_reports_gap_and_place(tmp_path):
    def build(msp):
        msp.add_line((100, 0), (150, 0))
        msp.add_line((150, 0), (150, 40))
        msp.add_line((150, 40), (100, 40))
        msp.add_line((100, 40), (100, 0.25), dxfattribs={"layer": "bore"})  # stops 0.25 mm short
    with pytest.raises(ProfileError, match=r"open\.dxf: the section is not closed: gap of 0\.25 mm between the "
                                           r"open ends at \(r, z\) = \(100, 0\) mm \(LINE #\w+ on layer '0'\) and "
                                           r"\(100, 0\.25\) mm \(LINE #\w+ on layer 'bore'\); 2 open ends"):
        profile_from_dxf(write(tmp_path, build, "open.dxf"), name="x")


def test_two_loops_branch_and_wrong_side_of_axis(tmp_path):
    two = write(tmp_path, lambda msp: (rect(msp), rect(msp, 200, 250)), "two.dxf")
    with pytest.raises(ProfileError, match=r"two\.dxf: 2 separate closed loops"):
        profile_from_dxf(two, name="x")
    branch = write(tmp_path, lambda msp: (rect(msp), msp.add_line((150, 40), (170, 60))), "branch.dxf")
    with pytest.raises(ProfileError, match=r"branch\.dxf: the outline branches at \(r, z\) = \(150, 40\) mm: 3 pieces"):
        profile_from_dxf(branch, name="x")
    twice = write(tmp_path, lambda msp: (rect(msp), msp.add_line((100, 40), (100, 0))), "twice.dxf")
    with pytest.raises(ProfileError, match=r"twice\.dxf: the outline branches at \(r, z\) = \(100, 0\) mm: 3 pieces.*"
                                           r"LINE #\w+ on layer '0' and LINE #\w+ on layer '0' join the same two points"):
        profile_from_dxf(twice, name="x")
    left = write(tmp_path, lambda msp: rect(msp, -150, -100), "left.dxf")
    with pytest.raises(ProfileError, match=r"left\.dxf: LINE #\w+ on layer '0' reaches r < 0 at \(r, z\) = \(-150, 0\) mm"):
        profile_from_dxf(left, name="x")


@pytest.mark.parametrize("add,kind", [
    (lambda msp: msp.add_spline([(100, 0), (120, 10), (150, 0)], dxfattribs={"layer": "groove"}), "SPLINE"),
    (lambda msp: msp.add_ellipse((120, 20), (10, 0), 0.5, dxfattribs={"layer": "groove"}), "ELLIPSE"),
])
def test_unsupported_entities_are_named_with_their_layer(tmp_path, add, kind):
    path = write(tmp_path, lambda msp: (rect(msp), add(msp)), "curvy.dxf")
    with pytest.raises(ProfileError, match=rf"curvy\.dxf: {kind} #\w+ on layer 'groove': entity type {kind} is not supported"):
        profile_from_dxf(path, name="x")


def test_circle_is_refused(tmp_path):
    path = write(tmp_path, lambda msp: msp.add_circle((120, 20), 10, dxfattribs={"layer": "hole"}), "circle.dxf")
    with pytest.raises(ProfileError, match=r"circle\.dxf: CIRCLE #\w+ on layer 'hole': a full circle is not a section"):
        profile_from_dxf(path, name="x")


def test_profile_checks_are_prefixed_with_the_file(tmp_path):
    # a closed loop that crosses itself passes the chaining and is refused by Profile
    bow = write(tmp_path, lambda msp: [msp.add_line(p, q) for p, q in
                                       [((100, 0), (150, 40)), ((150, 40), (150, 0)), ((150, 0), (100, 40)),
                                        ((100, 40), (100, 0))]], "bow.dxf")
    with pytest.raises(ProfileError, match=r"bow\.dxf: profile 'x': boundary crosses itself"):
        profile_from_dxf(bow, name="x")


def test_arc_bulging_across_the_axis_is_refused(tmp_path):
    # ends at r = 5 mm, but the arc about (5, 0) of radius 10 mm reaches r = −5 mm at z = 0
    def build(msp):
        msp.add_line((5, -10), (5, 10))
        msp.add_arc((5, 0), 10, 90, 270, dxfattribs={"layer": "nose"})
    with pytest.raises(ProfileError, match=r"nose\.dxf: ARC #\w+ on layer 'nose' reaches r < 0 at \(r, z\) = \(-5, 0\) mm"):
        profile_from_dxf(write(tmp_path, build, "nose.dxf"), name="x")


def test_endpoints_within_the_tolerance_are_joined(tmp_path):
    # Half disc of radius 20 mm about (120, 0) (size 40 mm, joining tolerance 1e-6·40 mm = 4e-5 mm),
    # its diameter drawn 2e-5 mm short at both ends: joined, and the arc keeps one radius.
    def build(msp):
        msp.add_line((100 + 2e-5, 1e-5), (140 - 2e-5, -1e-5), dxfattribs={"layer": "flat"})
        msp.add_arc((120, 0), 20, 0, 180, dxfattribs={"layer": "round"})
    prof = profile_from_dxf(write(tmp_path, build, "near.dxf"), name="x")
    # reference: πa²/2 with a = 20 mm; each joined point is the mean of the two ends, 1e-5 mm inside
    # the circle, so the arc's radius shrinks by 1e-5 mm: area −2·1e-5/20 = −1e-6 relative
    assert prof.area_m2 == pytest.approx(math.pi * 0.020**2 / 2 * (1 - 1e-6), rel=1e-8)
    assert prof.names == ("flat", "round") or prof.names == ("round", "flat")
