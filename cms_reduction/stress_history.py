"""Stresses over time of a modal body: peak history, worst instant, ParaView series and pictures.

A run records the modal coordinates η(t) of each flexible body, ``eta_t`` (n_t, m) √kg at the
times ``t_s`` (n_t,) s. With the body's stress modes σ_j (:mod:`cms_reduction.stress_modes`,
``extras["stress_modes"]`` (N, 6, m) Pa per unit η) the nodal stress at any instant is the modal
superposition

    σ(x_n, t) = Σ_j η_j(t) σ_j(x_n),

exact for linear elasticity: it equals the stress recovered from the displacement Φ η(t) by the
FE model (:func:`fem_rings.stress.nodal_stress_Pa`). Von Mises is not linear in η and is formed
from the combined tensor at each instant.

Between recorded samples η is interpolated linearly in time (or the nearest sample is taken,
``method="nearest"``); since σ is linear in η, the stress tensor is then interpolated linearly
too, but von Mises of the interpolated tensor is not the interpolation of von Mises.

Memory: all stresses of a long record never exist at once. The peak history works on blocks
of nodes × times whose stress tensors and von Mises temporaries fit in ``block_bytes`` (default
8 MB); a body of 73 000 nodes and 37 modes holds 124 MB of stress modes (and 62 MB of mode
shapes), and its peak history over 2 000 samples needed 9 MB more (traced) and 1.6–2.1 s on a
2-core AMD EPYC. Series and pictures compute one frame at a time.

Stress components are in Voigt order xx, yy, zz, yz, xz, xy (Pa) in the arrays returned here;
the ParaView files store them in VTK's order xx, yy, zz, xy, yz, xz
(:func:`fem_rings.output.voigt_to_vtk_tensor`).
"""

from __future__ import annotations

import logging
import os
import re
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path
from typing import NamedTuple

import numpy as np

from fem_rings.output import voigt_to_vtk_tensor, write_vtu_series
from fem_rings.stress import von_mises_Pa

from .body import ReducedBody

__all__ = [
    "PeakHistory", "WorstInstant", "StressAtTimes",
    "peak_von_mises_history", "worst_time", "modal_coordinates_at", "stress_at",
    "write_stress_series", "render_stress_pngs",
]

logger = logging.getLogger(__name__)

#: Default memory for one block of nodes × times: stress tensors plus von Mises temporaries,
#: bytes. Small blocks stay in the processor cache: 73 000 nodes × 37 modes × 2 000 times took
#: 2.1 s with 8 MB blocks and 3.4 s with 32 or 128 MB blocks (one thread, AMD EPYC).
BLOCK_BYTES = 8 * 2**20
# float64 values held per node and per time in a block: 6 stress components, the von Mises
# result and the temporaries of its formula
_VALUES_PER_NODE = 12
# a chunk of times is short enough that at least this many nodes fit in a block
_MIN_NODES_PER_BLOCK = 16

_BAR_LABEL = "von Mises"
_BAR_UNIT = "MPa"


class PeakHistory(NamedTuple):
    """Largest nodal von Mises stress at each time.

    Attributes
    ----------
    von_mises_Pa : (n_t,) float64, Pa
        Maximum over the nodes at each time.
    node : (n_t,) int64
        Node (row of ``body.nodes_m``) where that maximum occurs.
    """

    von_mises_Pa: np.ndarray
    node: np.ndarray


class WorstInstant(NamedTuple):
    """The recorded sample with the largest nodal von Mises stress of a history."""

    index: int
    time_s: float
    von_mises_Pa: float
    node: int


class StressAtTimes(NamedTuple):
    """Modal coordinates and nodal stresses at chosen times.

    Attributes
    ----------
    time_s : (k,) float64, s
    eta : (k, m) float64, √kg
        Modal coordinates at those times.
    stress_Pa : (k, N, 6) float64, Pa
        Nodal stress tensors, Voigt order xx, yy, zz, yz, xz, xy.
    von_mises_Pa : (k, N) float64, Pa
    """

    time_s: np.ndarray
    eta: np.ndarray
    stress_Pa: np.ndarray
    von_mises_Pa: np.ndarray


# ---------------------------------------------------------------------------------------------
# input checks
# ---------------------------------------------------------------------------------------------
def _stress_modes(body: ReducedBody) -> np.ndarray:
    """The body's stress modes as a (6N, m) matrix (rows node-major, Voigt components)."""
    modes = body.extras.get("stress_modes")
    if modes is None:
        raise ValueError(
            f"body {body.name!r} has no stress modes (extras['stress_modes']); reduce it with "
            "ReductionSpec(stress_modes=True) or add them with add_stress_modes")
    modes = np.asarray(modes, dtype=float)
    expected = (len(body.nodes_m), 6, body.n_modes)
    if modes.shape != expected:
        raise ValueError(f"body {body.name!r}: extras['stress_modes'] has shape {modes.shape}, "
                         f"expected {expected} (nodes, Voigt components, modes)")
    return np.ascontiguousarray(modes).reshape(-1, body.n_modes)


def _checked_eta(body: ReducedBody, eta_t) -> np.ndarray:
    eta = np.asarray(eta_t, dtype=float)
    if eta.ndim != 2 or eta.shape[1] != body.n_modes:
        raise ValueError(f"eta_t must have shape (n_t, {body.n_modes}), one column per mode of body "
                         f"{body.name!r}, got {eta.shape}")
    bad = ~np.isfinite(eta)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise ValueError(f"eta_t contains {int(bad.sum())} non-finite values "
                         f"(first at sample {i}, mode {j}: {eta[i, j]})")
    return eta


def _checked_t(t_s, n_t: int) -> np.ndarray:
    t = np.asarray(t_s, dtype=float)
    if t.shape != (n_t,):
        raise ValueError(f"t_s must have shape ({n_t},), one time per row of eta_t, got {t.shape}")
    if n_t == 0:
        raise ValueError("t_s is empty: a history needs at least one sample")
    bad = ~np.isfinite(t)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"t_s contains {int(bad.sum())} non-finite values (first t_s[{i}] = {t[i]})")
    steps = np.diff(t)
    if np.any(steps <= 0.0):
        i = int(np.argmax(steps <= 0.0)) + 1
        raise ValueError(f"t_s must increase strictly; t_s[{i}] = {t[i]!r} follows t_s[{i - 1}] = {t[i - 1]!r}")
    return t


def _checked_offset(body: ReducedBody, offset_Pa) -> np.ndarray:
    off = np.asarray(offset_Pa, dtype=float)
    if off.shape != (len(body.nodes_m), 6) or not np.all(np.isfinite(off)):
        raise ValueError(f"offset_Pa must be finite with shape ({len(body.nodes_m)}, 6), one Voigt stress per node "
                         f"of body {body.name!r}, got shape {off.shape}")
    return off


def _checked_nodes(body: ReducedBody, nodes) -> np.ndarray:
    idx = np.asarray(nodes)
    n = len(body.nodes_m)
    if idx.ndim != 1 or idx.size == 0 or not np.issubdtype(idx.dtype, np.integer):
        raise ValueError(f"nodes must be a non-empty 1-D sequence of node indices of body {body.name!r}")
    if idx.min() < 0 or idx.max() >= n:
        raise ValueError(f"nodes must lie in 0 … {n - 1} (body {body.name!r} has {n} nodes), got "
                         f"{int(idx.min())} … {int(idx.max())}")
    return idx


def _checked_history(body: ReducedBody, t_s, eta_t) -> tuple[np.ndarray, np.ndarray]:
    eta = _checked_eta(body, eta_t)
    return _checked_t(t_s, len(eta)), eta


def _checked_times(times_s, t: np.ndarray) -> np.ndarray:
    times = np.atleast_1d(np.asarray(times_s, dtype=float))
    if times.ndim != 1 or times.size == 0:
        raise ValueError(f"times_s must be one time or a 1-D sequence of times, got shape {times.shape}")
    if not np.all(np.isfinite(times)):
        raise ValueError(f"times_s must be finite, got {times[~np.isfinite(times)][:3]}")
    outside = (times < t[0]) | (times > t[-1])
    if outside.any():
        raise ValueError(f"times_s must lie within the record, {t[0]!r} … {t[-1]!r} s; "
                         f"got {times[outside][:3]}")
    return times


def _blocks(n_nodes: int, n_t: int, block_bytes: int) -> tuple[int, int]:
    """(times per chunk, nodes per block) so that one block's stresses fit in ``block_bytes``."""
    if int(block_bytes) <= 0:
        raise ValueError(f"block_bytes must be positive, got {block_bytes}")
    per_value = 8 * _VALUES_PER_NODE
    times = max(1, min(n_t, int(block_bytes) // (per_value * _MIN_NODES_PER_BLOCK)))
    nodes = max(1, min(n_nodes, int(block_bytes) // (per_value * times)))
    return times, nodes


# ---------------------------------------------------------------------------------------------
# stresses
# ---------------------------------------------------------------------------------------------
def _stress_of(modes: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """Nodal stresses (k, N, 6) Pa of modal coordinates (k, m), modes (6N, m)."""
    return (eta @ modes.T).reshape(len(eta), -1, 6)


def peak_von_mises_history(body: ReducedBody, eta_t, *, block_bytes: int = BLOCK_BYTES,
                           nodes=None, offset_Pa=None) -> PeakHistory:
    """Largest nodal von Mises stress, and where it occurs, at each recorded time.

    The record is cut into chunks of times and the nodes into blocks; each block's stresses
    (nodes × 6 × times) are one matrix product of a slice of the stress modes with the chunk's
    η, so the stress modes are read once per chunk and a block stays small enough for the cache.

    Parameters
    ----------
    body : ReducedBody
        Body with stress modes (``extras["stress_modes"]``).
    eta_t : (n_t, m) float64, √kg
        Modal coordinates at each recorded time.
    block_bytes : int, optional
        Memory for the stresses of one block, bytes.
    nodes : sequence of int, optional
        The nodes (rows of ``body.nodes_m``) to search; default all.
    offset_Pa : (N, 6) float64, Pa, optional
        A stress field added at every instant (Voigt order; e.g. a static correction for a load
        the modal model carries otherwise).

    Returns
    -------
    PeakHistory
        ``von_mises_Pa`` (n_t,) Pa and ``node`` (n_t,) of the maximum over the nodes (the lowest
        node number if several share it).
    """
    modes = _stress_modes(body)
    eta = _checked_eta(body, eta_t)
    offset = None if offset_Pa is None else _checked_offset(body, offset_Pa)
    if nodes is not None:
        nodes = _checked_nodes(body, nodes)
        modes = modes.reshape(-1, 6, body.n_modes)[nodes].reshape(-1, body.n_modes)
        offset = None if offset is None else offset[nodes]
    n_t, n_nodes = len(eta), len(modes) // 6
    chunk, block = _blocks(n_nodes, n_t, block_bytes)
    peak = np.full(n_t, -np.inf)
    node = np.zeros(n_t, dtype=np.int64)
    for t0 in range(0, n_t, chunk):
        eta_chunk_T = np.ascontiguousarray(eta[t0:t0 + chunk].T)       # (m, nt)
        peak_c, node_c = peak[t0:t0 + chunk], node[t0:t0 + chunk]      # views, filled in place
        columns = np.arange(eta_chunk_T.shape[1])
        for n0 in range(0, n_nodes, block):
            n1 = min(n0 + block, n_nodes)
            stress = (modes[6 * n0:6 * n1] @ eta_chunk_T).reshape(n1 - n0, 6, -1)
            if offset is not None:
                stress += offset[n0:n1, :, None]
            vm = von_mises_Pa(stress.transpose(0, 2, 1))                # (nodes, nt)
            arg = np.argmax(vm, axis=0)
            top = vm[arg, columns]
            better = top > peak_c
            peak_c[better] = top[better]
            node_c[better] = arg[better] + n0
    logger.debug("peak von Mises of %r: %d times in chunks of %d, %d nodes in blocks of %d",
                 body.name, n_t, chunk, n_nodes, block)
    return PeakHistory(peak, node if nodes is None else nodes[node])


def worst_time(body: ReducedBody, t_s, eta_t, *, block_bytes: int = BLOCK_BYTES) -> WorstInstant:
    """The recorded sample with the largest nodal von Mises stress (the first if several tie).

    Parameters
    ----------
    body : ReducedBody
        Body with stress modes.
    t_s : (n_t,) float64, s
        Recorded times, strictly increasing.
    eta_t : (n_t, m) float64, √kg
        Modal coordinates at those times.
    """
    t, eta = _checked_history(body, t_s, eta_t)
    history = peak_von_mises_history(body, eta, block_bytes=block_bytes)
    i = int(np.argmax(history.von_mises_Pa))
    return WorstInstant(i, float(t[i]), float(history.von_mises_Pa[i]), int(history.node[i]))


def modal_coordinates_at(t_s, eta_t, times_s, method: str = "linear") -> np.ndarray:
    """Modal coordinates (k, m) at ``times_s`` (k,) s from a record (t_s, eta_t).

    ``method="linear"`` interpolates linearly between the two samples around each time (a
    recorded time gives its sample exactly); ``"nearest"`` takes the nearest sample (the earlier
    one at a tie). ``t_s`` (n_t,) must increase strictly; times outside the record are refused.
    """
    eta = np.asarray(eta_t, dtype=float)
    if eta.ndim != 2:
        raise ValueError(f"eta_t must have shape (n_t, m), got {eta.shape}")
    t = _checked_t(t_s, len(eta))
    times = _checked_times(times_s, t)
    if method not in ("linear", "nearest"):
        raise ValueError(f"method must be 'linear' or 'nearest', got {method!r}")
    if len(t) == 1:
        return np.repeat(eta, len(times), axis=0)
    i = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 2)
    w = (times - t[i]) / (t[i + 1] - t[i])                          # in [0, 1]
    if method == "nearest":
        return eta[np.where(w > 0.5, i + 1, i)]
    return (1.0 - w)[:, None] * eta[i] + w[:, None] * eta[i + 1]


def stress_at(body: ReducedBody, t_s, eta_t, times_s, *, method: str = "linear") -> StressAtTimes:
    """Nodal stress tensors and von Mises stress at chosen times of a record.

    All k results are held at once (k × N × 7 values): meant for a few instants; a long series
    goes to files with :func:`write_stress_series`.

    Parameters
    ----------
    body : ReducedBody
        Body with stress modes.
    t_s : (n_t,) float64, s
        Recorded times, strictly increasing.
    eta_t : (n_t, m) float64, √kg
        Modal coordinates at those times.
    times_s : float or (k,) float64, s
        Times of interest within ``t_s[0] … t_s[-1]``.
    method : {"linear", "nearest"}
        Linear interpolation of η in time, or the nearest recorded sample
        (:func:`modal_coordinates_at`).

    Returns
    -------
    StressAtTimes
        ``time_s`` (k,), ``eta`` (k, m), ``stress_Pa`` (k, N, 6) Voigt, ``von_mises_Pa`` (k, N).
    """
    modes = _stress_modes(body)
    t, eta = _checked_history(body, t_s, eta_t)
    times = _checked_times(times_s, t)
    eta_k = modal_coordinates_at(t, eta, times, method)
    stress = _stress_of(modes, eta_k)
    return StressAtTimes(times, eta_k, stress, von_mises_Pa(stress))


# ---------------------------------------------------------------------------------------------
# ParaView series
# ---------------------------------------------------------------------------------------------
class _FrameFields(Mapping):
    """Nodal fields of one frame, computed when the file writer reads them.

    Only the frame being written holds its arrays, so memory does not grow with the number of
    frames of a series.
    """

    _NAMES = ("displacement_m", "stress_Pa", "von_mises_Pa")

    def __init__(self, body: ReducedBody, modes: np.ndarray, eta: np.ndarray) -> None:
        self._body, self._modes, self._eta = body, modes, eta

    def _fields(self) -> dict[str, np.ndarray]:
        stress = _stress_of(self._modes, self._eta[None, :])[0]
        return {"displacement_m": self._body.displacement_m(self._eta),
                "stress_Pa": voigt_to_vtk_tensor(stress),
                "von_mises_Pa": von_mises_Pa(stress)}

    def __getitem__(self, name: str) -> np.ndarray:
        return self._fields()[name]

    def __iter__(self):
        return iter(self._NAMES)

    def __len__(self) -> int:
        return len(self._NAMES)

    def items(self):
        return self._fields().items()  # all fields from one stress evaluation


def _series_times(t: np.ndarray, eta: np.ndarray, times_s, every: int):
    """(times, η) of the frames: every ``every``-th sample, or interpolated at ``times_s``."""
    if times_s is not None:
        if every != 1:
            raise ValueError("give either times_s or every, not both")
        times = _checked_times(times_s, t)
        if np.any(np.diff(times) <= 0.0):
            raise ValueError("times_s must increase strictly for a time series")
        return times, modal_coordinates_at(t, eta, times)
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
        raise ValueError(f"every must be an integer ≥ 1, got {every!r}")
    return t[::every], eta[::every]


def _remove_stale_frames(folder: Path, name: str, pvd: Path) -> None:
    """Delete ``{name}_<n>.vtu`` files of an earlier series that the new ``.pvd`` does not list."""
    listed = {d.get("file") for d in ET.parse(pvd).getroot().iter("DataSet")}
    pattern = re.compile(rf"{re.escape(name)}_\d+\.vtu")
    stale = [p for p in folder.iterdir() if pattern.fullmatch(p.name) and p.name not in listed]
    for p in stale:
        p.unlink()
    if stale:
        logger.info("removed %d frames of an earlier %s series in %s", len(stale), name, folder)


def write_stress_series(folder: str | os.PathLike, body: ReducedBody, t_s, eta_t, times_s=None, *,
                        every: int = 1, name: str = "stress") -> Path:
    """Write the stresses of a record as a ParaView time series (``.pvd`` + one ``.vtu`` per frame).

    Each frame holds per node ``displacement_m`` (N, 3) m, ``stress_Pa`` (N, 6) Pa in VTK's
    tensor order xx, yy, zz, xy, yz, xz, and ``von_mises_Pa`` (N,) Pa, on the undeformed mesh
    (use ParaView's *Warp By Vector* on ``displacement_m`` to draw it deformed).

    An existing ``{name}.pvd`` is removed first and the new one is written after the last frame
    (:func:`fem_rings.output.write_vtu_series`), so a failed write leaves no collection file that
    looks complete; after success, frames of an earlier series of the same name that are not
    part of the new one are deleted.

    Parameters
    ----------
    folder : str or os.PathLike
        Output folder, created if missing.
    body : ReducedBody
        Body with stress modes.
    t_s : (n_t,) float64, s
        Recorded times, strictly increasing.
    eta_t : (n_t, m) float64, √kg
        Modal coordinates at those times.
    times_s : (k,) float64, s, optional
        Frame times, strictly increasing, within the record; η linearly interpolated. Default:
        the recorded samples ``t_s[::every]``.
    every : int, optional
        Keep every ``every``-th recorded sample (only without ``times_s``).
    name : str, optional
        Stem of the files: ``{name}.pvd``, ``{name}_0000.vtu`` …

    Returns
    -------
    pathlib.Path
        The ``.pvd`` file.
    """
    modes = _stress_modes(body)
    t, eta = _checked_history(body, t_s, eta_t)
    times, eta_frames = _series_times(t, eta, times_s, every)
    folder = Path(folder)
    if not name or Path(name).name != name:
        raise ValueError(f"name must be a plain file stem, got {name!r}")
    (folder / f"{name}.pvd").unlink(missing_ok=True)
    frames = [(time, _FrameFields(body, modes, e)) for time, e in zip(times, eta_frames)]
    pvd = write_vtu_series(folder, body.mesh(), frames, name=name)
    _remove_stale_frames(folder, name, pvd)
    return pvd


# ---------------------------------------------------------------------------------------------
# pictures
# ---------------------------------------------------------------------------------------------
def _render_frame(path: Path, mesh, von_mises_MPa: np.ndarray, points_m: np.ndarray,
                  clim_MPa: tuple[float, float], text: str, window_size: tuple[int, int],
                  cmap: str) -> Path:
    """One PNG of the surface at ``points_m`` coloured on the fixed range ``clim_MPa``."""
    # fem_rings.render.render_png fits the colour range to each picture; the pieces below are
    # the same ones with a range shared by all frames
    from fem_rings.cache import atomic_path
    from fem_rings.render import _pyvista_surface, _render_surface, _write_png

    bar_title = f"{_BAR_LABEL} [{_BAR_UNIT}]"
    surface = _pyvista_surface(mesh, points_m, von_mises_MPa, bar_title)
    image = _render_surface(surface, bar_title, text, cmap, window_size, clim_MPa)
    with atomic_path(path, ".png") as tmp:
        _write_png(tmp, image)
    return path


def _shared_clim_MPa(peaks_Pa: np.ndarray, clim_Pa) -> tuple[float, float]:
    if clim_Pa is None:
        top = float(peaks_Pa.max()) * 1e-6
        return 0.0, top if top > 0.0 else 1.0
    lo, hi = (float(v) for v in clim_Pa)
    if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo):
        raise ValueError(f"clim_Pa must be two finite values, low < high, got {clim_Pa}")
    return lo * 1e-6, hi * 1e-6


def render_stress_pngs(folder: str | os.PathLike, body: ReducedBody, t_s, eta_t, times_s=None, *,
                       name: str = "stress", window_size: tuple[int, int] = (1200, 800),
                       warp_factor: float | None = None, clim_Pa: tuple[float, float] | None = None,
                       cmap: str = "viridis") -> list[Path]:
    """Off-screen PNGs of the deformed body coloured by von Mises stress (MPa) at chosen times.

    All frames share one colour range, 0 … the largest nodal von Mises stress of the frames
    (or ``clim_Pa``), and one deformation scale, so they can be compared; each title gives the
    body, the time, the frame's largest von Mises stress and the deformation scale.

    Parameters
    ----------
    folder : str or os.PathLike
        Output folder, created if missing; files ``{name}_0000.png`` … in the order of ``times_s``.
    body : ReducedBody
        Body with stress modes.
    t_s : (n_t,) float64, s
        Recorded times, strictly increasing.
    eta_t : (n_t, m) float64, √kg
        Modal coordinates at those times.
    times_s : float or (k,) float64, s, optional
        Times to draw (η linearly interpolated). Default: the recorded sample with the largest
        von Mises stress (:func:`worst_time`).
    window_size : (int, int), optional
        Image width and height, pixels.
    warp_factor : float, optional
        Displacement magnification; default: the largest displacement of the frames is drawn
        at 5 % of the body's size (:func:`fem_rings.render.auto_warp_factor`).
    clim_Pa : (float, float), optional
        Colour range, Pa, e.g. to match pictures of another call.
    cmap : str, optional
        Matplotlib colour map name.

    Returns
    -------
    list of pathlib.Path
        The PNG files, one per time.
    """
    from fem_rings.render import _title_text, auto_warp_factor

    modes = _stress_modes(body)
    t, eta = _checked_history(body, t_s, eta_t)
    width_px, height_px = (int(v) for v in window_size)
    if width_px < 16 or height_px < 16:
        raise ValueError(f"window_size must be at least 16 × 16 pixels, got {tuple(window_size)}")
    if not name or Path(name).name != name:
        raise ValueError(f"name must be a plain file stem, got {name!r}")
    if times_s is None:
        times_s = worst_time(body, t, eta).time_s
    times = _checked_times(times_s, t)
    eta_k = modal_coordinates_at(t, eta, times)
    peaks = peak_von_mises_history(body, eta_k)
    clim = _shared_clim_MPa(peaks.von_mises_Pa, clim_Pa)
    points0 = np.asarray(body.nodes_m, dtype=float)
    u_all = (body.shapes @ eta_k.T).T.reshape(-1, 3)                # every frame's displacement
    factor = auto_warp_factor(points0, u_all) if warp_factor is None else float(warp_factor)
    if not np.isfinite(factor):
        raise ValueError(f"warp_factor must be finite, got {warp_factor}")
    mesh, folder, paths = body.mesh(), Path(folder), []
    width = max(4, len(str(len(times) - 1)))
    for k, (time, e, peak) in enumerate(zip(times, eta_k, peaks.von_mises_Pa)):
        vm_MPa = von_mises_Pa(_stress_of(modes, e[None, :])[0]) * 1e-6
        title = f"{body.name}   t = {time:.6g} s   max {_BAR_LABEL} {peak * 1e-6:.4g} {_BAR_UNIT}"
        path = folder / f"{name}_{k:0{width}d}.png"
        paths.append(_render_frame(path, mesh, vm_MPa, points0 + factor * body.displacement_m(e), clim,
                                   _title_text(title, factor), (width_px, height_px), cmap))
    logger.info("wrote %d stress pictures of %r to %s (colour range %g … %g MPa)",
                len(paths), body.name, folder, *clim)
    return paths
