"""Export of ring models and nodal results to ParaView files (``.vtu``, ``.pvd``) through meshio.

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

Pictures: :mod:`fem_rings.render`.
"""

from __future__ import annotations

import logging
import math
import os
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from pathlib import Path

import meshio
import numpy as np
import skfem

from .cache import atomic_path

__all__ = [
    "to_meshio",
    "write_vtu",
    "write_vtu_series",
    "displacement_magnitude",
    "voigt_to_vtk_tensor",
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
    with atomic_path(path, ".vtu") as tmp:
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
    with atomic_path(pvd, ".pvd") as tmp:
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
