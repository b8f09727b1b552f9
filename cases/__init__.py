"""The studies and the ``flexbearing`` command line."""

from .catalog import BUILTIN_BEARINGS, builtin_bearing

__all__ = ["BUILTIN_BEARINGS", "builtin_bearing"]
