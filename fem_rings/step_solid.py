"""Checks of a ring solid given as a STEP file: is it a solid, how large, is it a ring about z.

The file is read with gmsh's OpenCASCADE importer (``gmsh.model.occ.importShapes``). OpenCASCADE
converts the length unit the file declares to millimetres; the checks run in millimetres (the
importer's and the point-in-solid test's native scale) and the results are returned in metres.

Units: ``unit="file"`` trusts the file's declared unit. ``unit="mm"`` or ``"m"`` states the unit
the file is expected to be in and refuses a file that declares another SI length unit (or none),
like :func:`fem_rings.dxf_section.profile_from_dxf` does with ``$INSUNITS``. The declared unit is
the ``SI_UNIT(prefix, .METRE.)`` of the file's length unit (ISO 10303-41, ``si_unit``; ISO
10303-21 for the file syntax).

A ring about z: its centre of mass lies on the z axis (within 1e-3 of its size: a CAD model placed
off the axis is off by a radius, while a ring's own asymmetric features — an odd number of gear
teeth or holes is symmetric, a single lubrication hole or notch moves the centre by ~1e-4 of the
size — stay far below) and the point of the axis at mid-height lies outside every volume (the bore).

A ring meshed from a STEP solid (:class:`StepSolid` in :class:`fem_rings.mesh.MeshSpec`) keeps a
nominal (r, z) section that names its faces: a boundary facet of the solid that lies on a revolved
segment of the section takes the segment's name (raceway, bolt face); the rest of the solid (gear
teeth, bolt holes, chamfers the section leaves out) is named ``other``. ``probes_m`` of
:func:`check_step_solid` measures, before any meshing, how far given points (the raceways' contact
points, the support face) lie from the solid's faces, so a section that does not describe the
solid is refused early.
"""

from __future__ import annotations

import logging
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from .cache import file_digest
from .mesh import gmsh_session, revolved_volumes

__all__ = ["StepInfo", "StepSolid", "check_step_solid", "step_solid", "write_step"]

log = logging.getLogger(__name__)

_UNIT_M = {"mm": 1e-3, "m": 1.0}
_SI_PREFIX = {"$": "m", ".MILLI.": "mm", ".CENTI.": "cm", ".MICRO.": "µm", ".KILO.": "km", ".DECI.": "dm"}
_SI_LENGTH = re.compile(r"SI_UNIT\s*\(\s*(\$|\.[A-Z]+\.)\s*,\s*\.METRE\.\s*\)")
_CENTRED_REL = 1e-3


@dataclass(frozen=True)
class StepInfo:
    """What :func:`check_step_solid` found in a STEP file.

    Attributes
    ----------
    path : str
    n_volumes, n_surfaces : int
        Solids and faces in the file.
    volume_m3 : float
        Total volume of the solids, m³.
    bbox_min_m, bbox_max_m : (3,) tuple of float, m
        Axis-aligned bounding box (x, y, z) of all entities.
    is_ring_about_z : bool
        Centre of mass on the z axis and the axis at mid-height outside the solid.
    not_ring_reason : str
        Why it is not a ring about z; empty when it is.
    """

    path: str
    n_volumes: int
    n_surfaces: int
    volume_m3: float
    bbox_min_m: tuple[float, float, float]
    bbox_max_m: tuple[float, float, float]
    is_ring_about_z: bool
    not_ring_reason: str = ""
    probe_distances_m: tuple = ()


@dataclass(frozen=True)
class StepSolid:
    """A ring solid to mesh from a STEP file (:class:`fem_rings.mesh.MeshSpec` ``solid``).

    ``unit`` is checked against the file as in :func:`check_step_solid`; the geometry is read in
    the file's declared unit and converted to metres. The cache keys hold ``sha256`` (the file's
    bytes) and not the path, so an edited file is meshed afresh and a moved one is not.
    """

    path: str = field(metadata={"hash": False})
    unit: str = "file"
    sha256: str = ""

    def check_unchanged(self) -> None:
        """ValueError when the file no longer has the digest it was described with."""
        if _digest(self.path) != self.sha256:
            raise ValueError(f"{self.path}: the file changed after it was checked; run again")


def _digest(path) -> str:
    try:
        return file_digest(path)
    except OSError as exc:
        raise ValueError(f"{path}: cannot be read ({exc.strerror})") from None


def step_solid(path, unit: str = "file") -> StepSolid:
    """The :class:`StepSolid` of a file (its digest taken now)."""
    if unit not in (*_UNIT_M, "file"):
        raise ValueError(f"{path}: unit must be 'file', 'mm' or 'm', got {unit!r}")
    return StepSolid(str(path), unit, _digest(path))


def check_step_solid(path, *, unit: str = "file", probes_m=None) -> StepInfo:
    """Read a STEP file and check that it holds a solid ring about the z axis.

    Parameters
    ----------
    path : str or Path
    unit : {"file", "mm", "m"}
        ``"file"`` uses the file's declared length unit; ``"mm"`` / ``"m"`` must agree with it.
    probes_m : (n, 3) array, optional
        Points (x, y, z), m, whose distances to the nearest face of the solid are returned in
        ``probe_distances_m``.

    Returns
    -------
    StepInfo
        Lengths in metres.

    Raises
    ------
    ValueError
        One line naming the file: missing or unreadable, unit disagreement, no volume
        (``"… is not a solid: N surfaces, 0 volumes"``).
    """
    label = str(path)
    if unit not in (*_UNIT_M, "file"):
        raise ValueError(f"{label}: unit must be 'file', 'mm' or 'm', got {unit!r}")
    if not Path(path).is_file():
        raise ValueError(f"{label}: no such file")
    if unit != "file":
        _check_declared_unit(label, Path(path), unit)
    with gmsh_session("step check") as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "MM")
        try:
            gmsh.model.occ.importShapes(str(path))
            gmsh.model.occ.synchronize()
        except Exception:  # gmsh raises a bare Exception ("Could not read file …")
            raise ValueError(f"{label}: not a readable STEP file") from None
        vols = [t for _, t in gmsh.model.getEntities(3)]
        n_surf = len(gmsh.model.getEntities(2))
        if not vols:
            raise ValueError(f"{label} is not a solid: {n_surf} surfaces, 0 volumes")
        box_mm = gmsh.model.getBoundingBox(-1, -1)
        volume_mm3 = sum(gmsh.model.occ.getMass(3, t) for t in vols)
        reason = _not_ring_reason(gmsh, vols, box_mm)
        probes = () if probes_m is None else tuple(1e-3 * _distance_to_faces_mm(gmsh, 1e3 * p) for p in probes_m)
    info = StepInfo(label, len(vols), n_surf, volume_mm3 * 1e-9,
                    tuple(v * 1e-3 for v in box_mm[:3]), tuple(v * 1e-3 for v in box_mm[3:]),
                    not reason, reason, probes)
    log.info("%s: %d volumes, %d surfaces, %.6g m³, %s", label, info.n_volumes, info.n_surfaces,
             info.volume_m3, "a ring about z" if not reason else f"not a ring about z ({reason})")
    return info


def _check_declared_unit(label: str, path: Path, unit: str) -> None:
    """Refuse a file whose declared SI length unit is not ``unit``."""
    try:
        text = path.read_text(errors="replace")
    except OSError as exc:
        raise ValueError(f"{label}: cannot be read ({exc.strerror})") from None
    found = {_SI_PREFIX.get(p, p) for p in _SI_LENGTH.findall(text)}
    if found != {unit}:
        said = ", ".join(sorted(found)) if found else "no SI length unit"
        raise ValueError(f"{label}: unit={unit!r} disagrees with the file, which declares {said}; "
                         "pass unit='file' to use the file's unit")


def _not_ring_reason(gmsh, vols, box_mm) -> str:
    """Empty when the solid is centred on the z axis with the axis outside it, else why not."""
    x0, y0, z0, x1, y1, z1 = box_mm
    size = max(x1 - x0, y1 - y0, z1 - z0)
    masses = [gmsh.model.occ.getMass(3, t) for t in vols]
    centres = [gmsh.model.occ.getCenterOfMass(3, t) for t in vols]
    cx, cy = (sum(m * c[i] for m, c in zip(masses, centres)) / sum(masses) for i in (0, 1))
    off = math.hypot(cx, cy)
    if off > _CENTRED_REL * size:
        return f"its centre of mass lies {off * 1e-3:.6g} m off the z axis"
    axis_point = [0.0, 0.0, (z0 + z1) / 2]
    inside = [t for t in vols if gmsh.model.isInside(3, t, axis_point)]
    if inside:
        return f"the z axis at mid-height (z = {axis_point[2] * 1e-3:.6g} m) lies inside volume {inside[0]}: no bore"
    return ""


def _distance_to_faces_mm(gmsh, point_mm) -> float:
    """Distance of a point to the nearest face of the model (OpenCASCADE's projection on each face)."""
    p = [float(v) for v in point_mm]
    return min(math.dist(gmsh.model.getClosestPoint(2, t, p)[0], p) for _, t in gmsh.model.getEntities(2))


def write_step(path, profile, modify=None) -> Path:
    """Write the solid of revolution of ``profile`` as a STEP file, in millimetres (the unit gmsh's
    OpenCASCADE writer declares), after ``modify(occ, volumes) -> volumes`` has changed it in the
    same kernel and unit: gear teeth fused on, bolt holes cut (``occ.fuse``, ``occ.cut``). A start
    for a ring whose CAD model is not at hand, and for tests of STEP rings."""
    with gmsh_session("step writer") as gmsh:
        occ = gmsh.model.occ
        volumes = revolved_volumes(occ, profile, scale=1e3)
        if modify is not None:
            volumes = modify(occ, volumes)
        occ.synchronize()
        gmsh.write(str(path))
    return Path(path)
