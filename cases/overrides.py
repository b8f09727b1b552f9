"""Case keys that a study does not read: refused, so that a case file says what ran.

Every study of a family is registered with a :class:`StudyEntry`: the function that runs it, the
``study.*`` fields it sweeps, the kinds of run it makes (``equilibria``, ``travels``,
``dynamic``) and the other keys it does not read, each with what does that key's job (the study
sets the value itself, or sweeps it through a ``study.*`` key). The keys of a kind of run that a
study does not make are unused as well, and so are the ``study.*`` fields other studies sweep.

:func:`check_case` refuses, before any meshing, a command-line ``--set`` of an unused key and a
case file whose unused keys differ from the values of the study's own named case, in one line
naming the key and what to set instead (:class:`cases.config.CaseError`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from .config import CaseError, to_mapping

__all__ = ["StudyEntry", "check_case", "unused_keys", "reference_case"]


@dataclass(frozen=True)
class StudyEntry:
    """One study of a case family.

    Attributes
    ----------
    run : callable
        ``run(case, out, progress)``, fills a :class:`cases.results.RunOutput`.
    sweeps : tuple of str
        The ``study.*`` fields (without ``study.``) it reads.
    runs : tuple of str
        The kinds of run it makes, keys of the family's ``RUN_KEYS``; empty: decided by the case
        (the family's ``runs_of``).
    unused : mapping
        Dotted key (or a whole table) → what does its job, e.g. ``"set study.undulation_scales"``.
    reads : tuple of str
        Keys of ``RUN_KEYS`` it reads although it does not make that kind of run.
    variants : bool
        Its runs are variants of the case, each an ordinary run in its own folder
        (:func:`cases.sweep.variants.run_variants`): they run in parallel with ``flexbearing run
        --workers N`` or ``--scheduler ADDRESS``.
    """

    run: Callable
    sweeps: tuple[str, ...] = ()
    runs: tuple[str, ...] = ()
    unused: Mapping[str, str] = field(default_factory=dict)
    reads: tuple[str, ...] = ()
    variants: bool = False


def unused_keys(kind: str, studies: Mapping[str, StudyEntry], run_keys: Mapping[str, tuple[Mapping[str, None], str]],
                runs: Sequence[str]) -> dict[str, str]:
    """Dotted key → what does its job, for every key the study ``kind`` does not read.

    ``run_keys``: kind of run → (its keys, the hint for a study that does not make it); ``runs``:
    the kinds of run this case makes.
    """
    entry = studies[kind]
    out: dict[str, str] = {}
    for run, (keys, hint) in run_keys.items():
        if run not in runs:
            out.update({k: hint for k in keys if k not in entry.reads})
    for other, e in studies.items():
        for name in e.sweeps:
            if name not in entry.sweeps:
                out.setdefault(f"study.{name}", f"read by the {other} study only")
    out.update(entry.unused)
    return out


def _covering(key: str, unused: Mapping[str, str]) -> str | None:
    """The entry of ``unused`` that is ``key`` or one of its tables."""
    parts = key.split(".")
    for i in range(len(parts), 0, -1):
        if ".".join(parts[:i]) in unused:
            return ".".join(parts[:i])
    return None


def _value(mapping: dict, key: str):
    node = mapping
    for p in key.split("."):
        if not isinstance(node, dict) or p not in node:
            return None
        node = node[p]
    return node


def reference_case(cls: type, presets: Mapping[str, object], kind: str):
    """The family's named case of study ``kind`` (its first), else the defaults with that study."""
    for case in presets.values():
        if case.study.kind == kind:
            return case
    default = cls()
    return dataclasses.replace(default, study=dataclasses.replace(default.study, kind=kind))


def check_case(case, unused: Mapping[str, str], assignments: Sequence[str] = (), source_case=None,
               reference=None, source: str = "") -> None:
    """Refuse unused keys set on the command line or changed in a case file.

    Parameters
    ----------
    case
        The resolved case (after ``--quick`` and ``--set``).
    unused : mapping
        :func:`unused_keys` of its study.
    assignments : sequence of str
        The ``--set key=value`` items.
    source_case, reference
        The case as read from a case file, and the study's named case to compare it with
        (:func:`reference_case`); None: no file.
    source : str
        The file's name, for the message.

    Raises
    ------
    CaseError
        ``key: not used by the X study; <what does its job>``.
    """
    kind = case.study.kind
    for item in assignments:
        key = ".".join(p.strip() for p in item.partition("=")[0].strip().split("."))
        hit = _covering(key, unused)
        if hit is not None:
            raise CaseError(f"--set {key}: not used by the {kind} study; {unused[hit]}")
    if source_case is None or reference is None:
        return
    mine, ref = to_mapping(source_case), to_mapping(reference)
    for key in sorted(unused):
        if _value(mine, key) != _value(ref, key):
            where = f"{source}: " if source else ""
            value = _value(ref, key)
            shown = "values" if isinstance(value, dict) else f"value {value!r}"
            raise CaseError(f"{where}{key}: not used by the {kind} study, leave it out or at the {reference.name} "
                            f"case's {shown}; {unused[key]}")
