"""Modal rings of a described bearing: the ``[rings.inner]`` / ``[rings.outer]`` tables.

A ring given a table bends: its section (a box around the rows' raceways, a profile of lines
and arcs, or a DXF drawing of one: :mod:`.ring_sections`, :mod:`fem_rings.dxf_section`) is revolved, meshed with quadratic hexahedra, held at its support
(bolts on a pitch circle, or a whole face) and reduced by Craig–Bampton with raceway load shapes
(:func:`cms_reduction.reduced_body`, cached on disk by its inputs). The fixed ring is held against
the ground; the moving ring's support rides on the moving ring's rigid displacement q (the
structure bolted to it is taken as rigid). The reduced rings enter the quasi-static load
distribution of :mod:`mbd_core.quasistatic.flexible`.

Support of a ring (one of):

- ``[rings.X.bolts]``: ``count`` bolts on ``pitch_diameter_m`` through ``face`` (``"top"`` or
  ``"bottom"`` of a box section, a segment name of a profile), each held over a washer disc of
  ``washer_diameter_m`` (default: half the bolt spacing, an assumption for a bolted joint whose
  clamped area is not known);
- ``clamped_face = NAME``: the whole face held (a ring on a stiff, continuous seat).

A whole ring can come from a STEP solid (``step_file``; gear teeth, bolt holes): it is meshed with
quadratic tetrahedra, and the section (any of the three) then names the solid's faces — the raceways
and the support face must lie on it, which is checked before meshing
(:func:`fem_rings.step_solid.check_step_solid` with probe points).

The format reference is ``cases/bearings/README.md``.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import numpy as np

from fem_rings.dxf_section import profile_from_dxf
from fem_rings.mesh import MeshSpec
from fem_rings.profile import Arc, Line, Profile, ProfileError
from fem_rings.step_solid import StepSolid, check_step_solid, step_solid
from foundation.materials import ElasticMaterial
from mbd_core.quasistatic import Bearing
from mbd_core.quasistatic.rows import RollerRow

from .config import CaseError, from_mapping
from .mesh_budget import check_model_size
from .ring_sections import box_section, match_raceways, raceway_places

__all__ = ["RingKeys", "BoltKeys", "RingModel", "ring_models", "ring_profile", "ring_part_of", "ring_mesh_spec", "with_fidelity", "RING_NAMES"]

RING_NAMES = ("inner", "outer")
#: Raceway samples round a ring: at least this many, and at least four per rolling element.
MIN_RACEWAY_SAMPLES = 360


@dataclass(frozen=True)
class BoltKeys:
    """``[rings.X.bolts]``: bolts through a face on a pitch circle."""

    count: int
    pitch_diameter_m: float
    face: str
    washer_diameter_m: float | None = None

    def __post_init__(self) -> None:
        if not 3 <= self.count <= 2000:
            raise ValueError(f"count: must lie in 3 … 2000, got {self.count}")
        if not (math.isfinite(self.pitch_diameter_m) and self.pitch_diameter_m > 0.0):
            raise ValueError(f"pitch_diameter_m: must be > 0, got {self.pitch_diameter_m!r}")
        w = self.washer_diameter_m
        if w is not None and not (math.isfinite(w) and w > 0.0):
            raise ValueError(f"washer_diameter_m: must be > 0, got {w!r}")

    @property
    def washer_radius_m(self) -> float:
        if self.washer_diameter_m is not None:
            return 0.5 * self.washer_diameter_m
        return 0.25 * math.pi * self.pitch_diameter_m / self.count


@dataclass(frozen=True)
class RingKeys:
    """``[rings.inner]`` / ``[rings.outer]`` (format reference: cases/bearings/README.md)."""

    section: Literal["box", "profile", "dxf"] = "box"
    inner_diameter_m: float | None = None
    outer_diameter_m: float | None = None
    z_min_m: float | None = None
    z_max_m: float | None = None
    segments: tuple[Any, ...] = ()
    dxf_file: str | None = None
    dxf_unit: Literal["mm", "m", "file"] = "mm"
    material: str = "bearing_steel"
    bolts: BoltKeys | None = None
    clamped_face: str | None = None
    n_modes: int = 20
    raceway_harmonics: int = 8
    element_load_shapes: bool = False
    raceway_spread_m: float | None = None
    element_size_m: float | None = None
    element: Literal["hex27", "tet10"] | None = None
    step_file: str | None = None
    step_unit: Literal["mm", "m", "file"] = "mm"

    def __post_init__(self) -> None:
        for key in ("inner_diameter_m", "outer_diameter_m", "z_min_m", "z_max_m", "element_size_m", "raceway_spread_m"):
            v = getattr(self, key)
            if v is not None and not math.isfinite(v):
                raise ValueError(f"{key}: must be a finite number, got {v!r}")
        for key in ("inner_diameter_m", "outer_diameter_m", "element_size_m"):
            v = getattr(self, key)
            if v is not None and not v > 0.0:
                raise ValueError(f"{key}: must be > 0, got {v!r}")
        if (self.bolts is None) == (self.clamped_face is None):
            raise ValueError("bolts: give the ring's support: a [bolts] table or clamped_face (one of them)")
        if self.raceway_spread_m is not None and self.raceway_spread_m < 0.0:
            raise ValueError(f"raceway_spread_m: must be ≥ 0, got {self.raceway_spread_m!r}")
        if self.element_load_shapes and self.raceway_spread_m == 0.0:
            raise ValueError("raceway_spread_m: element_load_shapes need a patch > 0 (a force at a point of a solid "
                             "has an unbounded displacement there); leave it out for 0.3 × the element diameter")
        if not 1 <= self.n_modes <= 400:
            raise ValueError(f"n_modes: must lie in 1 … 400, got {self.n_modes}")
        if not 0 <= self.raceway_harmonics <= 60:
            raise ValueError(f"raceway_harmonics: must lie in 0 … 60, got {self.raceway_harmonics}")
        if self.section != "profile" and self.segments:
            raise ValueError("segments: only for section = \"profile\"")
        if self.section != "dxf" and self.dxf_file is not None:
            raise ValueError("dxf_file: only for section = \"dxf\"")
        if self.section == "profile" and not self.segments:
            raise ValueError("segments: missing key (a profile section needs its [[segments]])")
        if self.section == "dxf" and not (self.dxf_file or "").strip():
            raise ValueError("dxf_file: missing key (the DXF drawing of the section, path relative to this file)")
        if self.step_file is not None and not self.step_file.strip():
            raise ValueError("step_file: must be a path (the STEP solid of the ring, relative to this file)")
        if self.step_file is not None and self.element == "hex27":
            raise ValueError("element: a STEP solid is meshed with \"tet10\" (hex27 sweeps a section); leave element out")
        if self.section != "box":
            given = [k for k in ("inner_diameter_m", "outer_diameter_m", "z_min_m", "z_max_m") if getattr(self, k) is not None]
            if given:
                raise ValueError(f"{given[0]}: only for section = \"box\" (a {self.section} gives its own outline)")

    @property
    def support_face(self) -> str:
        return self.bolts.face if self.bolts is not None else self.clamped_face

    @property
    def support_key(self) -> str:
        return "bolts.face" if self.bolts is not None else "clamped_face"

    @property
    def mesh_element(self) -> str:
        """tet10 for a STEP solid, else the element asked for (hex27 by default)."""
        return "tet10" if self.step_file is not None else (self.element or "hex27")


@dataclass(frozen=True)
class RingModel:
    """A ring ready to reduce: which side it is, its section, where its raceways lie, its support."""

    name: str
    side: str  # "moving" or "fixed"
    profile: Profile
    raceways: dict  # row name → segment (sample) name
    places: dict  # row name → RacewayPlace
    keys: RingKeys
    material: ElasticMaterial
    solid: StepSolid | None = None


def _point(value, at: str) -> tuple[float, float]:
    if not (isinstance(value, (list, tuple)) and len(value) == 2
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in value)):
        raise CaseError(f"{at}: expected [r, z] in metres, got {value!r:.60}")
    return (float(value[0]), float(value[1]))


_SEGMENT_KEYS = {"line": {"start_m", "end_m", "name"}, "arc": {"start_m", "end_m", "centre_m", "direction", "name"}}


def _segment(table, at: str):
    if not isinstance(table, dict):
        raise CaseError(f"{at}: expected a table, got {table!r:.60}")
    kind = table.get("kind")
    if kind not in _SEGMENT_KEYS:
        raise CaseError(f"{at}.kind: must be \"line\" or \"arc\", got {kind!r:.40}")
    unknown = sorted(set(table) - _SEGMENT_KEYS[kind] - {"kind"})
    if unknown:
        raise CaseError(f"{at}.{unknown[0]}: unknown key (known: kind, {', '.join(sorted(_SEGMENT_KEYS[kind]))})")
    for key in sorted(_SEGMENT_KEYS[kind] - {"name", "direction"}):
        if key not in table:
            raise CaseError(f"{at}.{key}: missing key")
    name = table.get("name", "face")
    if not isinstance(name, str) or not name.strip():
        raise CaseError(f"{at}.name: must be a non-empty string, got {name!r:.40}")
    start, end = _point(table["start_m"], f"{at}.start_m"), _point(table["end_m"], f"{at}.end_m")
    try:
        if kind == "line":
            return Line(start, end, name)
        direction = table.get("direction", "ccw")
        if direction not in ("ccw", "cw"):
            raise CaseError(f"{at}.direction: must be \"ccw\" or \"cw\", got {direction!r:.40}")
        return Arc(start, end, _point(table["centre_m"], f"{at}.centre_m"), direction == "ccw", name)
    except ProfileError as exc:
        raise CaseError(f"{at}: {exc}") from None


def _file(value: str, key: str, base_dir: Path | None) -> Path:
    path = Path(value)
    if not path.is_absolute():
        if base_dir is None:
            raise CaseError(f"{key}: a relative path needs the description file's folder")
        path = base_dir / path
    return path


def _profile(keys: RingKeys, name: str, places: dict, where: str, base_dir: Path | None) -> Profile:
    if keys.section == "dxf":
        path = _file(keys.dxf_file, f"{where}.dxf_file", base_dir)
        try:
            return profile_from_dxf(path, name=name, unit=keys.dxf_unit)
        except ProfileError as exc:
            raise CaseError(f"{where}.dxf_file: {exc}") from None
    if keys.section == "profile":
        segs = tuple(_segment(t, f"{where}.segments[{i}]") for i, t in enumerate(keys.segments))
        try:
            return Profile(name, segs)
        except ProfileError as exc:
            raise CaseError(f"{where}.segments: {exc}") from None
    r = lambda d: None if d is None else 0.5 * d  # noqa: E731
    sides = {"r_in_m": r(keys.inner_diameter_m), "r_out_m": r(keys.outer_diameter_m),
             "z_min_m": keys.z_min_m, "z_max_m": keys.z_max_m}
    key_of = {"r_in_m": "inner_diameter_m", "r_out_m": "outer_diameter_m", "z_min_m": "z_min_m", "z_max_m": "z_max_m"}
    try:
        return box_section(name, places, sides)
    except (ValueError, ProfileError) as exc:
        text = str(exc)
        head, _, rest = text.partition(": ")
        raise CaseError(f"{where}.{key_of.get(head, head)}: {rest}" if head in key_of or head == "rows"
                        else f"{where}: {text}") from None


def _element_size(row) -> float:
    return row.roller_diameter_m if isinstance(row, RollerRow) else row.ball_diameter_m


def ring_profile(bearing: Bearing, ring: str, moving_ring: str, keys: RingKeys, where: str,
                 base_dir: Path | None = None):
    """(side, profile, raceways, places) of the ``"inner"`` or ``"outer"`` ring; CaseError naming the key."""
    side = "moving" if ring == moving_ring else "fixed"
    try:
        places = raceway_places(bearing, side)
    except ValueError as exc:
        raise CaseError(f"{where}: {exc}") from None
    profile = _profile(keys, f"{ring} ring", places, where, base_dir)
    try:
        raceways = match_raceways(profile, places, {r.name: _element_size(r) for r in bearing.rows})
    except ValueError as exc:
        key = {"profile": "segments", "dxf": "dxf_file"}.get(keys.section, "section")
        raise CaseError(f"{where}.{key}: {exc}") from None
    face = keys.support_face
    if face not in profile.names:
        raise CaseError(f"{where}.{keys.support_key}: the section has no face {face!r}; its faces: "
                        f"{', '.join(profile.names)}")
    if face in raceways.values():
        raise CaseError(f"{where}.{keys.support_key}: {face!r} carries a raceway; support the ring on another face")
    return side, profile, raceways, places


#: azimuths at which a STEP solid must carry a row's raceway and the support face
STEP_PROBE_AZIMUTHS = 12
#: how far (share of the section's size) a probe point may lie from the solid's nearest face
STEP_PROBE_TOLERANCE = 1e-3


def _step_probes(keys: RingKeys, profile: Profile, places: dict) -> list[tuple[str, np.ndarray]]:
    """(what, (x, y, z) points) the solid must carry on its faces: each row's raceway contact point
    and the middle of each support-face segment, at up to ``STEP_PROBE_AZIMUTHS`` azimuths, taken
    halfway between bolts (the k-th bolt, and its hole, sits at (k + ½)·360°/count)."""
    psi = 2.0 * np.pi * np.arange(STEP_PROBE_AZIMUTHS) / STEP_PROBE_AZIMUTHS
    if keys.bolts is not None:
        n = keys.bolts.count
        psi = 2.0 * np.pi * np.unique(np.round(np.arange(STEP_PROBE_AZIMUTHS) * n / STEP_PROBE_AZIMUTHS)) / n

    def ring(rz) -> np.ndarray:
        return np.column_stack((rz[0] * np.cos(psi), rz[0] * np.sin(psi), np.full_like(psi, rz[1])))

    out = [(f"the raceway of row {row!r}", ring(np.asarray(place.point_rz_m, float))) for row, place in places.items()]
    for seg in profile.segments:
        if seg.name == keys.support_face:
            out.append((f"the support face {seg.name!r}", ring(seg.points(np.array([0.5]))[0])))
    return out


def _step_solid(keys: RingKeys, profile: Profile, places: dict, where: str, base_dir: Path | None) -> StepSolid:
    """The checked STEP solid of a ring: a solid ring about z whose faces carry the section's raceways
    and support face (CaseError naming ``step_file`` otherwise); before any meshing."""
    key = f"{where}.step_file"
    path = _file(keys.step_file, key, base_dir)
    probes = _step_probes(keys, profile, places)
    try:
        info = check_step_solid(path, unit=keys.step_unit, probes_m=np.concatenate([p for _, p in probes]))
        solid = step_solid(path, keys.step_unit)
    except ValueError as exc:  # the checker speaks of its argument unit=…; the file's key is step_unit
        text = str(exc).replace("pass unit='file' to use", 'step_unit = "file" uses').replace("unit=", "step_unit = ")
        raise CaseError(f"{key}: {text}") from None
    if not info.is_ring_about_z:
        raise CaseError(f"{key}: {path.name} is not a ring about the z axis ({info.not_ring_reason})")
    if info.n_volumes != 1:
        raise CaseError(f"{key}: {path.name} holds {info.n_volumes} solids; a ring is one (fuse its parts in the CAD "
                        "model, or describe each ring in its own table)")
    tol = STEP_PROBE_TOLERANCE * profile.size_m
    d = np.asarray(info.probe_distances_m)
    start = 0
    for what, pts in probes:
        worst = float(d[start:start + len(pts)].max())
        start += len(pts)
        if worst > tol:
            raise CaseError(f"{key}: the solid has no face at {what} of the section ({keys.section}): a point of it "
                            f"lies {1e3 * worst:.3g} mm from the nearest face (allowed {1e3 * tol:.2g} mm); the "
                            "section must describe the solid's raceways and support face")
    return solid


def ring_models(bearing: Bearing, moving_ring: str, tables: dict, materials: dict,
                base_dir: Path | None = None) -> dict[str, RingModel]:
    """Validated :class:`RingModel` of every ``[rings.X]`` table (before any meshing); ``base_dir``:
    the description file's folder (for a DXF section's relative path)."""
    out = {}
    for ring, table in tables.items():
        where = f"rings.{ring}"
        if ring not in RING_NAMES:
            raise CaseError(f"{where}: unknown ring (known: {', '.join(RING_NAMES)})")
        keys = from_mapping(RingKeys, table, where)
        if keys.material not in materials:
            raise CaseError(f"{where}.material: unknown material {keys.material!r}; known: {', '.join(sorted(materials))}")
        side, profile, raceways, places = ring_profile(bearing, ring, moving_ring, keys, where, base_dir)
        solid = None if keys.step_file is None else _step_solid(keys, profile, places, where, base_dir)
        model = RingModel(ring, side, profile, raceways, places, keys, materials[keys.material], solid)
        try:  # the mesh can give the modes and fits in memory (estimated before any meshing)
            check_model_size(profile, ring_mesh_spec(model).size_m, keys.n_modes, f"{where}.element_size_m",
                             f"{where}.n_modes", n_rigid=0)
        except ValueError as exc:
            raise CaseError(str(exc)) from None
        out[ring] = model
    return out


def _element_size_m(profile: Profile, keys: RingKeys) -> float:
    """The ring's element size: its key, or a third of the section's smaller side."""
    r0, r1, z0, z1 = profile.bounds_m
    return keys.element_size_m or min(r1 - r0, z1 - z0) / 3.0


def ring_mesh_spec(m: RingModel) -> MeshSpec:
    """The mesh a ring model is reduced on (its element, size and, for a STEP ring, its solid)."""
    return MeshSpec(_element_size_m(m.profile, m.keys), m.keys.mesh_element, solid=m.solid)


def with_fidelity(models: dict[str, RingModel], overrides: dict, where: str = "rings") -> dict[str, RingModel]:
    """The ring models with ``overrides`` of their keys (``n_modes``, ``raceway_harmonics``,
    ``element_load_shapes``; ``element_size_factor`` scales each ring's element size), checked as
    the file's own values are; CaseError naming ``where.key``."""
    if not overrides:
        return dict(models)
    if not models:
        key = next(iter(overrides))
        raise CaseError(f"{where}.{key}: the bearing file gives no [rings.X] tables (its rings are rigid); "
                        "leave the key out")
    out = {}
    for name, m in models.items():
        changes = {k: v for k, v in overrides.items() if k != "element_size_factor"}
        factor = overrides.get("element_size_factor", 1.0)
        if factor != 1.0:
            changes["element_size_m"] = round(factor * _element_size_m(m.profile, m.keys), 9)
        try:
            keys = dataclasses.replace(m.keys, **changes)
            check_model_size(m.profile, _element_size_m(m.profile, keys), keys.n_modes,
                             f"{where}.element_size_factor", f"{where}.n_modes", n_rigid=0)
        except ValueError as exc:
            text = str(exc)
            if text.startswith(f"{where}."):
                raise CaseError(text) from None
            head, _, rest = text.partition(": ")
            key = {"element_size_m": "element_size_factor", "raceway_spread_m": "element_load_shapes"}.get(head, head)
            raise CaseError(f"{where}.{key}: {rest} (ring {name}: {head} in the bearing file)") from None
        out[name] = dataclasses.replace(m, keys=keys)
    return out


def ring_part_of(desc, ring: str):
    """A described bearing's ``"inner"`` or ``"outer"`` ring as a :class:`cases.parts.RingPart`
    (``flexbearing modes FILE --ring …``); ValueError naming ``--ring`` when the file gives that ring
    no ``[rings.X]`` table."""
    from .parts import RingPart

    if ring not in desc.rings:
        given = ", ".join(desc.rings) or "none"
        raise ValueError(f"--ring {ring}: the description file gives no [rings.{ring}] table (rings given: {given})")
    m = desc.rings[ring]
    what = f"STEP solid {Path(m.solid.path).name}" if m.solid is not None else f"{m.keys.section} section"
    return RingPart(f"{desc.name}: {ring} ring", lambda: (m.profile, None), m.material, ring_mesh_spec(m).size_m,
                    m.keys.mesh_element, f"{ring} ring of {desc.name} ({what})", m.solid)
