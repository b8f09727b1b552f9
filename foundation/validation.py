"""Input checks shared by the library: errors name the offending field."""

from __future__ import annotations

import math

__all__ = ["check_positive"]


def check_positive(owner: str = "", /, **values: float) -> None:
    """Raise ValueError naming the first value that is not a positive finite number.

    ``owner`` (e.g. ``"ball row 'A'"``) prefixes the message when given.
    """
    prefix = f"{owner}: " if owner else ""
    for name, v in values.items():
        try:
            x = float(v)
        except (TypeError, ValueError):
            raise ValueError(f"{prefix}{name} must be a positive finite number, got {v!r}") from None
        if isinstance(v, bool) or not (math.isfinite(x) and x > 0.0):
            raise ValueError(f"{prefix}{name} must be a positive finite number, got {v!r}")
