"""The multibody core and the bearing mechanics it needs.

Subpackages: ``contact`` (Hertz point and line contact, subsurface stress, friction laws),
``bearing`` (kinematics, ISO 281 rating and life, case-depth factor), ``quasistatic`` (load
distribution with rigid rings), ``squeeze_film`` (squeeze-film dampers: Reynolds on a grid, its
short/long limits, force tables), ``multibody`` (rigid multibody dynamics of bearings: model,
static equilibrium, explicit and generalized-α integration, record) and ``kernels`` (its compiled
numba kernels, the only place numba is imported). Materials are in :mod:`foundation.materials`.
"""

from foundation.materials import BEARING_STEEL, ElasticMaterial
from .quasistatic import Bearing, RingLoad, solve_load_distribution

__all__ = ["ElasticMaterial", "BEARING_STEEL", "Bearing", "RingLoad", "solve_load_distribution"]
