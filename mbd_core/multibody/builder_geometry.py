"""The contact geometry a :class:`~mbd_core.multibody.builder.ModelBuilder` collects: ball grooves,
roller raceways and ribs, cage pockets (rigid, or sampled on a modal body so that they deform with it),
and the builder's record of a body."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..kernels.element_contacts import POCKET_CYLINDER, POCKET_SLOT
from ..kernels.roller_slices import (
    RACEWAY_INNER_CYLINDER,
    RACEWAY_OUTER_CYLINDER,
    RACEWAY_PLANE_DOWN,
    RACEWAY_PLANE_UP,
)
from foundation.validation import check_positive

SURFACE_KINDS = {
    "inner_cylinder": RACEWAY_INNER_CYLINDER, "outer_cylinder": RACEWAY_OUTER_CYLINDER,
    "plane_up": RACEWAY_PLANE_UP, "plane_down": RACEWAY_PLANE_DOWN,
}
POCKET_KINDS = {"cylinder": POCKET_CYLINDER, "slot": POCKET_SLOT}


@dataclass
class _Body:
    name: str
    mass: float
    inertia: np.ndarray
    q: np.ndarray
    v: np.ndarray
    free: np.ndarray
    force: np.ndarray = field(default_factory=lambda: np.zeros(6))
    modal: dict | None = None
    frame_z_m: float = 0.0  # ring-frame height of the reference point (a free modal body's centre of mass)


def _vec(owner: str, name: str, value, n: int) -> np.ndarray:
    a = np.asarray(value, dtype=float).reshape(-1)
    if a.shape != (n,) or not np.all(np.isfinite(a)):
        raise ValueError(f"{owner}: {name} must be {n} finite numbers, got {value!r}")
    return a


class GeometryMixin:
    """Grooves, surfaces and pockets of :class:`~mbd_core.multibody.builder.ModelBuilder` (which holds
    ``_bodies``, ``_grooves``, ``_surfaces``, ``_pockets`` and ``_body_index``)."""

    # -- contact geometry -----------------------------------------------------------------------
    def add_groove(self, ring, centre_radius_m: float, centre_height_m: float, groove_radius_m: float,
                   undulation_m=None, radial_offset_m=None, raceway=None) -> int:
        """A groove on ``ring``: circle of curvature centres (radius, height in the ring frame) and f·D.

        ``undulation_m`` h(θ) and ``radial_offset_m`` Δr(θ): tables on a uniform grid over
        [0, 2π) (ring frame angle), interpolated linearly and periodically; None = 0.
        ``raceway``: on a modal ring, the sampled raceway the groove deforms with — a
        :class:`cms_reduction.sampling.RacewaySample` or the name of one stored with the body.
        """
        owner = "groove"
        r = self._body_index(ring, owner)
        check_positive(owner, centre_radius_m=centre_radius_m, groove_radius_m=groove_radius_m)
        if not math.isfinite(centre_height_m):
            raise ValueError(f"{owner}: centre_height_m must be finite")
        tables = []
        for name, tab in (("undulation_m", undulation_m), ("radial_offset_m", radial_offset_m)):
            a = np.zeros(1) if tab is None else np.asarray(tab, float).reshape(-1)
            if a.size == 0 or not np.all(np.isfinite(a)):
                raise ValueError(f"{owner}: {name} must be a non-empty table of finite values")
            tables.append(a)
        body = self._bodies[r]
        sample = self._raceway_sample(body, raceway, owner)
        self._grooves.append(dict(ring=r, rc=float(centre_radius_m), zc=float(centre_height_m) - body.frame_z_m,
                                  r=float(groove_radius_m), h=tables[0], dr=tables[1], sample=sample))
        return len(self._grooves) - 1

    @staticmethod
    def _raceway_sample(body: _Body, raceway, owner: str):
        """The raceway sample of a groove on a modal body (None on a rigid one), in the body's frame."""
        if body.modal is None:
            if raceway is not None:
                raise ValueError(f"{owner}: body {body.name!r} is rigid; a raceway sample needs a modal body")
            return None
        from cms_reduction.sampling import RacewaySample, samples_from_arrays

        reduced = body.modal["reduced"]
        if isinstance(raceway, str):
            samples = samples_from_arrays(reduced.extras)
            if raceway not in samples:
                raise ValueError(f"{owner}: modal body {body.name!r} has no raceway sample {raceway!r} "
                                 f"(has {sorted(samples)})")
            raceway = samples[raceway]
        if not isinstance(raceway, RacewaySample):
            raise ValueError(f"{owner}: a groove on modal body {body.name!r} needs raceway= (the sampled raceway "
                             "it deforms with, a RacewaySample or its name)")
        if raceway.displacement.shape[2] != reduced.n_modes:
            raise ValueError(f"{owner}: raceway sample {raceway.name!r} has {raceway.displacement.shape[2]} modes, "
                             f"the body {reduced.n_modes}")
        th = np.asarray(raceway.theta_rad, float)
        if raceway.periodic and th.size > 1 and not np.allclose(np.diff(th), 2 * np.pi / th.size, rtol=1e-6):
            raise ValueError(f"{owner}: raceway sample {raceway.name!r} must be uniform in θ over the full circle")
        return dict(theta=th, points=np.asarray(raceway.points_m, float) - body.modal["shift"],
                    disp=np.asarray(raceway.displacement, float), rot=np.asarray(raceway.rotation, float),
                    periodic=int(raceway.periodic))

    def add_surface(self, ring, kind: str, value_m: float, raceway=None, raceway_s_m=None) -> int:
        """A raceway or rib surface on ``ring``: kind in {inner_cylinder, outer_cylinder, plane_up,
        plane_down} with its radius or height ``value_m`` (ring frame).

        On a modal ring, ``raceway`` is the (θ, s) grid the surface deforms with (roller slices and
        roller ends on it then follow the ring's modes): a list of
        :class:`cms_reduction.sampling.RacewaySample` circles (or names of samples stored with the
        body), or one name — a stored sample, or a segment whose ``"<segment>@s<k>"`` circles
        (:func:`cms_reduction.sampling.sample_across`) are stored with the body. Every circle has the
        same angles. ``raceway_s_m`` (n_c,) is the coordinate of each circle across the surface in the
        ring's FE frame — z on a cylinder, r on a plane; None takes it from the sample points. A
        surface on a modal ring without ``raceway`` carries no contacts.
        """
        owner = "surface"
        r = self._body_index(ring, owner)
        if kind not in SURFACE_KINDS:
            raise ValueError(f"{owner}: kind must be one of {sorted(SURFACE_KINDS)}, got {kind!r}")
        if not math.isfinite(value_m) or (kind.endswith("cylinder") and value_m <= 0):
            raise ValueError(f"{owner}: value_m must be finite (and > 0 for a cylinder), got {value_m!r}")
        body = self._bodies[r]
        if kind.startswith("plane"):
            value_m -= body.frame_z_m
        grid = self._surface_grid(body, kind, raceway, raceway_s_m, owner)
        self._surfaces.append(dict(kind=SURFACE_KINDS[kind], value=float(value_m), ring=r, grid=grid))
        return len(self._surfaces) - 1

    def _surface_grid(self, body: _Body, kind: str, raceway, raceway_s_m, owner: str):
        """The (θ, s) grid of a surface on a modal body, circles by ascending s, in the body's frame."""
        if raceway is None:
            if raceway_s_m is not None:
                raise ValueError(f"{owner}: raceway_s_m needs raceway= (the sampled circles)")
            return None
        if body.modal is None:
            raise ValueError(f"{owner}: body {body.name!r} is rigid; a raceway sample needs a modal body")
        from cms_reduction.sampling import RacewaySample, samples_from_arrays

        if isinstance(raceway, str):
            stored = samples_from_arrays(body.modal["reduced"].extras)
            if raceway in stored:
                circles = [stored[raceway]]
            else:
                found = {int(n[len(raceway) + 2:]): smp for n, smp in stored.items()
                         if n.startswith(f"{raceway}@s") and n[len(raceway) + 2:].isdigit()}
                if not found:
                    raise ValueError(f"{owner}: modal body {body.name!r} has no raceway sample {raceway!r} and no "
                                     f"circles '{raceway}@s<k>' (has {sorted(stored)})")
                circles = [found[k] for k in sorted(found)]
        elif isinstance(raceway, RacewaySample):
            circles = [raceway]
        else:
            circles = list(raceway)
            if not circles:
                raise ValueError(f"{owner}: raceway must name at least one sampled circle")
        samples = [self._raceway_sample(body, c, owner) for c in circles]
        th0, periodic = samples[0]["theta"], samples[0]["periodic"]
        for smp in samples[1:]:
            if smp["periodic"] != periodic or smp["theta"].shape != th0.shape or not np.allclose(
                    smp["theta"], th0, rtol=0.0, atol=1e-12):
                raise ValueError(f"{owner}: every circle of a (θ, s) grid needs the same sample angles")
        cylinder = kind.endswith("cylinder")
        if raceway_s_m is None:
            coords = [smp["points"][:, 2] if cylinder else np.hypot(smp["points"][:, 0], smp["points"][:, 1])
                      for smp in samples]
            scale = max(float(np.abs(np.concatenate(coords)).max()), 1.0)
            if any(np.ptp(x) > 1e-9 * scale for x in coords):
                raise ValueError(f"{owner}: a sampled circle does not lie at one {'z' if cylinder else 'r'}: give "
                                 "raceway_s_m, the coordinate of each circle across the surface")
            s_m = np.array([x.mean() for x in coords])
        else:
            s_m = _vec(owner, "raceway_s_m", raceway_s_m, len(samples)) - (body.frame_z_m if cylinder else 0.0)
        order = np.argsort(s_m, kind="stable")
        s_m = s_m[order]
        if np.any(np.diff(s_m) <= 0.0):
            raise ValueError(f"{owner}: the circles of a (θ, s) grid need distinct coordinates s, got {s_m.tolist()}")
        samples = [samples[i] for i in order]
        return dict(theta=np.concatenate([smp["theta"] for smp in samples]),
                    points=np.concatenate([smp["points"] for smp in samples]),
                    disp=np.concatenate([smp["disp"] for smp in samples]),
                    rot=np.concatenate([smp["rot"] for smp in samples]), periodic=periodic, circle_s=s_m)

    def add_pocket(self, cage, kind: str, angle_rad: float, radius_m: float, height_m: float, clearance_m: float,
                   walls=None) -> int:
        """A cage pocket (kind "cylinder" for balls, "slot" for rollers) at angle/radius/height in the cage frame.

        On a modal cage, ``walls`` gives the samples its walls deform with: the index k of the pocket
        in the body's stored ``"pockets"`` sample (rows 2k, 2k + 1: leading then trailing wall,
        :func:`cms_reduction.sampling.pocket_contact_points`), or (sample, k) with a
        :class:`cms_reduction.sampling.RacewaySample` or the name of one stored with the body. A
        pocket on a modal cage without ``walls`` carries no contacts.
        """
        owner = "pocket"
        i = self._body_index(cage, owner)
        if kind not in POCKET_KINDS:
            raise ValueError(f"{owner}: kind must be one of {sorted(POCKET_KINDS)}, got {kind!r}")
        check_positive(owner, radius_m=radius_m)
        if not (math.isfinite(clearance_m) and clearance_m >= 0):
            raise ValueError(f"{owner}: clearance_m must be ≥ 0, got {clearance_m!r}")
        body = self._bodies[i]
        height_m -= body.frame_z_m
        sample = None
        if walls is not None:
            sample, k = ("pockets", walls) if isinstance(walls, (int, np.integer)) else walls
            smp = self._raceway_sample(body, sample, owner)
            if not (isinstance(k, (int, np.integer)) and 0 <= 2 * k + 1 < smp["theta"].size):
                raise ValueError(f"{owner}: the wall sample has no pocket {k!r} ({smp['theta'].size // 2} pockets)")
            rows = slice(2 * int(k), 2 * int(k) + 2)
            sample = {key: smp[key][rows] for key in ("theta", "points", "disp", "rot")}
            centre = np.array([radius_m * math.cos(angle_rad), radius_m * math.sin(angle_rad), height_m])
            off = float(np.linalg.norm(sample["points"].mean(axis=0) - centre))
            if off > 1e-3 * radius_m:
                raise ValueError(f"{owner}: wall samples of pocket {k} are centred {off:.3g} m away from the pocket "
                                 f"at {angle_rad:.6g} rad, r = {radius_m} m")
        self._pockets.append(dict(kind=POCKET_KINDS[kind], angle=float(angle_rad), r=float(radius_m),
                                  z=float(height_m), clearance=float(clearance_m), cage=i, walls=sample))
        return len(self._pockets) - 1
