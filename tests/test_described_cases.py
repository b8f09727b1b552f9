"""`flexbearing run` on a case that points at a bearing description file (family "bearing").

Reference: `flexbearing loaddist FILE` — the run goes through the same path, so its element loads,
s0 and rating life equal loaddist's bit for bit; bad keys name themselves before any work.
"""

import json
from pathlib import Path

import pytest

from cases.cli import main
from cases.config import CaseError
from cases.run import resolve_case

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "bearings" / "pitch-bearing-four-point.toml"


def _case(tmp_path, body: str) -> Path:
    p = tmp_path / "case.toml"
    p.write_text(f'family = "bearing"\nname = "pitch"\n[bearing]\nfile = "{EXAMPLE}"\n{body}')
    return p


def test_run_equals_loaddist_of_the_file(tmp_path, capsys):
    case = _case(tmp_path, '[life]\nrotating_ring = "moving"\nspeed_rpm = 2.0\n')
    assert main(["run", str(case), "--out", str(tmp_path / "run")]) in (0, None)
    capsys.readouterr()
    run = json.loads((tmp_path / "run" / "loaddist" / "summary.json").read_text())
    assert main(["loaddist", str(EXAMPLE), "--rotating-ring", "moving", "--speed-rpm", "2", "--out",
                 str(tmp_path / "ld")]) in (0, None)
    ld = json.loads((tmp_path / "ld" / "summary.json").read_text())
    assert run["load_cases"] == ld["load_cases"] and run["rating_life"] == ld["rating_life"]
    top = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert top["largest_element_load_N"] == max(r["max_load_N"] for c in ld["load_cases"] for r in c["rows"])
    assert top["study"] == "load-distribution" and (tmp_path / "run" / "case.toml").is_file()


@pytest.mark.parametrize("body, message", [
    ("[study]\ns0 = 2.0\n", "study.s0"),
    ("[life]\nspeed_rpm = 3.0\n", "life.speed_rpm: give rotating_ring too"),
    ('[life]\nrotating_ring = "fixed"\n', "life.speed_rpm: must be > 0"),
    ('[study]\nkind = "dynamics"\n', "study.kind: must be one of"),
])
def test_bad_keys_are_refused_before_any_work(tmp_path, body, message):
    with pytest.raises(CaseError) as err:
        resolve_case(str(_case(tmp_path, body)))
    assert message in str(err.value), str(err.value)


def test_missing_bearing_file_names_the_key(tmp_path):
    p = tmp_path / "case.toml"
    p.write_text('family = "bearing"\n[bearing]\nfile = "nowhere/my-bearing.toml"\n')
    with pytest.raises(CaseError, match=r"bearing.file: no such file"):
        resolve_case(str(p))


def test_a_file_name_the_system_refuses_names_the_key(tmp_path):
    # a name longer than the file system allows (ENAMETOOLONG) is a message, not a traceback
    p = tmp_path / "case.toml"
    p.write_text(f'family = "bearing"\n[bearing]\nfile = "{"a" * 5000}.toml"\n')
    with pytest.raises(CaseError, match=r"^bearing.file: not a usable file name \(File name too long\)"):
        resolve_case(str(p))
    with pytest.raises(CaseError, match=r"^case file: not a usable file name"):
        resolve_case("b" * 5000 + ".toml")
