"""The wind main-bearing studies in their --quick variants, through `flexbearing run`.

References: rolling kinematics without slip (Harris & Kotzalas, *Essential Concepts*, ch. 8:
roller spin (d_m/2D)(1 − γ²) ω_i relative to the cage, cage ω_i(1 − γ)/2; the paper's Table 4
gives 535 and 545.5 r/min at 30 r/min), Newton's second law for the inner ring (its mean
acceleration over the run is zero, so the rollers' forces balance the applied load and its
weight), and the masses of the paper's Table 2.
"""

import json
import math

import numpy as np
import pytest

from cases.cli import main
from cases.config import CaseError, dumps_case, loads_case
from cases.run import resolve_case
from cases.wind.case import WindCase
from cases.wind.presets import PRESETS, quick
from cases.wind.scene import rolling_speeds, rows


def _run(name, tmp_path, *extra):
    out = tmp_path / name
    assert main(["run", name, "--quick", "--out", str(out), *extra]) == 0
    return json.loads((out / "summary.json").read_text()), out


def test_presets_round_trip_through_toml(tmp_path):
    for case in list(PRESETS.values()) + [quick(c) for c in PRESETS.values()]:
        assert loads_case(WindCase, dumps_case(case)) == case
    f = tmp_path / "c.toml"
    f.write_text(dumps_case(quick(PRESETS["wind-static"])))
    assert resolve_case(str(f)) == quick(PRESETS["wind-static"])  # a file with [rollers] is a wind case


def test_bad_values_are_named():
    with pytest.raises(CaseError, match=r"^contact\.mu_dynami: unknown key"):
        resolve_case("wind-speeds", overrides=["contact.mu_dynami=0.1"])
    with pytest.raises(CaseError, match=r"^loads.*csv_path is needed"):
        resolve_case("wind-speeds", overrides=["loads.source=csv"])
    with pytest.raises(CaseError, match=r"^study.*friction_sets"):
        resolve_case("wind-friction", overrides=["study.friction_sets=[[0.2, 0.1]]"])


def test_kinematic_roller_speeds_are_the_papers():
    # paper Table 4 (calculated values at 30 r/min): radial 535 r/min, thrust 545.5 r/min
    w = 30 * 2 * math.pi / 60
    radial, front, rear = rows(WindCase())
    to_rpm = 60 / (2 * math.pi)
    assert abs(rolling_speeds(radial, w)[1]) * to_rpm == pytest.approx(535.0, abs=0.1)
    assert abs(rolling_speeds(front, w)[1]) * to_rpm == pytest.approx(545.5, abs=1e-9)
    assert abs(rolling_speeds(rear, w)[1]) * to_rpm == pytest.approx(545.5, abs=1e-9)
    # cage (orbit) speed ω_i(1 − γ)/2, γ = D/d_m (Harris & Kotzalas ch. 8)
    assert rolling_speeds(radial, w)[0] == pytest.approx(w * (1 - 55 / 1963) / 2, rel=1e-12)
    assert rolling_speeds(front, w)[0] == pytest.approx(w / 2, rel=1e-12)


def test_static_load_cases(tmp_path):
    s, out = _run("wind-static", tmp_path)
    assert s["equilibrium_error_max"] < 1e-6  # Newton residual of the quasi-static solver
    # the radial row carries the weights (−1.275 MN + the inner ring): Stribeck's 4.37 F_r/Z
    # estimate for zero clearance (Harris & Kotzalas §7.1) bounds the largest roller load from below
    f_r = 1.2753e6 + 3971 * 9.81
    assert s["max_roller_load_N"]["radial"] > 4.37 * f_r / 98
    assert {p.name for p in out.iterdir()} >= {"load_spectrum.png", "max_roller_loads.png", "roller_loads.png",
                                              "load_history.csv", "load_case=01", "load_case=32"}


@pytest.fixture(scope="module")
def speeds_run(tmp_path_factory):
    return _run("wind-speeds", tmp_path_factory.mktemp("wind"))[0]


def test_rigid_run_speeds_and_equilibrium(speeds_run):
    s = speeds_run
    # inner ring equilibrium: the rollers' normal forces balance the applied load and the ring's
    # weight (0.5 % acceptance; 0.03 % force and 0.12 % moment measured)
    assert s["equilibrium"]["force_error"] < 0.005
    assert s["equilibrium"]["moment_error"] < 0.005
    # loaded rollers roll at the kinematic speed within 1 % (measured +0.00 / +0.07 / +0.12 %)
    for name in ("radial", "front thrust", "rear thrust"):
        assert abs(s["speeds"][name]["loaded_error"]) < 0.01, name


def test_rigid_run_cage_speeds(speeds_run):
    # cage (orbit) speed ω_i(1 − γ)/2 (Harris & Kotzalas ch. 8) within 1 % (measured +0.09 / +0.09 / −0.07 %)
    for name in ("radial", "front thrust", "rear thrust"):
        assert abs(speeds_run["cages"][name]["error"]) < 0.01, name


def test_rigid_run_ring_torques_balance_the_rollers_angular_momentum(speeds_run):
    """The friction torque of the rollers and cages on the two rings about the shaft axis (forces
    re-evaluated at the recorded states) against the rate of the angular momentum of the rigid
    bodies between them (from their recorded velocities): T_inner + T_outer = −dL/dt, Newton's
    second law for the roller set. Measured: −241.7 and +236.8 N·m, residual −1.6 N·m (0.7 %);
    tolerance 2 % of the inner ring's torque. The driven inner ring is held back (T_inner < 0, the
    drive turns it the positive way) and the fixed outer ring dragged along."""
    t = speeds_run["ring_torque"]
    assert t["inner_ring_Nm"] < 0.0 < t["outer_ring_Nm"]
    assert abs(t["balance_residual_Nm"]) < 0.02 * abs(t["inner_ring_Nm"])


def test_rigid_run_drive_power_balances_the_losses_and_the_energy_change(speeds_run):
    """Energy balance of the same run (mbd_core.multibody.power_losses, the forces re-evaluated at 160
    recorded states): the drive's and the loads' power equals the losses of every contact group
    plus the rate of change of the kinetic and elastic energy (the recorded states' own sums).
    Measured: 752 W in, 915 W lost, −159 W stored, residual −6.2 W (0.8 %); tolerance 2 % of the
    drive's power. The drive's power is −T_inner·Ω (the same torque, another sum over other samples:
    measured 752 against 759 W) within three standard errors or 2 %; the raceways' friction takes the
    largest share (measured 33 % each)."""
    t = speeds_run["ring_torque"]
    p = t["power_losses"]
    assert abs(p["balance_residual_W"]) < 0.02 * p["input_W"]
    omega = quick(PRESETS["wind-speeds"]).analysis.speed_rpm * math.pi / 30.0
    assert p["input_W"] == pytest.approx(-t["inner_ring_Nm"] * omega,
                                         abs=max(3 * p["input_error_W"], 0.02 * p["input_W"]))
    top = max(p["shares"], key=p["shares"].get)
    assert top in ("inner ring raceway friction", "outer ring raceway friction")


def test_rigid_and_flexible_quick_runs(tmp_path):
    """Modal rings and cages (8 modes, coarse meshes in the quick variant) against the rigid model."""
    # the quick variant meshes the rings at 0.18 m (the coarsest all-hexahedral section of the outer
    # ring) and the cages at 0.05 m: 150 s CPU and 1.5 GB measured (at 0.1 m and 0.03 m: 212 s,
    # 2.5 GB; flexible 0.14 % force, 0.05 % moment, speeds −0.01 / −0.01 / +0.28 %, stress peaks
    # 2.0–22 MPa)
    s, out = _run("wind-rigid-flexible", tmp_path)
    for label in ("rigid", "flexible"):
        # Newton's second law for the inner ring, 0.5 % acceptance (measured flexible: 0.04 % force,
        # 0.10 % moment; rigid: 0.03 %, 0.12 %)
        assert s[label]["equilibrium"]["force_error"] < 0.005, label
        assert s[label]["equilibrium"]["moment_error"] < 0.005, label
        # loaded rollers at the no-slip speed within 1 % (measured flexible −0.01 / +0.00 / +0.30 %)
        for name in ("radial", "front thrust", "rear thrust"):
            assert abs(s[label]["speeds"][name]["loaded_error"]) < 0.01, (label, name)
    # modal stresses: global ring and cage bending only (no contact stress in 8 modes); the peaks
    # stay far below the 42CrMo yield strength (≈ 650 MPa) and are not zero (1.6–14 MPa measured)
    for name, v in s["flexible"]["stress"].items():
        assert 0.1 < v["peak_von_mises_MPa"] < 650.0, name
        assert (out / v["png"]).stat().st_size > 10_000
    # each run's ring torque in its own files and summary entry
    for label in ("rigid", "flexible"):
        assert s["ring_torque"][label]["inner_ring_Nm"] < 0.0, label
        assert (out / f"ring_torque_{label}.csv").is_file() and (out / f"ring_torque_{label}.png").is_file()


def test_averages_need_samples_after_the_settling_time():
    """A run whose samples all fall before ``analysis.settle_s`` gave NaN speeds and a bare numpy
    error; now it names the keys. Four samples at 0, 1, 2, 3 ms with settle_s = 2.5 ms: one left."""
    from cases.wind import dynamic

    case = resolve_case("wind-speeds", True, ["analysis.duration_s=0.004", "analysis.settle_s=0.0025"])
    rec = {"t": np.array([0.0, 1e-3, 2e-3, 3e-3]), "timestep_s": 1e-5}
    with pytest.raises(CaseError, match=r"analysis\.settle_s = 0\.0025 s leaves 1 recorded sample before.*record_every"):
        dynamic.settled(case, rec)
    ok = dynamic.settled(case.with_(analysis={"settle_s": 0.0015}), rec)
    assert ok.tolist() == [False, False, True, True]
