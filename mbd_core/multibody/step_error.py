"""The time-step error of a run, estimated without a reference: a short window repeated at h/2 and h/4.

From one state, the same window of ``n`` steps of h is integrated three times, at h, h/2 and h/4,
recording at the same instants. A figure y read from each window (e.g. the mean load of the most
loaded rolling element over it) behaves as y_h = y* + C·h^p for a scheme of order p, so
(Richardson extrapolation; Hairer, Nørsett & Wanner, *Solving Ordinary Differential Equations I*,
§II.4):

    p = log2((y_h − y_{h/2}) / (y_{h/2} − y_{h/4})),    error of y_h = |y_h − y_{h/2}| / (1 − 2^−p).

The observed p is used when both differences have the same sign and p lies in [0.5, 4]; otherwise
(differences at round-off, or of opposite signs) p = 1 is assumed, the order of the scheme's
implicit friction and damping terms (velocity Verlet alone is of order 2), which gives the larger
estimate. The window measures the step's bias on the figure at the state it starts from; errors
that a long run accumulates through a chaotic path (single impacts in cage pockets) are not in it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from .explicit import simulate
from .model import Model, State

__all__ = ["StepError", "step_error", "largest_load_step_error", "WINDOW_STEPS"]

#: steps of the window :func:`largest_load_step_error` repeats
WINDOW_STEPS = 200
#: the range of observed orders that are believed; outside it p = ASSUMED_ORDER
ORDER_RANGE = (0.5, 4.0)
ASSUMED_ORDER = 1.0


@dataclass(frozen=True)
class StepError:
    """One figure's value at the run's step h, its estimated error there (same unit) and the order used."""

    value: float
    error: float
    order: float
    order_observed: bool

    @property
    def relative(self) -> float:
        """error / |value| (inf for a zero value with an error)."""
        if self.value == 0.0:
            return 0.0 if self.error == 0.0 else math.inf
        return self.error / abs(self.value)


def richardson(y_h: float, y_h2: float, y_h4: float) -> StepError:
    """The estimate of the module docstring from a figure at h, h/2 and h/4."""
    d1, d2 = y_h - y_h2, y_h2 - y_h4
    p, observed = ASSUMED_ORDER, False
    if d1 != 0.0 and d2 != 0.0 and (d1 > 0.0) == (d2 > 0.0):
        q = math.log2(d1 / d2)
        if ORDER_RANGE[0] <= q <= ORDER_RANGE[1]:
            p, observed = q, True
    return StepError(float(y_h), abs(d1) / (1.0 - 2.0 ** -p), p, observed)


def step_error(model: Model, state: State, timestep_s: float, figures: Callable[[dict], Mapping[str, float]],
               n_steps: int = WINDOW_STEPS) -> dict[str, StepError]:
    """Time-step error of each figure of ``figures(record)`` for a run at ``timestep_s``, from a window
    of ``n_steps`` steps starting at ``state`` (left unchanged), run at h, h/2 and h/4 (module
    docstring). ``figures`` reads a :func:`~.explicit.simulate` record, sampled every h."""
    if not (math.isfinite(timestep_s) and timestep_s > 0.0):
        raise ValueError(f"step_error: timestep_s must be positive, got {timestep_s!r}")
    if n_steps < 2:
        raise ValueError(f"step_error: n_steps must be ≥ 2, got {n_steps}")
    t_end = state.t + n_steps * timestep_s
    values = []
    for k in (1, 2, 4):
        # (the run's own step: its stability was checked where that run set it)
        rec = simulate(model, state.copy(), t_end, timestep_s=timestep_s / k, record_every=k, allow_unstable=True)
        values.append(dict(figures(rec)))
    return {name: richardson(values[0][name], values[1][name], values[2][name]) for name in values[0]}


def largest_load_step_error(model: Model, state: State, timestep_s: float, pairs, n_steps: int = WINDOW_STEPS) -> dict:
    """:func:`step_error` of the largest normal force among contact ``pairs`` (mean over the
    window of the largest at each sample), as ``summary.json`` reports it: relative error, value
    (N), order and whether it was observed, window length (s)."""
    pairs = list(pairs)
    est = step_error(model, state, timestep_s, lambda rec: {"q": float(rec["fn"][:, pairs].max(axis=1).mean())},
                     n_steps)["q"]
    return {"max_load": est.relative, "max_load_N": est.value, "order": est.order,
            "order_observed": est.order_observed, "window_s": n_steps * timestep_s,
            "what": f"relative time-step error of the largest contact load over {n_steps} steps from the run's "
                    "end, repeated at h/2 and h/4 (Richardson)"}
