"""Every key a wind main-bearing study discards is declared in its registry entry (and so refused).

The method of tests/test_study_keys_used.py: the study runs with its computing leaves replaced by
recorders (the dynamic run, the quasi-static load distribution, the load spectrum files), each
key of the study's quick case is perturbed in turn, and a key that changes no recorded input must
be covered by :func:`cases.wind.studies.case_unused_keys`.
"""

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

import cases.wind.dynamic as wind_dynamic
import cases.wind.studies as W
from cases.results import RunOutput
from mbd_core.multibody import warmup
from cases.overrides import _covering
from cases.wind.presets import PRESETS, quick
from tests.test_study_keys_used import _Out, _blank_figure, discarded_keys

ROWS = ("radial", "front thrust", "rear thrust")


def _bodies(b):
    """What a scene takes of ``bodies``: the keys of modal parts only."""
    keep = {"rings": b.rings, "cages": b.cages}
    if b.rings == "modal":
        keep.update(ring=(b.ring_element_size_m, b.bolts, b.n_theta, b.n_across))
    if b.cages == "modal":
        keep.update(cage=b.cage_element_size_m)
    if b.any_modal:
        keep.update(modes=(b.n_modes, b.modal_damping_ratio))
    return tuple(sorted(keep.items()))


def _contact(c):
    d = dataclasses.asdict(c)
    if c.preset == "adams":
        d.pop("damping_ratio")
    return tuple(sorted(d.items()))


def _install_recorders(monkeypatch, log: list) -> None:
    def run(c, progress=None):
        log.append(("dynamic", c.rollers, _bodies(c.bodies), _contact(c.contact), c.loads, c.analysis))
        return SimpleNamespace(model=None, modal=None), {"timestep_s": 1e-5}

    def roller_speeds(case, sc, rec):
        one = dict(loaded_mean_rpm=1.0, kinematic_rpm=1.0, loaded_error=0.01, one_roller=0, one_roller_mean_rpm=1.0,
                   one_roller_fluctuation_rpm=0.0, one_roller_error=0.01)
        return {n: one for n in ROWS}

    def solve(bearing, load):
        log.append(("load distribution", bearing, load))
        return SimpleNamespace(equilibrium_error=0.0, warnings=[],
                               rows=[SimpleNamespace(name=r.name, load_N=np.ones(3), azimuth_rad=np.zeros(3))
                                     for r in bearing.rows])

    monkeypatch.setattr(wind_dynamic, "run", run)
    monkeypatch.setattr(wind_dynamic, "roller_speeds", roller_speeds)
    monkeypatch.setattr(wind_dynamic, "cage_speeds", lambda *a: {n: {"error": 0.0} for n in ROWS})
    monkeypatch.setattr(wind_dynamic, "equilibrium_error", lambda *a: {"force_error": 0.0, "moment_error": 0.0})
    monkeypatch.setattr(wind_dynamic, "cage_forces", lambda *a: {n: {"mean_N": 1.0, "peak_N": 1.0} for n in ROWS})
    # the run's own error estimates read what the dynamic run records (its scene; rollers, contact, loads)
    monkeypatch.setattr(wind_dynamic, "step_error", lambda *a: {"max_load": 0.0, "window_s": 1e-3})
    monkeypatch.setattr(wind_dynamic, "slice_error", lambda *a: {"max_load": 0.0})
    monkeypatch.setattr(W, "solve_load_distribution", solve)
    monkeypatch.setattr(W, "_spectrum_files", lambda case, out: log.append(("spectrum", case.loads)))
    monkeypatch.setattr(W, "_stress", lambda *a: None)
    # the ring torque reads the record and the keys the dynamic run is recorded with (analysis, contact)
    monkeypatch.setattr(W, "_ring_torque", lambda case, out, *a, **k: out.summary.setdefault("ring_torque", {}).update(
        inner_ring_Nm=0.0, inner_ring_ripple_Nm=0.0, outer_ring_Nm=0.0, outer_ring_ripple_Nm=0.0))
    # the modal bodies built ahead of the rigid-flexible runs: recorded, not meshed and reduced
    monkeypatch.setattr(W, "modal_bodies", lambda c: log.append(("modal bodies", c.bodies)))
    monkeypatch.setattr(W, "plot_element_loads", lambda *a, **k: None)
    for name in ("roller_speed_figure", "sweep_figure", "max_loads_figure", "load_cases_figure", "spectrum_figure"):
        monkeypatch.setattr(W.plots, name, lambda *a, **k: _blank_figure())
    # the variants of the driving-speed and friction studies are ordinary runs (cases.sweep.variants)
    # into real results folders: their record is the recorders' stand-in, and no kernels compile
    monkeypatch.setattr(RunOutput, "write_timeseries", lambda self, *a, **k: None)
    monkeypatch.setattr(warmup, "start", lambda: False)
    monkeypatch.setattr(RunOutput, "save_figure", lambda self, fig, name: None)  # (figures are not inputs)


def _records(case, monkeypatch, tmp_path):
    log = []
    with monkeypatch.context() as m:
        _install_recorders(m, log)
        W.run_study(case, _Out(tmp_path))
    return log


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_the_keys_a_wind_study_discards_are_declared(name, monkeypatch, tmp_path):
    case = quick(PRESETS[name])
    base = _records(case, monkeypatch, tmp_path)
    assert base, name
    declared = W.case_unused_keys(case)
    discarded = discarded_keys(case, base, W.case_unused_keys, lambda c: _records(c, monkeypatch, tmp_path))
    undeclared = [k for k in discarded if _covering(k, declared) is None]
    assert not undeclared, f"{name}: discarded but not declared: {undeclared}"
    replaced = [k for k in W.STUDIES[case.study.kind].unused if k.split(".")[0] in ("analysis", "contact") and "." in k]
    assert set(replaced) <= set(discarded), f"{name}: declared but read: {set(replaced) - set(discarded)}"
