"""Craig–Bampton reduction of FE ring models into modal bodies for the floating frame of reference.

Second stage of the data flow (DESIGN §1, §4): ``FEModel`` (fem_rings) → ``reduce_model`` →
``ReducedBody`` (mass-normalised modes, frequencies, damping, mesh arrays; later stages add
inertia invariants, raceway samples and stress modes).
"""

from .body import ReducedBody
from .craig_bampton import Augmentation, Interface, reduce_model

__all__ = ["ReducedBody", "Interface", "Augmentation", "reduce_model"]
