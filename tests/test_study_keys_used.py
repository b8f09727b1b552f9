"""Every key a slewing-ring study discards is declared in its registry entry (and so refused).

Method (an independent measurement of what a study reads): the study runs with its computing
leaves replaced by recorders — the scenes (``scene.top_body``, ``bottom_body``, ``with_modulus``),
the quasi-static ``equilibrium`` and ``travel``, the dynamic run and the life calculation — which
return small stand-in results and record the arguments each call receives, of the case the tables
that leaf reads (a rigid ring: its kind only). Each key of
the study's quick case is then perturbed in turn; a key whose perturbation leaves every recorded
input unchanged is one the study discards (it sets or sweeps that value itself), and it must be
covered by the keys :func:`cases.slewing.studies.case_unused_keys` declares. The converse is
checked for the keys a study replaces (``top.E_Pa`` → ``study.top_E_Pa`` …): each really is
discarded. (A leaf that receives a key and does not read it, e.g. a quasi-static equilibrium and
the friction coefficients, is beyond this measurement; those keys are declared by kind of run.)
"""

import dataclasses
import functools
import typing
from types import SimpleNamespace

import numpy as np
import pytest

import cases.slewing.dynamic as slewing_dynamic
from mbd_core.multibody import warmup
import cases.slewing.scene as slewing_scene
import cases.slewing.studies as S
from cases.config import CaseError
from cases.overrides import _covering
from cases.results import RunOutput
from cases.slewing import PRESETS, quick
from cases.slewing.case import SlewingCase


class _Out:
    """Stand-in for :class:`cases.results.RunOutput` that keeps what the study writes."""

    def __init__(self, folder):
        self.folder, self.summary = folder, {}

    def note(self, *a): pass

    def warn(self, *a): pass

    def save_figure(self, *a): pass

    def write_csv(self, name, header, rows):
        list(rows)

    def write_timeseries(self, *a, **k): pass

    def path(self, name):
        p = self.folder / name
        p.parent.mkdir(parents=True, exist_ok=True)
        return p


def _fidelity(body):
    """What a scene takes of a ring's fidelity table: a rigid ring is its kind only."""
    return body if body.kind == "modal" else "rigid"


#: the tables each leaf reads (the quasi-static solver: geometry, load, races' shapes, the contact
#: preset, the rings' fidelity; a scene body: its own table and the geometry and load)
_QUASI_STATIC = ("geometry", "load", "undulation", "thermal", "contact.preset", "top", "bottom")


def _project(c, keys):
    out = []
    for key in keys:
        node = c
        for part in key.split("."):
            node = getattr(node, part)
        out.append((key, _fidelity(node) if key in ("top", "bottom") else node))
    return tuple(out)



@functools.lru_cache(maxsize=None)
def _blank_figure():
    """A figure with three empty axes in place of a plot (studies may align the axes of theirs);
    one for every plot (figures are not inputs of the work recorded)."""
    from matplotlib.figure import Figure

    fig = Figure()
    fig.subplots(3, 1)
    return fig

def _install_recorders(monkeypatch, log: list) -> None:
    def equilibrium(c, bodies, *a, **k):
        log.append(("equilibrium", _project(c, _QUASI_STATIC), a, tuple(sorted(k.items()))))
        n = c.geometry.n_balls
        row = SimpleNamespace(load_N=np.linspace(1.0, 2.0, n), azimuth_rad=np.linspace(0.0, 6.0, n),
                              contact_angle_rad=np.full(n, 1.0))
        return SimpleNamespace(rows=[row], warnings=[], equilibrium_error=0.0, displacement=np.zeros(5),
                               reaction=np.array([0.0, 0.0, c.dead_load_N]), modal=lambda name: np.zeros(0))

    def travel(c, bodies, steps, revolutions, progress=None):
        log.append(("travel", _project(c, _QUASI_STATIC), steps, revolutions))
        n = c.geometry.n_balls
        return SimpleNamespace(load_N=np.ones((2, n)), ball_azimuth_rad=np.zeros((2, n)),
                               top_rotation_rad=np.zeros(2), worst=(0, 0), warnings=[])

    def top_body(c):
        log.append(("top_body", _project(c, ("geometry", "load", "top"))))
        return SimpleNamespace(frequencies_Hz=np.array([1.0]), nodes_m=np.zeros((1, 3)))

    def bottom_body(c):
        log.append(("bottom_body", _project(c, ("geometry", "bottom"))))

    def with_modulus(body, E):
        log.append(("with_modulus", E))
        return body

    def worst_ball_life(Q, **kw):
        log.append(("life", Q, tuple(sorted(kw.items()))))
        fields = ("p0_inner_Pa", "tau_max_inner_Pa", "depth_tau_max_inner_m", "required_case_depth_m", "A_cd",
                  "C_a_N", "L10_nominal_Mrev", "L10_worst_Mrev", "L_cd_Mrev")
        return SimpleNamespace(**dict.fromkeys(fields, 1.0), to_dict=dict)

    def run_dynamic(c, out, progress=None):
        log.append(("dynamic", _project(c, _QUASI_STATIC[:3] + ("thermal", "contact", "top", "bottom", "analysis"))))
        out.summary.update(max_spacer_force_N=1.0, mean_spacer_force_N=1.0, p99_spacer_force_N=1.0)

    def error_estimates(c, bodies, res):  # reads the geometry, the body and the result the equilibrium recorded
        return {}

    def resolve_auto(c):  # the cheap pass of kind = "auto" reads the scene; it decides modal here
        log.append(("auto", _project(c, _QUASI_STATIC)))
        return c.with_(**{r: {"kind": "modal"} for r in ("top", "bottom") if getattr(c, r).kind == "auto"}), []

    for name, fake in (("equilibrium", equilibrium), ("travel", travel), ("worst_ball_life", worst_ball_life),
                       ("error_estimates", error_estimates), ("resolve_auto", resolve_auto)):
        monkeypatch.setattr(S, name, fake)
    for name, fake in (("top_body", top_body), ("bottom_body", bottom_body), ("with_modulus", with_modulus)):
        monkeypatch.setattr(slewing_scene, name, fake)
    monkeypatch.setattr(slewing_dynamic, "run_dynamic", run_dynamic)
    # the points of studies (c)–(e) are ordinary runs (cases.sweep.variants) into real results
    # folders; their dynamic run is the recorder above, so no kernels compile
    monkeypatch.setattr(warmup, "start", lambda: False)
    monkeypatch.setattr(RunOutput, "save_figure", lambda self, fig, name: None)  # (figures are not inputs)
    for name in ("plot_static", "plot_ball_loads", "plot_travel", "plot_subsurface_shear", "_write_balls_vtu",
                 "_write_top_vtu"):
        monkeypatch.setattr(S, name, lambda *a, **k: _blank_figure())


def _leaf_fields(cls, prefix=""):
    """(dotted key, table path, field name, type hint) of every leaf field below the top level."""
    hints = typing.get_type_hints(cls)
    for f in dataclasses.fields(cls):
        hint = hints[f.name]
        if dataclasses.is_dataclass(hint):
            yield from _leaf_fields(hint, f"{prefix}{f.name}.")
        elif prefix:
            yield f"{prefix}{f.name}", prefix[:-1], f.name, hint


#: a value for an optional field that is None in the case
_FOR_NONE = {"timestep_s": 1e-6, "element_size_m": 0.15, "spacer_diameter_m": 0.09, "dead_load_t": 100.0}


def _other(value, name, hint):
    """Another valid-looking value of a field (the dataclass checks it)."""
    args = typing.get_args(hint)
    if value is None:
        return _FOR_NONE.get(name)
    if isinstance(value, bool):
        return not value
    if typing.get_origin(hint) is typing.Literal:
        return next(a for a in args if a != value)
    if isinstance(value, int):
        return value + 1
    if isinstance(value, float):
        return value * 1.1 if value else (1e-4 if name.endswith("_m") else 0.5)
    if isinstance(value, tuple) and value and isinstance(value[0], tuple):  # (θ, h) pairs: change h
        return tuple((p[0], p[1] * 1.1 + 0.1) for p in value)
    if isinstance(value, tuple):
        return tuple(v * 1.1 for v in value)
    return None


def _records(case, monkeypatch, tmp_path):
    log = []
    with monkeypatch.context() as m:
        _install_recorders(m, log)
        try:
            S.run_study(case, _Out(tmp_path))
        except (CaseError, ValueError) as exc:  # the study made a case of it that is not valid
            log.append(("refused", str(exc)))
    return log


def _perturbed(case, table, name, hint):
    node = case
    for part in table.split("."):
        node = getattr(node, part)
    value = _other(getattr(node, name), name, hint)
    if value is None:
        return None
    try:
        return case.with_(**{table: {name: value}})
    except (CaseError, ValueError, TypeError):  # not a valid case: nothing to measure
        return None


def _cases():
    out = {kind: quick(next(c for c in PRESETS.values() if c.study.kind == kind))
           for kind in S.STUDIES if kind != "single"}
    base = SlewingCase(name="one")
    out["single equilibrium"] = quick(base)
    out["single travel"] = quick(base.with_(analysis={"travel_steps": 36}))
    out["single dynamic"] = quick(base.with_(analysis={"type": "dynamic_explicit"}))
    return out


def discarded_keys(case, base, unused_of, records) -> list[str]:
    """The leaf keys of ``case`` whose change leaves both the declared unused keys
    (``unused_of(case)``) and the recorded work (``records(case)``, ``base`` for ``case``) alone."""
    declared, out = unused_of(case), []
    for key, table, name, hint in _leaf_fields(type(case)):
        other = _perturbed(case, table, name, hint)
        if other is not None and unused_of(other) == declared and records(other) == base:
            out.append(key)
    return out


@pytest.mark.parametrize("label, case", list(_cases().items()))
def test_the_keys_a_study_discards_are_declared(label, case, monkeypatch, tmp_path):
    base = _records(case, monkeypatch, tmp_path)
    assert base, label  # the recorders saw the study's work
    declared = S.case_unused_keys(case)
    discarded = discarded_keys(case, base, S.case_unused_keys, lambda c: _records(c, monkeypatch, tmp_path))
    undeclared = [k for k in discarded if _covering(k, declared) is None]
    assert not undeclared, f"{label}: discarded but not declared: {undeclared}"
    # the keys a study replaces by its own (swept or fixed) value are really discarded
    replaced = [k for k in S.STUDIES[case.study.kind].unused
                if k.split(".")[0] in ("top", "thermal", "undulation") and "." in k]
    assert set(replaced) <= set(discarded), f"{label}: declared but read: {set(replaced) - set(discarded)}"
