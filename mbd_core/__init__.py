"""The multibody core and the bearing mechanics it needs.

Subpackages: ``contact`` (Hertz point and line contact, subsurface stress), ``bearing``
(kinematics, ISO 281 rating and life, case-depth factor), ``quasistatic`` (load distribution
with rigid rings). Materials are in :mod:`mbd_core.materials`.
"""

from .materials import BEARING_STEEL, ElasticMaterial
from .quasistatic import Bearing, RingLoad, solve_load_distribution

__all__ = ["ElasticMaterial", "BEARING_STEEL", "Bearing", "RingLoad", "solve_load_distribution"]
