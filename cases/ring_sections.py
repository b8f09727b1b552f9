"""Cross-sections of a described bearing's rings, and where each row's raceway lies in them.

The raceway geometry comes from the rows the solver uses (:func:`mbd_core.quasistatic.elements.build_groups`
at the first element of each row, in its meridian plane), so a section built here agrees with the
load-distribution model to round-off:

- ball row: the ring's groove is an arc of radius f·D about the ring's groove curvature centre. In a
  box section it is cut symmetric about the face normal, with half-angle max(|α| + 25°, 50°)
  (α the unloaded contact angle from that normal), capped at 80° — an assumption: a groove deep enough
  for the contact ellipse at loaded angles, whose exact depth barely changes how the ring bends.
  Raceway sample: the contact point at the unloaded contact angle.
- four-point row: a gothic arch, the arcs of the two diagonals' curvature centres (f·D) from their
  apex on the ball's mid-plane up to the row's shoulder angle, where the land (the face) begins.
  Raceway sample: the apex (it lies on both arcs, f·D from both centres).
- roller row (radial or thrust): the raceway is the flat or cylindrical face half a roller
  diameter from the roller axis. Raceway sample: the circle under the roller's middle.
- crossed roller row: a V-groove, one flank per diagonal, each half a roller diameter from the
  roller axis along that diagonal's normal (the other diagonal's normal is the first mirrored about
  the row's mid-plane); each flank runs from the apex to the end of its roller's contact line, where
  the land (the face) begins. Raceway sample: the apex (on both flanks); a roller's slices are
  coupled to it as the balls of a four-point row are to theirs, through the section's displacement
  and rotation there (:mod:`mbd_core.quasistatic.flexible`).

Box section (``section = "box"``): a rectangle whose face towards the rolling elements carries the
grooves and is placed by them (at the groove edges, or on the roller raceway); the user gives the
other three sides. Profile section (``section = "profile"``): the user's closed chain of lines and
arcs (:mod:`fem_rings.profile`); each row's raceway must lie on one of its segments.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fem_rings.arc_grooves import FACE_AXES, ArcGroove, VGroove
from fem_rings.nodesets import point_segment_distance
from fem_rings.profile import Profile
from fem_rings.sections import grooved_ring
from mbd_core.quasistatic import Bearing
from mbd_core.quasistatic.elements import build_groups
from mbd_core.quasistatic.rows import BallRow, FourPointRow, RollerRow

__all__ = ["RacewayPlace", "raceway_places", "box_section", "match_raceways", "raceway_segment_name",
           "GROOVE_MIN_HALF_ANGLE_DEG", "GROOVE_EXTRA_ANGLE_DEG", "GROOVE_MAX_HALF_ANGLE_DEG"]

GROOVE_MIN_HALF_ANGLE_DEG = 50.0
GROOVE_EXTRA_ANGLE_DEG = 25.0
GROOVE_MAX_HALF_ANGLE_DEG = 80.0
#: A raceway point counts as on a profile segment within this fraction of the element's diameter.
ON_SEGMENT_RTOL = 1e-3


def raceway_segment_name(row: str) -> str:
    """Name of the box section's segment carrying ``row``'s raceway (and of its raceway sample)."""
    return f"raceway {row}"


@dataclass(frozen=True)
class RacewayPlace:
    """A row's raceway on one ring, in the ring's (r, z) section.

    point_rz_m : (2,) the raceway sample point, m
    face : str
        The box face the raceway lies in ("inner", "outer", "top", "bottom").
    arcs : tuple
        Groove arcs (centre, radius, start angle, end angle) for :class:`fem_rings.arc_grooves.ArcGroove`;
        empty for a roller raceway (the face itself).
    directions : tuple of str
        Load directions of the ring's raceway load shapes (:class:`cms_reduction.RacewaySpec`).
    flanks : tuple
        A crossed roller row's V-groove (edge, apex, edge) for :class:`fem_rings.arc_grooves.VGroove`;
        empty otherwise.
    """

    row: str
    point_rz_m: tuple
    face: str
    arcs: tuple
    directions: tuple
    flanks: tuple = ()


def _rz(p: np.ndarray, psi: float) -> np.ndarray:
    """(r, z) of a point in the meridian plane at azimuth ψ."""
    return np.array([p[0] * math.cos(psi) + p[1] * math.sin(psi), p[2]])


def _face_of(direction_rz: np.ndarray) -> str:
    """The face whose into-material normal is closest to ``direction_rz``."""
    return max(FACE_AXES, key=lambda f: float(np.dot(FACE_AXES[f][1], direction_rz)))


def _angle(v) -> float:
    return math.atan2(float(v[1]), float(v[0]))


def _ball_place(row, psi: float, centres_rz: list[np.ndarray], into_rz: list[np.ndarray], radius_m: float):
    """Groove arcs of one ring of a ball row: ``centres_rz``/``into_rz`` per diagonal (one for a BallRow)."""
    if isinstance(row, FourPointRow):
        mid_z = 0.5 * (centres_rz[0][1] + centres_rz[1][1])
        arcs = []
        for c, n in zip(centres_rz, into_rz):
            s = math.copysign(1.0, n[1])  # this diagonal's contact side along z
            sh = np.array([math.copysign(math.cos(row.shoulder_angle_rad), n[0]), s * math.sin(row.shoulder_angle_rad)])
            a_sh = _angle(sh)
            x = (mid_z - c[1]) / radius_m
            a_apex = math.asin(x) if n[0] > 0 else math.pi - math.asin(x)
            a_apex = a_sh + math.remainder(a_apex - a_sh, 2.0 * math.pi)
            arcs.append((c, a_sh, a_apex))
        (c0, sh0, ap0), (c1, sh1, ap1) = arcs
        face = _face_of(np.array([math.copysign(1.0, into_rz[0][0]), 0.0]))
        apex = c0 + radius_m * np.array([math.cos(ap0), math.sin(ap0)])
        return RacewayPlace(row.name, tuple(apex), face,
                            ((tuple(c0), radius_m, sh0, ap0), (tuple(c1), radius_m, ap1, sh1)), ("radial", "axial"))
    c, n = centres_rz[0], into_rz[0]
    face = _face_of(n)
    m = np.asarray(FACE_AXES[face][1])
    tilt = math.degrees(math.acos(min(1.0, abs(float(np.dot(n, m))))))
    half = math.radians(min(max(tilt + GROOVE_EXTRA_ANGLE_DEG, GROOVE_MIN_HALF_ANGLE_DEG), GROOVE_MAX_HALF_ANGLE_DEG))
    a_m = _angle(m)
    return RacewayPlace(row.name, tuple(c + radius_m * n), face,
                        ((tuple(c), radius_m, a_m - half, a_m + half),), ("normal",))


def _roller_place(row: RollerRow, axis_rz: np.ndarray, normal_rz: np.ndarray, side: str) -> RacewayPlace:
    """The moving ring's raceway lies half a roller diameter before the axis along the load normal,
    the fixed ring's beyond it (:mod:`mbd_core.quasistatic.flexible`)."""
    into = -normal_rz if side == "moving" else normal_rz
    point = axis_rz + 0.5 * row.roller_diameter_m * into
    return RacewayPlace(row.name, tuple(point), _face_of(into), (), ("normal",))


def _crossed_place(row: RollerRow, axis_rz: np.ndarray, normal_rz: np.ndarray, side: str) -> RacewayPlace:
    """The V-groove of a crossed roller row on one ring (module docstring): the apex lies half a
    roller diameter from the roller axis along both diagonals' into-ring normals."""
    into = [-normal_rz if side == "moving" else normal_rz]
    into.append(np.array([into[0][0], -into[0][1]]))
    half = 0.5 * row.roller_diameter_m
    apex = axis_rz + np.linalg.solve(np.array(into), np.array([half, half]))
    edges = []
    for n in into:
        middle = axis_rz + half * n           # the middle of the roller's contact line on this flank
        t = (middle - apex) / np.linalg.norm(middle - apex)
        edges.append(apex + (np.linalg.norm(middle - apex) + 0.5 * row.roller_length_m) * t)
    face = _face_of(into[0] + into[1])
    return RacewayPlace(row.name, tuple(apex), face, (), ("radial", "axial"),
                        (tuple(edges[0]), tuple(apex), tuple(edges[1])))


def raceway_places(bearing: Bearing, side: str) -> dict[str, RacewayPlace]:
    """Row name → raceway of the ``"moving"`` or ``"fixed"`` ring, from the solver's own geometry."""
    balls, slices = build_groups(bearing)
    out = {}
    for i, row in enumerate(bearing.rows):
        psi = row.first_azimuth_rad
        if isinstance(row, (BallRow, FourPointRow)):
            sel = np.flatnonzero((balls.row == i) & (balls.element == 0))
            cm = [_rz(balls.p_m[k], psi) for k in sel]
            cf = [_rz(balls.p_m[k] - balls.s0_m[k], psi) for k in sel]
            s_hat = [(a - b) / np.linalg.norm(a - b) for a, b in zip(cm, cf)]
            if side == "moving":
                out[row.name] = _ball_place(row, psi, cm, [-s for s in s_hat], row.conformity_moving * row.ball_diameter_m)
            else:
                out[row.name] = _ball_place(row, psi, cf, s_hat, row.conformity_fixed * row.ball_diameter_m)
        elif isinstance(row, RollerRow):
            sel = np.flatnonzero((slices.row == i) & (slices.element == 0))
            axis = _rz(slices.p_m[sel].mean(axis=0), psi)
            normal = _rz(slices.normal[sel[0]], psi)
            place = _crossed_place if row.orientation == "crossed" else _roller_place
            out[row.name] = place(row, axis, normal, side)
        else:
            raise ValueError(f"row {row.name!r} ({type(row).__name__}): modal rings do not take this row type; "
                             "leave out the [rings] tables (rigid rings)")
    return out


def box_section(name: str, places: dict[str, RacewayPlace], sides: dict[str, float | None]) -> Profile:
    """A rectangle with the rows' grooves cut into its face towards the rolling elements.

    ``sides``: ``r_in_m``, ``r_out_m``, ``z_min_m``, ``z_max_m`` (None: placed by the raceways on that
    face). Raises ValueError starting with the side's name when a side is missing, or given on the
    raceway face but not where the raceways put it.
    """
    faces = {p.face for p in places.values()}
    if len(faces) != 1:
        raise ValueError("rows: the rows' raceways lie on different faces of this ring "
                         f"({', '.join(sorted(faces))}); give its section as a profile of lines and arcs")
    face = faces.pop()
    k = FACE_AXES[face][0]
    side_of = {"inner": "r_in_m", "outer": "r_out_m", "bottom": "z_min_m", "top": "z_max_m"}
    grooves = [ArcGroove(face, p.arcs, raceway_segment_name(p.row)) for p in places.values() if p.arcs]
    grooves += [VGroove(face, p.flanks, raceway_segment_name(p.row)) for p in places.values() if p.flanks]
    positions = [g.face_position_m for g in grooves]
    positions += [p.point_rz_m[k] for p in places.values() if not (p.arcs or p.flanks)]
    land = float(np.mean(positions))
    size = max(abs(land), 1e-3)
    if max(positions) - min(positions) > 1e-9 * size:
        raise ValueError(f"{side_of[face]}: the rows' raceways put the {face} face at different places "
                         f"({min(positions):.6g} m … {max(positions):.6g} m); give a profile section")
    given = sides.get(side_of[face])
    if given is not None and abs(given - land) > 1e-6 * size:
        raise ValueError(f"{side_of[face]}: the raceways put this face at {land:.6g} m, not {given:.6g} m "
                         "(leave the key out: the face towards the rolling elements is placed by them)")
    box = dict(sides)
    box[side_of[face]] = land
    for key in side_of.values():
        if box.get(key) is None:
            raise ValueError(f"{key}: missing key (the box section needs this side)")
    names = {f: f for f in FACE_AXES}
    if not grooves:
        names[face] = raceway_segment_name(next(iter(places)))
        if len(places) > 1:
            raise ValueError(f"rows: {len(places)} roller rows share one flat face; give a profile section")
    return grooved_ring(name, box["r_in_m"], box["r_out_m"], box["z_min_m"], box["z_max_m"], grooves, names)


def match_raceways(profile: Profile, places: dict[str, RacewayPlace], size_m: dict[str, float]) -> dict[str, str]:
    """Row name → name of the profile segment its raceway point lies on.

    ``size_m``: each row's element diameter (the tolerance is :data:`ON_SEGMENT_RTOL` of it).
    Raises ValueError naming the row when no segment passes through its raceway, or when two
    rows' raceways lie on segments of the same name (their samples would clash).
    """
    out, used = {}, {}
    for row, place in places.items():
        q = np.asarray(place.point_rz_m, dtype=float)
        d = [float(point_segment_distance(q, s)[0]) for s in profile.segments]
        k = int(np.argmin(d))
        if d[k] > ON_SEGMENT_RTOL * size_m[row]:
            raise ValueError(f"no segment passes through the raceway of row {row!r} at (r, z) = "
                             f"({q[0] * 1e3:.6g}, {q[1] * 1e3:.6g}) mm (nearest: segment {k}, "
                             f"{profile.segments[k].name!r}, {d[k] * 1e3:.4g} mm away)")
        seg = profile.segments[k].name
        if seg in used:
            raise ValueError(f"rows {used[seg]!r} and {row!r} have their raceways on segments named {seg!r}; "
                             "name the segments differently")
        used[seg], out[row] = row, seg
    return out
