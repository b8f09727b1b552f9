"""Case definitions (frozen dataclasses) to TOML and back, with errors that name the key.

The machinery knows no schema: it follows the dataclass fields and their type hints. Supported
hints are ``float`` (an integer is accepted), ``int``, ``bool``, ``str``, ``Literal[...]``,
``X | None``, nested dataclasses, ``tuple[X, ...]`` and fixed ``tuple[X, Y]``. TOML has no null,
so a field whose value is None is left out when writing and takes its default when reading.
Numbers must be finite (TOML's ``nan`` and ``inf`` are refused, naming the key). A case class
with a ``FAMILY`` class attribute is written with a top-level ``family = "..."`` key, which
reading checks.
Validation of values stays in the dataclasses' own ``__post_init__``; its ValueError/TypeError is
re-raised as :class:`CaseError` carrying the dotted path of the table.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import re
import sys
import tomllib
import types
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, Literal, Union, get_args, get_origin, get_type_hints

import tomli_w

__all__ = ["CaseTables", "CaseError", "FAMILY_KEY", "dumps_case", "from_mapping", "loads_case", "parse_toml", "qualified_message",
           "read_case", "read_toml", "to_mapping", "with_overrides", "write_case"]

_TYPE_NAMES = {int: "an integer", bool: "true or false", str: "a string"}
_LARGEST_FLOAT = sys.float_info.max
#: the top-level key naming a case file's family (see ``FAMILY`` on the case classes)
FAMILY_KEY = "family"


class CaseError(ValueError):
    """Bad case input; the message starts with the dotted key path, e.g. ``top.n_modes: ...``."""


def _join(where: str, name: str) -> str:
    if not re.fullmatch(r"[\w-]+", name):
        name = repr(name)  # a quoted TOML key may hold dots, spaces or line breaks
    return f"{where}.{name}" if where else name


def _show(value: Any) -> str:
    """A value as it is spelled in TOML where that differs from Python (booleans), kept short."""
    text = str(value).lower() if isinstance(value, bool) else repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


@functools.lru_cache(maxsize=256)
def _hints(cls: type) -> dict[str, Any]:
    """The resolved type hints of a dataclass (kept: resolving them is slow)."""
    return get_type_hints(cls)


def _init_fields(cls: type) -> dict[str, dataclasses.Field]:
    return {f.name: f for f in dataclasses.fields(cls) if f.init}


def _strip_optional(hint: Any) -> Any:
    """``X | None`` → ``X``; any other hint unchanged."""
    if get_origin(hint) in (Union, types.UnionType):
        options = [a for a in get_args(hint) if a is not type(None)]
        if len(options) == 1:
            return options[0]
    return hint


def _coerce(hint: Any, value: Any, where: str) -> Any:
    """Check ``value`` (as read from TOML) against the type hint and convert it."""
    hint = _strip_optional(hint)
    origin, args = get_origin(hint), get_args(hint)
    if dataclasses.is_dataclass(hint):
        if not isinstance(value, Mapping):
            raise CaseError(f"{where}: expected a table, got {_show(value)}")
        return from_mapping(hint, value, where)
    if origin is Literal:
        if any(value == c and type(value) is type(c) for c in args):
            return value
        raise CaseError(f"{where}: must be one of {', '.join(map(repr, args))}, got {_show(value)}")
    if origin is tuple:
        if not isinstance(value, (list, tuple)):
            raise CaseError(f"{where}: expected a list, got {_show(value)}")
        if len(args) == 2 and args[1] is Ellipsis:
            args = (args[0],) * len(value)
        elif len(args) != len(value):
            raise CaseError(f"{where}: expected a list of {len(args)} items, got {len(value)}")
        return tuple(_coerce(h, v, f"{where}[{i}]") for i, (h, v) in enumerate(zip(args, value)))
    if hint is float:
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            if isinstance(value, int) and abs(value) > _LARGEST_FLOAT:
                raise CaseError(f"{where}: expected a finite number, got {value:.3e}")
            if not math.isfinite(value):
                raise CaseError(f"{where}: expected a finite number, got {_show(value)}")
            return float(value)
        raise CaseError(f"{where}: expected a number, got {_show(value)}")
    if hint in _TYPE_NAMES:
        if type(value) is hint:  # type(), not isinstance(): bool is an int subclass
            return value
        raise CaseError(f"{where}: expected {_TYPE_NAMES[hint]}, got {_show(value)}")
    if hint is Any:
        return value
    raise TypeError(f"{where}: unsupported field type {hint!r}")


def _post_init_message(where: str, message: str, names: Sequence[str]) -> str:
    """Prefix a dataclass's own validation message with the path of that dataclass."""
    if not where:
        return message
    first = re.match(r"(\w+)[ :]", message)
    return f"{where}.{message}" if first and first.group(1) in names else f"{where}: {message}"


def _tables_with_field(cls: type, name: str, where: str = "") -> list[str]:
    """Dotted paths of the tables in the dataclass tree of ``cls`` that have a field ``name``."""
    out = [where] if name in _init_fields(cls) and where else []
    for field_name, hint in _hints(cls).items():
        hint = _strip_optional(hint)
        if isinstance(hint, type) and dataclasses.is_dataclass(hint):
            out += _tables_with_field(hint, name, _join(where, field_name))
    return out


def qualified_message(cls: type, message: str) -> str:
    """A dataclass's own validation message with its table's path in front of the field it
    starts with (``tmr_width_m … `` → ``geometry.tmr_width_m …``), where only one table has it."""
    first = re.match(r"(\w+)[ :]", message)
    tables = _tables_with_field(cls, first.group(1)) if first else []
    return f"{tables[0]}.{message}" if len(tables) == 1 else message


def from_mapping(cls: type, data: Mapping, where: str = "") -> Any:
    """Build a (possibly nested) frozen dataclass from a plain mapping.

    Parameters
    ----------
    cls : type
        The dataclass to build.
    data : Mapping
        Keys are field names; nested dataclass fields take sub-mappings.
    where : str
        Dotted path of ``data`` within the whole case, used in error messages.

    Returns
    -------
    cls
        The instance; missing keys take the field defaults.

    Raises
    ------
    CaseError
        Unknown or missing key, wrong type, or a value rejected by ``__post_init__``.
    """
    if not isinstance(data, Mapping):
        raise CaseError(f"{where or '<case>'}: expected a table, got {_show(data)}")
    if not where and hasattr(cls, "FAMILY"):
        data = _without_family(cls, data)
    hints = _hints(cls)
    fields = _init_fields(cls)
    unknown = sorted(set(data) - set(fields))
    if unknown:
        raise CaseError(f"{_join(where, unknown[0])}: unknown key (known: {', '.join(sorted(fields))})")
    kwargs = {}
    for name, f in fields.items():
        if name in data:
            kwargs[name] = _coerce(hints[name], data[name], _join(where, name))
        elif f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
            raise CaseError(f"{_join(where, name)}: missing key")
    try:
        return cls(**kwargs)
    except CaseError:
        raise
    except (ValueError, TypeError) as exc:
        raise CaseError(_post_init_message(where, str(exc), list(fields))) from exc


def _without_family(cls: type, data: Mapping) -> dict:
    """``data`` less its ``family`` key, which must name the family of ``cls`` when given."""
    data = dict(data)
    family = data.pop(FAMILY_KEY, cls.FAMILY)
    if family != cls.FAMILY:
        raise CaseError(f"{FAMILY_KEY}: this reads a {cls.FAMILY!r} case, the file says {_show(family)}")
    return data


def _plain(value: Any) -> Any:
    if dataclasses.is_dataclass(value):
        return to_mapping(value)
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    return value


def to_mapping(obj: Any) -> dict:
    """Nested dicts and lists of a case dataclass; None-valued fields are left out."""
    return {
        name: _plain(value)
        for name in _init_fields(type(obj))
        if (value := getattr(obj, name)) is not None
    }


def parse_toml(text: str, source: str = "<string>") -> dict:
    """The table of TOML text; CaseError naming ``source`` for bad syntax, excessive nesting or no keys."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"{source}: invalid TOML: {exc}") from exc
    except RecursionError:
        raise CaseError(f"{source}: invalid TOML: nested too deeply") from None
    if not data:
        raise CaseError(f"{source}: no case entries (the file is empty or holds only comments)")
    return data


def read_toml(path: str | Path) -> dict:
    """The table of a TOML file; CaseError naming the file when it cannot be read or parsed."""
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise CaseError(f"{path}: cannot read: {exc.strerror or exc}") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise CaseError(f"{path}: not UTF-8 text (byte {exc.start}: {exc.reason})") from None
    return parse_toml(text, str(path))


def loads_case(cls: type, text: str, source: str = "<string>") -> Any:
    """Build ``cls`` from TOML text; ``source`` names the text in a syntax error."""
    return from_mapping(cls, parse_toml(text, source))


def read_case(cls: type, path: str | Path) -> Any:
    """Build ``cls`` from a TOML file; a syntax error names the file and the line."""
    return from_mapping(cls, read_toml(path))


def dumps_case(obj: Any) -> str:
    """TOML text of a case: ``family`` (when the class has one), top-level scalars, then tables;
    reads back equal."""
    family = {FAMILY_KEY: type(obj).FAMILY} if hasattr(type(obj), "FAMILY") else {}
    return tomli_w.dumps({**family, **to_mapping(obj)})


def write_case(obj: Any, path: str | Path) -> None:
    """Write a case as TOML to ``path``."""
    Path(path).write_text(dumps_case(obj), encoding="utf-8")


def _parse_value(text: str, where: str) -> Any:
    """A TOML value, or the raw text when it is not one (``dynamic_explicit``)."""
    try:
        data = tomllib.loads("v = " + text)
    except tomllib.TOMLDecodeError:
        return text
    except RecursionError:
        raise CaseError(f"{where}: value nested too deeply") from None
    if len(data) != 1:  # "1\nx = 2" would set a second key
        raise CaseError(f"{where}: expected one value, got {_show(text)}")
    return data["v"]


def _check_path(cls: type, parts: Sequence[str]) -> None:
    """Raise CaseError unless ``parts`` names a field in the dataclass tree of ``cls``."""
    for i, name in enumerate(parts):
        where = ".".join(_join("", p) for p in parts[: i + 1])
        if not (isinstance(cls, type) and dataclasses.is_dataclass(cls)):
            raise CaseError(f"{'.'.join(_join('', p) for p in parts[:i])}: not a table, cannot set {where}")
        fields = _init_fields(cls)
        if name not in fields:
            raise CaseError(f"{where}: unknown key (known: {', '.join(sorted(fields))})")
        cls = _strip_optional(_hints(cls)[name])


def with_overrides(obj: Any, assignments: Sequence[str]) -> Any:
    """Apply ``key.path=value`` assignments (command-line ``--set``) to a case.

    Parameters
    ----------
    obj : dataclass instance
        The case to modify.
    assignments : sequence of str
        Items like ``"top.n_modes=30"`` or ``"analysis.type=dynamic_explicit"``; the right-hand
        side is read as a TOML value, and taken as a plain string when it is not valid TOML.

    Returns
    -------
    dataclass instance
        A new case, rebuilt with :func:`from_mapping` so that all validation runs again.
    """
    data = to_mapping(obj)
    for item in assignments:
        key, sep, rhs = item.partition("=")
        plain = item.strip() and item.isprintable() and len(item) <= 60
        if not sep:
            raise CaseError(f"{item if plain else '--set ' + _show(item)}: expected key=value")
        if not key.strip():
            raise CaseError(f"--set {_show(item)}: no key before '='")
        parts = [p.strip() for p in key.strip().split(".")]
        _check_path(type(obj), parts)
        node = data
        for i, name in enumerate(parts[:-1]):
            node = node.setdefault(name, {})  # a None-valued table is absent from the mapping
            if not isinstance(node, dict):  # an earlier assignment put a value in place of the table
                where = ".".join(_join("", p) for p in parts[: i + 1])
                raise CaseError(f"{where}: expected a table, got {_show(node)}")
        node[parts[-1]] = _parse_value(rhs.strip(), ".".join(parts))
    return from_mapping(type(obj), data)


class CaseTables:
    """What every case family's top dataclass shares: :meth:`with_`, a copy with some tables changed."""

    def with_(self, **tables):
        """A copy with some tables changed: ``case.with_(study={"kind": "static"}, top={"n_modes": 12})``."""
        return dataclasses.replace(self, **{k: dataclasses.replace(getattr(self, k), **v) for k, v in tables.items()})
