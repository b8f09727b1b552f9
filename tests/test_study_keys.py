"""A case file says what ran: keys a study does not read are refused (or honoured), and a run
without ``--out`` does not replace the results of another case source.

References: the registry of each family (``STUDIES``: the keys a study does not read and what does
their job, :mod:`cases.overrides`); the explicit stability limit of
:func:`mbd_core.multibody.explicit.stable_timestep` for an honoured ``analysis.timestep_s``.
"""

import dataclasses
import json
import re
import shlex
import shutil
import typing
from pathlib import Path

import pytest

import cases.slewing.studies as slewing_studies
from cases.cli import build_parser, main
from cases.config import CaseError, dumps_case
from cases.run import PRESETS, resolve_case
from cases.slewing import quick as slewing_quick
from cases.wind.case import WindCase

REPO = Path(__file__).resolve().parents[1]


# -- overrides a study does not read ---------------------------------------------------------------
@pytest.mark.parametrize("name, override, replacement", [
    # the README's own example: undulation.scale and top.E_Pa were recorded in case.toml and ignored
    ("slewing-undulation", "undulation.scale=2", "study.undulation_scales"),
    ("slewing-undulation", "top.E_Pa=20e9", "study.top_E_Pa"),
    ("slewing-undulation", "analysis.duration_s=3", "study.spacer_run_s"),
    ("slewing-thermal", "thermal.offset_m=3e-4", "study.offsets_m"),
    ("slewing-combined", "thermal.offset_m=3e-4", "study.combined_offsets_m"),
    ("slewing-life", "thermal.offset_m=3e-4", "study.life_offset_m"),
    ("slewing-full-scale", "top.E_Pa=20e9", "study.top_E_Pa"),
    ("wind-driving-speed", "analysis.speed_rpm=25", "study.speeds_rpm"),
    ("wind-friction", "contact.mu_static=0.3", "study.friction_sets"),
    # a rigid ring's modal keys: no run reads them
    ("slewing-thermal", "top.n_modes=30", 'top.kind = "modal"'),
    ("slewing-undulation", "bottom.E_Pa=100e9", 'bottom.kind = "modal"'),
    # the preset's top structure is chosen per equilibrium (auto): its modal keys are auto's
    ("slewing-undulation", "top.n_modes=30", 'set top.kind = "modal" to choose it'),
    ("wind-speeds", "bodies.n_modes=10", 'bodies.rings or bodies.cages = "modal"'),
    ("wind-speeds-adams", "contact.damping_ratio=0.3", "adams preset"),
])
def test_an_override_the_study_does_not_read_is_refused_naming_the_key_that_does(name, override, replacement):
    key = override.partition("=")[0]
    with pytest.raises(CaseError, match=rf"^--set {re.escape(key)}: not used by the .* study; .*{re.escape(replacement)}"):
        resolve_case(name, False, [override])


@pytest.mark.parametrize("name, overrides", [
    ("slewing-undulation", ["top.kind=modal", "top.n_modes=30"]),  # the modal keys once the user picks modal
    ("slewing-thermal", ["top.kind=modal", "top.n_modes=30"]),
    ("wind-speeds", ["bodies.rings=modal", "bodies.n_modes=10"]),
    ("wind-rigid-flexible", ["bodies.n_modes=10"]),  # it runs modal bodies
    ("slewing-rotation", ["analysis.timestep_s=1e-6"]),  # honoured (next tests)
])
def test_keys_a_run_reads_are_accepted(name, overrides):
    case = resolve_case(name, False, overrides)
    for item in overrides:
        key, _, value = item.partition("=")
        table, field = key.split(".")
        got = getattr(getattr(case, table), field)
        assert str(got) == value or got == float(value), item


@pytest.mark.parametrize("argv", [
    ["slewing-undulation", "--set", "undulation.scale=2", "--set", "top.n_modes=30"],
    ["slewing-undulation", "--set", "top.E_Pa=20e9"],
    ["slewing-rotation", "--set", "analysis.travel_steps=36"],  # a dynamic run makes no travel
    ["slewing-undulation", "--set", "study.spacer_run_s=0", "--set", "analysis.timestep_s=1e-6"],  # no dynamic run
    ["wind-static", "--set", "analysis.speed_rpm=20"],  # quasi-static: no speed
    ["wind-rigid-flexible", "--set", "bodies.rings=modal"],  # it runs both
])
def test_the_command_line_refuses_it_in_one_line_before_any_work(argv, tmp_path, capsys):
    out = tmp_path / "never"
    assert main(["run", *argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flexbearing: error: --set ") and err.count("\n") == 1, err
    assert not out.exists()


def test_a_case_file_that_changes_a_key_its_study_does_not_read_is_refused(tmp_path):
    base = PRESETS["slewing-undulation"]
    path = tmp_path / "u.toml"
    path.write_text(dumps_case(base.with_(undulation={"scale": 2.0})), encoding="utf-8")
    with pytest.raises(CaseError, match=r"u\.toml: undulation\.scale: not used by the undulation study.*"
                                        r"study\.undulation_scales"):
        resolve_case(str(path))
    path.write_text(dumps_case(base.with_(study={"undulation_scales": (2.0,)})), encoding="utf-8")
    assert resolve_case(str(path)).study.undulation_scales == (2.0,)  # the key that does the job


def test_every_named_case_and_its_quick_variant_read_back_from_their_case_toml(tmp_path):
    # what a run saves as case.toml must run again unchanged (no false refusals)
    from cases.run import _FAMILIES

    for name, case in PRESETS.items():
        q = _FAMILIES[type(case)][0].quick(case)
        for c in (case, q):
            path = tmp_path / f"{c.name}.toml"
            path.write_text(dumps_case(c), encoding="utf-8")
            assert resolve_case(str(path)) == c


@pytest.mark.parametrize("analysis, runs", [({}, "equilibria"), ({"travel_steps": 72}, "travels"),
                                             ({"type": "dynamic_explicit"}, "dynamic")])
def test_a_quick_single_case_keeps_its_kind_of_run_and_reads_back(analysis, runs, tmp_path):
    # before: --quick set travel_steps = 36 and duration_s = 0.4 on every single case, so a quick
    # equilibrium became a travel, and its saved case.toml carried a dynamic-only key
    from cases.slewing.case import SlewingCase

    case = SlewingCase(name="one").with_(analysis=analysis)
    q = slewing_quick(case)
    assert slewing_studies.runs_of(q) == slewing_studies.runs_of(case) == (runs,)
    path = tmp_path / "one.toml"
    path.write_text(dumps_case(q), encoding="utf-8")
    assert resolve_case(str(path)) == q


def _all_keys(cls, prefix=""):
    """Dotted keys of every field and table of the case class ``cls``."""
    out = set()
    for f in dataclasses.fields(cls):
        key = f"{prefix}{f.name}"
        out.add(key)
        hint = typing.get_type_hints(cls)[f.name]
        if dataclasses.is_dataclass(hint):
            out |= _all_keys(hint, key + ".")
    return out


def test_every_declared_key_exists_in_the_case_tables():
    # a renamed field would leave a declaration that matches nothing
    from cases.described import studies as described_studies
    from cases.described.case import DescribedCase
    from cases.slewing.case import SlewingCase
    from cases.wind import studies as wind_studies

    for cls, studies in ((SlewingCase, slewing_studies), (WindCase, wind_studies), (DescribedCase, described_studies)):
        keys = _all_keys(cls)
        for kind, entry in studies.STUDIES.items():
            assert set(entry.unused) <= keys, kind
            assert {f"study.{n}" for n in entry.sweeps} <= keys, kind
        for run_keys, _ in getattr(studies, "RUN_KEYS", {}).values():
            assert set(run_keys) <= keys


# -- a dynamic run's time step is honoured -----------------------------------------------------------
def test_the_time_step_of_a_dynamic_run_is_the_one_asked_for(tmp_path):
    # before: analysis.timestep_s was recorded in case.toml and the automatic step (1.56e-6 s) ran
    out = tmp_path / "r"
    argv = ["run", "slewing-rotation", "--quick", "--set", "analysis.duration_s=0.01",
            "--set", "analysis.timestep_s=1e-6", "--out", str(out)]
    assert main(argv) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["timestep_s"] == 1e-6  # the requested value, exactly
    assert s["steps"] == 10000  # 0.01 s / 1e-6 s
    # the run is still right: every ball carries the analytic thrust load (Harris & Kotzalas §7.2)
    assert s["mean_ball_load_N"] == pytest.approx(s["analytic_ball_load_N"], rel=5e-3)


def test_a_time_step_above_the_stability_limit_is_refused_naming_the_key(tmp_path, capsys):
    out = tmp_path / "r"
    argv = ["run", "slewing-rotation", "--quick", "--set", "analysis.duration_s=0.1",
            "--set", "analysis.timestep_s=5e-5", "--out", str(out)]
    assert main(argv) == 2
    err = capsys.readouterr().err.split("\r")[-1]  # after the progress bar's last refresh
    assert err.startswith("flexbearing: error: analysis.timestep_s = 5e-05 s: time step 5e-05 s exceeds the explicit "
                          "stability limit"), err
    assert not out.exists()


# -- the README's commands -----------------------------------------------------------------------------
def _readme_runs():
    for readme in (REPO / "README.md", REPO / "cases/slewing/README.md", REPO / "cases/wind/README.md"):
        for line in readme.read_text(encoding="utf-8").splitlines():
            command = line.split("#")[0].strip()
            if "flexbearing run " in command:
                yield readme.relative_to(REPO).as_posix(), command[command.index("flexbearing run "):]


@pytest.mark.parametrize("readme, command", list(_readme_runs()))
def test_the_readme_commands_pass_validation(readme, command, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    args = build_parser().parse_args(shlex.split(command)[1:])
    if args.list or args.case is None:
        return
    if args.case.endswith(".toml"):  # "write one from any case.toml"
        Path(args.case).write_text(dumps_case(PRESETS["slewing-static"]), encoding="utf-8")
    for item in args.set:  # a load file the command names
        key, _, value = item.partition("=")
        if key.endswith("_path"):
            Path(value).write_text("", encoding="utf-8")
    resolve_case(args.case, args.quick, args.set)


# -- a copied case.toml does not replace the original's results -------------------------------------
def _fake_study(case, out, progress=None):
    out.summary["value"] = 1.0


def test_a_copied_case_toml_does_not_replace_the_original_results(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(slewing_studies, "run_study", _fake_study)  # the run itself is not the point
    assert main(["run", "slewing-static", "--quick"]) == 0
    original = tmp_path / "results" / "slewing-static-quick"
    stamp = (original / "summary.json").read_text()
    shutil.copy(original / "case.toml", tmp_path / "my.toml")
    capsys.readouterr()
    for case_file in ("my.toml", str(original / "case.toml")):
        assert main(["run", case_file]) == 2
        err = capsys.readouterr().err
        assert err.startswith("flexbearing: error: ") and err.count("\n") == 1 and "--out" in err, err
        assert (original / "summary.json").read_text() == stamp  # untouched
    assert main(["run", "my.toml", "--out", "results/mine"]) == 0  # named with --out: fine
    assert main(["run", "my.toml", "--out", "results/mine"]) == 0  # and again into the same folder
    # the same source again replaces its own results, as before
    assert main(["run", "slewing-static", "--quick"]) == 0
    assert json.loads((original / "summary.json").read_text())["value"] == 1.0


def test_a_results_folder_written_before_sources_were_recorded(tmp_path, monkeypatch):
    # its marker names the case only: the named case of that name may replace it, a case file not
    from cases.outdir import MARKER
    from cases.run import default_out_dir

    monkeypatch.chdir(tmp_path)
    old = tmp_path / "results" / "slewing-static-quick"
    old.mkdir(parents=True)
    (old / MARKER).write_text('{"format": "flexbearing-results/1", "name": "slewing-static-quick"}\n')
    case = resolve_case("slewing-static", True)
    assert default_out_dir(case, "slewing-static") == Path("results/slewing-static-quick")
    with pytest.raises(CaseError, match="--out"):
        default_out_dir(case, str(tmp_path / "my.toml"))


def test_a_set_override_is_named_in_the_case_description():
    """A quick case changed by --set says so: its description (written to case.toml and
    summary.json) names the override, not only the quick variant's own changes."""
    from cases.run import resolve_case

    case = resolve_case("wind-rigid-flexible", True, ["bodies.ring_element_size_m=0.2"])
    assert case.bodies.ring_element_size_m == 0.2
    assert case.description.startswith("quick variant of wind-rigid-flexible")
    assert case.description.endswith("changed by --set bodies.ring_element_size_m=0.2")
