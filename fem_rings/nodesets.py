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
    "PatchError",
    "RacewayCurve",
    "classify_boundary",
    "point_segment_distance",
    "cylindrical",
    "nodes_where",
    "facets_where",
    "raceway_curve",
    "section_raceway_curve",
    "raceway_patch",
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


def classify_boundary(mesh, profile: Profile, spec, leftover: str | None = None, rel_tol: float = REL_TOL) -> dict:
    """Name every boundary facet after the profile segment (or sector end) it lies on; the facets
    on none take the name ``leftover`` (``"pocket"`` for a cage's pockets, ``"other"`` for the parts
    of a STEP solid its section leaves out).

    Returns
    -------
    dict of str -> (k,) int
        scikit-fem facet indices per name.

    Raises
    ------
    ValueError
        When a boundary facet lies on no segment and ``leftover`` is None, which means the mesh
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
        if leftover is None:
            i = int(np.argmax(left))
            raise ValueError(
                f"profile {profile.name!r}: {int(left.sum())} boundary facets lie on no profile "
                f"segment (first at r = {r[0, i]:.6g} m, z = {z[0, i]:.6g} m)"
            )
        name_of[left] = leftover
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
    if segment in ring.profile.names and segment not in ring.facet_sets:
        raise ValueError(f"segment {segment!r} has no facets in the mesh (fully cut away?)")
    if ring.spec.full_circle:
        th = np.linspace(0.0, 2.0 * math.pi, n_theta, endpoint=False)
    else:
        th = np.linspace(0.0, ring.spec.sector_rad, n_theta)
    return section_raceway_curve(ring.profile, segment, th, at_rz_m)


def section_raceway_curve(profile: Profile, segment: str, theta_rad: np.ndarray, at_rz_m=None) -> RacewayCurve:
    """The circle of :func:`raceway_curve` at given angles, from the section alone (no mesh)."""
    segs = [s for s in profile.segments if s.name == segment]
    if not segs:
        raise ValueError(f"profile {profile.name!r} has no segment {segment!r}; "
                         f"it has {list(profile.names)}")
    if at_rz_m is None:
        seg = segs[0]
        rz = np.asarray(seg.midpoint if isinstance(seg, Arc) else seg.points(np.array([0.5]))[0])
    else:
        q = np.asarray(at_rz_m, dtype=float)
        seg = min(segs, key=lambda s: float(point_segment_distance(q, s)[0]))
        rz = _project(q, seg)
    normal, center = _outward_normal(seg, rz)
    th = np.asarray(theta_rad, dtype=float)
    pts = np.column_stack((rz[0] * np.cos(th), rz[0] * np.sin(th), np.full(len(th), rz[1])))
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


def raceway_patch(curve: RacewayCurve, profile: Profile, spread_m: float, n_u: int = 4,
                  n_v: int = 3) -> list[tuple[RacewayCurve, float]]:
    """Circles through the Gauss points of a patch of the section around a raceway's contact point.

    The patch spans arc length u ∈ [−s, s] along the raceway surface and depth v ∈ [0, s] into the
    solid (against the outward normal), s = ``spread_m``: on a groove the points are
    c + (R + v) e(u / R), e the unit vector from the curvature centre c rotated by u / R in the
    (r, z) plane; on a straight raceway p + u t − v n. Every circle keeps the θ of ``curve``.

    The weights are the Gauss–Legendre weights (``n_u`` × ``n_v`` points) times the area element
    of the section ((R + v) / R on a groove, 1 on a line), normalised to sum 1: Σ w_k x_k is the
    area centroid of the patch (exactly on a straight raceway; on a groove to the accuracy of the
    Gauss rule in the angle). Averaging the mode shapes over the patch with these weights, and
    spreading a raceway load over it by the same weights (the transpose), is the weighted-average
    interpolation of an RBE3-type element (MSC Nastran Quick Reference Guide, RBE3). It is needed
    because the displacement under a line load on an elastic solid grows like log(1/distance)
    (Johnson, Contact Mechanics, 1985, §2.2 and §3.2), so a value sampled on the loaded line
    itself depends on the mesh and on the harmonic of the load, while its average over a patch of
    finite size converges.

    Parameters
    ----------
    curve : RacewayCurve
        The raceway circle (from :func:`raceway_curve`).
    profile : Profile
        The section of the ring it lies on: decides whether the points lie in the solid.
    spread_m : float
        Patch size s, m (> 0).
    n_u, n_v : int
        Gauss points along the surface and in depth.

    Returns
    -------
    list of (RacewayCurve, float)
        One circle per patch point (named ``"<raceway>~<k>"``, normal and centre of ``curve``)
        with its weight.

    Raises
    ------
    ValueError
        Naming ``spread_m`` and the raceway, when s is not positive and finite or a patch point
        leaves the solid (the patch runs past the raceway's edges or through the section).
    """
    s = float(spread_m)
    if not (math.isfinite(s) and s > 0.0):
        raise ValueError(f"raceway {curve.name!r}: spread_m must be positive and finite, got {spread_m!r}")
    xu, wu = np.polynomial.legendre.leggauss(int(n_u))
    xv, wv = np.polynomial.legendre.leggauss(int(n_v))
    u, v = np.meshgrid(s * xu, 0.5 * s * (xv + 1.0), indexing="ij")
    w = np.outer(wu, wv)
    n = np.asarray(curve.normal_rz, float)
    if curve.center_rz_m is None:
        t = np.array([-n[1], n[0]])
        rz = curve.rz_m + u[..., None] * t - v[..., None] * n
        foot = curve.rz_m + u[:, 0, None] * t
    else:
        c = np.asarray(curve.center_rz_m, float)
        R = float(np.linalg.norm(curve.rz_m - c))
        e0 = (curve.rz_m - c) / R
        phi = u / R
        e = np.cos(phi)[..., None] * e0 + np.sin(phi)[..., None] * np.array([-e0[1], e0[0]])
        rz = c + (R + v)[..., None] * e
        foot = c + R * e[:, 0]
        w = w * (R + v) / R
    rz, w = rz.reshape(-1, 2), (w / w.sum()).ravel()
    _check_patch(curve, profile, spread_m, rz, foot)
    out = []
    for k, (p, wk) in enumerate(zip(rz, w)):
        pts = np.column_stack((p[0] * np.cos(curve.theta_rad), p[0] * np.sin(curve.theta_rad),
                               np.full(len(curve.theta_rad), p[1])))
        out.append((RacewayCurve(f"{curve.name}~{k}", curve.theta_rad, pts, p, curve.normal_rz,
                                 curve.center_rz_m), float(wk)))
    return out


class PatchError(ValueError):
    """A raceway patch that leaves the section or its raceway (``spread_m`` too large)."""


def _check_patch(curve: RacewayCurve, profile: Profile, spread_m: float, rz: np.ndarray, foot: np.ndarray) -> None:
    """:class:`PatchError` unless every patch point lies strictly inside the section and every surface foot
    point on the raceway's own segment."""
    tol = REL_TOL * profile.size_m
    segs = [seg for seg in profile.segments if seg.name == curve.name]
    on_raceway = np.min([point_segment_distance(foot, seg) for seg in segs], axis=0) < tol
    poly, _ = profile.polyline(256)
    inside = _inside_polygon(rz, poly)
    if not (on_raceway.all() and inside.all()):
        bad = rz[np.argmin(inside)] if not inside.all() else foot[np.argmin(on_raceway)]
        raise PatchError(
            f"raceway {curve.name!r}: spread_m = {spread_m:g} m is too large: its patch reaches "
            f"(r, z) = ({bad[0]:.6g}, {bad[1]:.6g}) m, "
            + ("outside the section" if not inside.all() else "past the edge of the raceway"))


def _inside_polygon(q: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Points (n, 2) strictly inside a closed polygon (m, 2), by the crossing-number rule
    (O'Rourke, Computational Geometry in C, 2nd ed., 1998, §7.4)."""
    a, b = poly, np.roll(poly, -1, axis=0)
    x, y = q[:, 0, None], q[:, 1, None]
    straddle = (a[None, :, 1] > y) != (b[None, :, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[None, :, 0] + (y - a[None, :, 1]) * (b[None, :, 0] - a[None, :, 0]) / (b[None, :, 1] - a[None, :, 1])
    return (np.count_nonzero(straddle & (x < xc), axis=1) % 2) == 1
