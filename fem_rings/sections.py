"""Parametric cross-sections of bearing rings and cages in the (r, z) plane, SI units.

Ball grooves are arcs of radius f·D about the curvature centre c = b − (f − ½)·D·n, with b the
ball centre and n the unit contact direction from the ball centre to the contact point, so the
contact point b + ½·D·n lies on the arc. The groove meets a flat face (z = const) or a cylindrical
face (r = const) at two edge points; its depth is measured from that face to the deepest point.

Slewing ring of a fast-reactor rotatable plug (angular-contact thrust ball bearing, α = 60°, D = 95.25 mm,
f = 0.525, ball centres at r = pitch/2, z = 0). The thesis gives no cross-sections; chosen here:

=================  =========  ===========================================================
dimension          default    why
=================  =========  ===========================================================
race width         220 mm     with the height, the top race weighs 3.30 t at Ø6.69 m
race height        100 mm     (thesis: 3.25 t, and 0.486 t at Ø1 m, i.e. the same section)
groove depth       30 mm      0.31·D; arc half-angle 66.4° about c: the arc covers contact
                              angles 23.6°–156.4°, ≥ 36° beyond the nominal 60° contact and
                              more under load (60–65°); the race faces keep a 35.9 mm gap
TMR width          500 mm     solid ring centred on the pitch circle, stiff against bending,
TMR height         400 mm     sitting on the top race's bolt face
=================  =========  ===========================================================

Bottom race: groove in its top face, contact direction (+cos α, −sin α); top race: groove in its
bottom face, (−cos α, +sin α); both sections are centred on the pitch radius. Segment names:
``groove``, ``bolt_face`` (bottom race: bottom face on the support; top race: top face under the
TMR), ``bore``, ``outer``, ``top``/``bottom`` (the face pieces beside the groove); TMR:
``race_face``, ``load_face``, ``bore``, ``outer``.

12 MW three-row roller main bearing (conventions of :mod:`cases.catalog`: +z from the
rotor to the rear). Raceways sit where the rollers and clearances put them: radial raceways at
r = 0.9815 ∓ 0.0275 m (+0.10 mm on the nose tip), thrust raceways at z = ∓0.09 ∓ 0.030 m on the
inner-ring flanges and ∓0.09 ± (0.030 + 0.085e-3) m on the nose. Raceway segments span the nominal
roller length; the rest of each face is a land of its own name. Free dimensions, tuned to the
paper's ring masses with steel 7850 kg/m³:

=========================  =========  =====================================================
dimension                  default    why
=========================  =========  =====================================================
inner-ring flange Ø        2300 mm    29 mm beyond the thrust rollers' outer ends
outer-ring body bore Ø     2330 mm    15 mm radial gap to the flanges (seal space)
inner ring z range         −225…215   bolted on its front face (hub side); rear face
                                      recessed 10 mm so the main frame clears it
outer ring z range         −175…225   bolted on its rear face (main frame); front recessed
                                      so the hub clears it and the mass matches
=========================  =========  =====================================================

Achieved masses: inner ring 3977 kg (paper 2271 + 1700 = 3971 kg, +0.2 %), outer ring 3051 kg
(paper 3055 kg, −0.1 %); the tests hold them within 1 %. Cages: :mod:`fem_rings.cages`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from foundation.validation import check_positive

from .arc_grooves import FACE_AXES as _FACES
from .profile import Arc, Line, Profile, polygon, rectangle

__all__ = [
    "BallGroove", "ball_groove_arc", "grooved_ring",
    "SlewingSection", "slewing_bottom_race", "slewing_top_race", "slewing_tmr", "slewing_top_structure",
    "ThreeRowGeometry", "three_row_outer_ring", "three_row_inner_ring",
]

Point = tuple[float, float]

def _positive(value: float, what: str) -> float:
    """The shared positive-number check (:func:`foundation.validation.check_positive`), returning the value."""
    check_positive(**{what: value})
    return float(value)


def _ascending(items) -> None:
    """Check (label, value) pairs increase strictly; the error names both labels."""
    for (la, a), (lb, b) in zip(items, items[1:]):
        if not b > a:
            raise ValueError(f"{lb} ({b:.6g} m) must exceed {la} ({a:.6g} m)")


# -- ball grooves ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class BallGroove:
    """A ball groove cut into one face of a ring section.

    Parameters
    ----------
    ball_diameter_m : float
        Ball diameter D, m.
    conformity : float
        Groove radius over ball diameter f (> 0.5).
    contact_angle_deg : float
        Contact angle α in [0, 90]°, measured from the radial plane.
    ball_center_m : (r, z), m
        Ball centre.
    contact_signs : (s_r, s_z), each ±1
        Contact direction from the ball centre n = (s_r·cos α, s_z·sin α).
    groove_depth_m : float
        Depth from the face to the deepest point of the groove, 0 < depth < f·D, m.
    face : {"top", "bottom", "inner", "outer"}
        Face of the section the groove is cut into (top/bottom: z = const, inner/outer: r = const).
    name : str
        Name of the groove arc segment.
    """

    ball_diameter_m: float
    conformity: float
    contact_angle_deg: float
    ball_center_m: Point
    contact_signs: tuple[int, int]
    groove_depth_m: float
    face: str
    name: str = "groove"

    def __post_init__(self) -> None:
        _positive(self.ball_diameter_m, "ball_diameter_m")
        if not self.conformity > 0.5:
            raise ValueError(f"conformity must exceed 0.5 (groove radius above the ball radius), got {self.conformity!r}")
        if not 0.0 <= self.contact_angle_deg <= 90.0:
            raise ValueError(f"contact_angle_deg must lie in [0, 90], got {self.contact_angle_deg!r}")
        signs = tuple(self.contact_signs)
        if len(signs) != 2 or any(s not in (-1, 1) for s in signs):
            raise ValueError(f"contact_signs must be two signs (±1, ±1), got {self.contact_signs!r}")
        object.__setattr__(self, "contact_signs", (int(signs[0]), int(signs[1])))
        object.__setattr__(self, "ball_center_m", tuple(float(x) for x in self.ball_center_m[:2]))
        if self.face not in _FACES:
            raise ValueError(f"face must be one of {sorted(_FACES)}, got {self.face!r}")
        _positive(self.groove_depth_m, "groove_depth_m")
        R = self.radius_m
        if not self.groove_depth_m < R:
            raise ValueError(
                f"groove {self.name!r}: groove_depth_m ({self.groove_depth_m:.6g} m) must be below the groove "
                f"radius f·D = {R:.6g} m; a deeper groove sweeps more than 180° and undercuts the face")
        if not float(np.dot(self.direction(), _FACES[self.face][1])) > 0.0:
            raise ValueError(f"groove {self.name!r}: contact_signs {self.contact_signs} point away from the "
                             f"material behind the {self.face} face")
        if not self.edge_margin_deg() > 0.0:
            raise ValueError(f"groove {self.name!r}: contact point outside the groove: increase groove_depth_m "
                             f"(arc half-angle {math.degrees(self.half_angle_rad):.2f}°)")

    @property
    def radius_m(self) -> float:
        """Groove radius f·D, m."""
        return self.conformity * self.ball_diameter_m

    def direction(self, contact_angle_deg: float | None = None) -> np.ndarray:
        """Unit contact direction n from the ball centre at ``contact_angle_deg`` (default α), (2,)."""
        a = math.radians(self.contact_angle_deg if contact_angle_deg is None else contact_angle_deg)
        return np.array([self.contact_signs[0] * math.cos(a), self.contact_signs[1] * math.sin(a)])

    @property
    def curvature_center_m(self) -> np.ndarray:
        """c = b − (f − ½)·D·n, (2,) m."""
        return np.asarray(self.ball_center_m) - (self.conformity - 0.5) * self.ball_diameter_m * self.direction()

    @property
    def contact_point_m(self) -> np.ndarray:
        """b + ½·D·n = c + f·D·n, (2,) m."""
        return np.asarray(self.ball_center_m) + 0.5 * self.ball_diameter_m * self.direction()

    @property
    def deepest_point_m(self) -> np.ndarray:
        """Point of the groove farthest from the face, (2,) m."""
        return self.curvature_center_m + self.radius_m * np.asarray(_FACES[self.face][1])

    @property
    def face_position_m(self) -> float:
        """z (top/bottom face) or r (inner/outer face) of the face plane or cylinder, m."""
        k, m = _FACES[self.face]
        return float(self.curvature_center_m[k] + m[k] * (self.radius_m - self.groove_depth_m))

    @property
    def half_angle_rad(self) -> float:
        """Half the arc's sweep about the curvature centre, rad (< π/2)."""
        return math.acos((self.radius_m - self.groove_depth_m) / self.radius_m)

    @property
    def edge_points_m(self) -> tuple[Point, Point]:
        """Where the groove meets the face, ordered by increasing coordinate along the face, m."""
        c, w, x = self.curvature_center_m, self.radius_m * math.sin(self.half_angle_rad), self.face_position_m
        if _FACES[self.face][0] == 1:
            return (float(c[0] - w), x), (float(c[0] + w), x)
        return (x, float(c[1] - w)), (x, float(c[1] + w))

    def edge_margin_deg(self, contact_angle_deg: float | None = None) -> float:
        """Arc angle about c from the contact point at ``contact_angle_deg`` (default α) to the nearer
        groove edge, degrees; negative when that contact point lies outside the groove."""
        cos_psi = float(np.dot(self.direction(contact_angle_deg), _FACES[self.face][1]))
        return math.degrees(self.half_angle_rad - math.acos(min(1.0, max(-1.0, cos_psi))))

    def segments(self) -> tuple[list[Arc], tuple[Point, Point]]:
        """The groove arc as profile segments from the lower to the higher edge point, and the edge points."""
        arc, edges = ball_groove_arc(self)
        return [arc], edges


def ball_groove_arc(groove: BallGroove, name: str | None = None) -> tuple[Arc, tuple[Point, Point]]:
    """The groove arc and its two edge points on the face.

    Returns
    -------
    arc : Arc
        From the lower to the higher edge point (coordinate along the face) through the deepest
        point, named ``name`` or ``groove.name``.
    edges : ((r, z), (r, z)), m
        The edge points in the same order.
    """
    lo, hi = groove.edge_points_m
    c, q = groove.curvature_center_m, groove.deepest_point_m
    ccw = (lo[0] - c[0]) * (q[1] - c[1]) - (lo[1] - c[1]) * (q[0] - c[0]) > 0.0
    arc = Arc(lo, hi, (float(c[0]), float(c[1])), bool(ccw), name or groove.name)
    return arc, (lo, hi)


def grooved_ring(name: str, r_in_m: float, r_out_m: float, z_min_m: float, z_max_m: float,
                 grooves=(), face_names: dict | None = None) -> Profile:
    """Rectangular section with ball grooves cut into its faces.

    Parameters
    ----------
    name : str
        Profile name.
    r_in_m, r_out_m, z_min_m, z_max_m : float
        The rectangle, m. Each groove's ``face_position_m`` must equal the coordinate of its face.
    grooves : sequence of BallGroove or :class:`fem_rings.arc_grooves.ArcGroove`
        Any number per face, not overlapping each other or the corners.
    face_names : dict, optional
        Names of the face pieces beside the grooves, keyed ``"top"``, ``"bottom"``, ``"inner"``,
        ``"outer"`` (default: the keys themselves).
    """
    rectangle(name, r_in_m, r_out_m, z_min_m, z_max_m)  # validates the box
    names = {f: f for f in _FACES} | dict(face_names or {})
    if set(names) - set(_FACES):
        raise ValueError(f"face_names keys must be among {sorted(_FACES)}, got {sorted(set(names) - set(_FACES))}")
    corners = [(r_in_m, z_min_m), (r_out_m, z_min_m), (r_out_m, z_max_m), (r_in_m, z_max_m)]
    faces = (("bottom", "z_min_m", z_min_m), ("outer", "r_out_m", r_out_m),
             ("top", "z_max_m", z_max_m), ("inner", "r_in_m", r_in_m))
    tol = 1e-9 * max(1.0, *(abs(c) for c in (r_in_m, r_out_m, z_min_m, z_max_m)))
    segs = []
    for i, (face, param, coord) in enumerate(faces):
        start, end = corners[i], corners[(i + 1) % 4]
        j = 1 - _FACES[face][0]
        sgn = 1.0 if end[j] > start[j] else -1.0
        pos = start
        for g in sorted((g for g in grooves if g.face == face), key=lambda g: sgn * sum(p[j] for p in g.edge_points_m)):
            if abs(g.face_position_m - coord) > tol:
                raise ValueError(f"groove {g.name!r} lies on the plane {'rz'[1 - j]} = {g.face_position_m:.9g} m "
                                 f"(from its centre and depth) but {param} = {coord:.9g} m")
            arcs, (lo, hi) = g.segments()
            if sgn < 0.0:
                arcs, lo, hi = [a.reversed() for a in reversed(arcs)], hi, lo
            if not sgn * (lo[j] - pos[j]) > tol:
                raise ValueError(f"groove {g.name!r} runs past a corner or into another groove on the {face} "
                                 f"face of {name!r}: widen the face or move ball_center_m")
            segs += [Line(pos, lo, names[face]), *arcs]
            pos = hi
        if not sgn * (end[j] - pos[j]) > tol:
            raise ValueError(f"a groove runs past the end of the {face} face of {name!r}: widen the face "
                             f"or move ball_center_m")
        segs.append(Line(pos, end, names[face]))
    return Profile(name, tuple(segs))


# -- slewing ring ----------------------------------------------------------------------
@dataclass(frozen=True)
class SlewingSection:
    """Cross-section data of the slewing ring's races and TMR (defaults and reasons: module docstring).

    Parameters
    ----------
    ball_diameter_m, conformity, contact_angle_deg, groove_depth_m
        Load balls and grooves (both races alike), see :class:`BallGroove`.
    race_width_m, race_height_m : float
        Radial × axial size of each race's rectangle before the groove is cut, m.
    tmr_width_m, tmr_height_m : float
        Radial × axial size of the top-and-middle ring, m.
    """

    ball_diameter_m: float = 95.25e-3
    conformity: float = 0.525
    contact_angle_deg: float = 60.0
    groove_depth_m: float = 0.030
    race_width_m: float = 0.220
    race_height_m: float = 0.100
    tmr_width_m: float = 0.500
    tmr_height_m: float = 0.400

    def __post_init__(self) -> None:
        for f in ("race_width_m", "race_height_m", "tmr_width_m", "tmr_height_m"):
            _positive(getattr(self, f), f)
        if not self.race_height_m > self.groove_depth_m:
            raise ValueError(f"race_height_m ({self.race_height_m}) must exceed groove_depth_m ({self.groove_depth_m})")

    def groove(self, race: str, pitch_diameter_m: float) -> BallGroove:
        """Groove of the ``"bottom"`` race (in its top face) or the ``"top"`` race (in its bottom face)."""
        if race not in ("bottom", "top"):
            raise ValueError(f"race must be 'bottom' or 'top', got {race!r}")
        signs, face = {"bottom": ((1, -1), "top"), "top": ((-1, 1), "bottom")}[race]
        return BallGroove(self.ball_diameter_m, self.conformity, self.contact_angle_deg,
                          (0.5 * _positive(pitch_diameter_m, "pitch_diameter_m"), 0.0), signs,
                          self.groove_depth_m, face)

    def race(self, race: str, pitch_diameter_m: float, name: str) -> Profile:
        """Section of the ``"bottom"`` or ``"top"`` race, centred on the pitch radius."""
        g = self.groove(race, pitch_diameter_m)
        r0, r1 = 0.5 * (pitch_diameter_m - self.race_width_m), 0.5 * (pitch_diameter_m + self.race_width_m)
        z = sorted((g.face_position_m, g.face_position_m + (self.race_height_m if race == "top" else -self.race_height_m)))
        lo, hi = g.edge_points_m
        if not (r0 < lo[0] and hi[0] < r1):
            raise ValueError(f"race_width_m ({self.race_width_m}) is narrower than the groove ({hi[0] - lo[0]:.6g} m)")
        bolted = "top" if race == "top" else "bottom"
        return grooved_ring(name, r0, r1, z[0], z[1], (g,), {bolted: "bolt_face", "inner": "bore"})


def slewing_bottom_race(pitch_diameter_m: float = 6.69, section: SlewingSection = SlewingSection(),
                        name: str = "bottom race") -> Profile:
    """Bottom (fixed) race: groove in the top face, bolted on its bottom face."""
    return section.race("bottom", pitch_diameter_m, name)


def slewing_top_race(pitch_diameter_m: float = 6.69, section: SlewingSection = SlewingSection(),
                     name: str = "top race") -> Profile:
    """Top (rotating) race: groove in the bottom face, bolted to the TMR on its top face."""
    return section.race("top", pitch_diameter_m, name)


def slewing_tmr(pitch_diameter_m: float = 6.69, section: SlewingSection = SlewingSection(),
                name: str = "TMR") -> Profile:
    """Top-and-middle ring: solid rectangle on the pitch circle, on the top race's bolt face."""
    z0 = section.groove("top", pitch_diameter_m).face_position_m + section.race_height_m
    r0, r1 = 0.5 * (pitch_diameter_m - section.tmr_width_m), 0.5 * (pitch_diameter_m + section.tmr_width_m)
    if not r0 > 0.0:
        raise ValueError(f"tmr_width_m ({section.tmr_width_m}) must be below pitch_diameter_m ({pitch_diameter_m})")
    z1 = z0 + section.tmr_height_m
    return polygon(name, [(r0, z0), (r1, z0), (r1, z1), (r0, z1)], ["race_face", "outer", "load_face", "bore"])


def slewing_top_structure(pitch_diameter_m: float = 6.69, section: SlewingSection = SlewingSection(),
                          name: str = "top structure") -> Profile:
    """Top race with the TMR bolted on its top face, as one section (one flexible body).

    The TMR must be wider than the race on both sides. Segments: those of the top race with its
    ``bolt_face`` replaced by ``tmr_underside`` (the TMR overhangs), ``tmr_outer``, ``load_face``
    and ``tmr_bore``.
    """
    race = slewing_top_race(pitch_diameter_m, section, name)
    tmr = slewing_tmr(pitch_diameter_m, section)
    r0, r1, z0, z1 = tmr.bounds_m
    segs = []
    for seg in race.segments:
        if seg.name != "bolt_face":
            segs.append(seg)
            continue
        (a_r, z), (b_r, _) = seg.start, seg.end
        lo, hi = min(a_r, b_r), max(a_r, b_r)
        if not (r0 < lo and hi < r1):
            raise ValueError(f"tmr_width_m ({section.tmr_width_m}) must exceed race_width_m ({section.race_width_m})")
        outline = [(hi, z), (r1, z), (r1, z1), (r0, z1), (r0, z), (lo, z)]
        names = ["tmr_underside", "tmr_outer", "load_face", "tmr_bore", "tmr_underside"]
        if a_r < b_r:  # same orientation as the replaced face
            outline, names = outline[::-1], names[::-1]
        segs += [Line(outline[i], outline[i + 1], names[i]) for i in range(5)]
    return Profile(name, tuple(segs))


# -- three-row roller main bearing -------------------------------------------------------
@dataclass(frozen=True)
class ThreeRowGeometry:
    """Rollers, clearances and ring dimensions of the three-row roller bearing (module docstring).

    Roller rows: count, diameter, length, pitch diameter and axial position of each row, m; the
    radial clearance sits on the nose tip, the axial clearance on each nose face. Rings: bore and
    outer diameters, the inner ring's flange diameter, the outer ring's body bore (above and below
    the nose) and each ring's (z_front, z_rear), m. Construction checks that the parts nest in
    order; errors name the offending dimension.
    """

    n_radial: int = 98
    radial_roller_diameter_m: float = 55e-3
    radial_roller_length_m: float = 55e-3
    radial_pitch_diameter_m: float = 1.963
    radial_z_m: float = 0.0
    radial_clearance_m: float = 0.10e-3
    n_thrust: int = 94
    thrust_roller_diameter_m: float = 60e-3
    thrust_roller_length_m: float = 60e-3
    thrust_pitch_diameter_m: float = 2.182
    front_thrust_z_m: float = -0.09
    rear_thrust_z_m: float = 0.09
    axial_clearance_m: float = 0.085e-3
    bore_diameter_m: float = 1.710
    outer_diameter_m: float = 2.502
    flange_diameter_m: float = 2.300
    outer_ring_bore_diameter_m: float = 2.330
    inner_ring_z_m: tuple[float, float] = (-0.225, 0.215)
    outer_ring_z_m: tuple[float, float] = (-0.175, 0.225)

    def __post_init__(self) -> None:
        r, z = self.radial_box_m, self.thrust_box_m("front")
        _ascending([("bore_diameter_m/2", self.bore_diameter_m / 2), ("radial inner raceway r", r[0]),
                    ("radial outer raceway r (nose tip)", self.radial_outer_raceway_r_m),
                    ("thrust rollers' inner end r", z[0]), ("thrust rollers' outer end r", z[1]),
                    ("flange_diameter_m/2", self.flange_diameter_m / 2),
                    ("outer_ring_bore_diameter_m/2", self.outer_ring_bore_diameter_m / 2),
                    ("outer_diameter_m/2", self.outer_diameter_m / 2)])
        _ascending([("inner_ring_z_m[0]", self.inner_ring_z_m[0]), ("front flange face z", z[2]),
                    ("front nose face z", self.nose_z_m[0]), ("radial rollers' front end z", r[2]),
                    ("radial rollers' rear end z", r[3]), ("rear nose face z", self.nose_z_m[1]),
                    ("rear flange face z", self.thrust_box_m("rear")[3]), ("inner_ring_z_m[1]", self.inner_ring_z_m[1])])
        _ascending([("outer_ring_z_m[0]", self.outer_ring_z_m[0]), ("front nose face z", self.nose_z_m[0])])
        _ascending([("rear nose face z", self.nose_z_m[1]), ("outer_ring_z_m[1]", self.outer_ring_z_m[1])])

    @property
    def radial_box_m(self) -> tuple[float, float, float, float]:
        """(r_min, r_max, z_min, z_max) of a radial roller's axial section, m."""
        rp, d, L = self.radial_pitch_diameter_m / 2, self.radial_roller_diameter_m, self.radial_roller_length_m
        return rp - d / 2, rp + d / 2, self.radial_z_m - L / 2, self.radial_z_m + L / 2

    def thrust_box_m(self, row: str) -> tuple[float, float, float, float]:
        """(r_min, r_max, z_min, z_max) of a ``"front"`` or ``"rear"`` thrust roller's section, m."""
        z = {"front": self.front_thrust_z_m, "rear": self.rear_thrust_z_m}[row]
        rp, d, L = self.thrust_pitch_diameter_m / 2, self.thrust_roller_diameter_m, self.thrust_roller_length_m
        return rp - L / 2, rp + L / 2, z - d / 2, z + d / 2

    @property
    def radial_outer_raceway_r_m(self) -> float:
        return self.radial_box_m[1] + self.radial_clearance_m

    @property
    def nose_z_m(self) -> tuple[float, float]:
        """z of the nose's front and rear faces (thrust raceways with the clearance), m."""
        return (self.thrust_box_m("front")[3] + self.axial_clearance_m, self.thrust_box_m("rear")[2] - self.axial_clearance_m)


def _face(p0: Point, p1: Point, cuts, land: str, raceway: str) -> list[Line]:
    """Straight face p0 → p1 split at the two points ``cuts`` (in order) into land, raceway, land."""
    a, b = cuts
    return [Line(p0, a, land), Line(a, b, raceway), Line(b, p1, land)]


def three_row_outer_ring(geometry: ThreeRowGeometry = ThreeRowGeometry(), name: str = "outer ring") -> Profile:
    """Fixed outer ring with the nose between the thrust rows; bolted on its rear face.

    Segments: ``front_face``, ``outer``, ``bolt_face``, ``bore`` (body cylinder above and below
    the nose), ``nose_rear_face``/``rear_thrust_raceway``, ``nose_tip``/``radial_raceway``,
    ``nose_front_face``/``front_thrust_raceway``.
    """
    g = geometry
    rb, ro, rt = g.outer_ring_bore_diameter_m / 2, g.outer_diameter_m / 2, g.radial_outer_raceway_r_m
    (z0, z1), (zf, zr) = g.outer_ring_z_m, g.nose_z_m
    t0, t1 = g.thrust_box_m("front")[:2]
    rz0, rz1 = g.radial_box_m[2:]
    segs = [Line((rb, z0), (ro, z0), "front_face"), Line((ro, z0), (ro, z1), "outer"),
            Line((ro, z1), (rb, z1), "bolt_face"), Line((rb, z1), (rb, zr), "bore"),
            *_face((rb, zr), (rt, zr), ((t1, zr), (t0, zr)), "nose_rear_face", "rear_thrust_raceway"),
            *_face((rt, zr), (rt, zf), ((rt, rz1), (rt, rz0)), "nose_tip", "radial_raceway"),
            *_face((rt, zf), (rb, zf), ((t0, zf), (t1, zf)), "nose_front_face", "front_thrust_raceway"),
            Line((rb, zf), (rb, z0), "bore")]
    return Profile(name, tuple(segs))


def three_row_inner_ring(geometry: ThreeRowGeometry = ThreeRowGeometry(), name: str = "inner ring") -> Profile:
    """Rotating C-shaped inner ring (two pieces as one body) round the nose; bolted on its front face.

    Segments: ``bolt_face``, ``flange_outer``, ``front_flange_face``/``front_thrust_raceway``,
    ``web_face``/``radial_raceway``, ``rear_flange_face``/``rear_thrust_raceway``, ``rear_face``,
    ``bore``.
    """
    g = geometry
    ri, rf, rw = g.bore_diameter_m / 2, g.flange_diameter_m / 2, g.radial_box_m[0]
    z0, z1 = g.inner_ring_z_m
    zf, zr = g.thrust_box_m("front")[2], g.thrust_box_m("rear")[3]
    t0, t1 = g.thrust_box_m("front")[:2]
    rz0, rz1 = g.radial_box_m[2:]
    segs = [Line((ri, z0), (rf, z0), "bolt_face"), Line((rf, z0), (rf, zf), "flange_outer"),
            *_face((rf, zf), (rw, zf), ((t1, zf), (t0, zf)), "front_flange_face", "front_thrust_raceway"),
            *_face((rw, zf), (rw, zr), ((rw, rz0), (rw, rz1)), "web_face", "radial_raceway"),
            *_face((rw, zr), (rf, zr), ((t0, zr), (t1, zr)), "rear_flange_face", "rear_thrust_raceway"),
            Line((rf, zr), (rf, z1), "flange_outer"), Line((rf, z1), (ri, z1), "rear_face"),
            Line((ri, z1), (ri, z0), "bore")]
    return Profile(name, tuple(segs))
