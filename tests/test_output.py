"""Tests of the ParaView export and off-screen pictures in ``fem_rings.output``.

References used below:

* VTK's own cell definitions (``vtkQuadraticTetra``, ``vtkTriQuadraticHexahedron``):
  parametric node coordinates and shape-function derivatives, read from the installed VTK. A
  volume integrated with VTK's shape functions is the volume ParaView sees for a curved cell.
* scikit-fem: the isoparametric volume ``∫ 1 dV`` assembled on the mesh (``skfem.Functional``),
  and its meshio import ``skfem.io.meshio.from_meshio``.
* ``vtkMath.h`` (``TensorFromSymmetricTensor``): ParaView's order of a 6-component symmetric
  tensor is XX, YY, ZZ, XY, YZ, XZ.
* Analytic values where a shape is simple (volume of a straight cell, a warp-factor formula).
"""

from __future__ import annotations

import subprocess
import sys
import xml.etree.ElementTree as ET
from dataclasses import replace

import matplotlib.image
import meshio
import numpy as np
import pytest
import skfem
from skfem.io.meshio import from_meshio

from fem_rings.output import (
    displacement_magnitude,
    to_meshio,
    voigt_to_vtk_tensor,
    vtk_cells,
    write_vtu,
    write_vtu_series,
)
from fem_rings.render import auto_warp_factor, render_png

pv = pytest.importorskip("pyvista")
from vtkmodules.vtkCommonDataModel import (  # noqa: E402  (VTK comes with pyvista)
    vtkQuadraticTetra,
    vtkTriQuadraticHexahedron,
)

VTK_CELL = {"tetra10": vtkQuadraticTetra, "hexahedron27": vtkTriQuadraticHexahedron}
PV_CELL_TYPE = {"tetra10": pv.CellType.QUADRATIC_TETRA,
                "hexahedron27": pv.CellType.TRIQUADRATIC_HEXAHEDRON}


# ---------------------------------------------------------------------------------------------
# meshes
# ---------------------------------------------------------------------------------------------
def _ball() -> skfem.MeshTet2:
    """Unit ball of curved 10-node tetrahedra (boundary nodes on the sphere), 512 cells.

    scikit-fem does not orient its tetrahedra: half of these have a negative corner volume.
    """
    return skfem.MeshTet2.init_ball(2)


def _ring_segment(mirror: bool = False) -> skfem.MeshHex2:
    """270° segment of a ring, r = 40…50 mm, height 20 mm, 2 × 6 × 1 curved 27-node hexahedra.

    ``mirror`` maps z → −z, which turns every cell inside out in VTK's node order.
    """
    box = skfem.MeshHex1.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 1, 7),
                                     np.linspace(0, 1, 2))
    mesh = skfem.MeshHex2.from_mesh(box)
    x, y, z = mesh.doflocs
    r, theta = 0.040 + 0.010 * x, 1.5 * np.pi * y
    return replace(mesh, doflocs=np.array([r * np.cos(theta), r * np.sin(theta),
                                           (-0.020 if mirror else 0.020) * z]))


RING_VOLUME_M3 = 0.75 * np.pi * (0.050**2 - 0.040**2) * 0.020  # exact 270° annulus × height

CURVED_MESHES = {
    "tetra10 ball": _ball,
    "hexahedron27 ring": _ring_segment,
    "hexahedron27 mirrored ring": lambda: _ring_segment(mirror=True),
}


def _skfem_volume(mesh) -> float:
    basis = skfem.Basis(mesh, mesh.elem(), intorder=4)
    return float(skfem.Functional(lambda w: 1.0).assemble(basis))


# ---------------------------------------------------------------------------------------------
# volume with VTK's shape functions
# ---------------------------------------------------------------------------------------------
def _gauss_01(n: int):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def _reference_rule(cell_type: str, n: int = 5):
    """Quadrature on VTK's parametric cell: the unit cube, or the unit tetrahedron via the
    collapsed (Duffy) map r = a, s = b(1 − a), t = c(1 − a)(1 − b), |J| = (1 − a)²(1 − b).
    n = 5 Gauss points per direction integrate det J (degree ≤ 3 on the tetrahedron, ≤ 5 per
    variable on the hexahedron, times the Duffy factor) exactly."""
    x, w = _gauss_01(n)
    a, b, c = (g.ravel() for g in np.meshgrid(x, x, x, indexing="ij"))
    weights = np.einsum("i,j,k->ijk", w, w, w).ravel()
    if cell_type == "hexahedron27":
        return np.column_stack([a, b, c]), weights
    pcoords = np.column_stack([a, b * (1 - a), c * (1 - a) * (1 - b)])
    return pcoords, weights * (1 - a) ** 2 * (1 - b)


def _vtk_volumes(cell_type: str, points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Volume of each cell from VTK's shape-function derivatives (n_cells,)."""
    cell = VTK_CELL[cell_type]()
    n_local = cells.shape[1]
    pcoords, weights = _reference_rule(cell_type)
    volumes = np.zeros(len(cells))
    x = points[cells]  # (n_cells, n_local, 3)
    for pc, wq in zip(pcoords, weights):
        derivs = [0.0] * (3 * n_local)
        cell.InterpolationDerivs(list(pc), derivs)  # all d/dr, then all d/ds, then all d/dt
        dn = np.asarray(derivs).reshape(3, n_local)
        jac = np.einsum("kn,cnd->ckd", dn, x)
        volumes += wq * np.linalg.det(jac)
    return volumes


def _read_vtu_cells(path, cell_type):
    grid = pv.read(path)
    cells = np.asarray(grid.cells_dict[PV_CELL_TYPE[cell_type]])
    return grid, np.asarray(grid.points, dtype=float), cells


# ---------------------------------------------------------------------------------------------
# node order
# ---------------------------------------------------------------------------------------------
def _vtk_parametric_coords(cell_type: str) -> np.ndarray:
    cell = VTK_CELL[cell_type]()
    n = cell.GetNumberOfPoints()
    return np.array([cell.GetParametricCoords()[i] for i in range(3 * n)]).reshape(n, 3)


def test_reference_cells_land_on_vtk_parametric_coordinates():
    """A mesh that is exactly VTK's reference cell puts node i at VTK's parametric point i."""
    # tetrahedron with corners at VTK's parametric corners (0,0,0), (1,0,0), (0,1,0), (0,0,1)
    tet1 = skfem.MeshTet1(np.array([[0.0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
                          np.array([[0], [1], [2], [3]]))
    # scikit-fem's default MeshHex2 is the unit cube [0, 1]³, VTK's parametric hexahedron
    for mesh in (skfem.MeshTet2.from_mesh(tet1), skfem.MeshHex2()):
        cell_type, cells = vtk_cells(mesh)
        nodes = mesh.doflocs.T[cells[0]]
        # reference: parametric coordinates from the installed VTK cell classes
        np.testing.assert_array_equal(nodes, _vtk_parametric_coords(cell_type))


@pytest.mark.parametrize("make_mesh", CURVED_MESHES.values(), ids=CURVED_MESHES.keys())
def test_written_curved_cells_have_the_scikit_fem_volume_in_vtk(tmp_path, make_mesh):
    """Volume of the written VTU integrated with VTK's quadratic shape functions equals the
    scikit-fem isoparametric volume cell by cell and in total (1e-10 relative), and every cell
    is positively oriented."""
    mesh = make_mesh()
    cell_type, _ = vtk_cells(mesh)
    path = write_vtu(tmp_path / "curved.vtu", mesh)
    _, points, cells = _read_vtu_cells(path, cell_type)
    vtk_cell_volumes = _vtk_volumes(cell_type, points, cells)
    # reference: scikit-fem, ∫ 1 dV per element (|det J| quadrature on the curved cells)
    basis = skfem.Basis(mesh, mesh.elem(), intorder=4)
    skfem_cell_volumes = (basis.dx).sum(axis=1)
    assert np.all(vtk_cell_volumes > 0.0)
    np.testing.assert_allclose(vtk_cell_volumes, skfem_cell_volumes, rtol=1e-10)
    assert vtk_cell_volumes.sum() == pytest.approx(_skfem_volume(mesh), rel=1e-10)


def test_volume_check_detects_a_wrong_quadratic_node_order():
    """Exchanging the edge nodes 13 and 23 of each tetra10 (the order gmsh uses) moves curved
    edges to the wrong place: the VTK volume of the ball changes by far more than 1e-10."""
    mesh = _ball()
    cell_type, cells = vtk_cells(mesh)
    points = mesh.doflocs.T
    right = _vtk_volumes(cell_type, points, cells).sum()
    wrong = _vtk_volumes(cell_type, points, cells[:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]).sum()
    # reference: the scikit-fem volume of the same ball
    assert right == pytest.approx(_skfem_volume(mesh), rel=1e-10)
    assert abs(wrong - right) > 1e-3 * right


def test_straight_cells_compute_cell_sizes_equals_scikit_fem_volume(tmp_path):
    """pyvista's compute_cell_sizes() is exact for straight-sided quadratic cells: the refined
    unit cube has volume 1 for tetra10 and hexahedron27, all cells positive."""
    meshes = [skfem.MeshTet2.from_mesh(skfem.MeshTet1().refined(2)),
              skfem.MeshHex2.from_mesh(skfem.MeshHex1().refined(1))]
    for mesh in meshes:
        path = write_vtu(tmp_path / f"{type(mesh).__name__}.vtu", mesh)
        sizes = pv.read(path).compute_cell_sizes(length=False, area=False)["Volume"]
        assert np.all(sizes > 0.0)
        # references: analytic unit cube, and scikit-fem's assembled volume
        assert sizes.sum() == pytest.approx(1.0, rel=1e-12)
        assert sizes.sum() == pytest.approx(_skfem_volume(mesh), rel=1e-10)


def _subtetra_volume(x: np.ndarray) -> np.ndarray:
    """Volume of the 8 straight sub-tetrahedra between the 10 nodes of each tetra10, x: (n, 10, 3).

    Four corner tetrahedra and an octahedron; the octahedron's volume follows from its 8
    triangular faces, so any of its diagonals gives the same value.
    """
    sub = [(0, 4, 6, 7), (4, 1, 5, 8), (6, 5, 2, 9), (7, 8, 9, 3),
           (4, 9, 5, 6), (4, 9, 6, 7), (4, 9, 7, 8), (4, 9, 8, 5)]
    total = np.zeros(len(x))
    for a, b, c, d in sub:
        e1, e2, e3 = x[:, b] - x[:, a], x[:, c] - x[:, a], x[:, d] - x[:, a]
        total += np.einsum("ij,ij->i", e1, np.cross(e2, e3)) / 6.0
    return total


def test_curved_tetra10_compute_cell_sizes_is_the_volume_of_its_linear_subdivision(tmp_path):
    """For curved cells VTK's compute_cell_sizes() sums straight sub-tetrahedra; it is not the
    curved volume. It must still be positive per cell and equal the sub-tetrahedra volume."""
    mesh = _ball()
    path = write_vtu(tmp_path / "ball.vtu", mesh)
    grid, points, cells = _read_vtu_cells(path, "tetra10")
    sizes = grid.compute_cell_sizes(length=False, area=False)["Volume"]
    assert np.all(sizes > 0.0)
    # reference: independent sum over the 8 sub-tetrahedra of each cell (above)
    np.testing.assert_allclose(sizes, _subtetra_volume(points[cells]), rtol=1e-10)
    # the sub-tetrahedra miss the bulge of the curved faces: the sum is below the true volume
    assert sizes.sum() < _skfem_volume(mesh)


@pytest.mark.parametrize("make_mesh", [_ball, _ring_segment], ids=["tetra10", "hexahedron27"])
def test_meshio_round_trip_through_scikit_fem_keeps_the_volume(make_mesh):
    """to_meshio → skfem.io.meshio.from_meshio gives a mesh with the same volume and nodes."""
    mesh = make_mesh()
    back = from_meshio(to_meshio(mesh))
    assert type(back) is type(mesh)
    assert back.nelements == mesh.nelements
    # reference: scikit-fem's volume of the original mesh
    assert _skfem_volume(back) == pytest.approx(_skfem_volume(mesh), rel=1e-12)
    # from_meshio renumbers nodes (vertices first): compare the sorted node coordinates
    np.testing.assert_array_equal(np.sort(back.doflocs, axis=1), np.sort(mesh.doflocs, axis=1))


def test_ring_volume_is_close_to_the_exact_annulus():
    """Sanity of the test mesh: quadratic arcs over 45° approximate the 270° annulus."""
    # reference: π (R² − r²) h × 3/4; a 45° quadratic arc is within 1e-3 of the circle
    assert _skfem_volume(_ring_segment()) == pytest.approx(RING_VOLUME_M3, rel=1e-3)


# ---------------------------------------------------------------------------------------------
# point data and files
# ---------------------------------------------------------------------------------------------
def _fields(n_nodes: int, seed: int = 1) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(seed)
    return {
        "displacement": rng.normal(scale=1e-5, size=(n_nodes, 3)),
        "stress": rng.normal(scale=1e8, size=(n_nodes, 6)),
        "von_mises": rng.uniform(0.0, 5e8, size=n_nodes),
    }


def test_point_data_survives_write_and_read_exactly(tmp_path):
    """Fields written with write_vtu come back from meshio.read bit for bit, on the same
    points (every node, in node order) and cells."""
    mesh = _ring_segment()
    fields = _fields(mesh.doflocs.shape[1])
    path = write_vtu(tmp_path / "sub" / "dir" / "ring.vtu", mesh, fields)
    back = meshio.read(path)
    # reference: the arrays that were written
    np.testing.assert_array_equal(back.points, mesh.doflocs.T)
    np.testing.assert_array_equal(back.cells_dict["hexahedron27"], vtk_cells(mesh)[1])
    for name, values in fields.items():
        assert back.point_data[name].dtype == np.float64
        np.testing.assert_array_equal(back.point_data[name], values)
    # atomic write: only the finished file is left in the folder, with the permissions of any
    # newly created file (reference: a file made with open())
    assert sorted(p.name for p in path.parent.iterdir()) == ["ring.vtu"]
    reference = tmp_path / "reference.txt"
    reference.write_text("")
    assert path.stat().st_mode & 0o777 == reference.stat().st_mode & 0o777


def test_wrong_point_data_shape_names_the_field(tmp_path):
    mesh = _ball()
    n = mesh.doflocs.shape[1]
    fields = _fields(n)
    fields["stress"] = fields["stress"][: mesh.nvertices]  # vertex values only: a typical slip
    with pytest.raises(ValueError, match="'stress'.*one row per node"):
        write_vtu(tmp_path / "bad.vtu", mesh, fields)
    assert list(tmp_path.iterdir()) == []  # nothing written, no temporary file left
    with pytest.raises(ValueError, match="'von_mises'"):
        to_meshio(mesh, {"von_mises": np.zeros((n, 1, 1))})
    with pytest.raises(TypeError, match="MeshTet2"):
        to_meshio(skfem.MeshTet1())


def test_pvd_lists_the_frame_times_and_files(tmp_path):
    mesh = _ring_segment()
    n = mesh.doflocs.shape[1]
    times_s = [0.0, 0.5, 1.25e-3 + 1.0]
    frames = [(t, {"von_mises": np.full(n, 1e6 * (i + 1))}) for i, t in enumerate(times_s)]
    pvd = write_vtu_series(tmp_path / "series", mesh, frames, name="ring")
    datasets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    # reference: the times given in `frames`, written with full precision
    assert [float(d.get("timestep")) for d in datasets] == times_s
    assert [d.get("file") for d in datasets] == ["ring_0000.vtu", "ring_0001.vtu", "ring_0002.vtu"]
    for i, d in enumerate(datasets):
        values = meshio.read(pvd.parent / d.get("file")).point_data["von_mises"]
        np.testing.assert_array_equal(values, 1e6 * (i + 1))
    with pytest.raises(ValueError, match="times must increase"):
        write_vtu_series(tmp_path / "bad", mesh, [(1.0, None), (1.0, None)])


def test_voigt_to_vtk_tensor_order():
    """Voigt xx yy zz yz xz xy → VTK xx yy zz xy yz xz (vtkMath.h, TensorFromSymmetricTensor)."""
    voigt = np.array([[11.0, 22.0, 33.0, 23.0, 13.0, 12.0]])
    np.testing.assert_array_equal(voigt_to_vtk_tensor(voigt),
                                  [[11.0, 22.0, 33.0, 12.0, 23.0, 13.0]])


# ---------------------------------------------------------------------------------------------
# pictures
# ---------------------------------------------------------------------------------------------
def test_auto_warp_factor_and_displacement_magnitude():
    points = np.array([[0.0, 0.0, 0.0], [3.0, 4.0, 0.0]])  # bounding-box diagonal 5 m
    u = np.array([[0.0, 0.0, 0.0], [0.0, 0.06, 0.08]])  # largest |u| = 0.1 m
    np.testing.assert_allclose(displacement_magnitude(u), [0.0, 0.1], rtol=1e-15)
    # reference: 5 % of 5 m drawn for 0.1 m → factor 0.05 × 5 / 0.1 = 2.5
    assert auto_warp_factor(points, u) == pytest.approx(2.5, rel=1e-15)
    assert auto_warp_factor(points, np.zeros_like(u)) == 0.0


def test_render_png_size_and_content(tmp_path):
    """The PNG has the requested size, is not blank, shows several colours on the ring, and the
    model stays clear of the image border (the whole ring is in view)."""
    mesh = _ring_segment()
    x = mesh.doflocs.T
    theta = np.arctan2(x[:, 1], x[:, 0])
    von_mises_pa = 1e8 * (2.0 + np.cos(theta)) * (1.0 + 20.0 * x[:, 2])
    u = 1e-5 * np.column_stack([np.cos(theta), np.sin(theta), np.zeros(len(x))])
    width, height = 360, 240
    path = render_png(tmp_path / "png" / "ring.png", mesh, von_mises_pa, scale=1e-6,
                      displacement_m=u, window_size=(width, height), title="ring segment")
    image = matplotlib.image.imread(path)[:, :, :3]  # floats in [0, 1]
    assert image.shape == (height, width, 3)
    # a one-colour (blank) image has standard deviation 0; white background + coloured ring is
    # far above 0.05
    assert image.std() > 0.05
    # model region: left of the colour bar (x < 0.8 W), below the title (y > 0.16 H)
    model = image[int(0.16 * height):, : int(0.8 * width)]
    not_white = model[np.any(model < 0.95, axis=2)]
    assert len(not_white) > 0.05 * model.shape[0] * model.shape[1]
    assert len(np.unique(np.round(not_white, 2), axis=0)) > 20
    # nothing of the model touches the left, bottom or top-left border of the picture
    border = np.concatenate([image[:, 0], image[-1, : int(0.8 * width)]])
    assert np.all(border > 0.95)
    assert sorted(p.name for p in path.parent.iterdir()) == ["ring.png"]


def test_render_png_rejects_wrong_scalars_length(tmp_path):
    mesh = _ball()
    with pytest.raises(ValueError, match=r"one value per node"):
        render_png(tmp_path / "x.png", mesh, np.zeros(mesh.nvertices))
    with pytest.raises(ValueError, match=r"\.png"):
        render_png(tmp_path / "x.jpg", mesh, np.zeros(mesh.doflocs.shape[1]))
    assert list(tmp_path.iterdir()) == []


def test_importing_fem_rings_output_does_not_load_vtk():
    code = ("import sys, fem_rings.output; "
            "print(any(m.split('.')[0] in ('pyvista', 'vtk', 'vtkmodules') for m in sys.modules))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True)
    assert result.stdout.strip() == "False"
