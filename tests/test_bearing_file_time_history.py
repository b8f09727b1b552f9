"""``[load] time_history_csv``: a load time history read as load cases with trapezoid time shares."""

from __future__ import annotations

import json

import pytest

from cases.bearing_file import read_bearing_file
from cases.cli import main
from cases.config import CaseError
from cases.load_csv import trapezoid_time_shares

HEAD = "time_s,Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n"

BEARING = """[bearing]
name = "time history"
[[rows]]
type = "four_point"
name = "balls"
count = 40
ball_diameter_m = 0.04
pitch_diameter_m = 1.0
conformity_inner = 0.53
conformity_outer = 0.53
[load]
{load}
"""


def _file(tmp_path, csv_text: str, load: str = 'time_history_csv = "history.csv"'):
    (tmp_path / "history.csv").write_text(csv_text)
    path = tmp_path / "b.toml"
    path.write_text(BEARING.format(load=load))
    return path


def test_shares_are_the_trapezoid_weights_by_hand(tmp_path):
    # t = 0, 1, 3, 6 s: w = (1−0)/2, (3−0)/2, (6−1)/2, (6−3)/2 = 0.5, 1.5, 2.5, 1.5 s over T = 6 s
    csv_text = HEAD + "0,0,0,-1e5,0,0\n1,0,0,-2e5,0,1e4\n3,5e3,0,-3e5,0,0\n6,0,0,-4e5,2e4,0\n"
    d = read_bearing_file(_file(tmp_path, csv_text))
    assert d.time_share == pytest.approx((0.5 / 6, 1.5 / 6, 2.5 / 6, 1.5 / 6), rel=1e-15)
    assert [c.Fz_N for c in d.load_cases] == [-1e5, -2e5, -3e5, -4e5]
    assert (d.load_cases[1].My_Nm, d.load_cases[2].Fx_N, d.load_cases[3].Mx_Nm) == (1e4, 5e3, 2e4)
    # two instants: half the duration each
    assert trapezoid_time_shares([2.0, 7.0]).tolist() == [0.5, 0.5]


def _life(path, *extra) -> dict:
    return ["loaddist", str(path), "--rotating-ring", "moving", "--speed-rpm", "10", "--json", *extra]


def test_constant_history_gives_the_life_of_its_one_load(tmp_path, capsys):
    # the shares sum to 1 and every case is the same load: Palmgren–Miner 1/Σ(t_i/L) = L (rel 1e-9,
    # the same solver on the same load)
    path = _file(tmp_path, HEAD + "".join(f"{t},1e4,0,-2e5,0,3e4\n" for t in (0.0, 0.3, 2.0, 2.1, 5.0)))
    assert main(_life(path)) == 0
    history = json.loads(capsys.readouterr().out)["rating_life"]
    assert main(_life(path, "--Fx-N", "1e4", "--Fz-N", "-2e5", "--My-Nm", "3e4")) == 0
    one = json.loads(capsys.readouterr().out)["rating_life"]
    assert history["life_Mrev"] == pytest.approx(one["life_Mrev"], rel=1e-9)
    assert history["rows"][0]["life_Mrev"] == pytest.approx(one["rows"][0]["life_Mrev"], rel=1e-9)


def test_history_life_equals_the_spectrum_of_its_hand_shares(tmp_path, capsys):
    # the same loads as a spectrum with the hand-computed trapezoid shares (0.5, 1.5, 1)/3 (rel 1e-12)
    path = _file(tmp_path, HEAD + "0,0,0,-1e5,0,0\n1,0,0,-3e5,0,5e4\n3,0,0,-2e5,0,0\n")
    assert main(_life(path)) == 0
    history = json.loads(capsys.readouterr().out)["rating_life"]
    (tmp_path / "s.csv").write_text("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,time_share\n0,0,-1e5,0,0,0.5\n0,0,-3e5,0,5e4,1.5\n"
                                    "0,0,-2e5,0,0,1.0\n")
    (tmp_path / "s.toml").write_text(BEARING.format(load='spectrum_csv = "s.csv"'))
    assert main(_life(tmp_path / "s.toml")) == 0
    spectrum = json.loads(capsys.readouterr().out)["rating_life"]
    assert history["life_Mrev"] == pytest.approx(spectrum["life_Mrev"], rel=1e-12)
    assert history["time_share"] == pytest.approx([0.5 / 3, 1.5 / 3, 1.0 / 3], rel=1e-15)


@pytest.mark.parametrize("csv_text, load, expected", [
    (HEAD + "0,0,0,-1e5,0,0\n1,0,0,-1e5,0,0\n1,0,0,-1e5,0,0\n", None,
     "history.csv: row 4, column time_s: time must increase strictly"),
    (HEAD + "0,0,0,-1e5,0,0\n2,0,0,-1e5,0,0\n1,0,0,-1e5,0,0\n", None,
     "history.csv: row 4, column time_s: time must increase strictly, got 1.0 after 2.0"),
    (HEAD + "0,0,0,-1e5,0,0\n", None, "history.csv: one instant"),
    ("Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n0,0,-1e5,0,0\n", None, "history.csv, header: column time_s missing"),
    (HEAD.replace("\n", ",time_share\n") + "0,0,0,0,0,0,1\n", None, "header: unknown column 'time_share'"),
    (HEAD + "0,0,0,-1e5,0,0\n1,0,0,x,0,0\n", None, "history.csv: row 3, column Fz_N: not a number"),
    (HEAD + "-1e308,0,0,-1e5,0,0\n1e308,0,0,-1e5,0,0\n", None, "column time_s: the duration"),
    (HEAD, 'time_history_csv = "history.csv"\nspectrum_csv = "history.csv"', "load.time_history_csv: give a spectrum"),
    (HEAD, 'time_history_csv = "history.csv"\nFz_N = -1e5', "load.time_history_csv: give the load components or a "
     "time history file, not both (Fz_N given)"),
    (HEAD, 'time_history_csv = " "', "load.time_history_csv: must name a file"),
])
def test_errors_are_one_line_naming_the_key_and_row(tmp_path, csv_text, load, expected):
    path = _file(tmp_path, csv_text, *(() if load is None else (load,)))
    with pytest.raises(CaseError) as err:
        read_bearing_file(path)
    msg = str(err.value)
    assert msg.startswith("load.time_history_csv") and expected in msg and "\n" not in msg, msg
