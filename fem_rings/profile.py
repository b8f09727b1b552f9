"""Closed 2-D cross-sections of rings in the (r, z) plane, made of named lines and arcs.

A profile is revolved about the z axis to give a ring (``fem_rings.mesh``). Every segment carries a
name (``"groove"``, ``"bore"``, ``"bolt_face"`` …); the surfaces it sweeps become named node and
facet sets of the finite-element model, so raceways and supports are found by name.

Coordinates are metres: r ≥ 0 is the distance from the axis, z the axial position.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Line", "Arc", "Profile", "ProfileError", "polygon", "rectangle"]


class ProfileError(ValueError):
    """A cross-section is not a valid closed, simple region of positive thickness."""


Point = tuple[float, float]


def _as_point(p, what: str) -> Point:
    try:
        if len(p) != 2:
            raise ValueError
        r, z = (float(p[0]), float(p[1]))
    except (TypeError, ValueError, IndexError):
        raise ProfileError(f"{what} must be an (r, z) pair in metres, got {p!r}") from None
    if not (math.isfinite(r) and math.isfinite(z)):
        raise ProfileError(f"{what} must be finite, got {p!r}")
    return (r, z)


@dataclass(frozen=True)
class Line:
    """Straight segment from ``start`` to ``end``, (r, z) in m."""

    start: Point
    end: Point
    name: str = "face"

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _as_point(self.start, f"line {self.name!r} start"))
        object.__setattr__(self, "end", _as_point(self.end, f"line {self.name!r} end"))

    @property
    def length_m(self) -> float:
        return math.dist(self.start, self.end)

    def points(self, s: np.ndarray) -> np.ndarray:
        """Points at curve parameters ``s`` in [0, 1], shape (len(s), 2), m."""
        a, b = np.asarray(self.start), np.asarray(self.end)
        return a + np.outer(s, b - a)

    def reversed(self) -> "Line":
        return Line(self.end, self.start, self.name)


@dataclass(frozen=True)
class Arc:
    """Circular arc from ``start`` to ``end`` about ``center``, (r, z) in m.

    ``ccw`` selects the counter-clockwise (positive angle in the (r, z) plane) way round.
    The arc may not exceed a half circle (split longer arcs): the gmsh OCC kernel builds arcs from
    three points and a half circle is the largest sweep that stays unambiguous.
    """

    start: Point
    end: Point
    center: Point
    ccw: bool = True
    name: str = "face"

    def __post_init__(self) -> None:
        for attr in ("start", "end", "center"):
            object.__setattr__(self, attr, _as_point(getattr(self, attr), f"arc {self.name!r} {attr}"))
        r0, r1 = math.dist(self.start, self.center), math.dist(self.end, self.center)
        if math.dist(self.start, self.end) <= 1e-12 * max(r0, 1.0):
            raise ProfileError(f"arc {self.name!r}: start and end coincide (a full circle is two arcs)")
        if not r0 > 0.0:
            raise ProfileError(f"arc {self.name!r}: start coincides with the centre")
        if abs(r0 - r1) > 1e-9 * max(r0, 1.0) + 1e-12:
            raise ProfileError(
                f"arc {self.name!r}: start and end lie at different distances from the centre "
                f"({r0:.9g} m vs {r1:.9g} m)"
            )
        if self.sweep_rad > math.pi + 1e-12:
            raise ProfileError(
                f"arc {self.name!r}: sweeps {math.degrees(self.sweep_rad):.1f}° > 180°; split it"
            )

    @property
    def radius_m(self) -> float:
        return math.dist(self.start, self.center)

    @property
    def _angles(self) -> tuple[float, float]:
        c = self.center
        a0 = math.atan2(self.start[1] - c[1], self.start[0] - c[0])
        a1 = math.atan2(self.end[1] - c[1], self.end[0] - c[0])
        return a0, a1

    @property
    def sweep_rad(self) -> float:
        """Swept angle, positive, rad."""
        a0, a1 = self._angles
        d = (a1 - a0) if self.ccw else (a0 - a1)
        return d % (2.0 * math.pi)

    @property
    def length_m(self) -> float:
        return self.radius_m * self.sweep_rad

    def points(self, s: np.ndarray) -> np.ndarray:
        """Points at curve parameters ``s`` in [0, 1], shape (len(s), 2), m."""
        a0, _ = self._angles
        sign = 1.0 if self.ccw else -1.0
        ang = a0 + sign * self.sweep_rad * np.asarray(s, dtype=float)
        return np.asarray(self.center) + self.radius_m * np.column_stack((np.cos(ang), np.sin(ang)))

    @property
    def midpoint(self) -> Point:
        r, z = self.points(np.array([0.5]))[0]
        return (float(r), float(z))

    def reversed(self) -> "Arc":
        return Arc(self.end, self.start, self.center, not self.ccw, self.name)


Segment = Line | Arc


@dataclass(frozen=True)
class Profile:
    """A closed chain of segments bounding one simple region in the (r, z) plane.

    The chain is stored counter-clockwise. Construction checks that it is closed (each segment
    starts where the previous one ends), lies at r ≥ 0, does not cross itself and encloses a
    positive area; errors name the profile and the segment.

    Parameters
    ----------
    name : str
        Label of the part (``"bottom race"``).
    segments : tuple of Line | Arc
        The boundary in order; orientation is normalised to counter-clockwise.
    """

    name: str
    segments: tuple = field(default_factory=tuple)

    def __post_init__(self) -> None:
        segs = tuple(self.segments)
        if len(segs) < 2:
            raise ProfileError(f"profile {self.name!r}: needs at least two segments")
        for s in segs:
            if not isinstance(s, (Line, Arc)):
                raise ProfileError(f"profile {self.name!r}: segment {s!r} is not a Line or an Arc")
        scale = max(max(abs(c) for s in segs for c in (*s.start, *s.end)), 1e-3)
        tol = 1e-9 * scale
        for i, s in enumerate(segs):
            nxt = segs[(i + 1) % len(segs)]
            if math.dist(s.end, nxt.start) > tol:
                raise ProfileError(
                    f"profile {self.name!r}: not closed: segment {i} ({s.name!r}) ends at "
                    f"{s.end} but segment {(i + 1) % len(segs)} ({nxt.name!r}) starts at {nxt.start}"
                )
            if s.length_m <= tol:
                raise ProfileError(f"profile {self.name!r}: segment {i} ({s.name!r}) has zero length")
        if _signed_area(segs) < 0.0:
            segs = tuple(s.reversed() for s in reversed(segs))
        object.__setattr__(self, "segments", segs)
        _check_region(self.name, segs, tol)

    # -- geometry -------------------------------------------------------------------------------
    def polyline(self, points_per_arc: int = 64) -> tuple[np.ndarray, np.ndarray]:
        """Closed polyline sampling of the boundary.

        Returns
        -------
        pts : (n, 2) float64, m
            Points, counter-clockwise, the first not repeated at the end.
        seg : (n,) int
            Index of the segment each point starts.
        """
        return _polyline(self.segments, points_per_arc)

    @property
    def area_m2(self) -> float:
        return _signed_area(self.segments)

    @property
    def bounds_m(self) -> tuple[float, float, float, float]:
        """(r_min, r_max, z_min, z_max) of the boundary, m."""
        p, _ = self.polyline(256)
        return float(p[:, 0].min()), float(p[:, 0].max()), float(p[:, 1].min()), float(p[:, 1].max())

    @property
    def size_m(self) -> float:
        """Largest extent of the section (r or z), m: the length tolerances are relative to."""
        r0, r1, z0, z1 = self.bounds_m
        return max(r1 - r0, z1 - z0)

    @property
    def names(self) -> tuple[str, ...]:
        """Distinct segment names in boundary order."""
        return tuple(dict.fromkeys(s.name for s in self.segments))

    def revolved_properties(self, density_kg_m3: float, angle_rad: float = 2.0 * math.pi) -> dict:
        """Mass and inertia of the solid of revolution of this section about the z axis.

        Green's theorem turns the moment integrals ∫∫ rᵃ zᵇ dr dz over the section
        (Pappus–Guldinus generalised) into boundary integrals, evaluated with 24-point
        Gauss–Legendre quadrature per segment: exact for lines, to machine precision for arcs.

        Returns
        -------
        dict
            ``mass_kg``, ``z_cg_m``, ``J_zz_kg_m2`` (about the axis), ``J_xx_kg_m2`` and
            ``J_yy_kg_m2`` (about the x and y axes through the origin; equal for a full
            revolution; a sector starts at the x axis).
        """
        # section moments S_ab = ∫∫ r^a z^b dA; with the volume element r dθ dr dz:
        #   V = θ S_10, ∫z dV = θ S_11, ∫r² dV = θ S_30, ∫z² dV = θ S_12,
        #   ∫x² dV = S_30 ∫cos² = S_30 (θ/2 + sin 2θ/4).
        S10, S11, S30, S12 = (_section_moment(self.segments, a, b) for a, b in ((1, 0), (1, 1), (3, 0), (1, 2)))
        rho, th = density_kg_m3, angle_rad
        mass = rho * th * S10
        ix2 = S30 * (th / 2.0 + math.sin(2.0 * th) / 4.0)
        iy2 = S30 * (th / 2.0 - math.sin(2.0 * th) / 4.0)
        return {
            "mass_kg": mass,
            "z_cg_m": S11 / S10,
            "J_zz_kg_m2": rho * th * S30,
            "J_xx_kg_m2": rho * (iy2 + th * S12),
            "J_yy_kg_m2": rho * (ix2 + th * S12),
        }


def _gauss(n: int = 24) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def _segment_derivative(s: Segment, t: np.ndarray) -> np.ndarray:
    if isinstance(s, Line):
        d = np.asarray(s.end) - np.asarray(s.start)
        return np.tile(d, (len(t), 1))
    p = s.points(t) - np.asarray(s.center)
    sign = 1.0 if s.ccw else -1.0
    return sign * s.sweep_rad * np.column_stack((-p[:, 1], p[:, 0]))


def _section_moment(segs, a: int, b: int) -> float:
    """∫∫ r^a z^b dr dz over the region = ∮ r^(a+1) z^b /(a+1) dz (Green), m^(a+b+2)."""
    t, w = _gauss()
    total = 0.0
    for s in segs:
        p, d = s.points(t), _segment_derivative(s, t)
        total += float(np.sum(w * p[:, 0] ** (a + 1) * p[:, 1] ** b * d[:, 1])) / (a + 1)
    return total


def _signed_area(segs) -> float:
    return _section_moment(segs, 0, 0)


def _polyline(segs, points_per_arc: int) -> tuple[np.ndarray, np.ndarray]:
    pts, seg = [], []
    for i, s in enumerate(segs):
        k = 1 if isinstance(s, Line) else points_per_arc
        p = s.points(np.linspace(0.0, 1.0, k + 1)[:-1])
        pts.append(p)
        seg.append(np.full(len(p), i))
    return np.vstack(pts), np.concatenate(seg)


def _check_region(name: str, segs, tol: float) -> None:
    pts, idx = _polyline(segs, 48)
    if pts[:, 0].min() < -tol:
        i = int(idx[np.argmin(pts[:, 0])])
        raise ProfileError(f"profile {name!r}: segment {i} ({segs[i].name!r}) crosses the axis (r < 0)")
    if not _signed_area(segs) > tol**2:
        raise ProfileError(f"profile {name!r}: encloses no area (zero thickness)")
    a, b = pts, np.roll(pts, -1, axis=0)
    n = len(a)
    # pairwise proper intersections of the polyline edges, skipping neighbours
    d1 = b - a
    for i in range(n):
        j = np.arange(i + 2, n)
        if i == 0:
            j = j[j != n - 1]
        if not len(j):
            continue
        p, r = a[i], d1[i]
        q, s = a[j], d1[j]
        rxs = r[0] * s[:, 1] - r[1] * s[:, 0]
        qp = q - p
        ok = np.abs(rxs) > 1e-30
        t = np.where(ok, (qp[:, 0] * s[:, 1] - qp[:, 1] * s[:, 0]) / np.where(ok, rxs, 1.0), -1.0)
        u = np.where(ok, (qp[:, 0] * r[1] - qp[:, 1] * r[0]) / np.where(ok, rxs, 1.0), -1.0)
        hit = ok & (t > 1e-9) & (t < 1 - 1e-9) & (u > 1e-9) & (u < 1 - 1e-9)
        if hit.any():
            k = int(j[np.argmax(hit)])
            raise ProfileError(
                f"profile {name!r}: boundary crosses itself between segment {int(idx[i])} "
                f"({segs[int(idx[i])].name!r}) and segment {int(idx[k])} ({segs[int(idx[k])].name!r})"
            )
    _check_no_touching(name, segs, a, d1, idx, tol)


def _check_no_touching(name: str, segs, a: np.ndarray, d: np.ndarray, idx: np.ndarray, tol: float) -> None:
    """Reject a vertex lying on a non-adjacent edge: touching regions or zero-width slits."""
    n = len(a)
    dd = np.einsum("ij,ij->i", d, d)
    for i in range(n):
        t = np.clip(np.einsum("ij,ij->i", a[i] - a, d) / dd, 0.0, 1.0)
        dist = np.linalg.norm(a + t[:, None] * d - a[i], axis=1)
        dist[[i, (i - 1) % n]] = np.inf   # the two edges that start or end at vertex i
        k = int(np.argmin(dist))
        if dist[k] < tol * 10.0:
            raise ProfileError(
                f"profile {name!r}: boundary touches itself: segment {int(idx[i])} "
                f"({segs[int(idx[i])].name!r}) meets segment {int(idx[k])} ({segs[int(idx[k])].name!r}) "
                "(zero thickness there)"
            )


def polygon(name: str, points, names) -> Profile:
    """Profile of straight segments through ``points`` (closed automatically).

    ``names[i]`` names the segment from ``points[i]`` to ``points[i + 1]``.
    """
    pts = [tuple(p) for p in points]
    if len(names) != len(pts):
        raise ProfileError(f"profile {name!r}: {len(pts)} points need {len(pts)} segment names, got {len(names)}")
    return Profile(name, tuple(Line(pts[i], pts[(i + 1) % len(pts)], names[i]) for i in range(len(pts))))


def rectangle(name: str, r_in_m: float, r_out_m: float, z_min_m: float, z_max_m: float) -> Profile:
    """Rectangular section with segments ``bottom``, ``outer``, ``top``, ``inner``."""
    if not r_out_m > r_in_m:
        raise ProfileError(f"profile {name!r}: r_out_m ({r_out_m}) must exceed r_in_m ({r_in_m})")
    if not z_max_m > z_min_m:
        raise ProfileError(f"profile {name!r}: z_max_m ({z_max_m}) must exceed z_min_m ({z_min_m})")
    return polygon(
        name,
        [(r_in_m, z_min_m), (r_out_m, z_min_m), (r_out_m, z_max_m), (r_in_m, z_max_m)],
        ["bottom", "outer", "top", "inner"],
    )
