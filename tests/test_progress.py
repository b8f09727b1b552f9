"""Progress of long phases: the time-left estimate, the phases a model build and reduction report,
the command line's lines on stderr, and numba compilation shown only when it compiles."""

import importlib
import io
import json
import logging
import math
import sys

import pytest

from cases.cli import main
from cases.progress_display import TerminalReporter
from cms_reduction.craig_bampton import RHS_BLOCK
from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from fem_rings import MeshSpec, modal_analysis
from fem_rings.model import build_model
from fem_rings.profile import rectangle
from foundation.materials import ElasticMaterial
from foundation.progress import Reporter, phase, remaining_time_s, reporting, track
from mbd_core.kernels.compile_progress import COMPILING_LABEL

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)


class FakeClock:
    """Seconds that move only when the test says so."""

    def __init__(self) -> None:
        self.now_s = 100.0

    def __call__(self) -> float:
        return self.now_s


class Recorder(Reporter):
    """Every start and finish, in order, with the phase's path, total and pieces done."""

    def __init__(self) -> None:
        self.events = []

    def start(self, p):
        self.events.append(("start", tuple(p.path()), p.total, p.done))

    def finish(self, p):
        self.events.append(("finish", tuple(p.path()), p.total, p.done, p.detail))

    def started(self):
        return [e[1] for e in self.events if e[0] == "start"]

    def finished(self):
        return [e for e in self.events if e[0] == "finish"]


# ------------------------------------------------------------------------------ time-left estimate
@pytest.mark.parametrize("n, k, t_s", [(10, 3, 6.0), (7, 1, 0.5), (40, 39, 120.0), (5, 5, 9.0)])
def test_time_left_is_the_average_rate_so_far(n, k, t_s):
    # Reference: k of n equal pieces in t seconds leave (n − k)·t/k at the average rate.
    clock = FakeClock()
    with reporting(Reporter()), phase("pieces", total=n, clock=clock) as p:
        assert p.remaining_s() is None                 # nothing done yet: no estimate
        clock.now_s += t_s
        p.advance(k)
        assert p.remaining_s() == pytest.approx((n - k) * t_s / k, rel=1e-12)
    assert remaining_time_s(3, None, 5.0) is None       # no total, no estimate


def test_one_off_work_is_left_out_of_the_rate():
    # Reference: the first of 10 pieces took 2 s of work plus 30 s of one-off compiling; the nine
    # left will not compile again, so 9 × 2 s = 18 s are left (not 9 × 32 s).
    clock = FakeClock()
    with reporting(Reporter()), phase("time loop", total=10, clock=clock) as loop:
        with phase("compiling", once=True, clock=clock):
            clock.now_s += 30.0
        clock.now_s += 2.0
        loop.advance()
        assert loop.remaining_s() == pytest.approx(18.0, rel=1e-12)
        assert loop.elapsed_s() == pytest.approx(32.0, rel=1e-12)


def test_terminal_bar_shows_the_same_estimate():
    # Reference: 3 of 10 in 6 s → 14 s left; 6 s elapsed.
    clock, out = FakeClock(), io.StringIO()
    rep = TerminalReporter(out, interactive=True)
    try:
        with reporting(rep), phase("constraint modes", total=10, clock=clock) as p:
            clock.now_s += 6.0
            p.advance(3)
            assert "3/10" in out.getvalue()
            assert "6 s, 14 s left" in out.getvalue()
    finally:
        rep.close()
    assert out.getvalue().rstrip().endswith("constraint modes (3/10): 6.0 s")   # the outermost leaves a line


def test_terminal_draws_nested_phases_on_their_own_lines():
    # Reference: tqdm's multi-line layout — a bar at position 1 is drawn one line below (newline,
    # text, cursor up "ESC[A"); only the outermost phase leaves a line when it ends.
    clock, out = FakeClock(), io.StringIO()
    rep = TerminalReporter(out, interactive=True)
    try:
        with reporting(rep), phase("reducing ring", clock=clock):
            with phase("factorising (100 DOF)", clock=clock) as inner:
                clock.now_s += 3.0
                inner.note("")
                drawn = out.getvalue()
                assert "reducing ring" in drawn and "\nfactorising (100 DOF)  3 s\x1b[A" in drawn.replace("\r", "")
    finally:
        rep.close()
    kept = [ln for ln in out.getvalue().replace("\r", "\n").split("\n") if ln.endswith(" s") and ": " in ln]
    assert kept == ["reducing ring: 3.0 s"]


def test_track_counts_one_piece_per_item():
    # Reference: the items themselves — a list of 5 has a total of 5 and ends at 5/5; a generator
    # has no length, so no total, and counts the 3 items it gave.
    rec = Recorder()
    with reporting(rec):
        assert list(track([10, 20, 30, 40, 50], "load cases")) == [10, 20, 30, 40, 50]
        assert sum(track((k for k in range(3)), "positions")) == 3
    assert [e[1:4] for e in rec.finished()] == [(("load cases",), 5, 5), (("positions",), None, 3)]


def test_library_default_is_one_info_line_per_phase(caplog):
    # Reference: the fake clock advanced 2.5 s between start and end.
    clock = FakeClock()
    with caplog.at_level(logging.INFO, logger="foundation.progress"):
        with phase("outer", clock=clock):
            with phase("inner", total=2, clock=clock) as p:
                clock.now_s += 2.5
                p.advance(2)
    assert [r.getMessage() for r in caplog.records] == ["outer > inner (2/2): 2.50 s", "outer: 2.50 s"]


# ------------------------------------------------------------------- phases of build, modes, reduction
N_ITF, N_MAX, DIRECTIONS = 6, 8, ("normal", "axial")


def test_build_modes_and_reduction_report_their_phases_in_order():
    profile = rectangle("ring", 0.95, 1.05, -0.05, 0.05)
    mesh = MeshSpec(0.05, "hex27", n_theta=48)
    spec = ReductionSpec(n_modes=6, interfaces=(InterfaceSpec("bottom", tuple(60.0 * k for k in range(N_ITF)), 0.07,
                                                              grounded=False),),
                         raceways=(RacewaySpec("top", 90, directions=DIRECTIONS, n_max=N_MAX),), stress_modes=True)
    rec = Recorder()
    with reporting(rec):
        model = build_model(profile, mesh, STEEL, use_cache=False)
        modal_analysis(model, 10)
        body = reduced_body(profile, mesh, STEEL, spec, use_cache=False)
    n_dof = model.n_dofs
    # totals computed here: 6 free master DOFs per interface, 2 directions × (cos, sin of n = 1…8 and n = 0)
    # load shapes, RHS_BLOCK right-hand sides per block; one raceway sampled; one stress field per kept mode
    n_constraint_blocks = math.ceil(6 * N_ITF / RHS_BLOCK)
    n_load_blocks = math.ceil(len(DIRECTIONS) * (2 * N_MAX + 1) / RHS_BLOCK)
    assert (n_constraint_blocks, n_load_blocks) == (2, 2)          # several steps each, with RHS_BLOCK = 24
    R = ("reducing ring",)
    expected = [
        (("meshing ring",), None), ((f"assembling K and M ({n_dof} DOF)",), None),
        (("factorising",), None), (("eigen solve: 4 modes",), None),        # 10 modes = 6 rigid + 4 elastic
        (R, None), (R + ("meshing ring",), None), (R + (f"assembling K and M ({n_dof} DOF)",), None),
        (R + ("factorising",), None), (R + ("eigen solve: 6 modes",), None),
        (R + ("constraint modes",), n_constraint_blocks), (R + ("load shapes",), n_load_blocks),
        (R + ("orthonormalising the basis",), None), (R + ("inertia invariants",), None),
        (R + ("sampling raceways",), 1), (R + ("stress modes",), body.n_modes),
    ]
    started = rec.started()
    assert len(started) == len(expected)
    for path, (want, _total) in zip(started, expected):
        assert len(path) == len(want) and all(a.startswith(b) for a, b in zip(path, want)), (path, want)
    totals = {e[1][-1].split(" (")[0]: (e[2], e[3]) for e in rec.finished() if e[2] is not None}
    assert totals == {"constraint modes": (n_constraint_blocks,) * 2, "load shapes": (n_load_blocks,) * 2,
                      "sampling raceways": (1, 1), "stress modes": (body.n_modes,) * 2}
    # every factorisation names the order of the matrix it factorises: all DOFs free–free, the interior
    # (all minus the 6 interface patches' slave nodes) in the reduction
    fact = [p[-1] for p in started if p[-1].startswith("factorising")]
    assert fact[0].startswith(f"factorising ({n_dof} DOF")


# ------------------------------------------------------------------------------------ command line
def test_cli_phases_go_to_stderr_and_json_stays_clean(capsys):
    assert main(["modes", "slewing-bottom-race-1m", "--size-mm", "80", "--modes", "8", "--no-cache", "--json"]) == 0
    out, err = capsys.readouterr()
    summary = json.loads(out)                                   # stdout is the JSON document alone
    lines = err.strip().splitlines()
    # stderr is not a terminal here: one line per finished phase, in order, each with its time
    assert [ln.split(" (")[0].split(":")[0] for ln in lines] == ["meshing bottom race", "assembling K and M",
                                                                 "factorising", "eigen solve"]
    assert all(ln.endswith(" s") for ln in lines)
    # the DOF counts on the phase lines are the model's (summary "dofs"; free–free: all factorised)
    assert f"({summary['dofs']} DOF)" in lines[1]
    assert lines[2].startswith(f"factorising ({summary['dofs']} DOF")
    assert lines[3].startswith(f"eigen solve: {8 - 6} modes")


# ---------------------------------------------------------------------------------- numba compiling
KERNEL_SOURCE = '''
from numba import njit


@njit(cache=True)
def progress_probe_kernel(x):
    return 2.0 * x + 1.0
'''


def test_compiling_is_shown_once_and_a_cache_load_not(tmp_path, monkeypatch):
    # Reference: numba compiles a new cache=True kernel on its first call and saves it; a fresh
    # dispatcher of the unchanged source (a new import) loads it from the cache without compiling.
    (tmp_path / "progress_probe.py").write_text(KERNEL_SOURCE)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    rec = Recorder()
    with reporting(rec):
        mod = importlib.import_module("progress_probe")
        assert mod.progress_probe_kernel(3.0) == 7.0
        first = [e for e in rec.finished() if e[1][-1] == COMPILING_LABEL]
        assert mod.progress_probe_kernel(4.0) == 9.0         # in memory now: nothing to show
        sys.modules.pop("progress_probe")
        again = importlib.import_module("progress_probe")
        assert again.progress_probe_kernel is not mod.progress_probe_kernel
        assert again.progress_probe_kernel(5.0) == 11.0
    compiles = [e for e in rec.finished() if e[1][-1] == COMPILING_LABEL]
    assert len(first) == 1 and len(compiles) == 1
    assert first[0][4] == "progress_probe_kernel"            # the phase names the kernel it compiles
    assert again.progress_probe_kernel.stats.cache_hits and not again.progress_probe_kernel.stats.cache_misses
    sys.modules.pop("progress_probe", None)


def test_a_kernel_that_fails_to_compile_raises_as_before_and_leaves_no_line():
    # Reference: numba's own behaviour without the listener — a typing error reaches the caller;
    # the listener must neither swallow it nor break the compilation of a good kernel beside it.
    from numba import njit
    from numba.core.errors import TypingError

    @njit
    def doubled(x):
        return 2 * x

    @njit
    def broken(x):
        return x.no_such_attribute

    out = io.StringIO()
    with reporting(TerminalReporter(out, interactive=False)):
        assert doubled(21) == 42
        with pytest.raises(TypingError):
            broken(1)
    lines = out.getvalue().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"{COMPILING_LABEL}: doubled: ")
