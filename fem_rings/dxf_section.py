"""Ring cross-sections read from a DXF drawing.

Drawing conventions
-------------------
* The section is drawn in model space in the drawing's x–y plane: drawing **x is r** (the distance
  from the ring axis, the axis is the line x = 0, the section lies at x ≥ 0) and drawing **y is z**
  (the axial position). Drawing z coordinates (elevation) are ignored; entities whose plane is not
  the x–y plane (extrusion other than ±z) are refused.
* Each boundary piece is named after its **layer**: draw the raceway groove on a layer ``groove``,
  the bolted face on ``bolt_face``; these names become the node and facet sets of the finite-element
  model. Layer ``0`` (the default layer) gives the name ``face``. Names keep the case they are
  drawn with.
* Boundary entities: LINE, ARC, LWPOLYLINE and 2-D POLYLINE (straight pieces and bulge arcs).
  Annotation (TEXT, MTEXT, DIMENSION, HATCH, POINT, LEADER, block references …) is ignored. CIRCLE
  is refused (a full circle is no section boundary), and so are curves without an exact line/arc
  form (SPLINE, ELLIPSE, spline-fit polylines …).
* The pieces must form exactly one closed loop: endpoints closer than 1e-6 of the section size
  are joined; a gap, a branch (three pieces at one point) or a second loop is an error that names
  the file and the place (r, z in mm).

Units: ``unit="mm"`` or ``"m"`` states the drawing unit; the header variable ``$INSUNITS`` is then
only checked (a header unit different from ``unit`` is refused; an unset header is accepted).
``unit="file"`` takes the unit from ``$INSUNITS`` (inch, foot, mm, cm or m) and refuses a drawing
without it. Drawing templates set ``$INSUNITS`` whether or not the drawing follows it (new ezdxf
drawings say metres, AutoCAD's imperial template inches): a wrong header is corrected in the file
(AutoCAD: ``INSUNITS`` command), never overridden here.

References: Autodesk, *DXF Reference* (AutoCAD 2012), entities ARC (angles counter-clockwise
about the extrusion direction), LWPOLYLINE/VERTEX group 42 (bulge = tan(θ/4) of the included
angle θ, negative clockwise), "Arbitrary Axis Algorithm" (object coordinate systems), header
variable $INSUNITS.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from .profile import Arc, Line, Profile, ProfileError

__all__ = ["profile_from_dxf", "DXF_UNITS_M"]

log = logging.getLogger(__name__)

#: metres per drawing unit of the $INSUNITS codes accepted (inch and foot exact by definition).
DXF_UNITS_M = {1: ("inch", 0.0254), 2: ("foot", 0.3048), 4: ("mm", 1e-3), 5: ("cm", 1e-2), 6: ("m", 1.0)}
_UNIT_ARG_M = {"mm": 1e-3, "m": 1.0}

_BOUNDARY = {"LINE", "ARC", "LWPOLYLINE", "POLYLINE"}
_IGNORED = {
    "TEXT", "MTEXT", "DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION", "LEADER", "MLEADER",
    "MULTILEADER", "TOLERANCE", "HATCH", "MPOLYGON", "POINT", "INSERT", "ATTDEF", "ATTRIB", "IMAGE",
    "WIPEOUT", "VIEWPORT", "OLE2FRAME", "ACAD_TABLE", "XLINE", "RAY", "SHAPE", "UNDERLAY",
    "PDFUNDERLAY", "DWFUNDERLAY", "DGNUNDERLAY", "ACAD_PROXY_ENTITY",
}
_TOL_REL = 1e-6  # endpoint matching, relative to the section size


@dataclass(frozen=True)
class _Piece:
    """One boundary piece in metres: a line (center None) or an arc (≤ 180°)."""

    start: tuple[float, float]
    end: tuple[float, float]
    center: tuple[float, float] | None
    ccw: bool
    name: str
    where: str  # "LINE #2A on layer 'groove'"


def profile_from_dxf(path, *, name: str, unit: str = "mm", layer_names: bool = True) -> Profile:
    """Read one ring cross-section from the model space of a DXF file.

    Parameters
    ----------
    path : str or Path
        The DXF file (ASCII or binary).
    name : str
        Name of the profile (``"bottom race"``).
    unit : {"mm", "m", "file"}
        Drawing unit; ``"file"`` reads it from the header ``$INSUNITS``. See the module docstring
        for the check of the header against ``"mm"`` / ``"m"``.
    layer_names : bool
        Name each segment after its layer (layer ``0`` → ``"face"``); False names all ``"face"``.

    Returns
    -------
    Profile
        Coordinates in metres, x → r, y → z, counter-clockwise.

    Raises
    ------
    ProfileError
        One line naming the file and, where there is one, the entity and the place.
    """
    import ezdxf

    label = str(path)
    if unit not in (*_UNIT_ARG_M, "file"):
        raise ProfileError(f"{label}: unit must be 'mm', 'm' or 'file', got {unit!r}")
    if not Path(path).is_file():
        raise ProfileError(f"{label}: no such file")
    try:
        doc = ezdxf.readfile(str(path))
    except OSError:  # ezdxf: the file does not start like a DXF file
        raise ProfileError(f"{label}: not a DXF file (or unreadable)") from None
    except (UnicodeError, ValueError, ezdxf.DXFError) as exc:
        reason = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise ProfileError(f"{label}: cannot be read as a DXF file ({reason})") from None
    scale_m = _drawing_unit_m(label, unit, doc.header.get("$INSUNITS", 0))
    pieces, ignored = _read_pieces(label, doc.modelspace(), scale_m, layer_names)
    if ignored:
        log.debug("%s: ignored %s", label, ignored)
    if not pieces:
        kinds = ", ".join(f"{n} {k}" for k, n in sorted(ignored.items())) or "nothing"
        hint = " (explode block references to use them)" if "INSERT" in ignored else ""
        raise ProfileError(f"{label}: no LINE, ARC or polyline in model space (found {kinds}){hint}")
    try:
        return Profile(name, tuple(_chain(label, pieces)))
    except ProfileError as exc:  # the profile's own checks do not know the file
        msg = str(exc)
        raise ProfileError(msg if msg.startswith(f"{label}: ") else f"{label}: {msg}") from None


# -- units ----------------------------------------------------------------------------------------

def _drawing_unit_m(label: str, unit: str, insunits) -> float:
    """Metres per drawing unit from the ``unit`` argument, checked against ``$INSUNITS``."""
    code = int(insunits or 0)
    header = DXF_UNITS_M.get(code)
    if unit == "file":
        if code == 0:
            raise ProfileError(f"{label}: $INSUNITS is not set (unitless drawing); pass unit='mm' or unit='m'")
        if header is None:
            raise ProfileError(f"{label}: $INSUNITS = {code} is not a length unit this reader knows "
                               f"(codes {sorted(DXF_UNITS_M)}); pass unit='mm' or unit='m'")
        return header[1]
    if code != 0 and (header is None or header[0] != unit):
        said = header[0] if header else f"code {code}"
        raise ProfileError(f"{label}: unit={unit!r} disagrees with the drawing's $INSUNITS = {code} ({said}); "
                           "pass unit='file' to use the header, or correct the header")
    return _UNIT_ARG_M[unit]


# -- entities → pieces ----------------------------------------------------------------------------

def _read_pieces(label: str, msp, scale_m: float, layer_names: bool):
    def sc(v):
        return (v[0] * scale_m, v[1] * scale_m)

    pieces, ignored = [], {}
    for e in msp:
        kind = e.dxftype()
        layer = e.dxf.get("layer", "0")
        where = f"{kind} #{e.dxf.handle} on layer {layer!r}"
        if kind in _IGNORED:
            ignored[kind] = ignored.get(kind, 0) + 1
            continue
        if kind == "CIRCLE":
            raise ProfileError(f"{label}: {where}: a full circle is not a section boundary "
                               "(draw the section's outline as one closed chain of lines and arcs)")
        if kind not in _BOUNDARY:
            raise ProfileError(f"{label}: {where}: entity type {kind} is not supported "
                               "(use lines, arcs and polylines; convert splines and ellipses to arcs)")
        seg_name = ("face" if layer == "0" else layer) if layer_names else "face"
        flip = kind != "LINE" and _plane_flip(label, where, e)  # LINE points are world coordinates
        for p, q, c, ccw in _entity_geometry(label, where, e, kind):
            if flip:  # extrusion −z: the object x axis is the drawing's −x (arbitrary axis algorithm)
                p, q = (-p[0], p[1]), (-q[0], q[1])
                c, ccw = (None, ccw) if c is None else ((-c[0], c[1]), not ccw)
            pieces.append(_Piece(sc(p), sc(q), None if c is None else sc(c), ccw, seg_name, where))
    return pieces, ignored


def _plane_flip(label: str, where: str, e) -> bool:
    """True when the entity's extrusion is −z; refuses entities out of the x–y plane."""
    if not e.dxf.hasattr("extrusion"):
        return False
    ex = e.dxf.extrusion
    if abs(ex[0]) > 1e-9 or abs(ex[1]) > 1e-9:
        raise ProfileError(f"{label}: {where}: not drawn in the x–y plane (extrusion {tuple(ex)})")
    return ex[2] < 0.0


def _entity_geometry(label: str, where: str, e, kind: str):
    """(start, end, center or None, ccw) in object coordinates, arcs split to ≤ 180°."""
    if kind == "LINE":
        s, t = e.dxf.start, e.dxf.end
        return [((s[0], s[1]), (t[0], t[1]), None, True)]
    if kind == "ARC":
        c, r = e.dxf.center, float(e.dxf.radius)
        a0 = math.radians(e.dxf.start_angle)
        sweep = math.radians(e.dxf.end_angle - e.dxf.start_angle) % (2.0 * math.pi)
        if sweep < 1e-12 or not r > 0.0:
            raise ProfileError(f"{label}: {where}: zero or full sweep (a full circle is not a section boundary)")
        return _split_arc((c[0], c[1]), r, a0, sweep, True)
    if kind == "LWPOLYLINE":
        verts = [(float(x), float(y), float(b)) for x, y, b in e.get_points("xyb")]
        return _polyline_pieces(label, where, verts, bool(e.closed))
    # POLYLINE: only the 2-D kind; 3-D polylines, meshes and spline/curve fits have no exact arcs
    if not e.is_2d_polyline or e.dxf.flags & (e.CURVE_FIT_VERTICES_ADDED | e.SPLINE_FIT_VERTICES_ADDED):
        raise ProfileError(f"{label}: {where}: only 2-D polylines of straight and bulge pieces are supported "
                           "(not 3-D, mesh, curve-fit or spline-fit polylines)")
    verts = [(float(v.dxf.location[0]), float(v.dxf.location[1]), float(v.dxf.get("bulge", 0.0)))
             for v in e.vertices]
    return _polyline_pieces(label, where, verts, bool(e.is_closed))


def _polyline_pieces(label: str, where: str, verts, closed: bool):
    if len(verts) < 2:
        raise ProfileError(f"{label}: {where}: a polyline needs at least two vertices")
    n = len(verts) if closed else len(verts) - 1
    out = []
    for i in range(n):
        (x0, y0, b), (x1, y1, _) = verts[i], verts[(i + 1) % len(verts)]
        if math.hypot(x1 - x0, y1 - y0) == 0.0:
            continue  # repeated vertex: no piece
        if b == 0.0:
            out.append(((x0, y0), (x1, y1), None, True))
        else:
            out.extend(_bulge_arc((x0, y0), (x1, y1), b))
    return out


def _bulge_arc(p, q, bulge: float):
    """Arc from ``p`` to ``q`` with bulge b = tan(θ/4): counter-clockwise for b > 0.

    Centre on the left normal n of the chord (length c) from its midpoint at the signed distance
    c (1 − b²) / (4 b) (the radius c (1 + b²)/(4|b|) less the sagitta |b| c / 2).
    """
    dx, dy = q[0] - p[0], q[1] - p[1]
    c = math.hypot(dx, dy)
    h = c * (1.0 - bulge * bulge) / (4.0 * bulge)
    cx, cy = 0.5 * (p[0] + q[0]) - dy / c * h, 0.5 * (p[1] + q[1]) + dx / c * h
    r = math.hypot(p[0] - cx, p[1] - cy)
    sweep = 4.0 * math.atan(abs(bulge))
    a0 = math.atan2(p[1] - cy, p[0] - cx)
    return _split_arc((cx, cy), r, a0, sweep, bulge > 0.0, p, q)


def _split_arc(c, r: float, a0: float, sweep: float, ccw: bool, p=None, q=None):
    """Arc of ``sweep`` from angle ``a0`` in pieces of at most a half circle (``Arc``'s limit)."""
    n = max(1, math.ceil((sweep - 1e-12) / math.pi))  # Arc accepts up to π + 1e-12
    sign = 1.0 if ccw else -1.0
    ang = [a0 + sign * sweep * k / n for k in range(n + 1)]
    pts = [(c[0] + r * math.cos(a), c[1] + r * math.sin(a)) for a in ang]
    if p is not None:  # keep the polyline's own vertices exactly
        pts[0], pts[-1] = p, q
    return [(pts[k], pts[k + 1], c, ccw) for k in range(n)]


# -- chaining -------------------------------------------------------------------------------------

def _mm(p) -> str:
    return f"({p[0] * 1e3:.6g}, {p[1] * 1e3:.6g}) mm"


def _chain(label: str, pieces) -> list:
    """The pieces as one closed chain of ``Line`` / ``Arc`` segments, endpoints joined."""
    ends = np.array([pt for pc in pieces for pt in (pc.start, pc.end)], dtype=float)  # (2n, 2) m
    size = float(np.max(ends.max(axis=0) - ends.min(axis=0)))
    if not size > 0.0:
        raise ProfileError(f"{label}: the drawing's pieces have no extent (all endpoints coincide)")
    tol = _TOL_REL * size
    _check_axis_side(label, pieces, tol)
    # join endpoints closer than tol into nodes
    pairs = cKDTree(ends).query_pairs(tol, output_type="ndarray")
    adj = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(ends), len(ends)))
    _, node_of = connected_components(adj, directed=False)
    node_xy = np.array([ends[node_of == k].mean(axis=0) for k in range(node_of.max() + 1)])
    node_xy[np.abs(node_xy[:, 0]) <= tol, 0] = 0.0  # on the axis
    keep = [i for i in range(len(pieces)) if node_of[2 * i] != node_of[2 * i + 1]]
    for i in sorted(set(range(len(pieces))) - set(keep)):
        log.debug("%s: %s has zero length; skipped", label, pieces[i].where)
    at = {}  # node → the pieces ending there
    for i in keep:
        for k in (0, 1):
            at.setdefault(int(node_of[2 * i + k]), []).append(i)
    _check_degrees(label, pieces, at, node_of, node_xy)
    loops = _walk(pieces, keep, at, node_of, node_xy)
    if len(loops) > 1:
        where = "; ".join(f"loop {n + 1} ({len(lp)} pieces) through {_mm(lp[0].start)}" for n, lp in enumerate(loops))
        raise ProfileError(f"{label}: {len(loops)} separate closed loops, a section is one: {where}")
    return loops[0]


def _check_axis_side(label: str, pieces, tol: float) -> None:
    for pc in pieces:
        pts = [pc.start, pc.end]
        if pc.center is not None:  # an arc through the angle π reaches its smallest r there
            a0 = math.atan2(pc.start[1] - pc.center[1], pc.start[0] - pc.center[0])
            a1 = math.atan2(pc.end[1] - pc.center[1], pc.end[0] - pc.center[0])
            lo, hi = (a0, a1) if pc.ccw else (a1, a0)
            if (math.pi - lo) % (2 * math.pi) <= (hi - lo) % (2 * math.pi):
                rad = math.dist(pc.start, pc.center)
                pts.append((pc.center[0] - rad, pc.center[1]))
        worst = min(pts, key=lambda p: p[0])
        if worst[0] < -tol:
            raise ProfileError(f"{label}: {pc.where} reaches r < 0 at (r, z) = {_mm(worst)}: draw the section "
                               "at x ≥ 0 (x is the radius, the ring axis is the line x = 0)")


def _check_degrees(label, pieces, at, node_of, node_xy) -> None:
    """Refuse a branch (three or more pieces at a point) and open ends."""
    for k, idx in sorted(at.items()):
        if len(idx) > 2:
            ends = [frozenset((int(node_of[2 * i]), int(node_of[2 * i + 1]))) for i in idx]
            twice = [pieces[i].where for i, e in zip(idx, ends) if ends.count(e) > 1]
            hint = f"; {' and '.join(twice)} join the same two points (drawn twice?)" if twice else ""
            raise ProfileError(f"{label}: the outline branches at (r, z) = {_mm(node_xy[k])}: {len(idx)} pieces "
                               f"meet there ({', '.join(pieces[i].where for i in idx)}){hint}; "
                               "a section is one closed loop")
    open_ = np.array(sorted(k for k, idx in at.items() if len(idx) == 1), dtype=int)
    if len(open_):
        xy = node_xy[open_]
        d = np.linalg.norm(xy[:, None, :] - xy[None, :, :], axis=2)
        np.fill_diagonal(d, np.inf)
        a, b = np.unravel_index(int(np.argmin(d)), d.shape)
        k, m = int(open_[a]), int(open_[b])
        raise ProfileError(f"{label}: the section is not closed: gap of {d[a, b] * 1e3:.6g} mm between the open "
                           f"ends at (r, z) = {_mm(node_xy[k])} ({pieces[at[k][0]].where}) and {_mm(node_xy[m])} "
                           f"({pieces[at[m][0]].where}); "
                           f"{len(open_)} open ends in all")


def _walk(pieces, keep, at, node_of, node_xy) -> list:
    """Follow the pieces from node to node (every node joins two pieces here); one list per loop."""
    loops, todo = [], set(keep)
    while todo:
        first = min(todo)
        node, i, loop = int(node_of[2 * first]), first, []
        while True:
            todo.discard(i)
            forward = int(node_of[2 * i]) == node
            nxt = int(node_of[2 * i + 1]) if forward else int(node_of[2 * i])
            loop.append(_segment(pieces[i], node_xy[node], node_xy[nxt], forward))
            node = nxt
            i = next((j for j in at[node] if j != i), i)
            if i not in todo:
                break
        loops.append(loop)
    return loops


def _segment(pc: _Piece, a, b, forward: bool):
    """``Line`` or ``Arc`` from node ``a`` to node ``b`` (the piece reversed when not ``forward``)."""
    a, b = (float(a[0]), float(a[1])), (float(b[0]), float(b[1]))
    if pc.center is None:
        return Line(a, b, pc.name)
    # the joined endpoints moved by up to the tolerance: put the centre back on the chord's
    # perpendicular bisector (the point there nearest the drawn centre) so both ends share a radius
    m = np.array([(a[0] + b[0]) / 2, (a[1] + b[1]) / 2])
    t = np.array([b[0] - a[0], b[1] - a[1]])
    n = np.array([-t[1], t[0]]) / np.linalg.norm(t)
    c = m + n * float(np.dot(np.asarray(pc.center) - m, n))
    return Arc(a, b, (float(c[0]), float(c[1])), pc.ccw if forward else not pc.ccw, pc.name)
