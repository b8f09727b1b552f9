"""Built-in bearings of the two studies, for the quasi-static load distribution (rigid rings).

Each is a bearing description file shipped with the package in ``cases/bearings/`` (the format:
``cases/bearings/README.md``) and read by :func:`cases.bearing_file.read_bearing_file`, the reader
of any user's file; the files carry their sources and the choices made where the sources are silent:

- ``slewing-ring``, ``slewing-ring-1m``, ``slewing-ring-2m``: the slewing ring of a fast-reactor
  rotatable plug (the slewing-ring thesis, see README.md, Sources), full scale and its 1 m and 2 m
  models, single-row angular-contact thrust ball bearing at 60°, under its dead load;
- ``three-row-roller``: the 12 MW wind main bearing (Pang et al., *Lubricants* 12 (2024) 252),
  three-row cylindrical roller bearing under an illustrative rated-wind load.
"""

from __future__ import annotations

from dataclasses import dataclass

from mbd_core.quasistatic import Bearing, RingLoad

from .bearing_file import BUILTIN_DIR, read_bearing_file

__all__ = ["BuiltinBearing", "BUILTIN_BEARINGS", "builtin_bearing", "slewing_ring", "three_row_roller"]


@dataclass(frozen=True)
class BuiltinBearing:
    """A named bearing with its default load and where its data come from."""

    name: str
    bearing: Bearing
    default_load: RingLoad
    description: str


def _from_file(name: str) -> BuiltinBearing:
    d = read_bearing_file(BUILTIN_DIR / f"{name}.toml")
    return BuiltinBearing(name=name, bearing=d.bearing, default_load=d.default_load, description=d.description)


#: Slewing-ring variants of the thesis: the file of each.
_SLEWING_VARIANTS = {"full": "slewing-ring", "1m": "slewing-ring-1m", "2m": "slewing-ring-2m"}


def slewing_ring(variant: str = "full") -> BuiltinBearing:
    """The fast-reactor slewing ring (``variant`` "full", "1m" or "2m") under its dead load."""
    if variant not in _SLEWING_VARIANTS:
        raise ValueError(f"variant must be one of {sorted(_SLEWING_VARIANTS)}, got {variant!r}")
    return _from_file(_SLEWING_VARIANTS[variant])


def three_row_roller() -> BuiltinBearing:
    """The 12 MW three-row roller main bearing under an illustrative rated-wind load."""
    return _from_file("three-row-roller")


#: The built-in bearings: name → a function that reads its description file.
BUILTIN_BEARINGS = {name: (lambda name=name: _from_file(name))
                    for name in ("slewing-ring", "slewing-ring-1m", "slewing-ring-2m", "three-row-roller")}


def builtin_bearing(name: str) -> BuiltinBearing:
    """Look up a built-in bearing by name (see :data:`BUILTIN_BEARINGS`)."""
    try:
        return BUILTIN_BEARINGS[name]()
    except KeyError:
        raise ValueError(f"bearing must be one of {sorted(BUILTIN_BEARINGS)}, got {name!r}") from None
