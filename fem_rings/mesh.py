"""Meshing: revolve a cross-section with gmsh and bring the mesh into scikit-fem.

Two element families, both quadratic and with curved (isoparametric) geometry so that the ring's
circles and groove arcs are represented exactly to second order:

``"tet10"``
    The section is revolved as a solid with gmsh's OpenCASCADE kernel (optionally cut by cage
    pockets) and filled with 10-node tetrahedra. Works for any profile.
``"hex27"``
    The section is meshed with quadrilaterals (structured when it is a four-sided polygon) and swept
    about the axis in layers (gmsh built-in kernel, ``revolve`` with ``numElements``), giving
    27-node hexahedra. Converges much faster per degree of freedom.

A ring can instead be a solid from a STEP file (``MeshSpec.solid``, :class:`fem_rings.step_solid.StepSolid`):
gmsh's OpenCASCADE importer reads it in metres and fills it with 10-node tetrahedra; the profile
then only names the faces that lie on its revolved segments (raceways, support faces), and the
rest of the solid's boundary (gear teeth, bolt holes) is named ``other``.

gmsh writes a ``.msh`` file that meshio reads; the volume cells become a scikit-fem ``MeshTet2`` /
``MeshHex2``. Boundary facets are then named after the profile segment that generated them (and
``sector_start``/``sector_end``/``pocket``), see :mod:`fem_rings.nodesets`.

Node numbering: "nodes" are the columns of ``mesh.doflocs`` — the scalar degrees of freedom of the
quadratic element — and vector DOFs are interleaved, ``3 * node + component``.
"""

from __future__ import annotations

import logging
import math
import tempfile
import threading
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import meshio
import numpy as np
import skfem
from skfem.io.meshio import from_meshio

from foundation.validation import check_positive

from .profile import Arc, Line, Profile

if TYPE_CHECKING:
    from .cages import CagePockets
    from .step_solid import StepSolid

__all__ = ["MeshSpec", "RingMesh", "mesh_ring", "gmsh_session", "revolved_volumes", "ELEMENT_TYPES", "MESH_VERSION",
           "GmshError", "QuadMeshError", "TangledMeshError", "tangled_elements"]

log = logging.getLogger(__name__)

#: meshio cell type of each element family.
ELEMENT_TYPES = {"tet10": "tetra10", "hex27": "hexahedron27"}

#: Version of the meshing, part of the cache keys of FE models and reduced bodies: a change that
#: alters the mesh of the same inputs bumps it. 2: curved tet10 elements are untangled by gmsh's
#: high-order optimisation and every mesh is checked for tangled elements (before, 4–6 % of the
#: tet10 elements on a groove's curvature had a Jacobian changing sign inside them).
MESH_VERSION = 2

_GMSH_LOCK = threading.Lock()

#: reference points (vertices, edge midpoints, centre) at which the Jacobian of each element is checked
_CHECK_POINTS = {
    "tet10": np.array([[0, 1, 0, 0, .5, 0, 0, .5, .5, 0, .25], [0, 0, 1, 0, 0, .5, 0, .5, 0, .5, .25],
                       [0, 0, 0, 1, 0, 0, .5, 0, .5, .5, .25]], float),
    "hex27": np.array(np.meshgrid([0, .5, 1], [0, .5, 1], [0, .5, 1], indexing="ij")).reshape(3, -1),
}


class QuadMeshError(RuntimeError):
    """A section that gmsh cannot mesh with quadrilaterals only (hex27 needs them; tet10 does not)."""


class GmshError(RuntimeError):
    """gmsh could not build or mesh the geometry (its own message follows)."""


class TangledMeshError(RuntimeError):
    """A curved element whose Jacobian changes sign inside it (its stiffness would be wrong)."""


@dataclass(frozen=True)
class MeshSpec:
    """How to mesh a profile.

    Parameters
    ----------
    size_m : float
        Target element edge length, m (one parameter controls the whole mesh).
    element : {"tet10", "hex27"}
        Element family (module docstring).
    sector_deg : float
        Revolve angle, degrees, 0 < sector_deg ≤ 360.
    refine : dict of str -> float
        Size factor (0, 1] near the surfaces of the named profile segments, e.g.
        ``{"groove": 0.4}`` (tet10 only; for hex27 the factor applies to the section's edges of
        that name).
    n_theta : int or None
        Element layers round the sector (hex27); default from ``size_m`` at the outer radius;
        rounded up to a multiple of the number of ≤ 90° revolve pieces.
    solid : StepSolid or None
        Mesh this STEP solid (tet10, full circle) instead of revolving the profile; the profile
        names the faces on its segments (module docstring).
    """

    size_m: float
    element: str = "tet10"
    sector_deg: float = 360.0
    refine: dict = field(default_factory=dict)
    n_theta: int | None = None
    solid: "StepSolid | None" = field(default=None, metadata={"hash": "if-set"})

    def __post_init__(self) -> None:
        check_positive("mesh spec", size_m=self.size_m)
        if self.element not in ELEMENT_TYPES:
            raise ValueError(f"mesh spec: element must be one of {sorted(ELEMENT_TYPES)}, got {self.element!r}")
        if not 0.0 < self.sector_deg <= 360.0:
            raise ValueError(f"mesh spec: sector_deg must lie in (0, 360], got {self.sector_deg}")
        for k, v in self.refine.items():
            if not 0.0 < float(v) <= 1.0:
                raise ValueError(f"mesh spec: refine[{k!r}] must lie in (0, 1], got {v}")
        if self.n_theta is not None and int(self.n_theta) < 3:
            raise ValueError(f"mesh spec: n_theta must be ≥ 3, got {self.n_theta}")
        if self.solid is not None and (self.element != "tet10" or not self.full_circle):
            raise ValueError("mesh spec: a STEP solid is meshed whole with element='tet10' (hex27 sweeps a section)")

    @property
    def full_circle(self) -> bool:
        return self.sector_deg >= 360.0

    @property
    def sector_rad(self) -> float:
        return math.radians(self.sector_deg)


@dataclass(frozen=True, eq=False)
class RingMesh:
    """A quadratic solid mesh of a ring with named boundary sets.

    Attributes
    ----------
    mesh : skfem.MeshTet2 | skfem.MeshHex2
        Curved quadratic mesh, m.
    profile : Profile
        The revolved section.
    spec : MeshSpec
        How it was meshed.
    facet_sets : dict of str -> (k,) int
        Boundary facets (scikit-fem facet indices) named after profile segments, plus
        ``sector_start``/``sector_end`` for sectors and ``pocket`` for cage pocket faces.
    node_sets : dict of str -> (k,) int
        Nodes (columns of ``mesh.doflocs``) of each facet set.
    """

    mesh: skfem.Mesh
    profile: Profile
    spec: MeshSpec
    facet_sets: dict
    node_sets: dict

    @property
    def nodes_m(self) -> np.ndarray:
        """(n_nodes, 3) float64, m."""
        return self.mesh.doflocs.T

    @property
    def n_nodes(self) -> int:
        return self.mesh.doflocs.shape[1]

    @property
    def n_dofs(self) -> int:
        return 3 * self.n_nodes

    @property
    def size_m(self) -> float:
        """Largest extent of the model, m (reference length for geometric tolerances)."""
        x = self.mesh.doflocs
        return float(np.max(x.max(axis=1) - x.min(axis=1)))

    def summary(self) -> str:
        return (f"{self.profile.name}: {self.spec.element}, {self.mesh.t.shape[1]} elements, "
                f"{self.n_nodes} nodes, {self.n_dofs} DOF")


def mesh_ring(profile: Profile, spec: MeshSpec, pockets: CagePockets | None = None) -> RingMesh:
    """Mesh the solid of revolution of ``profile`` (optionally with cage pockets cut out).

    Returns a :class:`RingMesh` whose boundary facets are named after the profile's segments.
    """
    from .nodesets import classify_boundary

    if pockets is not None and spec.element != "tet10":
        raise ValueError("mesh spec: cage pockets need element='tet10' (a boolean cut cannot be swept)")
    if pockets is not None and spec.solid is not None:
        raise ValueError("mesh spec: a STEP solid carries its own pockets; pockets are for revolved sections")
    unknown = set(spec.refine) - set(profile.names)
    if unknown:
        raise ValueError(f"mesh spec: refine names {sorted(unknown)} are not segments of profile "
                         f"{profile.name!r} (has {list(profile.names)})")
    with tempfile.TemporaryDirectory() as tmp:
        msh = Path(tmp) / "ring.msh"
        _gmsh_mesh(profile, spec, pockets, msh)
        mesh = _read_volume_mesh(msh, ELEMENT_TYPES[spec.element])
    bad = tangled_elements(mesh, spec.element)
    if len(bad):
        raise TangledMeshError(f"{profile.name}: {len(bad)} of {mesh.t.shape[1]} curved elements are tangled (their "
                               f"Jacobian changes sign inside them) at element size {spec.size_m * 1e3:.4g} mm; "
                               "mesh finer")
    leftover = "pocket" if pockets is not None else ("other" if spec.solid is not None else None)
    facet_sets = classify_boundary(mesh, profile, spec, leftover)
    on_axis = {s.name for s in profile.segments if isinstance(s, Line) and max(s.start[0], s.end[0]) == 0.0}
    missing = [n for n in profile.names if n not in facet_sets and n not in on_axis]  # the axis sweeps no face
    if missing and spec.solid is not None:  # the section's faces the solid leaves out (teeth cut the outer face)
        log.info("%s: the STEP solid has no facets on the section's segments %s", profile.name, missing)
    elif missing:
        raise ValueError(f"profile {profile.name!r}: segments {missing} got no boundary facets "
                         "(cut away by pockets, or shorter than the element size and merged)")
    node_sets = {k: facet_nodes(mesh, f) for k, f in facet_sets.items()}
    ring = RingMesh(mesh, profile, spec, facet_sets, node_sets)
    log.info("meshed %s", ring.summary())
    return ring


def facet_nodes(mesh: skfem.Mesh, facets: np.ndarray) -> np.ndarray:
    """All nodes (vertex, edge and face nodes) of the given facets, sorted."""
    if len(facets) == 0:
        return np.zeros(0, dtype=np.int64)
    return np.unique(mesh.dofs.get_facet_dofs(np.asarray(facets)).flatten())


# -- gmsh ---------------------------------------------------------------------------------------

@contextmanager
def gmsh_session(model_name: str):
    """A gmsh session with one empty model, silent and without a display, always finalized.

    gmsh keeps one global state per process, so sessions are serialised by a lock; signals are
    left to Python (``interruptible=False``) so that a session can run outside the main thread.
    Yields the ``gmsh`` module.
    """
    import gmsh

    with _GMSH_LOCK:
        gmsh.initialize(interruptible=False)
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.model.add(model_name)
            yield gmsh
        finally:
            gmsh.finalize()


def _gmsh_mesh(profile: Profile, spec: MeshSpec, pockets, path: Path) -> None:
    with gmsh_session("ring") as gmsh:
        try:
            if spec.solid is not None:
                _build_solid(gmsh, spec)
                if spec.refine:
                    _refine_fields(gmsh, profile, spec)
            elif spec.element == "tet10":
                _build_tet(gmsh, profile, spec, pockets)
            else:
                _build_hex(gmsh, profile, spec)
            gmsh.option.setNumber("Mesh.ElementOrder", 2)
            gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
            # tetrahedra: curving the edges onto a groove tangles some elements, which gmsh's
            # high-order optimisation repairs (1: optimisation; Gmsh reference manual, Mesh.HighOrderOptimize)
            gmsh.option.setNumber("Mesh.HighOrderOptimize", 1 if spec.element == "tet10" else 0)
            if spec.element == "hex27":
                _quadrilateral_section(gmsh)
            gmsh.model.mesh.generate(3)
            gmsh.model.mesh.removeDuplicateNodes()
            gmsh.write(str(path))
        except Exception as exc:  # gmsh raises bare Exceptions with its log message
            what = f"the STEP solid {Path(spec.solid.path).name}" if spec.solid is not None else f"profile {profile.name!r}"
            raise GmshError(f"gmsh failed to mesh {what}: {exc}") from exc


def _split_arcs(profile: Profile):
    """Segments with arcs over 90° split in two (gmsh builds arcs shorter than a half circle)."""
    out = []
    for s in profile.segments:
        if isinstance(s, Arc) and s.sweep_rad > 0.5 * math.pi + 1e-12:
            mid = s.midpoint
            out += [Arc(s.start, mid, s.center, s.ccw, s.name), Arc(mid, s.end, s.center, s.ccw, s.name)]
        else:
            out.append(s)
    return out


def _add_section(kernel, profile: Profile, scale: float = 1.0):
    """Add the section in the x–z plane (y = 0), lengths × ``scale``; return (surface tag, [(curve tag, segment)])."""
    segs = _split_arcs(profile)
    pts = [kernel.addPoint(scale * s.start[0], 0.0, scale * s.start[1]) for s in segs]
    curves = []
    for i, s in enumerate(segs):
        a, b = pts[i], pts[(i + 1) % len(segs)]
        if isinstance(s, Line):
            c = kernel.addLine(a, b)
        else:
            cen = kernel.addPoint(scale * s.center[0], 0.0, scale * s.center[1])
            c = kernel.addCircleArc(a, cen, b)
        curves.append((c, s))
    loop = kernel.addCurveLoop([c for c, _ in curves])
    return kernel.addPlaneSurface([loop]), curves


def revolved_volumes(occ, profile: Profile, sector_rad: float = 2.0 * math.pi, scale: float = 1.0) -> list:
    """The solid of revolution of ``profile`` about z in gmsh's OpenCASCADE kernel ``occ``, lengths
    × ``scale`` (1e3: millimetres); its volume (dim, tag) pairs."""
    surf, _ = _add_section(occ, profile, scale)
    return [d for d in occ.revolve([(2, surf)], 0, 0, 0, 0, 0, 1, sector_rad) if d[0] == 3]


def _build_tet(gmsh, profile: Profile, spec: MeshSpec, pockets) -> None:
    occ = gmsh.model.occ
    vol = revolved_volumes(occ, profile, spec.sector_rad)
    if pockets is not None:
        tools = _pocket_tools(occ, pockets, profile)
        vol, _ = occ.cut(vol, tools)
    occ.synchronize()
    _tet_sizes(gmsh, spec)
    if spec.refine:
        _refine_fields(gmsh, profile, spec)


def _tet_sizes(gmsh, spec: MeshSpec) -> None:
    gmsh.option.setNumber("Mesh.MeshSizeMax", spec.size_m)
    gmsh.option.setNumber("Mesh.MeshSizeMin", spec.size_m * min([1.0, *spec.refine.values()]) * 0.5)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 12)  # elements per 2π of curvature


def _build_solid(gmsh, spec: MeshSpec) -> None:
    """Import the STEP solid in metres (OpenCASCADE converts from the file's declared unit)."""
    spec.solid.check_unchanged()
    gmsh.option.setString("Geometry.OCCTargetUnit", "M")
    gmsh.model.occ.importShapes(spec.solid.path)
    gmsh.model.occ.synchronize()
    _tet_sizes(gmsh, spec)


def _refine_fields(gmsh, profile: Profile, spec: MeshSpec) -> None:
    """Smaller elements within one element length of the named raceway surfaces."""
    from .nodesets import point_segment_distance

    fields = []
    for name, factor in spec.refine.items():
        tags = []
        for dim, tag in gmsh.model.getEntities(2):
            u0, u1 = gmsh.model.getParametrizationBounds(dim, tag)
            x, y, z = gmsh.model.getValue(dim, tag, [(u0[0] + u1[0]) / 2, (u0[1] + u1[1]) / 2])
            rz = np.array([[math.hypot(x, y), z]])
            segs = [s for s in profile.segments if s.name == name]
            if min(point_segment_distance(rz, s)[0] for s in segs) < 1e-6 * profile.size_m:
                tags.append(tag)
        if not tags:
            continue
        d = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(d, "SurfacesList", tags)
        th = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(th, "InField", d)
        gmsh.model.mesh.field.setNumber(th, "SizeMin", spec.size_m * float(factor))
        gmsh.model.mesh.field.setNumber(th, "SizeMax", spec.size_m)
        gmsh.model.mesh.field.setNumber(th, "DistMin", spec.size_m * float(factor))
        gmsh.model.mesh.field.setNumber(th, "DistMax", 2.0 * spec.size_m)
        fields.append(th)
    if fields:
        mn = gmsh.model.mesh.field.add("Min")
        gmsh.model.mesh.field.setNumbers(mn, "FieldsList", fields)
        gmsh.model.mesh.field.setAsBackgroundMesh(mn)


def _pocket_tools(occ, pockets: CagePockets, profile: Profile):
    """OCC solids to subtract for each pocket (cylinders or boxes on the pitch circle)."""
    r0, r1, z0, z1 = profile.bounds_m
    reach = 2.0 * max(r1 - r0, z1 - z0) + 1e-3
    tools = []
    for th in pockets.angles_rad:
        c = np.array([pockets.pitch_radius_m * math.cos(th), pockets.pitch_radius_m * math.sin(th), pockets.z_m])
        radial = np.array([math.cos(th), math.sin(th), 0.0])
        tangent = np.array([-math.sin(th), math.cos(th), 0.0])
        axis = radial if pockets.axis == "radial" else np.array([0.0, 0.0, 1.0])
        if pockets.shape == "cylinder":
            base = c - axis * reach / 2
            tools.append((3, occ.addCylinder(*base, *(axis * reach), pockets.radius_m)))
        else:
            # box: width along the circumference, height across (axial for radial pockets)
            across = np.array([0.0, 0.0, 1.0]) if pockets.axis == "radial" else radial
            box = occ.addBox(-pockets.width_m / 2, -pockets.height_m / 2, -reach / 2,
                             pockets.width_m, pockets.height_m, reach)
            # local x → tangent, y → across, z → axis
            R = np.column_stack((tangent, across, axis))
            affine = np.zeros(12)
            affine[[0, 1, 2, 4, 5, 6, 8, 9, 10]] = R.ravel()
            affine[[3, 7, 11]] = c
            occ.affineTransform([(3, box)], list(affine))
            tools.append((3, box))
    return tools


def _build_hex(gmsh, profile: Profile, spec: MeshSpec) -> None:
    geo = gmsh.model.geo
    surf, curves = _add_section(geo, profile)
    structured = len(curves) == 4 and all(isinstance(s, Line) for _, s in curves)
    n_el = [max(2, int(math.ceil(s.length_m / (spec.size_m * float(spec.refine.get(s.name, 1.0))) - 1e-9)))
            for _, s in curves]
    if sum(n_el) % 2:  # an all-quadrilateral mesh needs an even number of boundary edges
        n_el[int(np.argmax([s.length_m / n for (_, s), n in zip(curves, n_el)]))] += 1
    for (c, _), n in zip(curves, n_el):
        geo.mesh.setTransfiniteCurve(c, n + 1)
    if structured:
        n0 = max(2, int(math.ceil(curves[0][1].length_m / spec.size_m - 1e-9))) + 1
        n1 = max(2, int(math.ceil(curves[1][1].length_m / spec.size_m - 1e-9))) + 1
        for k, (c, _) in enumerate(curves):
            geo.mesh.setTransfiniteCurve(c, n0 if k % 2 == 0 else n1)
        geo.mesh.setTransfiniteSurface(surf)
    geo.mesh.setRecombine(2, surf)
    r_out = profile.bounds_m[1]
    n_theta = spec.n_theta or max(8, int(math.ceil(r_out * spec.sector_rad / spec.size_m)))
    # the built-in kernel revolves less than 180° at a time: equal pieces of ≤ 90°, equal layers
    pieces = max(1, int(math.ceil(spec.sector_deg / 90.0 - 1e-9)))
    per_piece = int(math.ceil(n_theta / pieces))
    if per_piece * pieces != n_theta:
        log.info("n_theta %d rounded up to %d (a multiple of the %d revolve pieces)", n_theta, per_piece * pieces, pieces)
    cur = [(2, surf)]
    for _ in range(pieces):
        out = geo.revolve(cur, 0, 0, 0, 0, 0, 1, spec.sector_rad / pieces, numElements=[per_piece], recombine=True)
        cur = [out[0]]
    geo.synchronize()
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)  # blossom: all quads for an even boundary


def _quadrilateral_section(gmsh) -> None:
    """Mesh the section with quadrilaterals only, trying the 2-D algorithms in order of quality:
    frontal-Delaunay for quads (8), frontal-Delaunay (6), Delaunay (5). Blossom recombination
    leaves a triangle now and then; the sweep needs none."""
    for algorithm in (8, 6, 5):
        gmsh.option.setNumber("Mesh.Algorithm", algorithm)
        gmsh.model.mesh.generate(2)
        if not set(gmsh.model.mesh.getElementTypes(2)) & {2, 9}:   # 3-node / 6-node triangles
            return
        gmsh.model.mesh.clear()
    raise QuadMeshError("the section could not be meshed with quadrilaterals only; use element='tet10'")


def tangled_elements(mesh: skfem.Mesh, element: str) -> np.ndarray:
    """Indices of the elements whose Jacobian determinant changes sign (or vanishes) between their
    vertices, edge midpoints and centre: such an element maps part of itself inside out, and its
    stiffness and mass are wrong. (A consistently negative determinant is only an orientation.)"""
    J = mesh.mapping().detDF(_CHECK_POINTS[element])
    return np.flatnonzero((J.min(axis=1) <= 0.0) & (J.max(axis=1) >= 0.0))


def _read_volume_mesh(path: Path, cell_type: str) -> skfem.Mesh:
    """meshio → scikit-fem, keeping only the volume cells and the nodes they use."""
    m = meshio.read(path)
    cells = m.cells_dict.get(cell_type)
    other = sorted(k for k in m.cells_dict if k in {"tetra", "tetra10", "hexahedron", "hexahedron27",
                                                      "wedge", "wedge18", "pyramid", "pyramid14"}
                   and k != cell_type)
    if cells is None or other:
        raise RuntimeError(
            f"gmsh produced {sorted(m.cells_dict)} instead of only {cell_type}: the section could not "
            "be meshed with quadrilaterals; use element='tet10'" if cell_type == "hexahedron27" else
            f"gmsh produced {sorted(m.cells_dict)}, expected {cell_type}"
        )
    used = np.unique(cells)
    renum = np.full(len(m.points), -1, dtype=np.int64)
    renum[used] = np.arange(len(used))
    return from_meshio(meshio.Mesh(m.points[used], [(cell_type, renum[cells])]))
