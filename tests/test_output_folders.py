"""Results folders: only the project's own folders are replaced, the swap keeps the old or the new
result whole, leftovers of killed runs are restored or removed, folders get the usual permissions."""

import json
import os
import signal
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from cases import cli, outdir
from cases.outdir import MARKER, OutputTargetError, atomic_folder, check_output_target, recover


def _write(out, text="new", name="demo"):
    with atomic_folder(out, name) as tmp:
        (tmp / "summary.json").write_text(json.dumps({"value": text}))
    return out


def _value(out):
    return json.loads((out / "summary.json").read_text())["value"]


def _run_code(code: str, out: Path) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh interpreter with the project importable and ``out`` as its argument."""
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]))
    return subprocess.run([sys.executable, "-c", code, str(out)], env=env, capture_output=True, text=True, timeout=60)


def _dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_a_folder_the_project_did_not_write_is_refused_and_kept(tmp_path):
    out = tmp_path / "results"
    out.mkdir()
    (out / "thesis.tex").write_text("years of work")
    (out / "data").mkdir()
    with pytest.raises(OutputTargetError, match=r"results.*did not write"):
        _write(out)
    assert (out / "thesis.tex").read_text() == "years of work" and (out / "data").is_dir()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]  # no temporary folder left


def test_own_and_empty_folders_are_replaced_and_marked(tmp_path):
    out = _write(tmp_path / "results", "first")
    marker = json.loads((out / MARKER).read_text())
    assert marker == {"format": outdir.MARKER_FORMAT, "name": "demo"}
    _write(out, "second")
    assert _value(out) == "second"
    empty = tmp_path / "empty"
    empty.mkdir()
    assert _value(_write(empty, "third")) == "third"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["empty", "results"]


@pytest.mark.parametrize("target", [".", "..", "home", "cwd-parent", "file", "link"])
def test_dangerous_targets_are_refused_by_the_command_line_in_one_line(tmp_path, monkeypatch, capsys, target):
    work = tmp_path / "work"
    work.mkdir()
    (work / "keep.txt").write_text("mine")
    (work / "afile").write_text("a file")
    (work / "link").symlink_to(work)
    monkeypatch.chdir(work)
    monkeypatch.setenv("HOME", str(work))
    arg = {"home": str(work), "cwd-parent": str(tmp_path), "file": "afile"}.get(target, target)
    assert cli.main(["loaddist", "slewing-ring", "--out", arg]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("flexbearing: error: output folder")
    assert (work / "keep.txt").read_text() == "mine" and (work / "afile").read_text() == "a file"
    assert sorted(p.name for p in work.iterdir()) == ["afile", "keep.txt", "link"]


def test_refusal_comes_before_any_work(tmp_path, monkeypatch):
    """run_case checks the target before the study starts (the study here would fail loudly)."""
    from cases import run as run_mod

    out = tmp_path / "results"
    out.mkdir()
    (out / "x.txt").write_text("x")
    case = run_mod.resolve_case("slewing-static", quick_run=True)
    monkeypatch.setattr(run_mod, "_FAMILIES", {})  # any study lookup would raise KeyError
    with pytest.raises(OutputTargetError, match="did not write"):
        run_mod.run_case(case, out)
    with pytest.raises(OutputTargetError, match="is a file"):
        check_output_target(out / "x.txt")


@pytest.mark.parametrize("command", [["loaddist", "slewing-ring"], ["modes", "slewing-bottom-race-1m"],
                                     ["run", "slewing-static", "--quick"]])
def test_every_command_refuses_a_foreign_or_empty_out_before_its_work(tmp_path, monkeypatch, capsys, command):
    """The solve, the modal analysis and the case resolution are never reached (they would raise)."""
    from cases import fem_report
    from cases import run as run_mod

    def no_work(*args, **kwargs):
        raise AssertionError("work started before --out was checked")

    monkeypatch.setattr(cli, "bearing_solver", no_work)
    monkeypatch.setattr(fem_report, "part_modes", no_work)
    monkeypatch.setattr(run_mod, "resolve_case", no_work)
    out = tmp_path / "results"
    out.mkdir()
    (out / "x.txt").write_text("x")
    for target, why in ((str(out), "output folder"), ("", "--out must name a folder")):
        assert cli.main([*command, "--out", target]) == 2
        err = capsys.readouterr().err.strip()
        assert err.count("\n") == 0 and why in err
    assert (out / "x.txt").read_text() == "x"


def test_folders_are_created_with_the_umask(tmp_path):
    old = os.umask(0o027)
    try:
        out = _write(tmp_path / "results")
    finally:
        os.umask(old)
    assert stat.S_IMODE(out.stat().st_mode) == 0o750  # 0777 less the umask, as mkdir(1) gives


def test_a_failing_run_keeps_the_old_result_and_leaves_nothing(tmp_path):
    out = _write(tmp_path / "results", "old")
    for exc in (RuntimeError("study failed"), KeyboardInterrupt()):
        with pytest.raises(type(exc)):
            with atomic_folder(out) as tmp:
                (tmp / "summary.json").write_text("{")
                raise exc
        assert _value(out) == "old"
        assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]


def test_a_failed_rename_in_puts_the_old_result_back(tmp_path, monkeypatch):
    out = _write(tmp_path / "results", "old")
    real = os.rename
    calls = []

    def rename(src, dst):
        calls.append((src, dst))
        if len(calls) == 2:  # old → aside done, new → target fails
            raise OSError(28, "No space left on device")
        return real(src, dst)

    monkeypatch.setattr(outdir, "_exchange", lambda a, b: False)  # the two-rename path, where no exchange exists
    monkeypatch.setattr(outdir.os, "rename", rename)
    with pytest.raises(OSError, match="No space"):
        _write(out, "new")
    monkeypatch.setattr(outdir.os, "rename", real)
    assert _value(out) == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]


def _leftover(parent, name, kind, pid, value=None):
    p = parent / f".{name}.{kind}-{pid}-0123abcd"
    p.mkdir()
    if value is not None:
        (p / "summary.json").write_text(json.dumps({"value": value}))
        (p / MARKER).write_text(json.dumps({"format": outdir.MARKER_FORMAT, "name": name}))
    return p


def test_recovery_after_a_kill_between_the_renames_restores_the_old_result(tmp_path):
    """SIGKILL after "target → aside" and before "new → target": the old result is back."""
    dead = _dead_pid()
    _leftover(tmp_path, "results", "fb-old", dead, "old")
    _leftover(tmp_path, "results", "fb-tmp", dead, "new, complete but not swapped in")
    recover(tmp_path)
    assert _value(tmp_path / "results") == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]


def test_recovery_after_a_kill_after_the_swap_drops_the_aside_copy(tmp_path):
    dead = _dead_pid()
    _write(tmp_path / "results", "new")
    _leftover(tmp_path, "results", "fb-old", dead, "old")
    _leftover(tmp_path, "other", "fb-tmp", dead)  # another target's half-written folder
    _write(tmp_path / "results", "newer")  # the next run recovers first
    assert _value(tmp_path / "results") == "newer"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]


def test_recovery_leaves_running_runs_and_foreign_names_alone(tmp_path):
    live = os.getppid()  # a process that is running
    running = [_leftover(tmp_path, "results", "fb-tmp", live), _leftover(tmp_path, "results", "fb-old", live, "old")]
    foreign = [tmp_path / ".results.fb-tmp-notapid", tmp_path / ".git"]
    for p in foreign:
        p.mkdir()
    recover(tmp_path)
    assert all(p.is_dir() for p in running + foreign)
    assert not (tmp_path / "results").exists()


def test_a_stop_signal_inside_a_finaliser_still_stops_the_run(tmp_path):
    """SIGTERM handled while Python runs a finaliser (here a __del__; in a run, an import's module-lock
    clean-up) cannot propagate from there: Python would print "Exception ignored … Traceback" and go
    on. The run must still be stopped, with its one line, the temporary folder removed and the old
    result kept."""
    _write(tmp_path / "results", "old")
    code = (
        "import gc, os, signal, sys, time\n"
        "from cases import signals\n"
        "from cases.outdir import atomic_folder\n"
        "signals.install()\n"
        "class Dying:\n"
        "    def __del__(self):\n"
        "        os.kill(os.getpid(), signal.SIGTERM)\n"
        "        sum(range(1000))\n"  # bytecodes: the handler runs here, inside the finaliser
        "with atomic_folder(sys.argv[1]) as tmp:\n"
        "    (tmp / 'summary.json').write_text('{}')\n"
        "    Dying()\n"
        "    time.sleep(30)\n"
        "    print('not stopped')\n"
    )
    proc = _run_code(code, tmp_path / "results")
    assert proc.returncode == -signal.SIGTERM, proc.stderr
    assert "Traceback" not in proc.stderr and "stopped by SIGTERM" in proc.stderr
    assert "not stopped" not in proc.stdout
    assert _value(tmp_path / "results") == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]


def test_a_stop_before_the_with_block_starts_still_removes_the_temporary_folder(tmp_path):
    """The folder is made when the block is entered; a stop handled right after (in the context
    manager's own code, before the ``with`` block that removes it on errors is set up) never reaches
    that cleanup. Here the context manager is entered by hand and the block never set up: the folder
    must still go, the old result stay, and the process end by the signal."""
    _write(tmp_path / "results", "old")
    code = (
        "import os, signal, sys, time\n"
        "from cases import signals\n"
        "from cases.outdir import atomic_folder\n"
        "signals.install()\n"
        "cm = atomic_folder(sys.argv[1])\n"
        "tmp = cm.__enter__()\n"
        "assert tmp.is_dir()\n"
        "os.kill(os.getpid(), signal.SIGTERM)\n"
        "time.sleep(30)\n"
    )
    proc = _run_code(code, tmp_path / "results")
    assert proc.returncode == -signal.SIGTERM and "stopped by SIGTERM" in proc.stderr, proc.stderr
    assert _value(tmp_path / "results") == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]


@pytest.mark.parametrize("name", ["SIGTERM", "SIGHUP", "SIGINT"])
def test_stop_signals_unwind_like_ctrl_c(tmp_path, name):
    """A stop signal in the middle of writing: the temporary folder is removed, the old result
    stays, and the process still ends by that signal (SIGTERM/SIGHUP: stderr says so)."""
    _write(tmp_path / "results", "old")
    code = (
        "import os, signal, sys, time\n"
        "from cases import signals\n"
        "from cases.outdir import atomic_folder\n"
        # an interactive shell's Ctrl-C: a job started in the background of a non-interactive
        # shell inherits SIGINT ignored, and Python then keeps it ignored
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "signals.install()\n"
        "with atomic_folder(sys.argv[1]) as tmp:\n"
        "    (tmp / 'summary.json').write_text('{}')\n"
        f"    os.kill(os.getpid(), signal.{name})\n"
        "    time.sleep(30)\n"
    )
    proc = _run_code(code, tmp_path / "results")
    signum = getattr(signal, name)
    if name == "SIGINT":
        assert proc.returncode in (-signum, 128 + signum, 1) and "KeyboardInterrupt" in proc.stderr
    else:
        assert proc.returncode == -signum and f"stopped by {name}" in proc.stderr
    assert _value(tmp_path / "results") == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]
