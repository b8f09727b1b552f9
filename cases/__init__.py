"""The studies and the ``flexbearing`` command line."""

from .bearing_file import read_bearing_file
from .catalog import BUILTIN_BEARINGS, builtin_bearing

__all__ = ["BUILTIN_BEARINGS", "builtin_bearing", "read_bearing_file"]
