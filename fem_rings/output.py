"""Export of ring models and nodal results: ParaView files (``.vtu``, ``.pvd``) and PNG pictures.

Node and field conventions (shared with the rest of :mod:`fem_rings`):

* The meshes are scikit-fem :class:`~skfem.MeshTet2` (10-node tetrahedra) or
  :class:`~skfem.MeshHex2` (27-node hexahedra) with curved (isoparametric) cells.
* "Nodes" are the columns of ``mesh.doflocs`` (m): vertex nodes first, then the higher-order
  nodes, numbered like the degrees of freedom of ``mesh.elem()``;
  ``mesh.dofs.element_dofs`` is the cell connectivity in node numbers.
* A nodal field is an array of shape ``(n_nodes,)`` or ``(n_nodes, k)`` aligned with
  ``mesh.doflocs.T``: displacement (n_nodes, 3) in m, stress (n_nodes, 6) in Pa in Voigt order
  xx, yy, zz, yz, xz, xy, von Mises stress (n_nodes,) in Pa.

Exported files keep every node as a point, in the node numbering above, so nodal fields are
written unchanged. Only the cell connectivity is translated to the VTK node order of
``tetra10`` (``VTK_QUADRATIC_TETRA``) and ``hexahedron27`` (``VTK_TRIQUADRATIC_HEXAHEDRON``), and
cells that scikit-fem stores with a negative orientation are renumbered so that every exported
cell has a positive volume in VTK (scikit-fem integrates with ``|det J|`` and does not orient
its cells; VTK and ParaView take the sign of the volume from the node order).

Symmetric tensors: ParaView reads a 6-component array as XX, YY, ZZ, XY, YZ, XZ (``vtkMath.h``),
which differs from the Voigt order used here; :func:`voigt_to_vtk_tensor` reorders a stress
array for filters that interpret tensors (principal values, tensor glyphs).

Pictures are rendered off screen with pyvista, which is imported inside the rendering
functions only, so importing :mod:`fem_rings` does not load VTK.
"""

from __future__ import annotations

import logging
import math
import os
import uuid
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path

import meshio
import numpy as np
import skfem

__all__ = [
    "to_meshio",
    "write_vtu",
    "write_vtu_series",
    "render_png",
    "displacement_magnitude",
    "voigt_to_vtk_tensor",
    "auto_warp_factor",
    "vtk_cells",
]

logger = logging.getLogger(__name__)

#: Local node order of a VTK ``hexahedron27`` cell as rows of scikit-fem's ``ElementHex2``
#: element DOFs. It is the ``HEX_MAPPING`` of ``skfem/io/meshio.py`` (the inverse of the
#: permutation scikit-fem applies when it imports a meshio ``hexahedron27``), checked against
#: the parametric coordinates of ``vtkTriQuadraticHexahedron``: 8 corners, 12 edge nodes
#: (01, 12, 23, 30, 45, 56, 67, 74, 04, 15, 26, 37), 6 face nodes (x-, x+, y-, y+, z-, z+),
#: the centre node.
HEX27_FROM_SKFEM = (0, 3, 6, 2, 1, 5, 7, 4,
                    10, 16, 14, 9, 12, 18, 17, 11, 8, 15, 19, 13,
                    20, 25, 22, 23, 21, 24, 26)

#: Local node order of a VTK ``tetra10`` cell as rows of scikit-fem's ``ElementTetP2`` element
#: DOFs: the identity. Both number the corners 0-3 and then the edge nodes 01, 12, 02, 03, 13, 23.
TETRA10_FROM_SKFEM = tuple(range(10))

# Renumbering of a VTK cell (in VTK local order) that mirrors it: corners 1 and 2 of a tetra10
# are exchanged, bottom (corners 0-3) and top (4-7) of a hexahedron27.
_TETRA10_MIRROR = (0, 2, 1, 3, 6, 5, 4, 7, 9, 8)
_HEX27_MIRROR = (4, 5, 6, 7, 0, 1, 2, 3,
                 12, 13, 14, 15, 8, 9, 10, 11, 16, 17, 18, 19,
                 20, 21, 22, 23, 25, 24, 26)

_VOIGT_TO_VTK = (0, 1, 2, 5, 3, 4)  # xx yy zz yz xz xy -> xx yy zz xy yz xz

# fraction of the model size (bounding-box diagonal) that the largest displacement is drawn at
# when render_png chooses the warp factor itself
_AUTO_WARP_FRACTION = 0.05


# ---------------------------------------------------------------------------------------------
# meshio / VTK export
# ---------------------------------------------------------------------------------------------
def _tet_orientation(x: np.ndarray) -> np.ndarray:
    """Signed volume × 6 of the straight tetrahedra on the corners, x: (n_cells, ≥4, 3)."""
    a, b, c = x[:, 1] - x[:, 0], x[:, 2] - x[:, 0], x[:, 3] - x[:, 0]
    return np.einsum("ij,ij->i", a, np.cross(b, c))


def _hex_orientation(x: np.ndarray) -> np.ndarray:
    """det J at the cell centre of the trilinear map on the VTK-ordered corners, x: (n, ≥8, 3)."""
    dxi = (x[:, 1] - x[:, 0]) + (x[:, 2] - x[:, 3]) + (x[:, 5] - x[:, 4]) + (x[:, 6] - x[:, 7])
    deta = (x[:, 3] - x[:, 0]) + (x[:, 2] - x[:, 1]) + (x[:, 7] - x[:, 4]) + (x[:, 6] - x[:, 5])
    dzeta = (x[:, 4] - x[:, 0]) + (x[:, 5] - x[:, 1]) + (x[:, 6] - x[:, 2]) + (x[:, 7] - x[:, 3])
    return np.einsum("ij,ij->i", dxi, np.cross(deta, dzeta))


_CELL_TABLE = {
    # scikit-fem mesh class: (meshio cell type, VTK order, mirror, orientation measure)
    skfem.MeshTet2: ("tetra10", TETRA10_FROM_SKFEM, _TETRA10_MIRROR, _tet_orientation),
    skfem.MeshHex2: ("hexahedron27", HEX27_FROM_SKFEM, _HEX27_MIRROR, _hex_orientation),
}


def _cell_info(mesh):
    for cls, info in _CELL_TABLE.items():
        if type(mesh) is cls:
            return info
    supported = ", ".join(c.__name__ for c in _CELL_TABLE)
    raise TypeError(f"mesh must be one of {supported}, got {type(mesh).__name__}")


def vtk_cells(mesh) -> tuple[str, np.ndarray]:
    """Quadratic cells of ``mesh`` in VTK node order, all with positive orientation.

    Parameters
    ----------
    mesh : skfem.MeshTet2 or skfem.MeshHex2
        Curved quadratic mesh.

    Returns
    -------
    cell_type : str
        meshio cell type, ``"tetra10"`` or ``"hexahedron27"``.
    cells : numpy.ndarray of int, shape (n_elements, 10 or 27)
        Node numbers (columns of ``mesh.doflocs``) of each cell in VTK local order.
    """
    cell_type, order, mirror, orientation = _cell_info(mesh)
    cells = np.asarray(mesh.dofs.element_dofs)[list(order)].T.astype(np.int64)
    x = np.asarray(mesh.doflocs).T[cells]
    inverted = orientation(x) < 0.0
    if inverted.any():
        cells[inverted] = cells[inverted][:, list(mirror)]
        logger.debug("renumbered %d of %d %s cells to positive orientation",
                     int(inverted.sum()), len(cells), cell_type)
    return cell_type, cells


def _n_nodes(mesh) -> int:
    return int(np.asarray(mesh.doflocs).shape[1])


def _checked_point_data(point_data: Mapping | None, n_nodes: int) -> dict[str, np.ndarray]:
    if point_data is None:
        return {}
    if not isinstance(point_data, Mapping):
        raise TypeError("point_data must be a mapping name -> array, "
                        f"got {type(point_data).__name__}")
    checked = {}
    for name, values in point_data.items():
        if not isinstance(name, str) or not name:
            raise ValueError(f"point_data names must be non-empty strings, got {name!r}")
        arr = np.asarray(values)
        if arr.ndim not in (1, 2) or arr.shape[0] != n_nodes:
            raise ValueError(
                f"point_data field {name!r} has shape {arr.shape}; expected ({n_nodes},) or "
                f"({n_nodes}, k), one row per node of the mesh"
            )
        if not (np.issubdtype(arr.dtype, np.number) or arr.dtype == bool):
            raise ValueError(f"point_data field {name!r} must be numeric, got dtype {arr.dtype}")
        checked[name] = arr
    return checked


def to_meshio(mesh, point_data: Mapping[str, np.ndarray] | None = None) -> meshio.Mesh:
    """Convert a quadratic scikit-fem mesh and nodal fields to a :class:`meshio.Mesh`.

    Every node (``mesh.doflocs``, vertices and higher-order nodes) becomes a point with the same
    number, so the ``point_data`` arrays are passed through unchanged. The cells are
    ``tetra10`` or ``hexahedron27`` in VTK node order (see :func:`vtk_cells`).

    Parameters
    ----------
    mesh : skfem.MeshTet2 or skfem.MeshHex2
        Curved quadratic mesh, coordinates in m.
    point_data : mapping of str to array_like, optional
        Nodal fields, each of shape (n_nodes,) or (n_nodes, k), SI units.

    Returns
    -------
    meshio.Mesh
        Points (n_nodes, 3) in m and one cell block.

    Raises
    ------
    TypeError
        If ``mesh`` is not a ``MeshTet2`` or ``MeshHex2``.
    ValueError
        If a field does not have one row per node; the message names the field.
    """
    cell_type, cells = vtk_cells(mesh)
    data = _checked_point_data(point_data, _n_nodes(mesh))
    points = np.ascontiguousarray(np.asarray(mesh.doflocs, dtype=float).T)
    return meshio.Mesh(points, [(cell_type, cells)], point_data=data)


@contextmanager
def _atomic_target(path: Path, suffix: str):
    """Yield a temporary file name next to ``path``; rename it to ``path`` on success.

    The file appears under its final name only when complete (``os.replace`` within one folder
    is atomic on POSIX and Windows); on error the temporary file is removed.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    # a unique name that the writer creates itself, so the file gets the usual permissions
    # (tempfile.mkstemp would leave it readable by the owner only)
    tmp = path.with_name(f".{path.name}.{os.getpid()}-{uuid.uuid4().hex[:12]}.part{suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def write_vtu(path: str | os.PathLike, mesh,
              point_data: Mapping[str, np.ndarray] | None = None) -> Path:
    """Write the mesh and nodal fields to a VTK unstructured-grid file (``.vtu``) for ParaView.

    The file is written under a temporary name in the same folder and then renamed, so a file
    with the final name is always complete. Missing parent folders are created.

    Parameters
    ----------
    path : str or os.PathLike
        Output file; must end in ``.vtu``.
    mesh : skfem.MeshTet2 or skfem.MeshHex2
        Curved quadratic mesh, coordinates in m.
    point_data : mapping of str to array_like, optional
        Nodal fields, each of shape (n_nodes,) or (n_nodes, k), SI units.

    Returns
    -------
    pathlib.Path
        The written file.
    """
    path = Path(path)
    if path.suffix.lower() != ".vtu":
        raise ValueError(f"path must end in .vtu, got {str(path)!r}")
    mio = to_meshio(mesh, point_data)
    with _atomic_target(path, ".vtu") as tmp:
        meshio.write(tmp, mio, file_format="vtu")
    logger.info("wrote %s (%d points, %d cells)", path, len(mio.points), len(mio.cells[0].data))
    return path


def _pvd_xml(entries: Sequence[tuple[float, str]]) -> bytes:
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    collection = ET.SubElement(root, "Collection")
    for time_s, file_name in entries:
        ET.SubElement(collection, "DataSet", timestep=repr(float(time_s)), group="", part="0",
                      file=file_name)
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"


def _checked_times(frames: Sequence) -> list[float]:
    times = []
    for i, frame in enumerate(frames):
        try:
            time_s, _ = frame
            time_s = float(time_s)
        except (TypeError, ValueError):
            raise ValueError(f"frame {i} must be a (time_s, point_data) pair") from None
        if not math.isfinite(time_s):
            raise ValueError(f"frame {i}: time must be finite, got {time_s}")
        if times and time_s <= times[-1]:
            raise ValueError(f"frame {i}: times must increase, got {time_s} after {times[-1]}")
        times.append(time_s)
    if not times:
        raise ValueError("frames is empty: a series needs at least one (time_s, point_data) frame")
    return times


def write_vtu_series(folder: str | os.PathLike, mesh,
                     frames: Sequence[tuple[float, Mapping[str, np.ndarray] | None]],
                     *, name: str = "frame") -> Path:
    """Write a time series: one ``.vtu`` per frame and a ParaView collection file (``.pvd``).

    Open the ``.pvd`` file in ParaView to step through the frames with their times. The
    collection file refers to the frames by relative names and is written last, so it exists
    only when all frames do.

    Parameters
    ----------
    folder : str or os.PathLike
        Output folder, created if missing.
    mesh : skfem.MeshTet2 or skfem.MeshHex2
        Curved quadratic mesh, coordinates in m (the same for all frames).
    frames : sequence of (float, mapping)
        ``(time_s, point_data)`` per frame, times in s strictly increasing; ``point_data`` as
        in :func:`write_vtu`.
    name : str, optional
        Stem of the file names: ``{name}.pvd`` and ``{name}_0000.vtu``, ``{name}_0001.vtu`` …

    Returns
    -------
    pathlib.Path
        The ``.pvd`` file.
    """
    if not name or Path(name).name != name:
        raise ValueError(f"name must be a plain file stem, got {name!r}")
    frames = list(frames)
    times = _checked_times(frames)
    folder = Path(folder)
    width = max(4, len(str(len(frames) - 1)))
    entries = []
    for i, (time_s, (_, point_data)) in enumerate(zip(times, frames)):
        file_name = f"{name}_{i:0{width}d}.vtu"
        write_vtu(folder / file_name, mesh, point_data)
        entries.append((time_s, file_name))
    pvd = folder / f"{name}.pvd"
    with _atomic_target(pvd, ".pvd") as tmp:
        tmp.write_bytes(_pvd_xml(entries))
    logger.info("wrote %s (%d frames, t = %g … %g s)", pvd, len(times), times[0], times[-1])
    return pvd


# ---------------------------------------------------------------------------------------------
# field helpers
# ---------------------------------------------------------------------------------------------
def displacement_magnitude(u: np.ndarray) -> np.ndarray:
    """Length of the displacement vector of each node.

    Parameters
    ----------
    u : array_like, shape (n_nodes, 3)
        Nodal displacement, m.

    Returns
    -------
    numpy.ndarray, shape (n_nodes,)
        ``|u|`` in m.
    """
    u = np.asarray(u, dtype=float)
    if u.ndim != 2 or u.shape[1] != 3:
        raise ValueError(f"displacement must have shape (n_nodes, 3), got {u.shape}")
    return np.linalg.norm(u, axis=1)


def voigt_to_vtk_tensor(stress: np.ndarray) -> np.ndarray:
    """Reorder symmetric tensors from Voigt (xx yy zz yz xz xy) to VTK (xx yy zz xy yz xz) order.

    Parameters
    ----------
    stress : array_like, shape (n, 6)
        Symmetric tensors in Voigt order, e.g. stress in Pa.

    Returns
    -------
    numpy.ndarray, shape (n, 6)
        The same tensors in the component order ParaView assumes for 6-component arrays.
    """
    stress = np.asarray(stress)
    if stress.ndim != 2 or stress.shape[1] != 6:
        raise ValueError(f"symmetric tensors must have shape (n, 6), got {stress.shape}")
    return stress[:, list(_VOIGT_TO_VTK)]


# ---------------------------------------------------------------------------------------------
# off-screen rendering
# ---------------------------------------------------------------------------------------------
def _model_size(points: np.ndarray) -> float:
    """Bounding-box diagonal of points (n, 3), m."""
    return float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))


def auto_warp_factor(points: np.ndarray, u: np.ndarray) -> float:
    """Warp factor that draws the largest displacement at 5 % of the model size.

    Parameters
    ----------
    points : array_like, shape (n_nodes, 3)
        Node coordinates, m.
    u : array_like, shape (n_nodes, 3)
        Nodal displacement, m.

    Returns
    -------
    float
        ``0.05 × bounding-box diagonal / max |u|``; 0 if the displacement is zero everywhere.
    """
    u_max = float(displacement_magnitude(u).max(initial=0.0))
    if u_max == 0.0:
        return 0.0
    return _AUTO_WARP_FRACTION * _model_size(np.asarray(points, dtype=float)) / u_max


def _checked_scalars(scalars, n_nodes: int, label: str) -> np.ndarray:
    s = np.asarray(scalars, dtype=float)
    if s.ndim != 1 or s.shape[0] != n_nodes:
        raise ValueError(
            f"scalars for {label!r} must have shape ({n_nodes},), one value per node "
            f"(columns of mesh.doflocs), got {s.shape}"
        )
    if not np.all(np.isfinite(s)):
        n_bad = int(np.sum(~np.isfinite(s)))
        raise ValueError(f"scalars for {label!r} contain {n_bad} non-finite values")
    return s


def _deformed_points(points: np.ndarray, displacement_m, warp_factor):
    """Points moved by displacement × factor; returns (points, factor or None)."""
    if displacement_m is None:
        if warp_factor is not None:
            raise ValueError("warp_factor was given without displacement_m")
        return points, None
    u = np.asarray(displacement_m, dtype=float)
    if u.shape != points.shape:
        raise ValueError(
            f"displacement_m must have shape {points.shape} (n_nodes, 3), got {u.shape}")
    if not np.all(np.isfinite(u)):
        raise ValueError("displacement_m contains non-finite values")
    factor = auto_warp_factor(points, u) if warp_factor is None else float(warp_factor)
    if not math.isfinite(factor):
        raise ValueError(f"warp_factor must be finite, got {warp_factor}")
    return points + factor * u, factor


def _title_text(title: str | None, factor: float | None) -> str:
    lines = [title] if title else []
    if factor is not None:
        shown = f"{factor:.0f}" if 100.0 <= factor < 1e6 else f"{factor:.3g}"
        lines.append(f"deformation × {shown}")
    return "\n".join(lines)


def _pyvista_surface(mesh, points: np.ndarray, scalars: np.ndarray, name: str):
    """Outer surface of the quadratic cells, faces tessellated to follow their curvature."""
    import pyvista as pv
    from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter

    cell_type, cells = vtk_cells(mesh)
    vtk_type = {"tetra10": pv.CellType.QUADRATIC_TETRA,
                "hexahedron27": pv.CellType.TRIQUADRATIC_HEXAHEDRON}[cell_type]
    grid = pv.UnstructuredGrid({vtk_type: cells}, points)
    grid.point_data[name] = scalars
    # the VTK filter is used directly: its keyword in pyvista's extract_surface varies by version
    surface_filter = vtkDataSetSurfaceFilter()
    surface_filter.SetNonlinearSubdivisionLevel(2)
    surface_filter.SetInputData(grid)
    surface_filter.Update()
    return pv.wrap(surface_filter.GetOutput())


# camera: looking at the model from +x, −y, +z, with z (the ring axis) up
_VIEW_DIRECTION = np.array([1.0, -1.0, 0.8])
_VIEW_UP = np.array([0.0, 0.0, 1.0])
# part of the window (normalised viewport x0, x1, y0, y1) left free for the model:
# the colour bar is to the right, the title on top
_MODEL_REGION = (0.03, 0.80, 0.04, 0.84)


def _fit_parallel_camera(camera, points: np.ndarray, aspect: float) -> None:
    """Point a parallel-projection camera so all ``points`` fill ``_MODEL_REGION``.

    With a parallel projection the window position is linear in the point coordinates, so the
    fit is exact: the projected extent sets the parallel scale (half the visible height) and the
    focal point is shifted so the projected box is centred in the region.
    """
    back = _VIEW_DIRECTION / np.linalg.norm(_VIEW_DIRECTION)  # from focal point to camera
    up = _VIEW_UP - np.dot(_VIEW_UP, back) * back
    up /= np.linalg.norm(up)
    right = np.cross(up, back)
    xr, yu = points @ right, points @ up
    x0, x1, y0, y1 = _MODEL_REGION
    width, height = max(np.ptp(xr), 1e-300), max(np.ptp(yu), 1e-300)
    scale = max(width / (2.0 * aspect * (x1 - x0)), height / (2.0 * (y1 - y0)))
    # window coordinate X = 0.5 + (p·right − F·right) / (2 scale aspect), likewise for Y
    f_right = 0.5 * (xr.min() + xr.max()) - ((x0 + x1) / 2 - 0.5) * 2.0 * scale * aspect
    f_up = 0.5 * (yu.min() + yu.max()) - ((y0 + y1) / 2 - 0.5) * 2.0 * scale
    centre = 0.5 * (points.min(axis=0) + points.max(axis=0))
    focal = (centre + (f_right - centre @ right) * right + (f_up - centre @ up) * up)
    distance = 4.0 * max(_model_size(points), 1e-300)
    camera.parallel_projection = True
    camera.focal_point = tuple(focal)
    camera.position = tuple(focal + distance * back)
    camera.up = tuple(up)
    camera.parallel_scale = scale


def render_png(path: str | os.PathLike, mesh, scalars: np.ndarray, *,
               label: str = "von Mises", unit: str = "MPa", scale: float = 1.0,
               displacement_m: np.ndarray | None = None, warp_factor: float | None = None,
               window_size: tuple[int, int] = (1200, 800), title: str | None = None,
               cmap: str = "viridis") -> Path:
    """Render the model coloured by a nodal scalar field to a PNG file, off screen.

    The outer surface of the curved cells is drawn (each face subdivided so that curvature and
    the quadratic field variation show) in a parallel projection from the +x, −y, +z octant,
    fitted so the whole model is visible, on a white background, with a colour bar titled
    ``f"{label} [{unit}]"``. The PNG is exactly ``window_size`` pixels and is written under a
    temporary name first, then renamed.

    Parameters
    ----------
    path : str or os.PathLike
        Output file; must end in ``.png``. Missing parent folders are created.
    mesh : skfem.MeshTet2 or skfem.MeshHex2
        Curved quadratic mesh, coordinates in m.
    scalars : array_like, shape (n_nodes,)
        Nodal values in SI units, e.g. von Mises stress in Pa.
    label, unit : str, optional
        Colour-bar title parts; ``unit`` is the unit after multiplication by ``scale``.
    scale : float, optional
        Factor applied to ``scalars`` for display, e.g. 1e-6 for Pa → MPa.
    displacement_m : array_like, shape (n_nodes, 3), optional
        Nodal displacement, m. If given, the model is drawn deformed by
        ``displacement_m × warp_factor``.
    warp_factor : float, optional
        Displacement magnification. If None (with ``displacement_m``), it is chosen so the
        largest displacement is drawn at 5 % of the bounding-box diagonal. The factor used is
        written in the title text.
    window_size : (int, int), optional
        Image width and height, pixels.
    title : str, optional
        Text at the top of the picture.
    cmap : str, optional
        Matplotlib colour map name.

    Returns
    -------
    pathlib.Path
        The written PNG file.

    Raises
    ------
    ValueError
        If ``scalars`` does not have one finite value per node, ``displacement_m`` has the wrong
        shape, or the file name or window size is invalid.
    """
    path = Path(path)
    if path.suffix.lower() != ".png":
        raise ValueError(f"path must end in .png, got {str(path)!r}")
    width_px, height_px = (int(v) for v in window_size)
    if width_px < 16 or height_px < 16:
        raise ValueError(f"window_size must be at least 16 × 16 pixels, got {tuple(window_size)}")
    _cell_info(mesh)
    points0 = np.ascontiguousarray(np.asarray(mesh.doflocs, dtype=float).T)
    values = _checked_scalars(scalars, len(points0), label) * float(scale)
    points, factor = _deformed_points(points0, displacement_m, warp_factor)
    bar_title = f"{label} [{unit}]"
    surface = _pyvista_surface(mesh, points, values, bar_title)
    image = _render_surface(surface, bar_title, _title_text(title, factor), cmap,
                            (width_px, height_px))
    with _atomic_target(path, ".png") as tmp:
        _write_png(tmp, image)
    logger.info("wrote %s (%d × %d px)", path, width_px, height_px)
    return path


def _render_surface(surface, bar_title: str, text: str, cmap: str,
                    window_size: tuple[int, int]) -> np.ndarray:
    """Off-screen render; returns the RGB image (height, width, 3) of uint8."""
    import pyvista as pv

    width_px, height_px = window_size
    values = surface.point_data[bar_title]
    clim = (float(values.min()), float(values.max()))
    font = max(8, round(height_px / 40))  # pixels, for colour-bar labels
    plotter = pv.Plotter(off_screen=True, window_size=(width_px, height_px))
    try:
        plotter.set_background("white")
        plotter.add_mesh(
            surface, scalars=bar_title, cmap=cmap, clim=clim,
            smooth_shading=True, split_sharp_edges=True,
            scalar_bar_args=dict(
                title=bar_title, vertical=True, position_x=0.84, position_y=0.08,
                width=0.05, height=0.74, color="black", fmt="%.4g", n_labels=6,
                title_font_size=font, label_font_size=font, unconstrained_font_size=True,
            ),
        )
        text_properties = [plotter.scalar_bar.GetTitleTextProperty(),
                           plotter.scalar_bar.GetLabelTextProperty()]
        if text:
            actor = plotter.add_text(text, position="upper_left",
                                     font_size=max(6, round(font * 0.6)), color="black")
            text_properties.append(actor.GetTextProperty())
        _use_font_file(text_properties)
        _fit_parallel_camera(plotter.camera, np.asarray(surface.points), width_px / height_px)
        plotter.renderer.ResetCameraClippingRange()
        image = plotter.screenshot(None, return_img=True)
    finally:
        plotter.close()
    return np.asarray(image)[:, :, :3]


def _use_font_file(text_properties) -> None:
    """Draw text in matplotlib's DejaVu Sans if available.

    VTK's built-in sans-serif font draws square brackets like parentheses, which would turn the
    colour-bar title "von Mises [MPa]" into "von Mises (MPa)".
    """
    import matplotlib

    font_file = Path(matplotlib.get_data_path(), "fonts", "ttf", "DejaVuSans.ttf")
    if not font_file.is_file():
        logger.debug("%s not found; VTK's built-in font is used", font_file)
        return
    for prop in text_properties:
        prop.SetFontFamilyAsString("File")
        prop.SetFontFile(str(font_file))


def _write_png(path: Path, image: np.ndarray) -> None:
    from PIL import Image  # a dependency of pyvista

    Image.fromarray(np.ascontiguousarray(image, dtype=np.uint8)).save(path, format="PNG")
