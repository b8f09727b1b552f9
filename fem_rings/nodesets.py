"""Named node and facet sets of a ring mesh, selected geometrically.

Boundary facets are named after the profile segment whose revolution they lie on (a facet belongs
to a segment when all its vertices lie on that segment's curve in the (r, z) plane), so the
``"groove"`` of a profile becomes the groove surface of the ring. Further sets are picked by
predicates in cylindrical coordinates (r, θ, z). Tolerances are relative to the model size and every
selection is checked non-empty, with an error naming the set.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .profile import Arc, Line, Profile

__all__ = [
    "RacewayCurve",
    "classify_boundary",
    "point_segment_distance",
    "cylindrical",
    "nodes_where",
    "facets_where",
    "raceway_curve",
    "patch_nodes",
    "REL_TOL",
]

#: Default geometric tolerance relative to the model size.
REL_TOL = 1e-6


def point_segment_distance(rz: np.ndarray, seg) -> np.ndarray:
    """Distance of points (n, 2) (r, z) in m to a Line or Arc of a profile, (n,) m."""
    rz = np.atleast_2d(np.asarray(rz, dtype=float))
    if isinstance(seg, Line):
        a, b = np.asarray(seg.start), np.asarray(seg.end)
        d = b - a
        t = np.clip((rz - a) @ d / (d @ d), 0.0, 1.0)
        return np.linalg.norm(rz - (a + np.outer(t, d)), axis=1)
    if isinstance(seg, Arc):
        c = np.asarray(seg.center)
        v = rz - c
        rho = np.linalg.norm(v, axis=1)
        a0 = math.atan2(seg.start[1] - c[1], seg.start[0] - c[0])
        ang = np.arctan2(v[:, 1], v[:, 0])
        rel = ((ang - a0) if seg.ccw else (a0 - ang)) % (2.0 * math.pi)
        on_arc = rel <= seg.sweep_rad + 1e-12
        d_end = np.minimum(np.linalg.norm(rz - np.asarray(seg.start), axis=1),
                           np.linalg.norm(rz - np.asarray(seg.end), axis=1))
        return np.where(on_arc, np.abs(rho - seg.radius_m), d_end)
    raise TypeError(f"not a profile segment: {seg!r}")


def cylindrical(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(r, θ, z) of points given as (3, n) or (n, 3) arrays; θ in [0, 2π)."""
    x = np.asarray(x, dtype=float)
    if x.shape[0] != 3:
        x = x.T
    return np.hypot(x[0], x[1]), np.arctan2(x[1], x[0]) % (2.0 * math.pi), x[2]


def classify_boundary(mesh, profile: Profile, spec, pockets=None, rel_tol: float = REL_TOL) -> dict:
    """Name every boundary facet after the profile segment (or sector end, or pocket) it lies on.

    Returns
    -------
    dict of str -> (k,) int
        scikit-fem facet indices per name.

    Raises
    ------
    ValueError
        When a boundary facet lies on no segment (and no pockets were cut), which means the mesh
        does not belong to the profile.
    """
    bf = mesh.boundary_facets()
    xv = mesh.p[:, mesh.facets[:, bf]]  # (3, n_vertices_per_facet, n_facets)
    r, th, z = np.hypot(xv[0], xv[1]), np.arctan2(xv[1], xv[0]), xv[2]
    tol = rel_tol * max(profile.size_m, profile.bounds_m[1])
    name_of = np.full(len(bf), "", dtype=object)
    if not spec.full_circle:
        # perpendicular distance to the two end half-planes of the sector
        d0 = np.abs(xv[1])
        ang = spec.sector_rad
        d1 = np.abs(-math.sin(ang) * xv[0] + math.cos(ang) * xv[1])
        mid_ok0 = np.cos(th) > 0.0
        name_of[np.all((d0 < tol) & mid_ok0, axis=0)] = "sector_start"
        mid_ok1 = (np.cos(th) * math.cos(ang) + np.sin(th) * math.sin(ang)) > 0.0
        name_of[np.all((d1 < tol) & mid_ok1, axis=0) & (name_of == "")] = "sector_end"
    rz = np.column_stack((r.ravel(), z.ravel()))
    for seg in profile.segments:
        free = name_of == ""
        if not free.any():
            break
        on = (point_segment_distance(rz, seg) < tol).reshape(r.shape).all(axis=0)
        name_of[free & on] = seg.name
    left = name_of == ""
    if left.any():
        if pockets is None:
            i = int(np.argmax(left))
            raise ValueError(
                f"profile {profile.name!r}: {int(left.sum())} boundary facets lie on no profile "
                f"segment (first at r = {r[0, i]:.6g} m, z = {z[0, i]:.6g} m)"
            )
        name_of[left] = "pocket"
    return {n: bf[name_of == n] for n in dict.fromkeys(name_of)}


def _require(idx: np.ndarray, what: str) -> np.ndarray:
    if len(idx) == 0:
        raise ValueError(f"node set {what!r} is empty: no nodes match its selection")
    return idx


def nodes_where(ring, predicate, name: str = "selection") -> np.ndarray:
    """Nodes whose cylindrical coordinates satisfy ``predicate(r_m, theta_rad, z_m) -> bool mask``."""
    r, th, z = cylindrical(ring.mesh.doflocs)
    return _require(np.flatnonzero(predicate(r, th, z)), name)


def facets_where(ring, facet_set: str, predicate, name: str = "selection") -> np.ndarray:
    """Facets of a named set whose vertices all satisfy ``predicate(r_m, theta_rad, z_m)``."""
    if facet_set not in ring.facet_sets:
        raise KeyError(f"no facet set {facet_set!r}; the ring has {sorted(ring.facet_sets)}")
    f = ring.facet_sets[facet_set]
    r, th, z = cylindrical(ring.mesh.p[:, ring.mesh.facets[:, f]].reshape(3, -1))
    ok = np.asarray(predicate(r, th, z)).reshape(ring.mesh.facets.shape[0], -1).all(axis=0)
    return _require(f[ok], name)


def patch_nodes(ring, facet_set: str, theta_deg: float, half_width_m: float, name: str | None = None,
                at_radius_m: float | None = None) -> np.ndarray:
    """Nodes of a named surface near the angle ``theta_deg``: a support pad or a bolt-head footprint.

    Without ``at_radius_m``: a strip across the surface, within an arc length ``half_width_m`` of the
    angle (measured at each node's own radius). With ``at_radius_m``: a disc of radius
    ``half_width_m`` about the point at that radius and angle, distances measured across the axis
    (for a flat face: the washer under a bolt on its pitch circle).
    """
    nodes = ring.node_sets[facet_set]
    r, th, _ = cylindrical(ring.mesh.doflocs[:, nodes])
    dth = np.angle(np.exp(1j * (th - math.radians(theta_deg))))
    if at_radius_m is None:
        dist = np.abs(dth) * r
    else:
        dist = np.hypot(r * np.cos(dth) - at_radius_m, r * np.sin(dth))
    sel = nodes[dist <= half_width_m + REL_TOL * ring.size_m]
    return _require(sel, name or f"{facet_set}@{theta_deg:g}°")


@dataclass(frozen=True)
class RacewayCurve:
    """Points along a raceway at which a moving contact samples the ring.

    Attributes
    ----------
    name : str
        Profile segment (surface) the points lie on.
    theta_rad : (n,) float64
        Angular positions, rad.
    points_m : (n, 3) float64
        Points on the raceway surface, m.
    rz_m : (2,) float64
        The (r, z) of the points in the section, m.
    normal_rz : (2,) float64
        Unit normal of the surface pointing out of the solid, in the (r, z) plane.
    center_rz_m : (2,) float64 or None
        Groove curvature centre (r, z) for a groove (the ball-centre side), m; None on a straight
        raceway (cylindrical or flat).
    """

    name: str
    theta_rad: np.ndarray
    points_m: np.ndarray
    rz_m: np.ndarray
    normal_rz: np.ndarray
    center_rz_m: np.ndarray | None


def raceway_curve(ring, segment: str, n_theta: int, at_rz_m=None) -> RacewayCurve:
    """Circle of points on the surface of a named profile segment.

    Parameters
    ----------
    ring : RingMesh
    segment : str
        Profile segment name (``"groove"``, ``"radial_raceway"`` …).
    n_theta : int
        Number of points, evenly spaced over the meshed sector (ends included for a sector).
    at_rz_m : (2,) or None
        Point to project on the segment (e.g. the nominal ball contact point); default the
        middle of the segment.
    """
    segs = [s for s in ring.profile.segments if s.name == segment]
    if not segs:
        raise ValueError(f"profile {ring.profile.name!r} has no segment {segment!r}; "
                         f"it has {list(ring.profile.names)}")
    if segment not in ring.facet_sets:
        raise ValueError(f"segment {segment!r} has no facets in the mesh (fully cut away?)")
    if at_rz_m is None:
        seg = segs[0]
        rz = np.asarray(seg.midpoint if isinstance(seg, Arc) else seg.points(np.array([0.5]))[0])
    else:
        q = np.asarray(at_rz_m, dtype=float)
        seg = min(segs, key=lambda s: float(point_segment_distance(q, s)[0]))
        rz = _project(q, seg)
    normal, center = _outward_normal(seg, rz)
    if ring.spec.full_circle:
        th = np.linspace(0.0, 2.0 * math.pi, n_theta, endpoint=False)
    else:
        th = np.linspace(0.0, ring.spec.sector_rad, n_theta)
    pts = np.column_stack((rz[0] * np.cos(th), rz[0] * np.sin(th), np.full(n_theta, rz[1])))
    return RacewayCurve(segment, th, pts, rz, normal, center)


def _project(q: np.ndarray, seg) -> np.ndarray:
    if isinstance(seg, Line):
        a, b = np.asarray(seg.start), np.asarray(seg.end)
        d = b - a
        return a + np.clip((q - a) @ d / (d @ d), 0.0, 1.0) * d
    c = np.asarray(seg.center)
    v = q - c
    return c + seg.radius_m * v / np.linalg.norm(v)


def _outward_normal(seg, rz: np.ndarray):
    """Outward normal at a boundary point of the counter-clockwise profile (solid on the left)."""
    if isinstance(seg, Line):
        t = np.subtract(seg.end, seg.start)
        t = t / np.linalg.norm(t)
        return np.array([t[1], -t[0]]), None
    c = np.asarray(seg.center)
    radial = (rz - c) / seg.radius_m
    # ccw arc with the solid on its left has the centre inside the solid (convex, e.g. a fillet);
    # a groove is traversed clockwise and its centre lies outside the solid.
    return (radial if seg.ccw else -radial), (None if seg.ccw else c.copy())
