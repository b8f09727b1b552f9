"""Off-screen pictures (PNG) of ring models coloured by a nodal field, with pyvista.

pyvista is imported inside the rendering functions only, so importing :mod:`fem_rings` does not
load VTK. Node and field conventions: :mod:`fem_rings.output`.
"""

from __future__ import annotations

import logging
import math
import os
from pathlib import Path

import numpy as np

from .cache import atomic_path
from .output import _cell_info, displacement_magnitude, vtk_cells

__all__ = ["render_png", "auto_warp_factor", "round_ticks"]

logger = logging.getLogger(__name__)

# fraction of the model size (bounding-box diagonal) that the largest displacement is drawn at
# when render_png chooses the warp factor itself
_AUTO_WARP_FRACTION = 0.05


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


def round_ticks(low: float, high: float, max_ticks: int = 7) -> np.ndarray:
    """Evenly spaced round values (1, 2, 2.5 or 5 × 10^k apart) from at or below ``low`` to at or
    above ``high``, at most ``max_ticks`` of them: the colour bar's range and labels."""
    low, high = float(low), float(high)
    if not high > low:  # a constant field: one step of a round size around it
        pad = abs(low) * 0.1 or 1.0
        low, high = low - pad, high + pad
    for step in _round_steps((high - low) / (max_ticks - 1)):
        first, last = math.floor(low / step + 1e-9), math.ceil(high / step - 1e-9)
        if last - first + 1 <= max_ticks:
            return np.arange(first, last + 1) * step
    raise AssertionError("unreachable: the steps grow without bound")


def _round_steps(smallest: float):
    """Round step sizes ≥ ``smallest``, increasing."""
    k = math.floor(math.log10(smallest))
    while True:
        for m in (1.0, 2.0, 2.5, 5.0):
            if m * 10.0**k >= smallest * (1 - 1e-12):
                yield m * 10.0**k
        k += 1


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
    ``f"{label} [{unit}]"`` whose range and labels are round values (:func:`round_ticks`). The PNG is exactly ``window_size`` pixels and is written under a
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
    # colour range of the nodal values: the tessellated faces interpolate the quadratic field
    # and may overshoot it (e.g. a slightly negative von Mises stress)
    # rounded to the colour bar's labels (round_ticks)
    ticks = round_ticks(values.min(), values.max())
    image = _render_surface(surface, bar_title, _title_text(title, factor), cmap,
                            (width_px, height_px), (float(ticks[0]), float(ticks[-1])), len(ticks))
    with atomic_path(path, ".png") as tmp:
        _write_png(tmp, image)
    logger.info("wrote %s (%d × %d px)", path, width_px, height_px)
    return path


def _render_surface(surface, bar_title: str, text: str, cmap: str,
                    window_size: tuple[int, int], clim: tuple[float, float], n_labels: int = 6) -> np.ndarray:
    """Off-screen render; returns the RGB image (height, width, 3) of uint8."""
    if not os.environ.get("DISPLAY"):
        # no X server: go straight to EGL instead of trying X first (VTK prints a warning)
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    width_px, height_px = window_size
    font = max(8, round(height_px / 40))  # pixels, for colour-bar labels
    plotter = pv.Plotter(off_screen=True, window_size=(width_px, height_px))
    try:
        plotter.set_background("white")
        plotter.add_mesh(
            surface, scalars=bar_title, cmap=cmap, clim=clim,
            smooth_shading=True, split_sharp_edges=True,
            scalar_bar_args=dict(
                title=bar_title, vertical=True, position_x=0.84, position_y=0.08,
                width=0.05, height=0.74, color="black", fmt="%.4g", n_labels=n_labels,
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
