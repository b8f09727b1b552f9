"""A run's raw time series as one NetCDF-4 file that xarray, pandas (through xarray), ParaView or any
HDF5 tool reads without flexbearing.

The file follows the NetCDF-4 data model (HDF5 underneath, written by h5netcdf) with CF-style
``units`` and ``long_name`` attributes on every variable. Variables are chunked along time and
compressed (zlib with byte shuffle), so a long run opens fast and a slice of it reads without the rest.

Dimensions: ``time`` (recorded samples), ``body``, ``contact`` (contact pairs), ``mode`` (the modal
coordinates of all modal bodies; absent in a rigid model), ``xyz`` (3), ``quaternion`` (4).

Coordinates and labels:

==================  =================  ======  ===================================================
variable            dimensions         units   meaning
==================  =================  ======  ===================================================
time                time               s       simulated time of the sample
body                body               —       body names (``ball 3``, ``cage``, ``top``, …): the
                                               coordinate of the ``body`` dimension
contact             contact            —       pair names, the coordinate of ``contact``
contact_kind        contact            —       ball_groove, ball_ball, roller_raceway, roller_rib,
                                               element_pocket
contact_element     contact            —       the pair's element body (body a: the force
                                               variables act on it)
contact_surface     contact            —       the pair's other body (ring, race, cage, ball)
mode_body           mode               —       the modal body each modal coordinate belongs to
==================  =================  ======  ===================================================

Data (world frame: the model's inertial axes; the bearing axis is z in the cases):

==================  =====================  ======  ===============================================
variable            dimensions             units   meaning
==================  =====================  ======  ===============================================
position            time, body, xyz        m       reference point (centre of mass) of each body
orientation         time, body, quaternion 1       unit quaternion (w, x, y, z), body → world
velocity            time, body, xyz        m/s     velocity of the reference point, world
angular_velocity    time, body, xyz        rad/s   angular velocity in the body's own axes
modal_coordinate    time, mode             √kg     η of the modal bodies (mass-normalized modes)
modal_rate          time, mode             √kg/s   η̇
normal_force        time, contact          N       F_n (sum over a pair's points)
penetration         time, contact          m       largest penetration (negative: the gap)
slip_speed          time, contact          m/s     sliding speed at the most loaded point
friction_force      time, contact          N       sum of the friction force magnitudes
contact_angle       time, contact          rad     atan2(|n_axial|, |n_radial|) in the ring's
                                                   frame (ball and roller raceway pairs)
groove_angle        time, contact          rad     the ball's angle on its groove (ball–groove)
contact_point       time, contact, xyz     m       contact point, world (float32)
contact_normal      time, contact, xyz     1       unit normal of the force on the element,
                                                   world (float32)
==================  =====================  ======  ===============================================

A pair of several points (roller slices, the two walls of a slot pocket) gives the point and normal
of its most loaded point (or its deepest, unloaded). The normal force on the element as a vector is
``normal_force · contact_normal`` at ``contact_point``, and the opposite on ``contact_surface``.

The file is written to a temporary name and renamed, so a file under its final name is complete.
"""

from __future__ import annotations

from pathlib import Path

import h5netcdf
import h5py
import numpy as np

from foundation.files import atomic_path

from .model import Model

__all__ = ["TIMESERIES_VARIABLES", "write_timeseries"]

#: record field → (NetCDF name, dimensions after time, units, long name)
TIMESERIES_VARIABLES = {
    "fn": ("normal_force", ("contact",), "N", "normal contact force, sum over the pair's points"),
    "delta": ("penetration", ("contact",), "m", "largest penetration of the pair (negative: gap)"),
    "slip": ("slip_speed", ("contact",), "m/s", "sliding speed at the most loaded point"),
    "ft": ("friction_force", ("contact",), "N", "sum of the friction force magnitudes"),
    "angle": ("contact_angle", ("contact",), "rad", "contact angle in the ring's frame"),
    "theta": ("groove_angle", ("contact",), "rad", "angle of the ball on its groove"),
    "point": ("contact_point", ("contact", "xyz"), "m", "contact point, world frame"),
    "normal": ("contact_normal", ("contact", "xyz"), "1", "unit normal of the force on the element, world frame"),
}
_CHUNK_BYTES = 1 << 20  # about 1 MB per chunk


def _time_chunk(n_time: int, per_sample: int, itemsize: int) -> int:
    return int(max(1, min(n_time, _CHUNK_BYTES // max(per_sample * itemsize, 1))))


def _variable(f, name: str, dims: tuple, data: np.ndarray, units: str, long_name: str) -> None:
    data = np.ascontiguousarray(data)
    per_sample = int(np.prod(data.shape[1:], dtype=np.int64)) if data.ndim > 1 else 1
    chunks = (_time_chunk(data.shape[0], per_sample, data.itemsize),) + data.shape[1:]
    var = f.create_variable(name, dims, data.dtype, data=data, chunks=chunks, compression="gzip",
                            compression_opts=1, shuffle=True)
    var.attrs["units"] = units
    var.attrs["long_name"] = long_name


def _labels(f, name: str, dim: str, values, long_name: str) -> None:
    var = f.create_variable(name, (dim,), dtype=h5py.string_dtype())
    if len(values):
        var[:] = [str(v) for v in values]
    var.attrs["long_name"] = long_name


def write_timeseries(path, model: Model, run: dict, attrs: dict | None = None) -> Path:
    """Write the record ``run`` of ``model`` (a dict from :func:`.simulate`, :func:`.simulate_implicit`
    or :func:`.read_run`) to the NetCDF file ``path`` (module docstring); ``attrs``: global
    attributes (case name, study, …). Returns the path."""
    path = Path(path)
    t = np.asarray(run["t"], float)
    n_t = t.size
    a = model.arrays
    mode_body = []
    for j, i in enumerate(a.modal_body):
        mode_body += [model.body_names[int(i)]] * int(a.modal_off[j + 1] - a.modal_off[j])
    with atomic_path(path, ".nc") as tmp, h5netcdf.File(tmp, "w") as f:
        dims = {"time": n_t, "body": model.n_bodies, "contact": model.n_pairs, "xyz": 3, "quaternion": 4}
        if model.n_modal:
            dims["mode"] = model.n_modal
        f.dimensions = dims
        f.attrs["Conventions"] = "CF-1.8"
        f.attrs["title"] = "flexbearing run: raw time series"
        f.attrs["timestep_s"] = float(run["timestep_s"])
        f.attrs["record_every"] = int(run.get("every", 1))
        for key, value in (attrs or {}).items():
            f.attrs[key] = value if isinstance(value, (int, float)) else str(value)
        _variable(f, "time", ("time",), t, "s", "simulated time")
        _labels(f, "body", "body", model.body_names, "body name")
        _labels(f, "contact", "contact", model.pair_names, "contact pair name")
        _labels(f, "contact_kind", "contact", model.pair_kinds, "contact pair kind")
        _labels(f, "contact_element", "contact", [model.body_names[int(i)] for i in a.pair_a],
                "the pair's element body (the force variables act on it)")
        _labels(f, "contact_surface", "contact", [model.body_names[int(i)] for i in a.pair_b],
                "the pair's other body")
        q, v = np.asarray(run["q"]), np.asarray(run["v"])
        _variable(f, "position", ("time", "body", "xyz"), q[:, :, :3], "m", "reference point, world frame")
        _variable(f, "orientation", ("time", "body", "quaternion"), q[:, :, 3:], "1",
                  "unit quaternion (w, x, y, z), body to world")
        _variable(f, "velocity", ("time", "body", "xyz"), v[:, :, :3], "m/s", "velocity, world frame")
        _variable(f, "angular_velocity", ("time", "body", "xyz"), v[:, :, 3:], "rad/s",
                  "angular velocity in the body's axes")
        if model.n_modal:
            _labels(f, "mode_body", "mode", mode_body, "modal body of the coordinate")
            _variable(f, "modal_coordinate", ("time", "mode"), run["eta"], "sqrt(kg)",
                      "modal coordinate (mass-normalized modes)")
            _variable(f, "modal_rate", ("time", "mode"), run["eta_dot"], "sqrt(kg)/s", "modal coordinate rate")
        for field, (name, rest, units, long_name) in TIMESERIES_VARIABLES.items():
            if field in run:
                _variable(f, name, ("time",) + rest, run[field], units, long_name)
    return path
