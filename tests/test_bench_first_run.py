"""The phase clock of benchmarks/bench_first_run.py: exclusive CPU time per phase.

Reference: the accounting is a telescoping sum of process-time increments, so the phases' times
add up to the process time elapsed between the clock's creation and its last switch, whatever
the nesting; a phase entered inside another takes its time from the outer one.
"""

import importlib.util
from pathlib import Path

import pytest

_SPEC = importlib.util.spec_from_file_location(
    "bench_first_run", Path(__file__).resolve().parents[1] / "benchmarks" / "bench_first_run.py")
bench = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(bench)


def _spin(n: int = 200_000) -> float:
    return sum(i * 0.5 for i in range(n))


def test_phase_times_add_up_to_the_process_time():
    clock = bench._Clock()
    t0 = clock.last
    clock.enter("outer")
    _spin()
    clock.enter(bench.COMPILE)
    _spin()
    clock.leave()
    _spin()
    clock.leave()
    _spin()
    clock._switch()
    assert sum(clock.cpu_s.values()) == pytest.approx(clock.last - t0, rel=1e-12, abs=1e-12)
    assert set(clock.cpu_s) == {bench.OTHER, "outer", bench.COMPILE}
    assert clock.stack == [bench.OTHER]


def test_wrapped_function_counts_in_its_phase_and_returns_its_value():
    clock = bench._Clock()
    timed = bench._wrap(clock, "factorisation", lambda x: (_spin(), x * 2)[1])
    assert timed(21) == 42
    assert clock.cpu_s["factorisation"] > 0.0
    assert clock.stack == [bench.OTHER]
    with pytest.raises(ZeroDivisionError):
        bench._wrap(clock, "eigen solve", lambda: 1 / 0)()
    assert clock.stack == [bench.OTHER]   # a failing phase is left too
