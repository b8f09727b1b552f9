"""From a ring description to a cached reduced body: the one call a case makes.

``reduced_body(profile, mesh_spec, material, spec)`` builds the FE model (cached by fem_rings),
condenses the interfaces, reduces with optional raceway augmentation, samples the raceways,
computes the inertia invariants and, when asked, the stress modes — and stores the result keyed
by a hash of every input, so a second run loads it in a fraction of a second.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, replace

from fem_rings.cache import input_hash
from fem_rings.mesh import MESH_VERSION, MeshSpec
from fem_rings.model import build_model
from fem_rings.nodesets import patch_nodes, raceway_curve, raceway_patch
from fem_rings.profile import Profile
from fem_rings.spinning import centrifugal_geometric_stiffness, statically_determinate_holds
from foundation.materials import ElasticMaterial
from foundation.progress import phase

from .body import ReducedBody
from .augmentation import Augmentation, CentrifugalAugmentation, ElementAugmentation
from .craig_bampton import Interface, InterfaceError, reduce_model
from .invariants import compute_invariants
from .persist import cached_body
from .prestress import SPIN_STIFFENING
from .sampling import pocket_contact_points, sample_across, sample_points, sample_raceway, sample_to_arrays
from .stress_modes import add_stress_modes

__all__ = ["InterfaceSpec", "RacewaySpec", "ReductionSpec", "reduced_body"]

log = logging.getLogger(__name__)

#: Version of the reduction algorithm, part of the cache key: a change that alters the bodies built
#: from the same inputs bumps it, so stale cached bodies are not reused. 2: rigid-body modes by
#: deflation (no frequency threshold), fixed start vector and canonical degenerate pairs, block
#: orthonormalisation of the basis.
REDUCTION_VERSION = 2


@dataclass(frozen=True)
class InterfaceSpec:
    """Patches of a named surface condensed to master nodes (one per angle).

    Parameters
    ----------
    facet_set : str
        Profile segment the patches lie on (e.g. ``"bolt_face"``).
    angles_deg : tuple of float
        Patch centres round the ring, degrees.
    half_width_m : float
        Patch half-length along the circumference, m; with ``pitch_radius_m`` the radius of a disc.
    grounded : bool
        Held (bolted to a rigid housing) or kept as boundary DOFs.
    kind : {"rigid", "averaging"}
        RBE2-like or RBE3-like condensation (:class:`cms_reduction.craig_bampton.Interface`).
    pitch_radius_m : float or None
        None: each patch is a strip across the surface. Else each patch is a disc (a bolt's
        washer) of radius ``half_width_m`` centred at this radius (bolt pitch circle), m.
    """

    facet_set: str
    angles_deg: tuple
    half_width_m: float
    grounded: bool = True
    kind: str = "rigid"
    pitch_radius_m: float | None = None


@dataclass(frozen=True)
class RacewaySpec:
    """A raceway sampled for moving contacts and (optionally) used for load-mode augmentation.

    ``at_rz_m`` is the contact point in the section (e.g. the nominal ball contact on a groove);
    ``directions``/``n_max`` set the augmentation harmonics (``n_max < 0``: no augmentation);
    ``n_across > 0`` samples a (θ, s) grid of that many circles across a straight raceway (roller
    slices) instead of one circle. ``element_angles_deg`` adds the static shapes of radial and axial
    forces at those angles (the rolling elements' places in a scene), each spread over the patch
    and over ±``spread_m`` along the circumference (:class:`.augmentation.ElementAugmentation`).
    ``spread_m > 0`` averages the sampled mode shapes over a patch
    of the section of that size around the contact point and spreads the load shapes' line loads
    over the same patch (:func:`fem_rings.nodesets.raceway_patch`): a sampling that converges with
    the mesh, where the line itself (0, the default) sits on the log-singular displacement of its
    own line load. (The harmonics still matter: a ball's load needs many of them to be resolved.)
    ``probe_spread_m > 0`` measures the residual flexibility of the basis at θ = 0: the compliance
    to unit radial and axial forces spread over a patch of that size (as ``element_angles_deg``)
    that the kept modes and shapes do not hold (metadata ``residual_compliance_m_per_N``, radial
    then axial, m/N; :func:`.craig_bampton.residual_compliance`), an estimate of the truncation
    error that costs two solves with the factor the reduction has. ``probe_angles_deg``: the
    angles of those probe forces (two solves each); the compliance (metadata
    ``probe_compliance_m_per_N``) is then (2k, 2k), radial and axial at each angle in turn.
    """

    segment: str
    n_theta: int = 360
    at_rz_m: tuple | None = None
    directions: tuple = ("normal",)
    n_max: int = 8
    n_across: int = 0
    spread_m: float = 0.0
    element_angles_deg: tuple = ()
    probe_spread_m: float = 0.0
    probe_angles_deg: tuple = (0.0,)

    def __post_init__(self) -> None:
        if not self.probe_angles_deg or not all(math.isfinite(a) for a in self.probe_angles_deg):
            raise ValueError(f"raceway {self.segment!r}: probe_angles_deg must hold finite angles, got "
                             f"{self.probe_angles_deg!r}")
        p = float(self.probe_spread_m)
        if not (math.isfinite(p) and p >= 0.0):
            raise ValueError(f"raceway {self.segment!r}: probe_spread_m must be ≥ 0 and finite, got {self.probe_spread_m!r}")
        s = float(self.spread_m)
        if not (math.isfinite(s) and s >= 0.0):
            raise ValueError(f"raceway {self.segment!r}: spread_m must be ≥ 0 and finite, got {self.spread_m!r}")
        if self.element_angles_deg and s <= 0.0:
            raise ValueError(f"raceway {self.segment!r}: element_angles_deg needs spread_m > 0 (a force at a "
                             "point of a solid has an unbounded displacement there)")
        if s > 0.0 and self.n_across > 0:
            raise ValueError(f"raceway {self.segment!r}: spread_m applies to one circle of samples; "
                             f"it cannot be combined with n_across = {self.n_across}")


@dataclass(frozen=True)
class ReductionSpec:
    """What to keep of a ring: normal modes, interfaces, raceways, damping, stress modes, and (with
    ``centrifugal``) the static shape of the ring's centrifugal stretch for bodies that spin; with
    ``spin_stiffening`` the modal geometric stiffness of the centrifugal prestress at 1 rad/s about z
    (``extras["spin_stiffening"]``, for :func:`.prestress.prestressed`)."""

    n_modes: int = 20
    interfaces: tuple = ()
    raceways: tuple = ()
    damping_ratio: float = 0.0
    stress_modes: bool = False
    sample_pockets: bool = True
    centrifugal: bool = False
    spin_stiffening: bool = False

    def __post_init__(self) -> None:
        if int(self.n_modes) < 1:
            raise ValueError(f"reduction spec: n_modes must be ≥ 1, got {self.n_modes}")
        if not 0.0 <= float(self.damping_ratio) < 1.0:
            raise ValueError(f"reduction spec: damping_ratio must lie in [0, 1), got {self.damping_ratio}")


def _patch(ring, spec: InterfaceSpec, angle_deg: float):
    """The nodes of one interface patch; InterfaceError when the patch holds no node of the mesh."""
    try:
        return patch_nodes(ring, spec.facet_set, angle_deg, spec.half_width_m, at_radius_m=spec.pitch_radius_m)
    except ValueError as exc:
        raise InterfaceError(f"interface {spec.facet_set}@{angle_deg:g}°: {exc}") from None


def reduced_body(profile: Profile, mesh_spec: MeshSpec, material: ElasticMaterial, spec: ReductionSpec,
                 pockets=None, *, name: str | None = None, use_cache: bool = True) -> ReducedBody:
    """Build (or load from the cache) the reduced body of a ring."""
    key = input_hash("reduced-body", REDUCTION_VERSION, MESH_VERSION, profile, mesh_spec, material, spec, pockets, name)

    def build() -> ReducedBody:
        with phase(f"reducing {name or profile.name}"):
            return _build()

    def _build() -> ReducedBody:
        model = build_model(profile, mesh_spec, material, pockets, use_cache=use_cache)
        interfaces = [Interface(f"{i.facet_set}@{a:g}°", _patch(model.ring, i, a), grounded=i.grounded, kind=i.kind)
                      for i in spec.interfaces for a in i.angles_deg]
        curves = [raceway_curve(model.ring, r.segment, r.n_theta, r.at_rz_m) for r in spec.raceways]
        patches = [tuple(raceway_patch(c, model.ring.profile, r.spread_m)) if r.spread_m > 0 else ()
                   for c, r in zip(curves, spec.raceways)]
        aug = [Augmentation(c, r.directions, r.n_max, patch=pt)
               for c, r, pt in zip(curves, spec.raceways, patches) if r.n_max >= 0]
        aug += [ElementAugmentation(c, tuple(math.radians(a) for a in r.element_angles_deg), pt, r.spread_m)
                for c, r, pt in zip(curves, spec.raceways, patches) if r.element_angles_deg]
        if spec.centrifugal:
            aug.append(CentrifugalAugmentation())
        probes = [ElementAugmentation(c, tuple(math.radians(a) for a in r.probe_angles_deg),
                                      tuple(raceway_patch(c, model.ring.profile, r.probe_spread_m)), r.probe_spread_m)
                  for c, r in zip(curves, spec.raceways) if r.probe_spread_m > 0]
        body = reduce_model(model, spec.n_modes, interfaces, aug, damping_ratio=spec.damping_ratio,
                            name=name or profile.name, probes=probes)
        with phase("inertia invariants"):
            extras = dict(compute_invariants(model.M, body.nodes_m, body.shapes).to_arrays())
        if spec.spin_stiffening:
            with phase("centrifugal stress stiffening"):
                K_sigma, _ = centrifugal_geometric_stiffness(model, statically_determinate_holds(model))
                extras[SPIN_STIFFENING] = body.shapes.T @ (K_sigma @ body.shapes)
        with phase("sampling raceways", total=len(spec.raceways) + (pockets is not None and spec.sample_pockets)) as p:
            for c, r, pt in zip(curves, spec.raceways, patches):
                samples = (sample_across(body, model.ring, r.segment, r.n_theta, r.n_across) if r.n_across > 0
                           else [sample_raceway(body, c, mesh_spec.full_circle, pt)])
                for smp in samples:
                    extras.update(sample_to_arrays(smp))
                p.advance()
            if pockets is not None and spec.sample_pockets:
                pts, th = pocket_contact_points(pockets)
                extras.update(sample_to_arrays(sample_points(body, "pockets", pts, th)))
                p.advance()
        body = replace(body, extras=extras, metadata={**body.metadata, "input_hash": key,
                                                       "material": material.name,
                                                       "element": mesh_spec.element,
                                                       "element_size_m": mesh_spec.size_m})
        if spec.stress_modes:
            body = add_stress_modes(body, model)
        return body

    if not use_cache:
        return build()
    return cached_body(key, build)
