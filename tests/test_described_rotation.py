"""The ``rotation`` study of a described bearing: a dynamic run of any ball row with its cage,
spacer balls or as a full complement.

References:
- the quasi-static load distribution of the same rows (:func:`mbd_core.quasistatic.solve_load_distribution`,
  Newton on the ring displacement, an independent solver of the same Hertz contacts): without
  friction and at a low speed (centrifugal ball forces < 0.05 % of the loads) the turning bearing
  carries the load with the quasi-static ball loads at the balls' azimuths, whatever keeps the
  balls apart;
- the no-slip cage speed ω_c = ω_i (1 − D cos α / d_m)/2 at the loaded contact angle (Harris &
  Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed., ch. 8), through
  :func:`mbd_core.bearing.rolling_kinematics`;
- force balance along the axis: Σ Q_j sin α_j over the balls equals the axial load;
- with modal rings, the flexible-ring quasi-static solution of the same reduced rings
  (:func:`mbd_core.quasistatic.flexible_solve.solve_flexible_load_distribution`, Newton on the
  ring displacement and the modal coordinates with the balls condensed).
"""

import json
import math

import numpy as np
import pytest

from cases.bearing_file import loads_bearing
from cases.cli import main
from cases.config import CaseError
from cases.described.case import Rotation
from cases.described.rotation import build_scene, check_rotation, compare, modal_rings, start_state
from cases.integrate import integrate
from mbd_core.quasistatic import solve_load_distribution

ROW = """
[[rows]]
type = "angular_contact"
name = "balls"
count = 12
ball_diameter_m = 0.012
pitch_diameter_m = 0.1
contact_angle_deg = 30
conformity_inner = 0.52
conformity_outer = 0.52
loaded_direction = "+z"
"""
SEPARATORS = {
    "cage": 'kind = "cage"\nmass_kg = 0.05',
    "spacer_balls": 'kind = "spacer_balls"\nspacer_diameter_m = 0.0119',
    "full_complement": 'kind = "full_complement"',
}
LOAD = "[load]\nFz_N = 2000.0\nFx_N = 800.0\n"


def _bearing(separator: str, row: str = ROW, load: str = LOAD):
    text = f'[bearing]\nname = "angular-contact test bearing"\n{row}[rows.separator]\n{separator}\n{load}'
    return loads_bearing(text)


def _run(desc, rotation: Rotation, modal=None):
    reference = solve_load_distribution(desc.bearing, desc.default_load)
    sc = build_scene(desc, rotation, reference, modal)
    state = start_state(sc)
    run = integrate(sc.model, state, rotation.duration_s, rotation.record_every)
    return sc, run, compare(sc, desc, run, rotation.speed_rpm * math.pi / 30.0)


@pytest.mark.parametrize("kind", SEPARATORS)
def test_without_friction_the_turning_bearing_keeps_the_quasistatic_ball_loads(kind):
    desc = _bearing(SEPARATORS[kind])
    rotation = Rotation(speed_rpm=200.0, moving_ring_mass_kg=1.0, duration_s=0.02, record_every=20, friction=False)
    sc, run, fig = _run(desc, rotation)
    row = fig["rows"][0]
    # the quasi-static loads at the balls' azimuths, 12 samples of the settled window; measured
    # 0.14 % (cage), 0.25 % (spacer balls), 0.06 % (full complement): the ring's small vibration
    # about its equilibrium and the balls' centrifugal force; tolerance 1 %
    assert row["max_deviation_from_quasistatic"] < 0.01, row
    # (without friction nothing holds the balls to the no-slip speeds: they keep those of the
    # start, so the orbit speed is checked with friction, below)
    # the moving ring sits where the quasi-static solver puts it (x, z within 1 %; measured 0.5 %)
    ring = fig["moving_ring"]
    for k in (0, 2):
        assert ring["dynamic_mean"][k] == pytest.approx(ring["quasistatic"][k], rel=0.01), ring
    # axial force balance at the last sample: Σ Q sin α = Fz (damping forces have died out: 1 %)
    pairs = list(sc.row_bodies[0].moving_pairs)
    axial = float(np.sum(run["fn"][-1, pairs] * np.sin(run["angle"][-1, pairs])))
    assert axial == pytest.approx(2000.0, rel=0.01)


def test_with_friction_the_cage_runs_near_the_no_slip_speed_and_pockets_push_it():
    desc = _bearing(SEPARATORS["cage"])
    rotation = Rotation(speed_rpm=1000.0, moving_ring_mass_kg=1.0, duration_s=0.03, record_every=50)
    _, _, fig = _run(desc, rotation)
    row = fig["rows"][0]
    # friction drives the balls and the cage: the cage's mean speed within 1 % of no-slip
    # (measured 0.9994 ×; the load-dependent contact angles make the balls slip a little)
    assert row["orbit_over_kinematic"] == pytest.approx(1.0, abs=0.01), row
    assert row["max_pocket_force_N"] > 0.0
    # the largest ball load within 2 % of the quasi-static one (measured 0.8 %). The cage holds the
    # balls to one orbit speed although their contact angles, and so their no-slip speeds, differ
    # round the row: they slide, and the friction moves the load zone some degrees round (the
    # moving ring 2.7 µm sideways), which puts single balls up to 6 % of the largest load off
    # their quasi-static loads (without a cage: 1.1 %, spacer balls; 0.14 %, full complement)
    assert row["largest_load_N"] == pytest.approx(row["quasistatic_largest_load_N"], rel=0.02), row


def _caged_case(tmp_path, name: str, rotation_keys: str):
    """A rotation case file of the caged test bearing with these ``[rotation]`` keys."""
    bearing = tmp_path / "acbb.toml"
    bearing.write_text(f'[bearing]\nname = "acbb"\n{ROW}[rows.separator]\n{SEPARATORS["cage"]}\n{LOAD}')
    case = tmp_path / f"{name}.toml"
    case.write_text(f'family = "bearing"\nname = "acbb"\n[bearing]\nfile = "{bearing}"\n[study]\nkind = "rotation"\n'
                    f"[rotation]\n{rotation_keys}")
    return case


def test_the_rotation_case_writes_its_outputs(tmp_path, capsys):
    case = _caged_case(tmp_path, "case", "speed_rpm = 300.0\nmoving_ring_mass_kg = 1.0\nduration_s = 0.01\n"
                                         "friction = false\n")
    assert main(["run", str(case), "--out", str(tmp_path / "run")]) in (0, None)
    capsys.readouterr()
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["max_deviation_from_quasistatic"] < 0.01
    table = np.loadtxt(tmp_path / "run" / "element_loads_balls.csv", delimiter=",", skiprows=1)
    assert table.shape[1] == 13 and (tmp_path / "run" / "rotation.png").is_file()
    # friction torque: frictionless contacts put no moment about the axis on the rings (Hertz forces
    # along the contact normals, which meet the axis plane of the ball: round-off of the largest
    # contact moment only), and the CSV holds what the summary averages
    torque = summary["ring_torque"]
    lever = 0.05 * 2e3                            # 50 mm pitch radius × a ball load of the order of 2 kN
    assert abs(torque["moving_ring_Nm"]) < 1e-6 * lever and abs(torque["fixed_ring_Nm"]) < 1e-6 * lever
    series = np.loadtxt(tmp_path / "run" / "ring_torque.csv", delimiter=",", skiprows=1)
    assert series.shape[1] == 3 and (tmp_path / "run" / "ring_torque.png").is_file()


def test_friction_torque_on_both_rings_balances_the_rolling_sets_momentum(tmp_path, capsys):
    """With friction the rings' torques together equal −dL/dt of the balls and cage about the axis
    (they get all their forces from the rings): the summary's residual within 2 % of the moving
    ring's torque (explicit friction, the torque at every step against the momentum's end points;
    measured 7e-5 N·m against 0.0133 N·m, 0.5 %)."""
    case = _caged_case(tmp_path, "torque", "speed_rpm = 1000.0\nmoving_ring_mass_kg = 1.0\nduration_s = 0.01\n"
                                           "record_every = 1\n")
    assert main(["run", str(case), "--out", str(tmp_path / "torque")]) in (0, None)
    capsys.readouterr()
    torque = json.loads((tmp_path / "torque" / "summary.json").read_text())["ring_torque"]
    assert abs(torque["moving_ring_Nm"]) > 1e-4
    assert abs(torque["balance_residual_Nm"]) < 0.02 * abs(torque["moving_ring_Nm"]), torque
    # where the drive's power goes (mbd_core.multibody.power_losses): the energy balance over the
    # settled part within 2 % of the drive's power (measured 0.7 % at the 400 samples; 0.5 % with every
    # step, the rest the quadrature of the pockets' impacts, ±0.45 % at other sampling rates); the
    # pockets' friction takes most (measured 82 %), each groove's friction some (9 %)
    power = torque["power_losses"]
    assert abs(power["balance_residual_W"]) < 0.02 * power["input_W"], power
    assert power["shares"]["balls cage pockets friction"] > 0.5
    assert power["shares"]["moving ring groove friction"] > 0.02 and power["shares"]["fixed ring groove friction"] > 0.02
    rows = (tmp_path / "torque" / "power_losses.csv").read_text().splitlines()
    assert rows[0] == "loss,mean_power_W,share" and len(rows) == 1 + len(power["losses_W"])
    assert (tmp_path / "torque" / "power_losses.png").stat().st_size > 10_000


def test_a_run_with_one_recorded_sample_has_no_torque_and_says_so(tmp_path, capsys):
    """record_every beyond the run's steps: one sample, so no torque or losses — a warning naming
    what to change, not an internal error."""
    case = _caged_case(tmp_path, "one", "speed_rpm = 1000.0\nmoving_ring_mass_kg = 1.0\nduration_s = 0.0001\n"
                                        "record_every = 100000\n")
    assert main(["run", str(case), "--out", str(tmp_path / "one")]) in (0, None)
    capsys.readouterr()
    summary = json.loads((tmp_path / "one" / "summary.json").read_text())
    assert any("recorded 1 sample" in w for w in summary["warnings"]), summary["warnings"]
    assert not (tmp_path / "one" / "ring_torque.csv").exists()


def _rotation_case(tmp_path, name, rotation_keys):
    return _caged_case(tmp_path, name, "speed_rpm = 1000.0\nmoving_ring_mass_kg = 1.0\nduration_s = 0.01\n"
                                       f"record_every = 10\nimplicit_friction = true\n{rotation_keys}")


def test_the_implicit_integrator_agrees_with_the_explicit_run(tmp_path, capsys):
    # the generalized-α run at 3× the automatic explicit step (an independent integrator) against
    # the explicit one: per ball, every load at the implicit samples (the explicit record
    # interpolated) within 0.5 % of the largest load (measured 0.096 %), the cage speed within 1e-3
    # (measured 2e-5); 1.5 s wall against 1.2 s explicitly
    runs = {}
    for name, keys in (("explicit", ""), ("implicit", 'integrator = "implicit"\n')):
        assert main(["run", str(_rotation_case(tmp_path, name, keys)), "--out", str(tmp_path / name)]) in (0, None)
        summary = json.loads((tmp_path / name / "summary.json").read_text())
        table = np.loadtxt(tmp_path / name / "element_loads_balls.csv", delimiter=",", skiprows=1)
        runs[name] = (summary, table)
    capsys.readouterr()
    (s_ex, ex), (s_im, im) = runs["explicit"], runs["implicit"]
    assert s_im["integrator"]["kind"].startswith("generalized-alpha") and s_im["error_estimates"]["time_step"] is None
    assert s_im["timestep_s"] == pytest.approx(3.0 * s_ex["timestep_s"], rel=1e-6)
    loads_ex = np.column_stack([np.interp(im[:, 0], ex[:, 0], ex[:, j]) for j in range(1, ex.shape[1])])
    assert np.abs(im[:, 1:] - loads_ex).max() < 0.005 * ex[:, 1:].max()
    r_ex, r_im = s_ex["rows"][0], s_im["rows"][0]
    assert r_im["orbit_over_kinematic"] == pytest.approx(r_ex["orbit_over_kinematic"], abs=1e-3)


def test_rho_inf_is_refused_for_an_explicit_run(tmp_path):
    case = _rotation_case(tmp_path, "explicit", "rho_inf = 0.5\n")
    with pytest.raises(CaseError, match=r"rotation.rho_inf.*implicit"):
        from cases.run import resolve_case
        resolve_case(str(case))


@pytest.mark.parametrize("row, separator, load, rings, message", [
    (ROW, None, LOAD, "file", "has no [rows.separator] table"),
    ('[[rows]]\ntype = "radial_roller"\nname = "rollers"\ncount = 12\nroller_diameter_m = 0.012\n'
     'roller_length_m = 0.012\npitch_diameter_m = 0.1\n', SEPARATORS["cage"], "[load]\nFx_N = 800.0\n", "file",
     "roller rows are modelled quasi-statically only"),
    (ROW, SEPARATORS["cage"], "[load]\nspectrum_csv = 'x.csv'\n", "file", None),
])
def test_what_the_rotation_does_not_model_is_refused_naming_it(row, separator, load, rings, message, tmp_path):
    if "spectrum_csv" in load:
        (tmp_path / "x.csv").write_text("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,time_share\n0,0,1000,0,0,0.5\n0,0,2000,0,0,0.5\n")
        text = f'[bearing]\nname = "b"\n{row}[rows.separator]\n{separator}\n{load}'
        desc = loads_bearing(text, base_dir=tmp_path)
        message = "applies one constant load; the file gives 2 load cases"
    elif separator is None:
        desc = loads_bearing(f'[bearing]\nname = "b"\n{row}{load}')
    else:
        desc = _bearing(separator, row, load)
    with pytest.raises(CaseError) as err:
        check_rotation(desc, rings, Rotation(moving_ring_mass_kg=1.0))
    assert message in str(err.value) and "\n" not in str(err.value)


def test_the_moving_ring_mass_is_required():
    with pytest.raises(CaseError, match="rotation.moving_ring_mass_kg: missing key"):
        check_rotation(_bearing(SEPARATORS["cage"]), "file", Rotation())


@pytest.mark.parametrize("separator, message", [
    ('kind = "cage"', "separator.mass_kg: missing key"),
    ('kind = "spacer_balls"\nspacer_diameter_m = 0.012',
     "separator.spacer_diameter_m: must be below the ball diameter"),
    ('kind = "spacer_balls"\nspacer_diameter_m = 0.0119\n', None),
    ('kind = "cage"\nmass_kg = 0.05\nspacer_diameter_m = 0.01',
     "separator.spacer_diameter_m: not used with kind = 'cage'"),
    ('kind = "cage"\nmass_kg = 0.05\npocket_clearance_m = 0.007', "separator.pocket_clearance_m: must be below half"),
    ('kind = "basket"', "separator.kind: must be one of"),
])
def test_bad_separators_name_their_key(separator, message):
    if message is None:  # 12 balls of 12 mm and 12 spacers of 11.9 mm fit on π·0.1 m; 26 balls do not
        row = ROW.replace("count = 12", "count = 14")
        with pytest.raises(CaseError, match=r"rows\[0\].separator.spacer_diameter_m: 14 balls .* do not fit"):
            _bearing(separator, row)
        return
    with pytest.raises(CaseError) as err:
        _bearing(separator)
    assert str(err.value).startswith("rows[0].") and message in str(err.value), str(err.value)


def test_modal_rings_turning_keep_the_flexible_quasistatic_loads():
    from tests.test_bearing_tradeoff import BEARING  # 16 balls in two box rings, the inner bolted, 20 modes each

    separator = f'[rows.separator]\n{SEPARATORS["cage"]}\n\n[rings.inner]'
    desc = loads_bearing(BEARING.replace("[rings.inner]", separator, 1))
    modal = modal_rings(desc, "file")
    assert set(modal) == {"moving", "fixed"}
    rotation = Rotation(speed_rpm=100.0, duration_s=0.02, record_every=50, friction=False)
    check_rotation(desc, "file", rotation)  # a modal moving ring brings its own mass
    _, _, fig = _run(desc, rotation, modal)
    row = fig["rows"][0]
    # against the flexible quasi-static solution at the balls' phase and the ring's angle: measured
    # 0.16 % (its raceway sampled like the multibody groove, not identically), tolerance 1 %
    assert row["max_deviation_from_quasistatic"] < 0.01, row
    ring = fig["moving_ring"]
    for k in (0, 2):  # x and z of the moving ring's frame, measured within 0.2 %
        assert ring["dynamic_mean"][k] == pytest.approx(ring["quasistatic"][k], rel=0.01), ring
    # the run follows the flexible solution, not the rigid-ring one: rigid rings move the largest
    # load by 1.26 %, eight times the run's deviation from the flexible solution
    rigid = solve_load_distribution(desc.bearing, desc.default_load).rows[0].load_N.max()
    gap = abs(rigid / row["quasistatic_largest_load_N"] - 1.0)
    assert gap > 3.0 * row["max_deviation_from_quasistatic"], (gap, row)
    with pytest.raises(CaseError, match="rotation.moving_ring_mass_kg: the moving ring is modal"):
        check_rotation(desc, "file", Rotation(moving_ring_mass_kg=3.0))


FOUR_POINT = """
[[rows]]
type = "four_point"
name = "balls"
count = 40
ball_diameter_m = 0.03
pitch_diameter_m = 0.8
conformity_inner = 0.53
conformity_outer = 0.53
diametral_clearance_m = {clearance}
"""


@pytest.mark.parametrize("clearance, load, friction", [
    (0.0, "[load]\nFz_N = -50000.0\nFx_N = 10000.0\nMy_Nm = 20000.0\n", True),
    (0.0002, "[load]\nFx_N = 30000.0\n", False),
])
def test_a_four_point_row_turning_keeps_its_two_and_four_point_contact_loads(clearance, load, friction):
    desc = _bearing('kind = "cage"\nmass_kg = 2.0', FOUR_POINT.format(clearance=clearance), load)
    reference = solve_load_distribution(desc.bearing, desc.default_load).rows[0]
    points = set(reference.n_contact_points.tolist())
    # the scenes hold what a four-point row is for: balls in two-point and in four-point contact
    # (combined load: 25 and 15 of 40), or (radial load, clearance) four-point and unloaded balls
    assert points == ({2, 4} if friction else {0, 4}), points
    rotation = Rotation(speed_rpm=20.0, moving_ring_mass_kg=50.0, duration_s=0.03, record_every=50, friction=friction)
    _, _, fig = _run(desc, rotation)
    row = fig["rows"][0]
    # per ball and diagonal against the four-point quasi-static solver (Amasorrain et al. 2003's
    # model, its two diagonals as angular-contact pairs): measured 0.007 % (combined, friction) and
    # 0.015 % (radial, 0.2 mm clearance); tolerance 1 % of the largest contact load
    assert row["max_deviation_from_quasistatic"] < 0.01, row
    if friction:  # the cage at the no-slip speed (measured 0.9997 ×)
        assert row["orbit_over_kinematic"] == pytest.approx(1.0, abs=0.01), row
