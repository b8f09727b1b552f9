"""Grooves made of one or more circular arcs, cut into one face of a rectangular ring section.

A groove is a chain of arcs given by their curvature centres (r, z), radii and the polar angles
(in the (r, z) plane, about each centre) at which each arc starts and ends. One arc is a plain ball
groove; two arcs meeting at an apex on the ball's mid-plane are a gothic arch (four-point contact
groove). Both ends of the chain must lie on the face the groove is cut into — a plane z = const
(``"top"``/``"bottom"`` face) or a cylinder r = const (``"inner"``/``"outer"`` face) — and the chain
must run into the material behind that face. :func:`fem_rings.sections.grooved_ring` cuts such
grooves (and :class:`fem_rings.sections.BallGroove`) into a rectangle.

A V-groove (:class:`VGroove`) is the straight counterpart: two flanks from the face to an apex
behind it, the raceways of a crossed roller row.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .profile import Arc, Line

__all__ = ["ArcGroove", "VGroove", "FACE_AXES"]

#: face → (index of the coordinate that is constant on it, unit vector into the material)
FACE_AXES = {"bottom": (1, (0.0, 1.0)), "top": (1, (0.0, -1.0)),
             "inner": (0, (1.0, 0.0)), "outer": (0, (-1.0, 0.0))}


def _check_face(name: str, face: str) -> None:
    if face not in FACE_AXES:
        raise ValueError(f"groove {name!r}: face must be one of {sorted(FACE_AXES)}, got {face!r}")


def _point(centre, radius_m: float, angle_rad: float) -> tuple[float, float]:
    return (float(centre[0] + radius_m * math.cos(angle_rad)), float(centre[1] + radius_m * math.sin(angle_rad)))


@dataclass(frozen=True)
class ArcGroove:
    """A groove of arcs in one face of a section.

    Parameters
    ----------
    face : {"top", "bottom", "inner", "outer"}
        Face the groove is cut into.
    arcs : tuple of (centre (r, z) m, radius m, start angle rad, end angle rad)
        The arcs in order along the groove; arc k ends where arc k + 1 starts. Angles are polar
        angles about the arc's centre, counter-clockwise positive; each arc sweeps less than 180°.
    name : str
        Segment name of every arc (a raceway is sampled by this name).
    """

    face: str
    arcs: tuple
    name: str = "groove"

    def __post_init__(self) -> None:
        _check_face(self.name, self.face)
        arcs = tuple((tuple(map(float, c)), float(r), float(a0), float(a1)) for c, r, a0, a1 in self.arcs)
        if not arcs:
            raise ValueError(f"groove {self.name!r}: needs at least one arc")
        object.__setattr__(self, "arcs", arcs)
        size = max(r for _, r, _, _ in arcs)
        for k, (c, r, a0, a1) in enumerate(arcs):
            if not (r > 0.0 and 0.0 < abs(a1 - a0) < math.pi):
                raise ValueError(f"groove {self.name!r}: arc {k} needs a radius > 0 and a sweep in (0°, 180°)")
            if k and math.dist(_point(c, r, a0), self.segments_points[k - 1][1]) > 1e-9 * size:
                raise ValueError(f"groove {self.name!r}: arc {k} does not start where arc {k - 1} ends")
        j = FACE_AXES[self.face][0]
        a, b = self.segments_points[0][0], self.segments_points[-1][1]
        if abs(a[j] - b[j]) > 1e-9 * size:
            raise ValueError(f"groove {self.name!r}: its ends lie at {'rz'[j]} = {a[j]:.9g} m and {b[j]:.9g} m, "
                             f"not on one {self.face} face")
        if not self.depth_m > 0.0:
            raise ValueError(f"groove {self.name!r}: does not run into the material behind the {self.face} face")

    @property
    def segments_points(self) -> list[tuple[tuple[float, float], tuple[float, float]]]:
        """(start, end) (r, z) of every arc, m."""
        return [(_point(c, r, a0), _point(c, r, a1)) for c, r, a0, a1 in self.arcs]

    @property
    def face_position_m(self) -> float:
        """z (top/bottom face) or r (inner/outer face) of the face, m."""
        return float(self.segments_points[0][0][FACE_AXES[self.face][0]])

    @property
    def edge_points_m(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """Where the groove meets the face, ordered by increasing coordinate along the face, m."""
        a, b = self.segments_points[0][0], self.segments_points[-1][1]
        j = 1 - FACE_AXES[self.face][0]
        return (a, b) if a[j] <= b[j] else (b, a)

    @property
    def depth_m(self) -> float:
        """Largest distance of the groove behind its face, m (sampled along the arcs)."""
        j, into = FACE_AXES[self.face]
        x = self.face_position_m
        deepest = 0.0
        for c, r, a0, a1 in self.arcs:
            for t in np.linspace(0.0, 1.0, 33):
                p = _point(c, r, a0 + t * (a1 - a0))
                deepest = max(deepest, (p[j] - x) * into[j])
        return deepest

    def segments(self) -> tuple[list[Arc], tuple]:
        """The arcs as profile segments from the lower to the higher edge point, and the edge points."""
        out = [Arc(_point(c, r, a0), _point(c, r, a1), c, a1 > a0, self.name) for c, r, a0, a1 in self.arcs]
        lo, hi = self.edge_points_m
        if math.dist(out[0].start, lo) > math.dist(out[0].start, hi):
            out = [a.reversed() for a in reversed(out)]
        return out, (lo, hi)


@dataclass(frozen=True)
class VGroove:
    """A V-groove of two straight flanks in one face of a section (a crossed roller row's raceways).

    Parameters
    ----------
    face : {"top", "bottom", "inner", "outer"}
        Face the groove is cut into.
    points : ((r, z), (r, z), (r, z)), m
        First flank's edge on the face, the apex, second flank's edge on the face.
    name : str
        Segment name of both flanks (a raceway is sampled by this name).
    """

    face: str
    points: tuple
    name: str = "groove"

    def __post_init__(self) -> None:
        _check_face(self.name, self.face)
        pts = tuple(tuple(map(float, q)) for q in self.points)
        if len(pts) != 3 or any(len(q) != 2 for q in pts):
            raise ValueError(f"groove {self.name!r}: needs three (r, z) points (edge, apex, edge)")
        object.__setattr__(self, "points", pts)
        a, apex, b = pts
        j, into = FACE_AXES[self.face]
        size = max(math.dist(a, apex), math.dist(apex, b))
        if not size > 0.0 or abs(a[j] - b[j]) > 1e-9 * size:
            raise ValueError(f"groove {self.name!r}: its edges lie at {'rz'[j]} = {a[j]:.9g} m and {b[j]:.9g} m, "
                             f"not on one {self.face} face")
        if not self.depth_m > 1e-9 * size:
            raise ValueError(f"groove {self.name!r}: does not run into the material behind the {self.face} face")

    @property
    def face_position_m(self) -> float:
        """z (top/bottom face) or r (inner/outer face) of the face, m."""
        return self.points[0][FACE_AXES[self.face][0]]

    @property
    def edge_points_m(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """Where the groove meets the face, ordered by increasing coordinate along the face, m."""
        a, b = self.points[0], self.points[2]
        j = 1 - FACE_AXES[self.face][0]
        return (a, b) if a[j] <= b[j] else (b, a)

    @property
    def depth_m(self) -> float:
        """Distance of the apex behind the face, m."""
        j, into = FACE_AXES[self.face]
        return (self.points[1][j] - self.face_position_m) * into[j]

    def segments(self) -> tuple[list[Line], tuple]:
        """The flanks as profile segments from the lower to the higher edge point, and the edge points."""
        lo, hi = self.edge_points_m
        apex = self.points[1]
        return [Line(lo, apex, self.name), Line(apex, hi, self.name)], (lo, hi)
