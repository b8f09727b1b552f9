"""Craig–Bampton reduction of FE ring models into modal bodies for the floating frame of reference.

Second stage of the data flow: ``FEModel`` (fem_rings) → ``reduce_model`` →
``ReducedBody`` (mass-normalised modes, frequencies, damping, mesh arrays, and as extras the
inertia invariants, raceway samples and optional stress modes). ``reduced_body`` does all of it
from a section and caches the result by input hash. After a run, ``stress_history`` turns the
recorded modal coordinates η(t) into stresses: peak von Mises over time, the worst instant,
ParaView series and pictures.
"""

from .body import ReducedBody
from .augmentation import Augmentation
from .craig_bampton import Interface, reduce_model
from .invariants import Invariants, compute_invariants
from .persist import load_body, save_body
from .prestress import prestressed
from .pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from .stress_history import (peak_von_mises_history, render_stress_pngs, stress_at, worst_time,
                             write_stress_series)

__all__ = [
    "ReducedBody", "Interface", "Augmentation", "reduce_model",
    "Invariants", "compute_invariants", "save_body", "load_body",
    "prestressed", "InterfaceSpec", "RacewaySpec", "ReductionSpec", "reduced_body",
    "peak_von_mises_history", "worst_time", "stress_at", "write_stress_series", "render_stress_pngs",
]
