"""The top structure's stress over a dynamic slewing run (:mod:`cases.slewing.dynamic_stress`).

Run: `slewing-combined-modal --quick --set top.stress_modes=true` (2 m ring, undulation ×1,
thermal offset 0.4 mm, the quick modal top structure with E = 1.5975 GPa: its stress modes are
those of the 200 GPa reduction scaled by E).

Reference: the finite-element model of the top structure built anew with the case's modulus
(1.5975 GPa), its stress recovered from the displacement field Φ η(t) of the recorded modal
coordinates (read back from ``timeseries.nc`` with h5py) by :func:`fem_rings.stress.nodal_stress_Pa`,
plus the dead load's seat correction (whose physics ``tests/test_slewing_modal_dynamic.py`` checks
against the FE model under the real loads), and the nodes beyond the groove zone (one element or a ball diameter, the larger) of the groove
surface picked here by their own distance to the groove circle. Linear elasticity makes the modal
superposition equal to it up to round-off (tolerance 1e-9 relative; the CSV columns carry six
significant digits, hence 1e-5 there). This checks the wiring: the top structure's columns of the
record, the stress modes scaled to the case's modulus, the groove zone, the instant and its node.
"""

from __future__ import annotations

import csv
import json
import math

import h5py
import numpy as np
import pytest

from cases.run import resolve_case, run_case


@pytest.fixture(scope="module")
def stress_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("stress") / "run"
    case = resolve_case("slewing-combined-modal", quick_run=True, overrides=["top.stress_modes=true"])
    run_case(case, out)
    return case, out, json.loads((out / "summary.json").read_text())


def test_the_ring_peak_is_the_fe_stress_of_the_recorded_displacement(stress_run):
    from fem_rings import build_model
    from fem_rings.stress import nodal_stress_Pa, von_mises_Pa
    from foundation.materials import ElasticMaterial

    from cases.slewing import scene
    from cases.slewing.dynamic_stress import seat_correction_Pa

    case, out, s = stress_run
    r = s["race_stress"]["top structure"]
    body = scene.top_body(case)
    g = case.geometry
    profile, mesh, _ = scene.top_model_inputs(case)
    model = build_model(profile, mesh, ElasticMaterial("top", case.top.E_Pa, scene.NU, 7850.0))
    assert np.array_equal(model.nodes_m, body.nodes_m)
    with h5py.File(out / "timeseries.nc", "r") as f:
        t = f["time"][:]
        columns = f["mode_body"].asstr()[:] == "top structure"
        k = int(np.argmin(np.abs(t - r["time_s"])))
        eta = f["modal_coordinate"][k][columns]
    assert t[k] == pytest.approx(r["time_s"], abs=1e-12)
    seat = seat_correction_Pa(case)  # the dead load on the seat: validated in tests/test_slewing_modal_dynamic.py
    vm = von_mises_Pa(nodal_stress_Pa(model, body.shapes @ eta) + seat)
    groove = g.section().groove("top", g.pitch_diameter_m)
    rc, zc = groove.curvature_center_m
    rho = np.hypot(np.hypot(model.nodes_m[:, 0], model.nodes_m[:, 1]) - rc, model.nodes_m[:, 2] - zc)
    far = np.abs(rho - groove.radius_m) >= max(mesh.size_m, g.ball_diameter_m)
    assert 0 < far.sum() < far.size
    assert r["ring_peak_von_mises_MPa"] * 1e6 == pytest.approx(vm[far].max(), rel=1e-9)
    n = int(np.flatnonzero(far)[np.argmax(vm[far])])
    x, y, z = model.nodes_m[n]
    assert r["ring_peak_radius_mm"] == pytest.approx(1e3 * math.hypot(x, y), abs=1e-9)
    assert r["ring_peak_height_mm"] == pytest.approx(1e3 * z, abs=1e-9)
    # the instant is the largest of the history after the start-up, which the CSV lists sample by sample
    with open(out / "top_structure_stress_time.csv") as fh:
        rows = [row for row in csv.DictReader(fh) if float(row["t_s"]) >= s["start_up_excluded_s"]]
    ring = np.array([float(row["ring_von_mises_MPa"]) for row in rows])
    assert ring.max() == pytest.approx(r["ring_peak_von_mises_MPa"], rel=1e-5)
    assert r["ring_von_mises_range_MPa"][0] == pytest.approx(ring.min(), rel=1e-5)
    # the cycle at the peak's node: equal to the ring peak at its instant, and at the first settled
    # sample the FE stress of that sample's displacement at that node
    at_node = np.array([float(row["peak_node_von_mises_MPa"]) for row in rows])
    assert at_node[np.argmax(ring)] == pytest.approx(ring.max(), rel=1e-5)
    with h5py.File(out / "timeseries.nc", "r") as f:
        j = int(np.argmin(np.abs(f["time"][:] - float(rows[0]["t_s"]))))
        eta0 = f["modal_coordinate"][j][columns]
    vm0 = von_mises_Pa(nodal_stress_Pa(model, body.shapes @ eta0) + seat)
    assert at_node[0] * 1e6 == pytest.approx(vm0[n], rel=1e-5)
    assert r["peak_node_von_mises_range_MPa"] == pytest.approx([at_node.min(), at_node.max()], rel=1e-5)
    groove_vm = np.array([float(row["groove_von_mises_MPa"]) for row in rows])
    assert groove_vm.max() == pytest.approx(r["groove_peak_von_mises_MPa"], rel=1e-5)
    assert (out / "top_structure_ring_peak.png").stat().st_size > 0
    assert (out / "race_stress_time.png").stat().st_size > 0


def test_stress_modes_are_refused_where_no_dynamic_run_reads_them(tmp_path, capsys):
    from cases.cli import main

    assert main(["run", "slewing-undulation", "--quick", "--set", "top.stress_modes=true",
                 "--out", str(tmp_path / "r")]) != 0
    err = capsys.readouterr().err
    assert "top.stress_modes" in err and "dynamic runs only" in err
    assert not (tmp_path / "r").exists()
