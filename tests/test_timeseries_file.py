"""The raw time-series file of a run (mbd_core.multibody.timeseries), read back with h5py alone.

References: the in-memory record of the same run (bit for bit), Newton's law on the inner ring at
its static equilibrium (the normal-force vectors rebuilt from the file's forces and normals balance
the applied thrust) and the ball geometry (each contact point lies on its ball's surface, on the
line from the centre along the normal)."""

from __future__ import annotations

import json
import math

import h5py
import numpy as np
import pytest

from mbd_core.contact.friction import Coulomb
from mbd_core.multibody import Driven, Fixed, ModelBuilder, simulate
from mbd_core.multibody.bearings import add_ball_row
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.multibody.timeseries import write_timeseries
from mbd_core.quasistatic import BallRow

THRUST_N = 2000.0
BALL_D_M = 12e-3


def _bearing(speed_rad_s: float, friction: bool):
    """12 balls at 30°, inner ring driven (translations free) under an axial thrust; a cage with friction."""
    row = BallRow("balls", 12, BALL_D_M, 0.1, math.radians(30), 0.52, 0.52, "inner", axial_sign=1)
    b = ModelBuilder()
    inner = b.add_body("inner ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Driven(speed_rad_s, translation_free=True))
    outer = b.add_body("outer ring", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    mu = Coulomb(0.1, 0.05, 0.05, 0.1) if friction else None
    cage = dict(cage_mass_kg=0.05, pocket_clearance_m=0.2e-3, cage_stiffness_N_per_m=2e6, pocket_friction=mu)
    added = add_ball_row(b, row, inner, outer, friction=mu, damping_N_s_m=200.0, **(cage if friction else {}))
    b.add_force(inner, (0.0, 0.0, THRUST_N))
    model, state = b.finalize()
    return model, state, added


def test_the_file_holds_the_run_bit_for_bit(tmp_path):
    model, state, added = _bearing(100.0, friction=True)
    run = simulate(model, state, 2e-3, record_every=20)
    path = write_timeseries(tmp_path / "run.nc", model, run, {"case": "test"})
    c = int(added.moving_pairs[3])  # one ball's inner-ring contact
    with h5py.File(path, "r") as f:
        assert f.attrs["case"] == "test" and f.attrs["Conventions"] == "CF-1.8"
        names = list(f["contact"].asstr()[:])
        assert names == list(model.pair_names) and list(f["body"].asstr()[:]) == list(model.body_names)
        assert list(f["contact_kind"].asstr()[:]) == list(model.pair_kinds)
        assert np.array_equal(f["time"][:], run["t"]) and f["time"].attrs["units"] == "s"
        assert np.array_equal(f["normal_force"][:, c], run["fn"][:, c]) and f["normal_force"].attrs["units"] == "N"
        assert run["fn"][:, c].max() > 10.0  # a loaded ball, not zeros
        assert np.array_equal(f["position"][:], run["q"][:, :, :3])
        assert np.array_equal(f["orientation"][:], run["q"][:, :, 3:])
        assert np.array_equal(f["angular_velocity"][:], run["v"][:, :, 3:])
        assert np.array_equal(f["contact_point"][:], run["point"]) and f["contact_point"].dtype == np.float32
        assert np.array_equal(f["slip_speed"][:], run["slip"])
        assert f["normal_force"].chunks is not None and f["normal_force"].compression == "gzip"
        assert "modal_coordinate" not in f  # a rigid model has no modes
    assert [p.name for p in tmp_path.iterdir()] == ["run.nc"]  # written under a temporary name, renamed


def test_force_vectors_rebuilt_from_the_file_balance_the_thrust(tmp_path):
    model, state, added = _bearing(0.0, friction=False)
    eq = static_equilibrium(model, state).state
    run = simulate(model, eq, eq.t + 1e-5, record_every=10)
    path = write_timeseries(tmp_path / "eq.nc", model, run)
    with h5py.File(path, "r") as f:
        fn, n, p = f["normal_force"][0], f["contact_normal"][0].astype(float), f["contact_point"][0].astype(float)
        surface = f["contact_surface"].asstr()[:]
        element = f["contact_element"].asstr()[:]
        body = {name: i for i, name in enumerate(f["body"].asstr()[:])}
        r = f["position"][0]
        angle = f["contact_angle"][0]
    on_inner = surface == "inner ring"
    # Newton: the inner ring gets −F_n n from each of its contacts and the thrust; at rest they cancel.
    # Tolerance: the equilibrium's residual (1e-10 of the load) and the float32 normals (6e-8).
    total = -(fn[on_inner, None] * n[on_inner]).sum(axis=0)
    assert total + np.array([0.0, 0.0, THRUST_N]) == pytest.approx(np.zeros(3), abs=1e-6 * THRUST_N)
    # the same along the axis from the file's contact angles: Σ F_n sin α = F_a
    assert (fn * np.sin(angle))[on_inner].sum() == pytest.approx(THRUST_N, rel=1e-6)
    assert np.degrees(angle[on_inner]).min() > 30.0  # the loaded contact angle opens beyond the free 30°
    # geometry: a ball's contact point is its centre minus D/2 along the normal of the force on it
    loaded = np.flatnonzero(fn > 0)
    assert loaded.size >= 24
    centres = np.array([r[body[e]] for e in element[loaded]])
    assert p[loaded] == pytest.approx(centres - 0.5 * BALL_D_M * n[loaded], abs=1e-7)
    assert np.linalg.norm(n, axis=1) == pytest.approx(np.ones(len(n)), abs=1e-6)


def test_a_case_run_writes_the_file_with_its_name(tmp_path, capsys):
    from cases.cli import main

    out = tmp_path / "run"
    assert main(["run", "slewing-rotation", "--quick", "--set", "analysis.duration_s=0.02", "--out", str(out)]) in (0, None)
    capsys.readouterr()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["timeseries_files"] == ["timeseries.nc"]
    table = np.loadtxt(out / "ball_loads_time.csv", delimiter=",", skiprows=1)
    with h5py.File(out / "timeseries.nc", "r") as f:
        assert f.attrs["case"] == "slewing-rotation-quick" and f.attrs["study"] == "rotation"
        assert f["time"][:] == pytest.approx(table[:, 0], abs=1e-9)
        # the first ball's load on the top race, as the CSV gives it (4 decimals)
        c = list(f["contact"].asstr()[:]).index("load balls ball 0–moving")
        assert f["contact_surface"].asstr()[c] == "top structure"
        assert f["normal_force"][:, c] == pytest.approx(table[:, 1], abs=1e-4)
