"""Words of messages and reports shared by every package."""

from __future__ import annotations

__all__ = ["plural"]


def plural(n: int, word: str, many: str | None = None) -> str:
    """A count with its noun in agreement: ``plural(1, "ball") == "1 ball"``, ``plural(3, "ball")
    == "3 balls"``; ``many`` gives an irregular plural (``plural(2, "entry", "entries")``)."""
    return f"{n} {word if n == 1 else (many or word + 's')}"
