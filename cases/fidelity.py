"""Fidelity ladders: the knobs of a case that trade speed for accuracy, the rungs built from them,
the errors of a rung against the reference, and the choice of the cheapest rung for a tolerance.

A family declares its ladder next to its case schema (e.g. :mod:`cases.slewing.fidelity`): each
:class:`Knob` is a dotted case key with its values ordered from cheap to expensive; ``base`` holds
every knob at the value the sweeps start from; ``reference`` is the most accurate model the machine
affords. The rungs are the base, every single-knob variation of it (a convergence sweep per knob),
the combined rungs a user would pick, and the reference. Every rung is an ordinary case: the
overrides go through :meth:`cases.config.CaseTables.with_`, so a knob that is not a key of the
schema fails when the ladder is built, not later.

Errors are those an engineer reads off a load distribution, all relative to the reference's largest
element load Q_ref,max (:func:`rung_errors`). The choice for a tolerance (:func:`choose_rung`) takes
the rung of least wall time whose error in the family's primary quantity meets it; the reference
is not a choice, since its own error is not measured.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Knob", "fixed_knob", "Ladder", "Rung", "Outcome", "ToleranceError", "ERROR_NAMES", "QUASI_STATIC_ERRORS", "FIGURE_ERRORS",
           "rungs", "rung_errors", "case_tables",
           "choose_rung", "parse_tolerance", "observed_order"]

#: error columns of a rung, with what they are (all relative to the reference's largest load
#: except ``unloaded``, a count difference, and ``contact_angle_deg``, degrees); the last five are
#: those of dynamic scenes, each the largest over the rows (or bodies) of its :attr:`Outcome.figures`
ERROR_NAMES = {
    "max_load": "|Q_max − Q_max,ref| / Q_max,ref",
    "load_max": "max over elements |Q − Q_ref| / Q_max,ref",
    "load_rms": "RMS over elements (Q − Q_ref) / Q_max,ref",
    "unloaded": "unloaded elements − those of the reference",
    "contact_angle_deg": "max over loaded elements |α − α_ref|, degrees",
    "tau_max": "|τ_max − τ_max,ref| / τ_max,ref at the largest load (peak subsurface shear)",
    "roller_speed": "max over rows |ω − ω_ref| / ω_ref, ω the mean spin of the loaded rollers",
    "cage_speed": "max over rows |Ω − Ω_ref| / Ω_ref, Ω the mean cage speed",
    "cage_force_mean": "max over rows |F − F_ref| / F_ref, F the mean roller–pocket force",
    "cage_force_peak": "max over rows |F − F_ref| / F_ref, F the peak roller–pocket force",
    "ring_von_mises": "max over rings |σ − σ_ref| / σ_ref, σ the peak von Mises stress of a modal ring",
    "race_torque": "max over races |T − T_ref| / |T_ref|, T the mean friction torque on a race about the axis",
}
#: the errors of a quasi-static ladder (the default of :attr:`Ladder.errors`)
QUASI_STATIC_ERRORS = ("max_load", "load_max", "load_rms", "unloaded", "contact_angle_deg", "tau_max")
#: the errors that compare :attr:`Outcome.figures` (name → {row, body or race: value})
FIGURE_ERRORS = ("roller_speed", "cage_speed", "cage_force_mean", "cage_force_peak", "ring_von_mises", "race_torque")


class ToleranceError(ValueError):
    """A tolerance that is no relative error, or one no rung of the ladder meets."""


@dataclass(frozen=True)
class Knob:
    """A dotted case key and its values, cheap → expensive. ``resolution`` maps a value to a
    positive number that grows with fidelity (modes: n; element size: 1/h), for convergence
    orders, and ``resolution_label`` says what it is; None for a knob without one (rigid / modal).
    ``implies``: value → other knob settings that value needs (e.g. element load shapes need a
    raceway patch), applied with it in the knob's sweep."""

    key: str
    values: tuple
    label: str
    resolution: object = None
    resolution_label: str = ""
    implies: Mapping = field(default_factory=dict)

    def __post_init__(self) -> None:
        if len(self.values) < 1 or len(set(self.values)) != len(self.values):
            raise ValueError(f"knob {self.key}: values must be distinct, got {self.values}")


def fixed_knob(key: str, value, label: str) -> Knob:
    """A setting every rung of a ladder shares (shown in its table, not varied)."""
    return Knob(key, (value,), label)


@dataclass(frozen=True)
class Ladder:
    """Knobs, the base rung they vary from, the reference, named combined rungs, and the
    family's primary quantity (a key of :data:`ERROR_NAMES`) and what it is. ``primary_figure``:
    (figure name, row) whose value the convergence plots follow along each knob; None, the largest
    element load."""

    knobs: tuple[Knob, ...]
    base: Mapping
    reference: Mapping
    combined: Mapping = field(default_factory=dict)
    primary: str = "max_load"
    primary_label: str = "largest element load"
    scene: str = ""
    #: the error columns the ladder reports (keys of :data:`ERROR_NAMES`)
    errors: tuple = QUASI_STATIC_ERRORS
    #: the rungs' own error estimates (columns of ``Outcome.estimates``) → what each estimates:
    #: None, the whole ``primary`` error against the reference; a knob key, the part of it that
    #: knob's sweep measures (the error against the rung of that sweep at its last, finest value)
    estimates: Mapping = field(default_factory=lambda: {"estimated_error": None})
    primary_figure: tuple | None = None

    def __post_init__(self) -> None:
        keys = {k.key for k in self.knobs}
        for what, rung in (("base", self.base), ("reference", self.reference), *self.combined.items()):
            if set(rung) - keys:
                raise ValueError(f"ladder {what}: {sorted(set(rung) - keys)} are no knobs of the ladder")
        if set(self.base) != keys:
            raise ValueError(f"ladder base must set every knob, missing {sorted(keys - set(self.base))}")
        if set(self.errors) - set(ERROR_NAMES):
            raise ValueError(f"ladder errors: {sorted(set(self.errors) - set(ERROR_NAMES))} are no error names")
        if self.primary not in self.errors:
            raise ValueError(f"ladder primary must be one of {list(self.errors)}, got {self.primary!r}")
        for name, knob in self.estimates.items():
            if knob is not None and knob not in keys:
                raise ValueError(f"ladder estimates: {name} estimates {knob!r}, no knob of the ladder")
        if self.primary_figure is not None and self.primary_figure[0] not in FIGURE_ERRORS:
            raise ValueError(f"ladder primary_figure: {self.primary_figure[0]!r} is no figure of {list(FIGURE_ERRORS)}")

    def primary_value(self, outcome: "Outcome") -> float:
        """The quantity the convergence plots follow: ``primary_figure`` of ``outcome``, or its largest
        element load."""
        if self.primary_figure is None:
            return float(np.max(outcome.load_N))
        name, row = self.primary_figure
        return float(outcome.figures[name][row])


@dataclass(frozen=True)
class Rung:
    """One model of the ladder: a name, the knob values that differ from the case, and which
    knob it sweeps (None for base, combined and reference rungs)."""

    name: str
    settings: Mapping
    knob: str | None = None


@dataclass(frozen=True)
class Outcome:
    """What a rung computes, per rolling element (Z of them): normal load (N) and, for
    quasi-static scenes, the loaded contact angle (rad) and the peak subsurface shear stress under
    the largest load (Pa); for dynamic scenes ``figures`` (error name of :data:`FIGURE_ERRORS` →
    {row or body: value}); and the errors of its ``primary`` quantity the run estimates for itself
    (``error_estimates``; column of :attr:`Ladder.estimates` → value, None: none), to compare with
    its true errors."""

    load_N: np.ndarray
    contact_angle_rad: np.ndarray | None = None
    tau_max_Pa: float | None = None
    unloaded_share: float = 1e-3
    estimates: Mapping = field(default_factory=dict)
    figures: Mapping = field(default_factory=dict)

    @property
    def unloaded(self) -> int:
        """Elements below ``unloaded_share`` of the mean load."""
        return int(np.sum(self.load_N < self.unloaded_share * self.load_N.mean()))

    def to_json(self) -> dict:
        def listed(x):
            return None if x is None else np.asarray(x, float).tolist()

        return {"load_N": listed(self.load_N), "contact_angle_rad": listed(self.contact_angle_rad),
                "tau_max_Pa": self.tau_max_Pa, "unloaded_share": self.unloaded_share,
                "estimates": dict(self.estimates),
                "figures": {k: {kk: float(vv) for kk, vv in v.items()} for k, v in self.figures.items()}}

    @classmethod
    def from_json(cls, d: Mapping) -> "Outcome":
        angle = d["contact_angle_rad"]
        tau = d["tau_max_Pa"]
        return cls(np.array(d["load_N"], float), None if angle is None else np.array(angle, float),
                   None if tau is None else float(tau), float(d["unloaded_share"]), dict(d["estimates"]),
                   {k: dict(v) for k, v in d["figures"].items()})


def case_tables(settings: Mapping) -> dict[str, dict]:
    """Dotted knob keys → values as the tables of :meth:`cases.config.CaseTables.with_`:
    ``{"top.n_modes": 5}`` → ``{"top": {"n_modes": 5}}``."""
    tables: dict[str, dict] = {}
    for key, value in settings.items():
        table, name = key.split(".")
        tables.setdefault(table, {})[name] = value
    return tables


def _settings_name(settings: Mapping) -> str:
    return ", ".join(f"{k}={v}" for k, v in settings.items())


def rungs(ladder: Ladder) -> list[Rung]:
    """Base, single-knob sweeps (each other value of each knob), combined rungs, reference; a
    setting met twice is one rung (its first name). ``top.kind = rigid``-like knobs whose first
    value switches the others off still vary alone."""
    out, seen = [], {}

    def add(name, settings, knob=None):
        full = {**ladder.base, **settings}
        key = tuple(sorted(full.items()))
        if key in seen:
            return
        seen[key] = name
        out.append(Rung(name, full, knob))

    add("base", {})
    for k in ladder.knobs:
        for v in k.values:
            add(f"{k.key}={v}", {k.key: v, **k.implies.get(v, {})}, k.key)
    for name, settings in ladder.combined.items():
        add(name, settings)
    ref_key = tuple(sorted({**ladder.base, **ladder.reference}.items()))
    if ref_key in seen:  # the reference must be its own rung
        out = [r for r in out if tuple(sorted(r.settings.items())) != ref_key]
        del seen[ref_key]
    add("reference", ladder.reference)
    return out


def sweep_members(ladder: Ladder, all_rungs: list[Rung], knob: Knob) -> list[Rung]:
    """The rungs of one knob's sweep in the order of its values (the base sits at its value)."""
    by_value = {}
    for r in all_rungs:
        implied = knob.implies.get(r.settings[knob.key], {})
        others_base = all(r.settings[k] == implied.get(k, v) for k, v in ladder.base.items() if k != knob.key)
        if others_base and r.name != "reference":
            by_value.setdefault(r.settings[knob.key], r)
    return [by_value[v] for v in knob.values if v in by_value]


def _figure_error(value: Mapping | None, reference: Mapping | None) -> float | None:
    """Largest relative difference over the rows (bodies) both have; None when one has none."""
    if not value or not reference:
        return None
    common = [k for k in reference if k in value and reference[k] != 0.0]
    if not common:
        return None
    return max(abs(float(value[k]) - float(reference[k])) / abs(float(reference[k])) for k in common)


def rung_errors(outcome: Outcome, reference: Outcome) -> dict[str, float | None]:
    """The errors of :data:`ERROR_NAMES` of ``outcome`` against ``reference`` (same elements);
    None for an error one of them cannot give (no contact angles, a rigid ring's stress)."""
    q, qr = np.asarray(outcome.load_N, float), np.asarray(reference.load_N, float)
    if q.shape != qr.shape:
        raise ValueError(f"a rung has {q.shape[0]} elements, the reference {qr.shape[0]}")
    qmax = float(qr.max())
    d = q - qr
    out = {
        "max_load": abs(float(q.max()) - qmax) / qmax,
        "load_max": float(np.abs(d).max()) / qmax,
        "load_rms": float(np.sqrt(np.mean(d * d))) / qmax,
        "unloaded": float(outcome.unloaded - reference.unloaded),
        "contact_angle_deg": None,
        "tau_max": None,
    }
    if outcome.contact_angle_rad is not None and reference.contact_angle_rad is not None:
        loaded = (q > 0.0) | (qr > 0.0)
        dalpha = np.abs(np.asarray(outcome.contact_angle_rad) - np.asarray(reference.contact_angle_rad))[loaded]
        out["contact_angle_deg"] = float(np.degrees(dalpha.max())) if dalpha.size else 0.0
    if outcome.tau_max_Pa is not None and reference.tau_max_Pa is not None:
        out["tau_max"] = abs(outcome.tau_max_Pa - reference.tau_max_Pa) / reference.tau_max_Pa
    for name in FIGURE_ERRORS:
        out[name] = _figure_error(outcome.figures.get(name), reference.figures.get(name))
    return out


def parse_tolerance(text: str) -> float:
    """``"1%"`` → 0.01, ``"0.01"`` → 0.01; a relative error strictly between 0 and 100 %."""
    s = str(text).strip()
    try:
        value = float(s[:-1]) / 100.0 if s.endswith("%") else float(s)
    except ValueError:
        raise ToleranceError(f"--tolerance: {text!r} is no number (write 1% or 0.01)") from None
    if not (math.isfinite(value) and 0.0 < value < 1.0):
        raise ToleranceError(f"--tolerance: {text!r} is no relative error; it must lie strictly between 0 and "
                             "100 % (e.g. 1% or 0.01)")
    return value


def choose_rung(rows: list[dict], tolerance: float, primary: str) -> tuple[dict, str]:
    """The row (a ``tradeoff.csv`` row as a dict) of least ``wall_s`` among the non-reference rungs
    whose ``primary`` error is ≤ ``tolerance``, and why it was chosen.

    Raises :class:`ToleranceError` naming the best error reached and its rung when none meets it.
    """
    candidates = [r for r in rows if r["rung"] != "reference"]
    if not candidates:
        raise ToleranceError("the ladder holds no rung besides the reference")
    meeting = [r for r in candidates if float(r[primary]) <= tolerance]
    if not meeting:
        best = min(candidates, key=lambda r: float(r[primary]))
        raise ToleranceError(f"--tolerance {100 * tolerance:g} %: no rung of the ladder meets it; the best is "
                             f"{best['rung']} with {100 * float(best[primary]):.3g} % ({primary})")
    chosen = min(meeting, key=lambda r: float(r["wall_s"]))
    why = (f"the fastest of {len(meeting)} rungs (of {len(candidates)}) whose {primary} error is ≤ "
           f"{100 * tolerance:g} %: {100 * float(chosen[primary]):.3g} % in {float(chosen['wall_s']):.1f} s")
    return chosen, why


def observed_order(resolution: list[float], values: list[float]) -> float | None:
    """Order p of convergence of ``values`` along rising ``resolution`` r, v ≈ v∞ + C·r^(−p), from
    successive differences: |v_{k+1} − v_k| ∝ r̄_k^(−p) (r̄_k the geometric mean of r_k and r_{k+1};
    exact for a constant refinement ratio), by a least-squares line in log–log. None: fewer than
    three values, or fewer than two non-zero differences."""
    r = np.asarray(resolution, float)
    v = np.asarray(values, float)
    if len(v) < 3:
        return None
    d = np.abs(np.diff(v))
    rm = np.sqrt(r[:-1] * r[1:])
    ok = d > 0.0
    if ok.sum() < 2:
        return None
    return float(-np.polyfit(np.log(rm[ok]), np.log(d[ok]), 1)[0])
