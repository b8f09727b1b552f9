"""Bearing description files: every row type through the registry, the inner/outer mapping, the
double-row arrangements, the spectrum CSV, and one-line errors that start with the dotted key."""

from __future__ import annotations

import math

import pytest

from cases.bearing_file import loads_bearing, read_bearing_file
from cases.bearing_rows import ROW_TYPES
from cases.config import CaseError
from mbd_core.quasistatic import BallRow, FourPointRow, RollerRow

BALL = """count = 30
ball_diameter_m = 0.05
pitch_diameter_m = 0.6
conformity_inner = 0.52
conformity_outer = 0.53
"""
ROLLER = """count = 30
roller_diameter_m = 0.04
roller_length_m = 0.04
pitch_diameter_m = 0.6
"""
EVERY_TYPE = f"""
[bearing]
name = "every row type"
moving_ring = "outer"
[materials.bronze]
E_Pa = 1.1e11
nu = 0.34
[[rows]]
type = "deep_groove"
name = "dg"
{BALL}
[[rows]]
type = "angular_contact"
name = "ac"
contact_angle_deg = 40.0
loaded_direction = "+z"
{BALL}
[[rows]]
type = "angular_contact"
name = "o"
contact_angle_deg = 30.0
arrangement = "back_to_back"
row_spacing_m = 0.1
{BALL}
[[rows]]
type = "thrust_ball"
name = "tb"
loaded_direction = "-z"
{BALL}
[[rows]]
type = "four_point"
name = "fp"
contact_angle_deg = 45.0
shoulder_angle_deg = 65.0
{BALL}
[[rows]]
type = "double_four_point"
name = "dfp"
row_spacing_m = 0.08
axial_position_m = 0.2
{BALL}
[[rows]]
type = "radial_roller"
name = "rr"
profile = "logarithmic"
roller_material = "bronze"
diametral_clearance_m = 0.1e-3
{ROLLER}
[[rows]]
type = "thrust_roller"
name = "tr"
profile = "crowned"
crown_drop_m = 5e-6
axial_gap_m = 0.05e-3
{ROLLER}
[[rows]]
type = "crossed_roller"
name = "xr"
contact_angle_deg = 40.0
diametral_clearance_m = -0.02e-3
pattern = "++-"
{ROLLER}
[load]
Fz_N = -1.0e5
Mx_Nm = 2.0e4
"""


def test_every_row_type_builds_its_rows():
    d = loads_bearing(EVERY_TYPE)
    rows = {r.name: r for r in d.bearing.rows}
    assert set(ROW_TYPES) == {"deep_groove", "angular_contact", "thrust_ball", "four_point", "double_four_point",
                              "radial_roller", "thrust_roller", "crossed_roller"}
    assert list(rows) == ["dg", "ac", "o (1)", "o (2)", "tb", "fp", "dfp (1)", "dfp (2)", "rr", "tr", "xr"]
    assert rows["dg"].contact_angle_rad == 0.0 and rows["tb"].contact_angle_rad == math.pi / 2
    assert rows["ac"].contact_angle_rad == math.radians(40.0) and rows["ac"].axial_sign == 1
    assert rows["tb"].axial_sign == -1
    # moving_ring = "outer": the moving ring's groove is the outer one
    for name in ("dg", "ac", "fp"):
        r = rows[name]
        assert (r.moving_raceway, r.conformity_moving, r.conformity_fixed) == ("outer", 0.53, 0.52)
    assert isinstance(rows["fp"], FourPointRow) and rows["fp"].shoulder_angle_rad == math.radians(65.0)
    assert [rows[f"dfp ({k})"].axial_position_m for k in (1, 2)] == pytest.approx([0.16, 0.24], abs=1e-15)
    assert isinstance(rows["rr"], RollerRow) and rows["rr"].orientation == "radial"
    assert rows["rr"].load_sign == -1  # the outer ring moving outwards unloads the rollers there
    assert rows["rr"].gap_m == pytest.approx(0.05e-3, rel=1e-15) and rows["rr"].profile == "logarithmic"
    assert rows["rr"].roller_material.E_Pa == 1.1e11
    assert (rows["tr"].orientation, rows["tr"].load_sign, rows["tr"].gap_m, rows["tr"].crown_drop_m) == \
        ("thrust", 1, 0.05e-3, 5e-6)
    # crossed: gap (P_d/2)·cos α0 along each normal, the pattern repeated around the row
    xr = rows["xr"]
    assert (xr.orientation, xr.load_sign, xr.contact_angle_rad) == ("crossed", -1, math.radians(40.0))
    assert xr.gap_m == pytest.approx(-0.01e-3 * math.cos(math.radians(40.0)), rel=1e-15)
    assert list(xr.diagonal_signs[:6]) == [1, 1, -1, 1, 1, -1]
    assert d.default_load.Fz_N == -1.0e5 and d.default_load.Mx_Nm == 2.0e4


def _pressure_centre_z(row: BallRow) -> float:
    """Where the contact line through the ball centre meets the bearing axis: the line runs from the
    ball centre (d_m/2, z_b) in the direction of the contact normal (s_r·cos α, s_z·sin α) of the
    row's geometry (Harris & Kotzalas, ch. 1, load centres of paired bearings)."""
    a, R = row.contact_angle_rad, 0.5 * row.pitch_diameter_m
    n_r, n_z = row.radial_sign * math.cos(a), row.axial_sign * math.sin(a)
    t = -R / n_r  # r = R + t·n_r = 0
    return row.axial_position_m + t * n_z


@pytest.mark.parametrize("moving", ["inner", "outer"])
@pytest.mark.parametrize("arrangement, outside", [("back_to_back", True), ("face_to_face", False)])
def test_double_row_pressure_centres(moving, arrangement, outside):
    text = f"""[bearing]
name = "pair"
moving_ring = "{moving}"
[[rows]]
type = "angular_contact"
name = "pair"
contact_angle_deg = 40.0
arrangement = "{arrangement}"
row_spacing_m = 0.1
{BALL}"""
    rows = loads_bearing(text).bearing.rows
    assert [r.axial_position_m for r in rows] == [-0.05, 0.05]
    assert rows[0].axial_sign == -rows[1].axial_sign
    for r in rows:
        zc = _pressure_centre_z(r)
        # O: the load centres lie outside the rows (|z_c| > |z_b|, same side); X: between them
        assert (abs(zc) > abs(r.axial_position_m) and zc * r.axial_position_m > 0) == outside


def test_back_to_back_is_stiffer_in_tilt_than_face_to_face():
    """A back-to-back pair carries a tilting moment on a wider base than a face-to-face pair (Harris &
    Kotzalas, Rolling Bearing Analysis, 5th ed., ch. 1, load centres of paired bearings). The contact
    lines of a row all pass through its load centre on the axis, so a rotation about that point
    leaves the row's balls unloaded to first order: the pair's tilt stiffness is 2·k_a·(a/2)², k_a the
    axial stiffness of one row (equal preload: equal in both pairs) and a the distance of the load
    centres, s + 2·(d_m/2)·tan α (O) or 2·(d_m/2)·tan α − s (X). The ratio of the two is (a_O/a_X)²;
    0.5 %: the geometric stiffness of the turning contact lines (Q/|s| term) is left out here."""
    from mbd_core.quasistatic import RingLoad, solve_load_distribution

    K = {}
    for arrangement in ("back_to_back", "face_to_face"):
        d = loads_bearing(f"""[bearing]
name = "pair"
[[rows]]
type = "angular_contact"
name = "pair"
contact_angle_deg = 40.0
arrangement = "{arrangement}"
row_spacing_m = 0.1
diametral_clearance_m = -20e-6
{BALL}""")
        K[arrangement] = solve_load_distribution(d.bearing, RingLoad()).stiffness[3, 3]
    c = 0.6 * math.tan(math.radians(40.0))
    assert K["back_to_back"] / K["face_to_face"] == pytest.approx(((0.1 + c) / (c - 0.1)) ** 2, rel=5e-3)


def _spectrum_file(tmp_path, csv_text: str):
    (tmp_path / "spectrum.csv").write_text(csv_text)
    path = tmp_path / "b.toml"
    path.write_text(f"""[bearing]
name = "spectrum"
[[rows]]
type = "four_point"
name = "fp"
{BALL}
[load]
spectrum_csv = "spectrum.csv"
""")
    return path


def test_spectrum_csv_is_read_relative_to_the_file(tmp_path):
    path = _spectrum_file(tmp_path, "Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,time_share\n0,0,-1e5,0,0,0.25\n1e3,0,-2e5,5e3,0,0.75\n")
    d = read_bearing_file(path)
    assert [c.Fz_N for c in d.load_cases] == [-1e5, -2e5]
    assert d.load_cases[1].Mx_Nm == 5e3 and d.time_share == (0.25, 0.75)


@pytest.mark.parametrize("csv_text, expected", [
    ("Fx_N,Fy_N,Fz_N,Mx_Nm\n0,0,0,0\n", "header: column My_Nm missing"),
    ("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,extra\n0,0,0,0,0,0\n", "header: unknown column 'extra'"),
    ("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n0,0,0,0,0\n0,0,abc,0,0\n", "row 3, column Fz_N: not a number: 'abc'"),
    ("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n0,0,nan,0,0\n", "row 2, column Fz_N: not a finite number"),
    ("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n0,0,0\n", "row 2: 3 values for 5 columns"),
    ("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n", "no load cases"),
    ("", "empty"),
    ("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,time_share\n0,0,0,0,0,-1\n", "column time_share: must be >= 0"),
])
def test_spectrum_errors_name_file_row_and_column(tmp_path, csv_text, expected):
    path = _spectrum_file(tmp_path, csv_text)
    with pytest.raises(CaseError) as err:
        read_bearing_file(path)
    msg = str(err.value)
    assert msg.startswith(f"load.spectrum_csv: {tmp_path / 'spectrum.csv'}") and expected in msg, msg
    assert "\n" not in msg


def test_missing_spectrum_names_the_file(tmp_path):
    path = _spectrum_file(tmp_path, "")
    (tmp_path / "spectrum.csv").unlink()
    with pytest.raises(CaseError, match=r"^load\.spectrum_csv: .*spectrum\.csv: cannot read"):
        read_bearing_file(path)


def _one_row(extra: str, kind: str = "angular_contact", base: str = BALL, head: str = "") -> str:
    return f"""[bearing]
name = "b"
{head}
[[rows]]
type = "{kind}"
name = "r"
{extra}
{base}"""


AC = 'contact_angle_deg = 40.0\nloaded_direction = "+z"\n'


@pytest.mark.parametrize("text, prefix", [
    (_one_row(AC + "colour = 1"), "rows[0].colour: unknown key"),
    (_one_row("", kind="foo"), "rows[0].type: unknown row type 'foo'; one of deep_groove, angular_contact"),
    (_one_row(AC).replace("conformity_inner = 0.52", "conformity_inner = 0.5"), "rows[0].conformity_inner: must be > 0.5"),
    (_one_row(AC).replace("count = 30", "count = 40"), "rows[0].count: 40 balls of 0.05 m do not fit"),
    (_one_row(AC + "diametral_clearance_m = -0.01"), "rows[0].diametral_clearance_m: a preload of 0.01 m exceeds"),
    (_one_row(AC + "diametral_clearance_m = 0.01"), "rows[0].diametral_clearance_m: radial_clearance_m = 0.005 must be below A·cos α0"),
    (_one_row("contact_angle_deg = 40.0"), "rows[0].loaded_direction: required"),
    (_one_row(AC + 'arrangement = "tandem"'), "rows[0].row_spacing_m: arrangement 'tandem' needs"),
    (_one_row(AC + 'ball_material = "gold"'), "rows[0].ball_material: unknown material 'gold'; one of bearing_steel"),
    (_one_row("profile = \"crowned\"", kind="radial_roller", base=ROLLER), "rows[0].crown_drop_m: a crowned roller needs"),
    (_one_row("n_slices = 0", kind="radial_roller", base=ROLLER), "rows[0].n_slices: must be > 0"),
    (_one_row("contact_angle_deg = 90.0", kind="crossed_roller", base=ROLLER), "rows[0].contact_angle_deg: must lie in (0, 90)"),
    (_one_row("contact_angle_deg = \"45\"", kind="crossed_roller", base=ROLLER), "rows[0].contact_angle_deg: expected a number"),
    (_one_row("pattern = \"+x\"", kind="crossed_roller", base=ROLLER), "rows[0].pattern: must be \"alternate\" or a string"),
    (_one_row("pattern = \"\"", kind="crossed_roller", base=ROLLER), "rows[0].pattern: must be \"alternate\" or a string"),
    (_one_row("diametral_clearance_m = -0.1", kind="crossed_roller", base=ROLLER), "rows[0].diametral_clearance_m: a preload of 0.1 m"),
    (_one_row("diametral_clearance_m = nan", kind="crossed_roller", base=ROLLER), "rows[0].diametral_clearance_m:"),
    (_one_row("axial_gap_m = 0.0", kind="crossed_roller", base=ROLLER), "rows[0].axial_gap_m: unknown key"),
    (_one_row(AC, head="moving_ring = \"middle\""), "bearing.moving_ring: must be one of 'inner', 'outer'"),
    (_one_row(AC) + "[load]\nFz_N = \"a lot\"\n", "load.Fz_N: expected a number"),
    (_one_row(AC) + "[load]\nFz_N = 1.0\nspectrum_csv = \"s.csv\"\n", "load.spectrum_csv: give the load components"),
    (_one_row(AC) + "[materials.x]\nE_Pa = -1.0\nnu = 0.3\n", "materials.x.E_Pa: must be > 0"),
    (_one_row(AC) + "[[rows]]\ntype = \"four_point\"\nname = \"r\"\n" + BALL, "rows[1].name: row name 'r' is already used by rows[0]"),
    ("[bearing]\nname = \"b\"\n", "rows: missing key"),
    ("extra = 1\n" + _one_row(AC), "extra: unknown key"),
])
def test_errors_are_one_line_starting_with_the_key(text, prefix):
    with pytest.raises(CaseError) as err:
        loads_bearing(text)
    msg = str(err.value)
    assert msg.startswith(prefix), msg
    assert "\n" not in msg


def test_file_errors_name_the_file(tmp_path):
    for path, expected in ((tmp_path / "nonexist.toml", "cannot read"), (tmp_path, "is a folder"),
                           (tmp_path / "b.csv", "invalid TOML")):
        if path.suffix == ".csv":
            path.write_text("a,b\n1,2\n")
        with pytest.raises(CaseError) as err:
            read_bearing_file(path)
        assert str(err.value).startswith(f"{path}: {expected}"), str(err.value)
