"""Modal rings of a bearing file reduced: each ``[rings.X]`` ring held at its support (bolts or a
clamped face), its raceways sampled for the rows it carries, optionally with the static shapes of
the element forces at their places, and the probe of its compliance at a row's elements
(``bearing.rings = "auto"``, :mod:`cases.described.auto`). The ring models themselves (sections,
keys, meshes) are :mod:`cases.bearing_rings`."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from cms_reduction.craig_bampton import InterfaceError
from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from fem_rings.mesh import GmshError, QuadMeshError, TangledMeshError
from fem_rings.nodesets import PatchError
from mbd_core.quasistatic import Bearing
from mbd_core.quasistatic.flexible import FlexibleRing
from mbd_core.quasistatic.rows import FourPointRow, RollerRow

from .bearing_rings import MIN_RACEWAY_SAMPLES, RingModel, _element_size, ring_mesh_spec
from .config import CaseError

__all__ = ["ELEMENT_PATCH_SHARE", "two_sided", "element_patch_m", "reduce_ring", "probe_compliance_m_per_N",
           "probe_block", "contact_normals_rz", "flexible_rings"]


def _support(m: RingModel) -> InterfaceSpec:
    b = m.keys.bolts
    if b is None:
        r0, r1, _, _ = m.profile.bounds_m
        return InterfaceSpec(m.keys.clamped_face, (0.0,), math.pi * r1)
    angles = tuple(360.0 * (k + 0.5) / b.count for k in range(b.count))
    return InterfaceSpec(b.face, angles, b.washer_radius_m, pitch_radius_m=0.5 * b.pitch_diameter_m)


#: the raceway patch a rolling element's load is spread over, as a share of its diameter, when
#: ``element_load_shapes`` is on and ``raceway_spread_m`` is left out: the groove patch that the
#: slewing ring's fidelity ladder found to converge with the mesh (cases/slewing/README.md)
ELEMENT_PATCH_SHARE = 0.3


#: the share of a groove's room on either side of the contact point that a default patch may take
GROOVE_ROOM_SHARE = 0.9


def _default_spread_m(row, place) -> float:
    """The default raceway patch with element load shapes: ``ELEMENT_PATCH_SHARE`` of the element
    diameter, or less where the groove leaves less room on one side of the contact point (a box
    section's groove of an angular-contact row reaches only 25° beyond the contact angle: f·D·25°
    ≈ 0.23·D)."""
    spread = ELEMENT_PATCH_SHARE * _element_size(row)
    p = np.asarray(place.point_rz_m, float)
    for c, radius, a0, a1 in place.arcs:
        a = math.atan2(p[1] - c[1], p[0] - c[0])
        lo, hi = min(a0, a1), max(a0, a1)
        a = lo + (a - lo) % (2.0 * math.pi)
        if a <= hi:
            spread = min(spread, GROOVE_ROOM_SHARE * radius * min(a - lo, hi - a))
    return round(spread, 6)


def two_sided(row) -> bool:
    """A four-point or crossed roller row: its contacts lie on the two flanks of its groove."""
    return isinstance(row, FourPointRow) or getattr(row, "orientation", "") == "crossed"


def element_patch_m(m: RingModel, row) -> float:
    """The raceway patch of ``row``'s element load shapes on ring ``m`` (the file's
    ``raceway_spread_m``, else :func:`_default_spread_m`)."""
    spread = m.keys.raceway_spread_m
    return _default_spread_m(row, m.places[row.name]) if spread is None else spread


def _element_angles_deg(row) -> tuple:
    """The angles of ``row``'s elements at their first position, degrees."""
    first = math.degrees(row.first_azimuth_rad)
    return tuple((first + 360.0 * k / row.n_elements) % 360.0 for k in range(row.n_elements))


def _raceway_spec(m: RingModel, row, n_theta: int, probe_all: bool = False) -> RacewaySpec:
    """The sampled raceway of ``row`` on ring ``m``: its patch and, with ``element_load_shapes``, the
    static shapes of radial and axial element forces at the row's elements (their first position);
    the ring's compliance to an element force on the element patch at the first element (the
    truncation estimate's probe), or at every element (``probe_all``: ``auto``'s static response).
    A four-point or crossed row has no probe: its raceway sample lies at the groove's apex, between
    its two contact flanks, where no patch fits."""
    keys, place = m.keys, m.places[row.name]
    if keys.element_load_shapes and two_sided(row):
        kind = "four-point" if isinstance(row, FourPointRow) else "crossed roller"
        raise CaseError(f"rings.{m.name}.element_load_shapes: not for the {kind} row {row.name!r} yet (its "
                        "contacts lie on the two sides of its groove, away from the raceway sample at the apex)")
    spread = keys.raceway_spread_m
    if spread is None:
        spread = _default_spread_m(row, place) if keys.element_load_shapes else 0.0
    places = _element_angles_deg(row)
    probe_m = 0.0 if two_sided(row) else element_patch_m(m, row)
    return RacewaySpec(m.raceways[row.name], n_theta, at_rz_m=tuple(map(float, place.point_rz_m)),
                       directions=place.directions, n_max=keys.raceway_harmonics, spread_m=spread,
                       element_angles_deg=places if keys.element_load_shapes else (), probe_spread_m=probe_m,
                       probe_angles_deg=places if probe_all else places[:1])


def _raceway_specs(m: RingModel, bearing: Bearing, probe_row: str | None) -> dict:
    """Row name → :func:`_raceway_spec` of every raceway of ring ``m``."""
    n_theta = max(MIN_RACEWAY_SAMPLES, 4 * max(r.n_elements for r in bearing.rows))
    rows = {r.name: r for r in bearing.rows}
    return {name: _raceway_spec(m, rows[name], n_theta, name == probe_row) for name in m.places}


def probe_block(m: RingModel, bearing: Bearing, row_name: str, matrix, probe_row: str | None = None):
    """The rows and columns of a probe matrix of ring ``m``'s reduction (metadata
    ``probe_compliance_m_per_N`` or ``residual_compliance_m_per_N``) that belong to ``row_name``'s
    raceway, or None when that raceway has no probe; ``probe_row`` as the reduction had it."""
    start = 0
    for name, spec in _raceway_specs(m, bearing, probe_row).items():
        n = 2 * len(spec.probe_angles_deg) if spec.probe_spread_m > 0.0 else 0
        if name == row_name:
            return None if n == 0 else np.asarray(matrix, float)[start:start + n, start:start + n]
        start += n
    raise KeyError(row_name)


def reduce_ring(m: RingModel, bearing: Bearing, probe_row: str | None = None):
    """The reduced body of a ring (built once, then loaded from the cache); ``probe_row``: measure
    the ring's compliance at every element of that row (:func:`_raceway_spec`)."""
    raceways = tuple(_raceway_specs(m, bearing, probe_row).values())
    spec = ReductionSpec(n_modes=m.keys.n_modes, interfaces=(_support(m),), raceways=raceways)
    try:
        return reduced_body(m.profile, ring_mesh_spec(m), m.material, spec, name=f"{bearing.name}: {m.name} ring")
    except PatchError as exc:
        raise CaseError(f"rings.{m.name}.raceway_spread_m: {exc}; give a smaller patch (with element_load_shapes "
                        f"its default is {ELEMENT_PATCH_SHARE:g} × the element diameter)") from None
    except QuadMeshError as exc:
        raise CaseError(f"rings.{m.name}.element: {exc} (element = \"tet10\" in [rings.{m.name}])") from None
    except TangledMeshError as exc:
        raise CaseError(f"rings.{m.name}.element_size_m: {exc}") from None
    except GmshError as exc:
        key = "step_file" if m.solid is not None else "element_size_m"
        raise CaseError(f"rings.{m.name}.{key}: {exc}") from None
    except InterfaceError as exc:
        key = "bolts.washer_diameter_m" if m.keys.bolts is not None else "clamped_face"
        raise CaseError(f"rings.{m.name}.{key}: the support cannot be built on this mesh ({exc}); change the washer "
                        f"or element_size_m (now {ring_mesh_spec(m).size_m * 1e3:.4g} mm)") from None


def probe_compliance_m_per_N(m: RingModel, bearing: Bearing, row_name: str, n_modes: int) -> np.ndarray:
    """(2Z, 2Z) compliance of ring ``m`` held at its support to radial and axial forces at the Z
    elements of ``row_name`` (their first position; radial then axial at each element in turn),
    spread over the element patch (:func:`element_patch_m`), m/N; reduced on the file's mesh with
    ``n_modes`` modes and no load shapes (the probe is the static solution itself). Not for a
    four-point or crossed row (:func:`_raceway_spec`)."""
    keys = dataclasses.replace(m.keys, n_modes=n_modes, raceway_harmonics=0, element_load_shapes=False)
    m = dataclasses.replace(m, keys=keys)
    body = reduce_ring(m, bearing, probe_row=row_name)
    return probe_block(m, bearing, row_name, body.metadata["probe_compliance_m_per_N"], probe_row=row_name)


def contact_normals_rz(m: RingModel, row, alpha_rad) -> np.ndarray:
    """(Z, 2) contact normal of each element of ``row`` on ring ``m``, into the ring's material, in its
    (r, z) section: the loaded contact angle with the groove's signs (a ball row), the raceway face's
    normal (a roller row)."""
    from .ring_sections import FACE_AXES

    place = m.places[row.name]
    alpha = np.asarray(alpha_rad, float)
    if isinstance(row, RollerRow) or not place.arcs:
        return np.tile(np.asarray(FACE_AXES[place.face][1], float), (alpha.size, 1))
    into = np.asarray(place.point_rz_m, float) - np.asarray(place.arcs[0][0], float)
    return np.column_stack((np.copysign(np.cos(alpha), into[0]), np.copysign(np.sin(alpha), into[1])))


def flexible_rings(models: dict[str, RingModel], bearing: Bearing) -> tuple[FlexibleRing, ...]:
    """The :class:`FlexibleRing` of every ring model (reducing or loading each body)."""
    return tuple(FlexibleRing(m.name, reduce_ring(m, bearing), m.side, dict(m.raceways)) for m in models.values())
