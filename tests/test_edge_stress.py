"""Edge stresses of loaded rollers (``mbd_core.bearing.edge_stress``, ``flexbearing loaddist --edge-stress``).

References:
- ISO/TS 16281:2008 slices: q_k = (c_L/n_s)·e_k^(10/9) with e_k = a + θ·x_k − g_k (rigid rings,
  profile drop g_k); the tilt θ read back from such slice loads is exact.
- Hertz line contact per slice (Johnson, *Contact Mechanics*, 1985, eq. 4.45): the slice load is
  (π/2)·p0·b·w, so the coupled pressures written must carry the roller load.
- The half-space pressures themselves are checked against an independent grid solver in
  tests/test_line_halfspace.py.
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from cases.catalog import builtin_bearing
from cases.cli import main
from mbd_core.bearing.edge_stress import raceway_tilt_rad, roller_edge_stress
from mbd_core.quasistatic import RollerRow

ROW = RollerRow("r", 20, 0.03, 0.03, 0.3, n_slices=16, profile="logarithmic")


def _iso_slices(row, approach_m, tilt_rad):
    x = -0.5 * row.roller_length_m + (np.arange(row.n_slices) + 0.5) * row.roller_length_m / row.n_slices
    e = approach_m + tilt_rad * x - row.drop_m(x)
    return row.contact_stiffness() / row.n_slices * np.maximum(e, 0.0) ** (10.0 / 9.0)


@pytest.mark.parametrize("tilt_rad", [0.0, 2e-4, -5e-4])
def test_tilt_read_back_from_iso_slices(tilt_rad):
    q = _iso_slices(ROW, 15e-6, tilt_rad)
    assert np.count_nonzero(q) >= 2
    assert raceway_tilt_rad(ROW, q) == pytest.approx(tilt_rad, abs=1e-12)


def test_each_raceway_carries_the_roller_load_and_tilt_moves_the_peak():
    q = _iso_slices(ROW, 15e-6, 4e-4)
    out = roller_edge_stress(ROW, q, 3)
    assert [e.raceway for e in out] == ["inner", "outer"]
    for e in out:
        assert e.load_N == pytest.approx(q.sum(), rel=1e-12)
        assert e.x_m[int(np.argmax(e.pressure_Pa))] > 0.0  # the tilt loads the +x end
        assert e.roller == 3
    # the inner contact (convex raceway, smaller R) has the higher pressure
    assert out[0].peak_pressure_Pa > out[1].peak_pressure_Pa
    assert roller_edge_stress(ROW, np.zeros(16), 0) == []
    with pytest.raises(ValueError, match="slice_load_N must hold 16"):
        roller_edge_stress(ROW, np.zeros(5), 0)


@pytest.fixture(scope="module")
def wind_out(tmp_path_factory):
    out = tmp_path_factory.mktemp("es") / "wind"
    assert main(["loaddist", "three-row-roller", "--edge-stress", "--out", str(out)]) == 0
    return out


def test_loaddist_edge_stress_of_the_most_loaded_roller(wind_out):
    """Every roller row's most loaded roller (element_loads.csv), both raceways; the coupled pressures
    integrate to its load (Hertz slices, module docstring); straight rollers show their edge peak
    (measured 1.18–1.20× the ISO slices' peak, at an end slice, with the warning that says so)."""
    summary = json.loads((wind_out / "summary.json").read_text())
    with open(wind_out / "element_loads.csv") as fh:
        elements = list(csv.DictReader(fh))
    bearing = builtin_bearing("three-row-roller").bearing
    assert len(summary["edge_stress"]) == 2 * len(bearing.rows)
    with open(wind_out / "roller_edge_stress.csv") as fh:
        slices = list(csv.DictReader(fh))
    for entry in summary["edge_stress"]:
        row = next(r for r in bearing.rows if r.name == entry["row"])
        loads = {int(e["element"]): float(e["load_N"]) for e in elements if e["row"] == entry["row"]}
        assert entry["roller"] == max(loads, key=loads.get)
        assert entry["load_N"] == pytest.approx(loads[entry["roller"]], rel=1e-5)
        mine = [s for s in slices if s["row"] == entry["row"] and s["raceway"] == entry["raceway"]]
        p0 = np.array([float(s["p_coupled_MPa"]) for s in mine]) * 1e6
        (race_d, concave), = [(d, c) for name, d, c in row.raceway_diameters_m() if name == entry["raceway"]]
        curv = 2.0 / row.roller_diameter_m + (0.0 if math.isinf(race_d) else (-2.0 if concave else 2.0) / race_d)
        e_eff = 207e9 / (1.0 - 0.29**2)  # E' = 2/((1 − ν²)/E · 2) of two steel bodies (BEARING_STEEL)
        w = row.roller_length_m / row.n_slices
        b = 4.0 * p0 * (1.0 / curv) / e_eff  # b² = 8 q' R/(π E'), p0 = 2 q'/(π b) → b = 4 p0 R / E'
        assert np.sum(0.5 * math.pi * p0 * b * w) == pytest.approx(entry["load_N"], rel=1e-6)
        assert 1.1 < entry["peak_over_iso"] < 1.3
        assert entry["warning"] and "end slice" in entry["warning"]
    assert (wind_out / "roller_edge_stress.png").stat().st_size > 10_000


def test_edge_stress_needs_a_roller_row(capsys):
    assert main(["loaddist", "slewing-ring", "--edge-stress"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--edge-stress" in err[0] and "no roller rows" in err[0]
