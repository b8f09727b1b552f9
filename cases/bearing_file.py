"""Bearing description files (TOML): a bearing's rows, materials and load, read into :mod:`mbd_core.quasistatic`.

The format reference, every key with its unit, is ``cases/bearings/README.md``. In short::

    [bearing]                  # name, description, moving_ring = "inner" | "outer"
    [materials.NAME]           # E_Pa, nu, density_kg_m3; "bearing_steel" is built in
    [[rows]]                   # type = one of ROW_TYPES (cases.bearing_rows), then its keys
    [load]                     # Fx_N, Fy_N, Fz_N, Mx_Nm, My_Nm, or spectrum_csv = "file.csv",
                               # or time_history_csv = "file.csv"
    [rings.inner], [rings.outer]  # optional: the ring bends (section, support, modes; cases.bearing_rings)

Everything is checked before any work; every error is a :class:`cases.config.CaseError` whose
one-line message starts with the dotted key (``rows[2].conformity_inner: must be > 0.5 …``) or
the file. A spectrum CSV (path relative to the description file) has the columns
``Fx_N, Fy_N, Fz_N, Mx_Nm, My_Nm`` and optionally ``time_share``, one load case a line; a time
history CSV ``time_s`` and the five load columns, one instant a line, each instant a load case
with its trapezoid-rule time share (:mod:`cases.load_csv`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

from foundation.materials import BEARING_STEEL, ElasticMaterial
from mbd_core.bearing.distribution_case_depth import CaseDepth
from mbd_core.quasistatic import Bearing, RingLoad
from mbd_core.quasistatic.results import LOAD_NAMES

from .bearing_rings import ring_models
from .bearing_rows import ROW_TYPES, RowContext, build_rows
from .config import CaseError, from_mapping, parse_toml, read_toml
from .load_csv import MAX_LOAD_CASES, read_spectrum_csv, read_time_history_csv

__all__ = ["BearingDescription", "BUILTIN_DIR", "read_bearing_file", "loads_bearing", "bearing_from_mapping",
           "read_spectrum_csv", "read_time_history_csv", "MAX_LOAD_CASES"]

#: Folder of the description files shipped with the package (the built-in bearings).
BUILTIN_DIR = Path(__file__).resolve().parent / "bearings"
#: Name of the built-in material (:data:`foundation.materials.BEARING_STEEL`).
BUILTIN_MATERIAL = "bearing_steel"


@dataclass(frozen=True)
class BearingKeys:
    """``[bearing]``: ``name``; ``description`` (free text); ``moving_ring`` (the ring the load acts on)."""

    name: str
    description: str = ""
    moving_ring: Literal["inner", "outer"] = "inner"

    def __post_init__(self) -> None:
        if not self.name.strip():
            raise ValueError("name: must not be empty")


@dataclass(frozen=True)
class MaterialKeys:
    """``[materials.NAME]``: Young's modulus Pa, Poisson's ratio, density kg/m³."""

    E_Pa: float
    nu: float
    density_kg_m3: float = 7850.0


@dataclass(frozen=True)
class LoadKeys:
    """``[load]``: the load on the moving ring at the bearing centre (N, N·m), or a spectrum file,
    or a load time history file (:mod:`cases.load_csv`)."""

    Fx_N: float = 0.0
    Fy_N: float = 0.0
    Fz_N: float = 0.0
    Mx_Nm: float = 0.0
    My_Nm: float = 0.0
    spectrum_csv: str | None = None
    time_history_csv: str | None = None

    def __post_init__(self) -> None:
        if self.spectrum_csv is not None and self.time_history_csv is not None:
            raise ValueError("time_history_csv: give a spectrum file or a time history file, not both "
                             "(spectrum_csv given)")
        for key, what in (("spectrum_csv", "a spectrum file"), ("time_history_csv", "a time history file")):
            if getattr(self, key) is None:
                continue
            given = [n for n in LOAD_NAMES if getattr(self, n) != 0.0]
            if given:
                raise ValueError(f"{key}: give the load components or {what}, not both ({given[0]} given)")
            if not getattr(self, key).strip():
                raise ValueError(f"{key}: must name a file")


@dataclass(frozen=True)
class BearingDescription:
    """A bearing read from a description file.

    Attributes
    ----------
    name, description : str
    bearing : Bearing
        The rows, ready for :func:`mbd_core.quasistatic.solve_load_distribution`.
    load_cases : tuple of RingLoad
        The file's load: one case, or one per line of its spectrum or time history CSV.
    time_share : tuple of float or None
        The spectrum's time shares, or the time history's trapezoid shares (None when the file has none).
    source : str
        The file read.
    case_depths : dict of row name → CaseDepth
        The rows given a case depth (``case_depth_m`` and a core strength), for the DG03 life factor.
    rings : dict of str → cases.bearing_rings.RingModel
        The rings given a ``[rings.X]`` table (they bend), validated but not meshed yet; the
        others are rigid.
    separators : dict of row name → cases.row_keys.SeparatorKeys
        The rows given a ``[rows.separator]`` table (cage, spacer balls, full complement).
    """

    name: str
    description: str
    bearing: Bearing
    load_cases: tuple[RingLoad, ...]
    time_share: tuple[float, ...] | None = None
    source: str = "<string>"
    case_depths: Mapping[str, CaseDepth] = field(default_factory=dict)
    rings: Mapping = field(default_factory=dict)
    separators: Mapping = field(default_factory=dict)

    @property
    def default_load(self) -> RingLoad:
        """The first load case (the only one unless the file gives a spectrum)."""
        return self.load_cases[0]


def _materials(data, where: str = "materials") -> dict[str, ElasticMaterial]:
    out = {BUILTIN_MATERIAL: BEARING_STEEL}
    if data is None:
        return out
    if not isinstance(data, Mapping):
        raise CaseError(f"{where}: expected a table of [materials.NAME] tables, got {data!r:.60}")
    for name, table in data.items():
        at = f"{where}.{name}"
        if name == BUILTIN_MATERIAL:
            raise CaseError(f"{at}: {BUILTIN_MATERIAL!r} is built in (E = 207 GPa, ν = 0.29); name yours differently")
        keys = from_mapping(MaterialKeys, table, at)
        try:
            out[name] = ElasticMaterial(name, keys.E_Pa, keys.nu, keys.density_kg_m3)
        except ValueError as exc:
            key, _, rest = str(exc).partition(": ")[2].partition(" ")
            raise CaseError(f"{at}.{key}: {rest}") from None
    return out


def _row_tables(data) -> list:
    if data is None:
        raise CaseError("rows: missing key (at least one [[rows]] table)")
    if not isinstance(data, list) or not data:
        raise CaseError(f"rows: expected one or more [[rows]] tables, got {data!r:.60}")
    return data


def _rows(data, ctx_of) -> tuple[tuple, dict[str, CaseDepth], dict]:
    """All rows of the ``[[rows]]`` tables, in file order, the case depths and the separators by row name."""
    rows, first_use, case_depths, separators = [], {}, {}, {}
    for i, table in enumerate(_row_tables(data)):
        where = f"rows[{i}]"
        if not isinstance(table, Mapping):
            raise CaseError(f"{where}: expected a table, got {table!r:.60}")
        kind = table.get("type")
        if kind is None:
            raise CaseError(f"{where}.type: missing key; one of {', '.join(ROW_TYPES)}")
        if not isinstance(kind, str) or kind not in ROW_TYPES:
            raise CaseError(f"{where}.type: unknown row type {kind!r:.60}; one of {', '.join(ROW_TYPES)}")
        row_type = ROW_TYPES[kind]
        keys = from_mapping(row_type.keys, {k: v for k, v in table.items() if k != "type"}, where)
        for row in build_rows(keys, row_type, ctx_of(where)):
            if row.name in first_use:
                raise CaseError(f"{where}.name: row name {row.name!r} is already used by {first_use[row.name]}")
            first_use[row.name] = where
            rows.append(row)
            if keys.case_depth_m is not None:
                case_depths[row.name] = CaseDepth(keys.case_depth_m, keys.core_shear_fatigue_Pa)
            if keys.separator is not None:
                separators[row.name] = keys.separator
    return tuple(rows), case_depths, separators


def _load(data, base_dir: Path | None) -> tuple[tuple[RingLoad, ...], tuple[float, ...] | None]:
    keys = from_mapping(LoadKeys, {} if data is None else data, "load")
    for name, read in (("spectrum_csv", read_spectrum_csv), ("time_history_csv", read_time_history_csv)):
        given = getattr(keys, name)
        if given is None:
            continue
        path = Path(given)
        if not path.is_absolute():
            if base_dir is None:
                raise CaseError(f"load.{name}: a relative path needs the description file's folder")
            path = base_dir / path
        return read(path, f"load.{name}")
    return (RingLoad(**{n: getattr(keys, n) for n in LOAD_NAMES}),), None


TOP_LEVEL = ("bearing", "materials", "rows", "load", "rings")


def bearing_from_mapping(data: Mapping, base_dir: Path | None = None, source: str = "<string>") -> BearingDescription:
    """A :class:`BearingDescription` from the table of a description file (``base_dir``: the file's folder)."""
    unknown = sorted(set(data) - set(TOP_LEVEL))
    if unknown:
        raise CaseError(f"{unknown[0]}: unknown key (known: {', '.join(TOP_LEVEL)})")
    if "bearing" not in data:
        raise CaseError("bearing: missing key (a [bearing] table with at least name)")
    head = from_mapping(BearingKeys, data["bearing"], "bearing")
    materials = _materials(data.get("materials"))
    rows, case_depths, separators = _rows(data.get("rows"),
                                          lambda where: RowContext(head.moving_ring, materials, where))
    loads, shares = _load(data.get("load"), base_dir)
    try:
        bearing = Bearing(head.name, rows)
    except ValueError as exc:
        raise CaseError(f"rows: {exc}") from None
    rings = data.get("rings", {})
    if not isinstance(rings, Mapping):
        raise CaseError(f"rings: expected [rings.inner] and/or [rings.outer] tables, got {rings!r:.60}")
    rings = ring_models(bearing, head.moving_ring, rings, materials, base_dir)
    return BearingDescription(head.name, head.description, bearing, loads, shares, source, case_depths, rings,
                              separators)


def loads_bearing(text: str, source: str = "<string>", base_dir: Path | None = None) -> BearingDescription:
    """A :class:`BearingDescription` from TOML text."""
    return bearing_from_mapping(parse_toml(text, source), base_dir, source)


def read_bearing_file(path: str | Path) -> BearingDescription:
    """A :class:`BearingDescription` from a description file; CaseError naming the file or the key."""
    path = Path(path)
    if path.is_dir():
        raise CaseError(f"{path}: is a folder, not a bearing description file (.toml)")
    return bearing_from_mapping(read_toml(path), path.resolve().parent, str(path))

