"""Every failure of the command line is one line with its exit status; input is checked before work.

Exit status 2 with one line naming the cause and the option or key for anything the input causes,
1 with one line and a hint for an internal error (traceback behind ``--debug``), 130 on Ctrl-C.
"""

from __future__ import annotations

import argparse
import errno
import json
import math
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import cases.cli
import cases.run
from cases.cli import main
from cases.config import CaseError, dumps_case
from cases.run import resolve_case
from cases.slewing.case import SlewingCase
from cases.wind.case import Loads, WindCase
from mbd_core.multibody import DivergenceError
from mbd_core.multibody.statics import StaticEquilibriumError

BALL = ["hertz", "ball", "--ball-diameter-mm", "95.25", "--conformity", "0.525", "--pitch-diameter-mm", "6690"]


def one_line_error(capsys, argv, status=2) -> str:
    assert main(argv) == status
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    return err


def _raising(exc):
    def run_case(case, out_dir, progress=None, resume=False, source=None):
        raise exc
    return run_case


# -- failures of a run ----------------------------------------------------------------------------

@pytest.mark.parametrize("exc, words", [
    (DivergenceError("penetration 0.000602 m at contact 'front thrust roller 9–pocket' beyond its bound"),
     "front thrust roller 9–pocket"),
    (StaticEquilibriumError("static equilibrium not found: residual force 4.6e+04 N — can the bearing carry "
                            "the load?"), "can the bearing carry the load?"),
])
def test_a_run_that_fails_numerically_is_one_line_exit_2(exc, words, monkeypatch, capsys, tmp_path):
    # `run wind-speeds --quick --set contact.mu_static=1 --set contact.mu_dynamic=1` diverges after
    # 6 min; the exception it raises is raised here in place of the run
    monkeypatch.setattr(cases.run, "run_case", _raising(exc))
    err = one_line_error(capsys, ["run", "wind-speeds", "--quick", "--out", str(tmp_path / "r")])
    assert err.startswith("flexbearing: error: ") and words in err


def test_a_run_with_friction_it_cannot_integrate_ends_in_one_line(capsys, tmp_path):
    # the reproduction: μ = 1 makes a thrust roller push through its cage pocket within 0.03 s
    argv = ["run", "wind-speeds", "--quick", "--set", "contact.mu_static=1", "--set", "contact.mu_dynamic=1",
            "--out", str(tmp_path / "r")]
    assert main(argv) == 2
    err = capsys.readouterr().err
    last = err.replace("\r", "\n").strip().splitlines()[-1]
    assert last.startswith("flexbearing: error: the simulation stopped: ") and "Traceback" not in err
    assert not (tmp_path / "r").exists()


def test_disk_full_names_the_path_and_the_option(monkeypatch, capsys, tmp_path):
    out = tmp_path / "r"
    monkeypatch.setattr(cases.run, "run_case", _raising(OSError(errno.ENOSPC, "No space left on device",
                                                                 str(out / "summary.json"))))
    err = one_line_error(capsys, ["run", "wind-speeds", "--out", str(out)])
    assert f"cannot write {out / 'summary.json'}: No space left on device (--out)" in err


def test_out_pointing_at_a_file_is_refused_and_the_file_kept(capsys, tmp_path):
    target = tmp_path / "notes.txt"
    target.write_text("mine")
    err = one_line_error(capsys, ["loaddist", "--out", str(target)])
    assert "--out" in err or str(target) in err
    assert target.read_text() == "mine"


def test_internal_error_is_one_line_with_a_hint_and_the_traceback_behind_debug(monkeypatch, capsys, tmp_path):
    monkeypatch.setattr(cases.run, "run_case", _raising(ZeroDivisionError("float division by zero")))
    argv = ["run", "wind-speeds", "--out", str(tmp_path / "r")]
    err = one_line_error(capsys, argv, status=1)
    assert err.startswith("flexbearing: internal error: ZeroDivisionError: float division by zero") and "--debug" in err
    assert main(["--debug", *argv]) == 1
    assert "Traceback" in capsys.readouterr().err


def test_ctrl_c_is_one_line_exit_130(monkeypatch, capsys, tmp_path):
    monkeypatch.setattr(cases.run, "run_case", _raising(KeyboardInterrupt()))
    err = one_line_error(capsys, ["run", "wind-speeds", "--out", str(tmp_path / "r")], status=130)
    assert err == "flexbearing: interrupted\n"


def test_a_closed_pipe_ends_quietly():
    # `flexbearing run --list | head -0`: the reader is gone before anything is written
    proc = subprocess.Popen([sys.executable, "-m", "cases.cli", "run", "--list", "--json"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=60) == 1
    assert err == ""


# -- hertz: material and loads --------------------------------------------------------------------

@pytest.mark.parametrize("extra, option", [
    (["--load-N", "1000", "--E-GPa", "inf"], "--E-GPa"),
    (["--load-N", "1000", "--nu", "nan"], "--nu"),
    (["--load-N", "-inf"], "--load-N"),
    (["--load-N", "nan"], "--load-N"),
])
def test_non_finite_inputs_are_refused_naming_the_option(extra, option, capsys):
    err = one_line_error(capsys, [*BALL, *extra])
    assert f"{option} must be a" in err


def test_infinite_conformity_is_refused(capsys):
    argv = ["hertz", "ball", "--ball-diameter-mm", "95.25", "--conformity", "inf", "--pitch-diameter-mm", "6690",
            "--load-N", "1000"]
    assert "--conformity" in one_line_error(capsys, argv)


def test_a_load_beyond_the_range_of_the_formulas_is_refused(capsys):
    # before: exit 0 and `"approach_m": Infinity` on stdout (invalid JSON); δ = (Q/K)^(2/3) overflows
    err = one_line_error(capsys, [*BALL, "--load-N", "1e300", "--json"])
    assert "--load-N must lie in [1e-30, 1e+30], got 1e+300" in err
    assert capsys.readouterr().out == ""


def test_json_output_is_strict_with_non_finite_values_as_null(capsys):
    cases.cli._print_json({"a": math.inf, "b": [1.0, math.nan], "c": np.array([1, 2]), "d": np.float64(2.5), 3: "x"})
    out, err = capsys.readouterr()
    assert json.loads(out, parse_constant=lambda c: pytest.fail(f"non-standard JSON constant {c}")) == \
        {"a": None, "b": [1.0, None], "c": [1, 2], "d": 2.5, "3": "x"}
    assert err == "flexbearing: warning: not finite, written as null: a, b[1]\n"


# -- modes: model size before meshing -------------------------------------------------------------

def test_more_modes_than_the_mesh_has_are_refused_before_meshing(capsys):
    # before: 25 s of meshing and assembly, then a scipy TypeError (k ≥ number of DOF)
    t0 = time.perf_counter()
    err = one_line_error(capsys, ["modes", "slewing-bottom-race-1m", "--modes", "100000"])
    assert "--modes = 100000" in err and "DOF" in err
    assert time.perf_counter() - t0 < 5.0


def test_a_mesh_larger_than_the_memory_is_refused_with_the_estimate(capsys):
    # before: 5 GB in 10 s on the way to running out of memory
    t0 = time.perf_counter()
    err = one_line_error(capsys, ["modes", "slewing-bottom-race-1m", "--size-mm", "0.001"])
    assert "--size-mm = 0.001 would give" in err and "GB" in err and "more than this machine's" in err
    assert time.perf_counter() - t0 < 5.0


# -- case files -----------------------------------------------------------------------------------

def write(tmp_path, text: str | bytes, name="case.toml"):
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return str(path)


@pytest.mark.parametrize("text", ["", "\n\n", "# nothing but a comment\n"])
def test_an_empty_case_file_is_refused_naming_it(text, tmp_path):
    path = write(tmp_path, text)
    with pytest.raises(CaseError, match=f"^{path}: no case entries"):
        resolve_case(path)


def test_invalid_utf8_names_the_file(tmp_path):
    path = write(tmp_path, b'name = "r\xe9sum\xe9"\n')
    with pytest.raises(CaseError, match=f"^{path}: not UTF-8 text"):
        resolve_case(path)


def test_deeply_nested_toml_is_one_line_naming_the_file(tmp_path, capsys):
    path = write(tmp_path, "a = " + "[" * 100_000 + "]" * 100_000)
    err = one_line_error(capsys, ["run", path, "--out", str(tmp_path / "r")])
    assert f"{path}: invalid TOML: nested too deeply" in err


@pytest.mark.parametrize("text, key", [
    ("family = 'slewing'\n[geometry]\nconformity = inf\n", "geometry.conformity"),
    ("family = 'slewing'\n[undulation]\nscale = 1.0\nprofile_deg_mm = [[0, 0], [90, nan], [180, 0], [270, 0]]\n",
     "undulation.profile_deg_mm[1][1]"),
])
def test_non_finite_values_in_a_case_file_name_the_key(text, key, tmp_path):
    path = write(tmp_path, text)
    with pytest.raises(CaseError, match=f"^{re.escape(f'{path}: {key}')}: expected a finite number"):
        resolve_case(path)


def test_case_files_name_their_family(tmp_path):
    wind = resolve_case("wind-static")
    assert dumps_case(wind).startswith('family = "wind"\n')
    assert resolve_case(write(tmp_path, dumps_case(wind))) == wind
    # a wind file without [rollers] (written before `family` existed) is still a wind file
    assert resolve_case(write(tmp_path, "[loads]\nscale = 0.5\n")) == WindCase(loads=Loads(scale=0.5))
    # tables of both families, or of neither: refused with the line to add
    with pytest.raises(CaseError, match="family: missing key; add family = 'slewing' or 'wind'"):
        resolve_case(write(tmp_path, "[contact]\nmu_static = 0.3\n"))
    with pytest.raises(CaseError, match="unknown key"):
        resolve_case(write(tmp_path, "family = 'wind'\n[geometry]\nconformity = 0.53\n"))
    with pytest.raises(CaseError, match="family: must be one of 'slewing', 'wind', 'bearing', 'dma', 'crb', 'turbocharger', got 'roller'"):
        resolve_case(write(tmp_path, "family = 'roller'\n"))
    assert resolve_case(write(tmp_path, "family = 'slewing'\n")) == SlewingCase()


# -- case values checked before meshing -----------------------------------------------------------

@pytest.mark.parametrize("overrides, start", [
    (["top.n_modes=100000"], "top.n_modes = 100000 is more than the mesh can give"),
    (["top.element_size_m=0.001"], "top.element_size_m = 0.001 would give"),
    (["bodies.cages='modal'", "bodies.cage_element_size_m=1e-4"], "bodies.cage_element_size_m = 0.0001 would give"),
    (["top.groove_harmonics=1000000"], "top.groove_harmonics must be below 360"),
])
def test_models_too_large_are_refused_when_the_case_is_read(overrides, start):
    name = "wind-speeds" if overrides[0].startswith("bodies") else "slewing-undulation"
    with pytest.raises(CaseError, match=f"^{start}"):
        resolve_case(name, True, overrides)


@pytest.mark.parametrize("override, start", [
    ("geometry.conformity=5", "geometry: groove"),          # the contact point leaves the groove
    ("geometry.tmr_height_m=1e-9", "geometry: profile 'TMR'"),  # a TMR of no thickness
])
def test_sections_the_geometry_cannot_make_are_geometry_errors(override, start):
    # the sections refuse these, which used to happen only when the run built them
    with pytest.raises(CaseError, match=f"^{re.escape(start)}"):
        resolve_case("slewing-static", overrides=[override])


@pytest.mark.parametrize("overrides, start", [
    (["loads='constant'", "loads.scale=2"], "loads: expected a table"),
    (["top.n_modes=13\nname = 'other'"], "top.n_modes: expected one value"),
    (["=3"], "--set '=3': no key before '='"),
])
def test_set_values_that_used_to_crash_or_pass_silently(overrides, start):
    with pytest.raises(CaseError, match=f"^{re.escape(start)}"):
        resolve_case("wind-speeds" if "loads" in overrides[0] else "slewing-undulation", False, overrides)


def test_a_case_file_that_quick_makes_invalid_names_the_key(tmp_path):
    # a TMR 1.5 m wide fits the 2 m ring's file but not the 1 m ring that --quick makes of it; the
    # error used to be a bare ValueError from the dataclass, without the table
    path = write(tmp_path, "family = 'slewing'\n[study]\nkind = 'static'\n[geometry]\ntmr_width_m = 1.5\n")
    assert resolve_case(path).geometry.tmr_width_m == 1.5
    with pytest.raises(CaseError, match=r"^--quick: geometry\.tmr_width_m \(1\.5\) must be below pitch_diameter_m \(1\.0\)"):
        resolve_case(path, True)


@pytest.mark.parametrize("csv", ["/nonexistent/loads.csv", "."])
def test_a_missing_load_file_is_refused_naming_the_key(csv):
    # before: the study ran, then "cannot read ...: No such file" (or "Is a directory") without
    # the key (wind-speeds: the static study does not read loads.source, which is refused)
    with pytest.raises(CaseError, match=f"^loads.csv_path: no such file: {re.escape(repr(csv))}$"):
        resolve_case("wind-speeds", True, ["loads.source=csv", f"loads.csv_path={csv!r}"])


def test_infinite_and_nan_set_values_are_refused():
    for rhs in ("inf", "-inf", "nan"):
        with pytest.raises(CaseError, match="^geometry.conformity: expected a finite number"):
            resolve_case("slewing-static", overrides=[f"geometry.conformity={rhs}"])
    assert math.isfinite(resolve_case("slewing-static", overrides=["geometry.conformity=0.53"]).geometry.conformity)


def test_no_static_equilibrium_raises_its_own_class():
    # a load lifting the top race off its balls: contacts only push, so no equilibrium exists
    # (the residual stays at the whole load). A RuntimeError before; now a class the CLI reports.
    sys.path.insert(0, str(Path(__file__).parent))
    from test_multibody import G, SLEWING_ROW, slewing_model

    from mbd_core.multibody.statics import static_equilibrium
    from mbd_core.quasistatic import RingLoad

    model, state, _ = slewing_model(SLEWING_ROW, RingLoad(Fz_N=+68.9e3 * G))
    with pytest.raises(StaticEquilibriumError, match="static equilibrium not found.*can the bearing carry the load"):
        static_equilibrium(model, state, max_evaluations=20)
    assert issubclass(StaticEquilibriumError, RuntimeError)  # callers catching RuntimeError still do


def test_an_os_error_in_the_cache_names_the_setting(monkeypatch, tmp_path):
    cache = tmp_path / "cache-is-a-file"
    monkeypatch.setenv("FLEXBEARING_CACHE", str(cache))
    exc = NotADirectoryError(errno.ENOTDIR, "Not a directory", str(cache / "fe-model"))
    text = cases.cli._os_error_text(exc, argparse.Namespace(out=None))
    assert text == f"cannot write {cache / 'fe-model'}: Not a directory (the cache folder, $FLEXBEARING_CACHE)"
