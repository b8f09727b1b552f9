"""Limiting load curve: the envelope of axial force and tilting moment a bearing carries statically.

Slewing-bearing catalogues print the static limiting load curve, F_a against M, at which the most
loaded contact reaches the static criterion. Here: for n rays in the (F_a, M) plane,

    load(λ) = (Fx = F_r, Fz = λ·F_ref·cos θ, My = λ·M_ref·sin θ),

the scale λ at which max over all contact sets of p0/p_allow reaches 1 is found by bracketing and
Brent's method (Brent, *Algorithms for Minimization without Derivatives*, 1973, ch. 4; scipy
``brentq``), each evaluation a rigid-ring :func:`~mbd_core.quasistatic.solve_load_distribution`.
A load the rows cannot carry (no equilibrium) counts as over the limit. The allowed pressure is
p_allow = p_lim·s0^(−1/n) for a static safety s0 (ISO 76:2006: s0 = (p_lim/p0)^n, n = 3 point,
2 line contact; see :mod:`.static_safety`), or a pressure given by the user for every contact.

The tilting moment is My (about the y axis, through the bearing centre); F_r, if given, is Fx and
stays fixed along every ray. Rays cover the whole plane where the bearing carries axial load
both ways (a four-point row: a closed curve about the origin), else the half-plane of the carried
direction; rays steeper than the rows can carry at all (a single angular-contact row under a
nearly pure moment) have no point and are marked ``carried = False``. F_ref and M_ref only spread the rays over the plane: by default the
pure-axial limit (of whichever axial sign the bearing carries) and M_ref = F_ref·d_m/4, the ratio of
the pure-moment to the pure-axial limit of a ball row (Q_max = 4M/(Z d_m sin α) against
F_a/(Z sin α); Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., 2007, ch. 7).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..quasistatic.contacts import ContactSet, contact_sets
from ..quasistatic.results import LoadDistributionError, RingLoad
from ..quasistatic.rows import Bearing
from ..quasistatic.solver import solve_load_distribution

__all__ = ["LimitingLoadCurve", "limiting_load_curve", "ray_limit", "ray_ratios", "Criterion"]

log = logging.getLogger(__name__)

#: Stand-in for u − 1 where the rows cannot carry the load: over the limit, finite for Brent.
_NO_EQUILIBRIUM = 1e3
#: Relative width to which the end of equilibrium along a ray is located (each failed solve is slow).
_EQUILIBRIUM_RTOL = 1e-4
#: Below this fraction of the starting scale a ray without equilibrium counts as not carried.
_SMALLEST_SCALE = 1e-4


@dataclass(frozen=True)
class Criterion:
    """The allowed contact pressure: ISO 76 limit over s0^(1/n), or one pressure for every contact."""

    s0: float = 1.0
    pressure_limit_Pa: float | None = None

    def __post_init__(self) -> None:
        if not (isinstance(self.s0, (int, float)) and math.isfinite(self.s0) and self.s0 > 0.0):
            raise ValueError(f"s0 must be a finite number > 0, got {self.s0!r}")
        p = self.pressure_limit_Pa
        if p is not None and not (isinstance(p, (int, float)) and math.isfinite(p) and p > 0.0):
            raise ValueError(f"pressure_limit_Pa must be a finite number > 0, got {p!r}")

    def allowed_Pa(self, s: ContactSet) -> float:
        if self.pressure_limit_Pa is not None:
            return float(self.pressure_limit_Pa)
        return s.static_limit_Pa * self.s0 ** (-1.0 / s.pressure_exponent)

    @property
    def label(self) -> str:
        if self.pressure_limit_Pa is not None:
            return f"p0 = {self.pressure_limit_Pa / 1e9:.3g} GPa"
        return f"s0 = {self.s0:.3g} (ISO 76)"


@dataclass(frozen=True)
class LimitingLoadCurve:
    """Points of the limiting load curve, one per ray (n = rays).

    Attributes
    ----------
    criterion : str
    radial_N : float
        The fixed radial force Fx, N.
    ray_angle_rad : (n,) θ of each ray in the plane (F_a/F_ref, M/M_ref), rad
    axial_N : (n,) F_a at the limit, N (NaN where the ray is not carried)
    moment_Nm : (n,) M = My at the limit, N·m (NaN where the ray is not carried)
    row, contact : (n,) str, deciding row and contact set ("" where none)
    element : (n,) int, deciding element in its row (−1 where none)
    carried : (n,) bool, False where the bearing carries no load along the ray
    equilibrium_limited : (n,) bool, True where the limit is the end of equilibrium, not p0
    axial_ref_N, moment_ref_Nm : float, F_ref and M_ref of the rays (pass them to another curve to
        put its points on the same rays, :func:`ray_ratios`)
    """

    criterion: str
    radial_N: float
    ray_angle_rad: np.ndarray
    axial_N: np.ndarray
    moment_Nm: np.ndarray
    row: tuple[str, ...]
    contact: tuple[str, ...]
    element: np.ndarray
    carried: np.ndarray
    equilibrium_limited: np.ndarray
    axial_ref_N: float = math.nan
    moment_ref_Nm: float = math.nan

    def to_dict(self) -> dict:
        """Plain lists; points of rays not carried are None."""
        def values(a):
            return [float(v) if np.isfinite(v) else None for v in a]

        return {"criterion": self.criterion, "radial_N": self.radial_N,
                "ray_angle_deg": np.degrees(self.ray_angle_rad).tolist(), "axial_N": values(self.axial_N),
                "moment_Nm": values(self.moment_Nm), "row": list(self.row), "contact": list(self.contact),
                "element": self.element.tolist(), "carried": self.carried.tolist(),
                "equilibrium_limited": self.equilibrium_limited.tolist()}


def utilisation(bearing: Bearing, load: RingLoad, criterion: Criterion, solve=None):
    """(max p0/p_allow, (row, contact, element)) of the load; (inf, None) without equilibrium.

    ``solve``: load → load distribution of ``bearing`` (default: rigid rings,
    :func:`~mbd_core.quasistatic.solve_load_distribution`; e.g. a flexible-ring model's solve).
    """
    try:
        dist = solve_load_distribution(bearing, load) if solve is None else solve(load)
    except LoadDistributionError:
        return math.inf, None
    u, who = 0.0, None
    for s in contact_sets(bearing, dist):
        p = np.asarray(s.max_pressure_Pa, dtype=float)
        if p.size == 0:
            continue
        k = int(np.argmax(p))
        r = p[k] / criterion.allowed_Pa(s)
        if r > u:
            u, who = float(r), (s.row, s.label, k)
    return u, who


def ray_limit(bearing: Bearing, base: np.ndarray, direction: np.ndarray, criterion: Criterion,
              start: float = 1.0, rtol: float = 1e-7, solve=None):
    """Largest λ with load base + λ·direction within the criterion.

    ``base``, ``direction``: (5,) (Fx, Fy, Fz, Mx, My), N and N·m. Returns (λ, who, limited_by_equilibrium)
    with ``who`` = (row, contact, element) of the deciding contact; λ = NaN where even λ → 0 is over.
    ``solve`` as in :func:`utilisation`.
    """
    def u_of(lam: float) -> float:
        return utilisation(bearing, RingLoad(*(float(v) for v in base + lam * direction)), criterion, solve)[0]

    def who_at(lam: float):
        return utilisation(bearing, RingLoad(*(float(v) for v in base + lam * direction)), criterion, solve)[1]

    if np.any(base) and not u_of(0.0) < 1.0:
        return math.nan, who_at(0.0), False
    lo, hi, u = _bracket(u_of, start)
    if not math.isfinite(u):
        if lo == 0.0 and not math.isfinite(u_of(_SMALLEST_SCALE * start)):
            return math.nan, None, True
        lo, hi, over = _close_in_on_equilibrium_end(u_of, lo, hi, start)
        if not over:
            return (math.nan, None, True) if lo == 0.0 else (lo, who_at(lo), True)
    lam = brentq(lambda x: min(u_of(x) - 1.0, _NO_EQUILIBRIUM), lo, hi, xtol=1e-12 * hi, rtol=rtol)
    return lam, who_at(lam), False


def _bracket(u_of, start: float) -> tuple[float, float, float]:
    """(lo, hi, u(hi)) with u(lo) < 1 ≤ u(hi) (u = inf: no equilibrium at hi), lo = 0 or a tried scale."""
    lo, hi = 0.0, start
    for _ in range(200):
        u = u_of(hi)
        if not u < 1.0:
            return lo, hi, u
        lo = hi
        # p0 ∝ Q^(1/3) ∝ λ^(1/3) roughly: jump towards the limit, at least ×1.5
        hi = hi * max(1.5, min(1.2 * u**-3.0 if u > 0 else 10.0, 1e3))
    raise RuntimeError("no limit found along the ray: the load never reaches the criterion")


def _close_in_on_equilibrium_end(u_of, lo: float, hi: float, start: float) -> tuple[float, float, bool]:
    """Bisect [lo, hi] (no equilibrium at hi) until hi has an equilibrium over the limit (True), or
    the end of equilibrium is located to :data:`_EQUILIBRIUM_RTOL` below the limit (False)."""
    while hi - lo > _EQUILIBRIUM_RTOL * hi and not (lo == 0.0 and hi < _SMALLEST_SCALE * start):
        mid = 0.5 * (lo + hi)
        um = u_of(mid)
        if math.isfinite(um) and um >= 1.0:
            return lo, mid, True
        if math.isfinite(um):
            lo = mid
        else:
            hi = mid
    return lo, hi, False


def _pitch_diameter_m(bearing: Bearing) -> float:
    return 2.0 * bearing.reference_length_m


def limiting_load_curve(bearing: Bearing, n_rays: int = 36, s0: float = 1.0, pressure_limit_Pa: float | None = None,
                        radial_N: float = 0.0, axial_ref_N: float | None = None,
                        moment_ref_Nm: float | None = None, solve=None) -> LimitingLoadCurve:
    """The (F_a, M) envelope at the static criterion (module docstring).

    Parameters
    ----------
    bearing : Bearing
    n_rays : int
        Rays evenly spread over θ ∈ [0, 2π) in the plane (F_a/F_ref, M/M_ref) if the bearing
        carries axial load both ways, else over the half-plane of the carried direction
        (θ ∈ [−π/2, π/2) about the pure-axial ray), ≥ 3.
    s0 : float
        Static safety factor of the criterion (default 1: p0 at the ISO 76 limit).
    pressure_limit_Pa : float, optional
        Allowed p0 for every contact instead of the ISO 76 limit over s0, Pa.
    radial_N : float
        Fixed radial force Fx, N.
    axial_ref_N, moment_ref_Nm : float, optional
        F_ref and M_ref of the rays (default: the pure-axial limit and F_ref·d_m/4).
    solve : callable RingLoad → LoadDistribution, optional
        The bearing's load distribution (default: rigid rings); a flexible-ring model's solve gives
        the curve with ring flexibility.
    """
    if not isinstance(bearing, Bearing):
        raise TypeError(f"bearing must be a Bearing, got {type(bearing).__name__}")
    if isinstance(n_rays, bool) or not isinstance(n_rays, int) or n_rays < 3:
        raise ValueError(f"n_rays must be an integer >= 3, got {n_rays!r}")
    if not (isinstance(radial_N, (int, float)) and math.isfinite(radial_N)):
        raise ValueError(f"radial_N must be a finite number, got {radial_N!r}")
    for name, v in (("axial_ref_N", axial_ref_N), ("moment_ref_Nm", moment_ref_Nm)):
        if v is not None and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0.0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
    crit = Criterion(s0, pressure_limit_Pa)
    base = np.array([radial_N, 0.0, 0.0, 0.0, 0.0])
    axial_limits = _axial_limits_N(bearing, base, crit, solve)
    if axial_ref_N is None:
        axial_ref_N = float(np.nanmax(np.abs(axial_limits)))
    if moment_ref_Nm is None:
        moment_ref_Nm = axial_ref_N * _pitch_diameter_m(bearing) / 4.0
    theta = _ray_angles_rad(n_rays, np.isfinite(axial_limits))
    lam = np.full(n_rays, math.nan)
    rows, contacts = [""] * n_rays, [""] * n_rays
    element = np.full(n_rays, -1)
    eq_limited = np.zeros(n_rays, dtype=bool)
    start = 1.0
    for i, t in enumerate(theta):
        direction = np.array([0.0, 0.0, axial_ref_N * math.cos(t), 0.0, moment_ref_Nm * math.sin(t)])
        lam[i], who, eq_limited[i] = ray_limit(bearing, base, direction, crit, start=start, solve=solve)
        if who is not None and math.isfinite(lam[i]):
            rows[i], contacts[i], element[i] = who
            start = 0.7 * lam[i]
        else:
            start = 1.0
            log.info("limiting load curve of %r: no load carried along the ray θ = %.1f°", bearing.name,
                     math.degrees(t))
    carried = np.isfinite(lam)
    return LimitingLoadCurve(crit.label, float(radial_N), theta, lam * axial_ref_N * np.cos(theta),
                             lam * moment_ref_Nm * np.sin(theta), tuple(rows), tuple(contacts), element,
                             carried, eq_limited & carried, float(axial_ref_N), float(moment_ref_Nm))


def ray_ratios(curve: LimitingLoadCurve, reference: LimitingLoadCurve) -> np.ndarray:
    """Load scale of ``curve`` over that of ``reference`` along each ray (NaN where either is not
    carried): < 1 where ``curve`` carries less. Both must share rays and references (give the
    second curve the first one's ``axial_ref_N`` and ``moment_ref_Nm``)."""
    same = (np.allclose(curve.ray_angle_rad, reference.ray_angle_rad, rtol=0.0, atol=1e-12)
            and math.isclose(curve.axial_ref_N, reference.axial_ref_N)
            and math.isclose(curve.moment_ref_Nm, reference.moment_ref_Nm) and curve.radial_N == reference.radial_N)
    if not same:
        raise ValueError("the curves do not share their rays (ray angles, F_ref, M_ref and radial force)")
    c, s = np.cos(curve.ray_angle_rad), np.sin(curve.ray_angle_rad)
    use_axial = np.abs(c) >= np.abs(s)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(use_axial, curve.axial_N / reference.axial_N, curve.moment_Nm / reference.moment_Nm)
    return np.where(curve.carried & reference.carried, ratio, math.nan)


def _axial_limits_N(bearing: Bearing, base: np.ndarray, crit: Criterion, solve=None) -> np.ndarray:
    """Pure-axial limits towards +z and −z, N (NaN where not carried); ValueError if neither is."""
    guess = 1e3 * sum(r.n_elements for r in bearing.rows)
    out = np.full(2, math.nan)
    for j, sign in enumerate((1.0, -1.0)):
        lam, _, _ = ray_limit(bearing, base, np.array([0.0, 0.0, sign * guess, 0.0, 0.0]), crit, solve=solve)
        out[j] = sign * lam * guess
    if not np.any(np.isfinite(out)):
        raise ValueError(f"bearing {bearing.name!r} carries no axial load in either direction: its limiting "
                         "load curve in the (F_a, M) plane is empty")
    return out


def _ray_angles_rad(n_rays: int, carried: np.ndarray) -> np.ndarray:
    """θ over the whole plane if both axial directions are carried, else over the carried half
    (centred on its pure-axial ray, θ = 0 or π), rad."""
    if carried.all():
        return 2.0 * np.pi * np.arange(n_rays) / n_rays
    half = np.pi * (np.arange(n_rays) - n_rays // 2) / n_rays
    return half if carried[0] else half + np.pi
