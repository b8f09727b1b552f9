"""Multibody dynamics of bearings: build a model, find its static equilibrium, integrate it.

Data flow: :class:`ModelBuilder` → ``finalize()`` → (:class:`Model`, :class:`State`) →
:func:`static_equilibrium` (optional start) → :func:`simulate` (explicit, compiled loop) or
:func:`simulate_implicit` (generalized-α reference) → record folder → :func:`read_run`.
Assemblers of whole bearings with Hertz-derived contact laws are in :mod:`.bearings`.
"""

from .builder import ContactLaw, Driven, Fixed, Free, ModelBuilder, quat_from_axis_angle, quat_z_to
from .implicit import simulate_implicit
from .explicit import DivergenceError, SimulationError, StepTooLargeError, evaluate_forces, simulate, stable_timestep
from .model import Model, State
from .recorder import read_run
from .step_error import StepError, largest_load_step_error, step_error

__all__ = [
    "ModelBuilder", "ContactLaw", "Free", "Fixed", "Driven", "quat_from_axis_angle", "quat_z_to",
    "Model", "State", "simulate", "simulate_implicit", "stable_timestep", "evaluate_forces", "read_run",
    "SimulationError", "StepTooLargeError", "DivergenceError", "StepError", "step_error", "largest_load_step_error",
]
