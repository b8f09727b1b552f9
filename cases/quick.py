"""The ``--quick`` variant of a named case: the same question at a reduced size, named and
described as such (a quick run never prints the full case's description as its own)."""

from __future__ import annotations

from dataclasses import replace

__all__ = ["quick_variant", "changes_text"]


def _value_text(v) -> str:
    if isinstance(v, float):
        return f"{v:g}"
    if isinstance(v, (tuple, list)):
        return "(" + ", ".join(_value_text(x) for x in v) + ")"
    return repr(v) if isinstance(v, str) else str(v)


def changes_text(tables: dict) -> str:
    """``{"top": {"n_modes": 12}}`` → ``"top.n_modes = 12"`` (entries joined by commas)."""
    return ", ".join(f"{table}.{key} = {_value_text(v)}" for table, entries in tables.items()
                     for key, v in entries.items())


def quick_variant(case, tables: dict):
    """``case`` with the entries ``tables`` (table → key → value) changed, its name suffixed
    ``-quick`` and its description saying that it is the quick variant and what it changes."""
    changed = case.with_(**tables) if tables else case
    what = f"reduced to {changes_text(tables)}" if tables else "as the full case, which is quick already"
    full = f"; the full case: {case.description}" if case.description else ""
    return replace(changed, name=f"{case.name}-quick", description=f"quick variant of {case.name}, {what}{full}")
