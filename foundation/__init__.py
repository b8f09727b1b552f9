"""The bottom layer every package builds on: elastic materials, input checks, npz file reading,
progress of long phases (:mod:`foundation.progress`), the words of messages (:mod:`foundation.text`),
files written complete or not at all (:mod:`foundation.files`).

Nothing here imports the rest of flexbearing; ``fem_rings``, ``cms_reduction``, ``mbd_core`` and
``cases`` all import from it.
"""

from .materials import BEARING_STEEL, ElasticMaterial, effective_modulus_Pa
from .validation import check_positive

__all__ = ["BEARING_STEEL", "ElasticMaterial", "check_positive", "effective_modulus_Pa"]
