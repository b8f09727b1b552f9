"""Basic rating life per row and of the bearing from a load distribution (ISO/TS 16281:2008).

Lundberg–Palmgren, as ISO/TS 16281:2008 (*Rolling bearings — Methods for calculating the modified
reference rating life for universally loaded bearings*) and ISO/TR 1281-1 (explanatory notes on
ISO 281) apply it to a computed load distribution; Harris & Kotzalas, *Rolling Bearing Analysis*,
5th ed., 2007, vol. 2, ch. 8:

* dynamic equivalent load of a raceway contact family (a contact set, :mod:`..quasistatic.contacts`)
  over its Z elements, unloaded ones counting zero::

      Q_e = (Σ Q_j^w / Z)^(1/w),   w = 3 on the ring rotating relative to the load (every point of
                                    its raceway passes every element), w = 10/3 on the ring
                                    stationary relative to the load (ball, point contact)

* its life, 10^6 revolutions: L = (Q_c/Q_e)^3 with the basic dynamic load rating of the raceway
  contact (ISO/TR 1281-1; Harris & Kotzalas, vol. 2, ch. 8), N and mm::

      Q_c = 98.1·b_m·(2f/(2f − 1))^0.41·(1 ∓ γ)^1.39/(1 ± γ)^(1/3)·(γ/cos α0)^0.3·D^1.8·Z^(−1/3)

  upper signs for the inner, lower for the outer raceway, γ = D·cos α0/d_m, f the groove
  conformity, D^1.8 → 3.647·D^1.4 above D = 25.4 mm (as ISO 281 :mod:`.rating`); b_m of ISO 281
  Table 1 (default 1.3). ISO 281's reduction factor λ for edge stresses is not applied (1);
  give ``contact_ratings_N`` to use other values;
* the life of a row and of the bearing: the contact families in series (Weibull slope e),

      L = (Σ L_k^(−e))^(−1/e),   e = 10/9 (ball).

ISO 281's catalogue rating is this calibrated for a radial bearing without clearance under a
radial load (Stribeck's load zone ε = 0.5): C_r = 0.407·Q_ci·Z·cos α·(1 + (1.04·Q_ci/Q_ce)^(10/3))^(−0.3)
(ISO/TR 1281-1), which the tests reproduce. Roller rows (ISO/TS 16281's lamina method) are not
implemented here. The modified life multiplies by a_ISO (ISO 281:2007, 9.3), here a number given by
the user (default 1: the basic rating life); κ, e_C and C_u are not evaluated.

Load spectra: Palmgren–Miner per contact family, L = 1/Σ(t_i/L_i) with time shares t_i (summing
to 1; ISO 281:2007, 9.5 / Harris & Kotzalas vol. 2, ch. 8), then combined as above.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..quasistatic.contacts import ContactSet, contact_sets
from ..quasistatic.results import LoadDistribution, RingLoad
from ..quasistatic.rows import BallRow, Bearing, FourPointRow
from ..quasistatic.solver import solve_load_distribution

__all__ = ["RowLife", "BearingLife", "ball_contact_rating_N", "equivalent_contact_load_N", "combined_life",
           "rating_life", "spectrum_rating_life", "BALL_WEIBULL_SLOPE"]

#: Weibull slope e of ball bearings (ISO 281; Lundberg–Palmgren).
BALL_WEIBULL_SLOPE = 10.0 / 9.0
#: Life exponent p of a point contact.
_P_BALL = 3.0
#: Equivalent-load exponents w of the ring rotating / stationary relative to the load (ball).
_W_ROTATING, _W_STATIONARY = 3.0, 10.0 / 3.0
_DW_LIMIT_MM = 25.4
_LARGE_BALL_CONST = 3.647


@dataclass(frozen=True)
class RowLife:
    """Life of one row: per contact set its Q_c, Q_e, life, and the row's combined life.

    ``set_labels``, ``set_rating_N``, ``set_equivalent_load_N``, ``set_life_Mrev``: per contact set
    (N, N, 10^6 rev); ``life_Mrev`` = a_ISO·(Σ L_k^(−e))^(−1/e); ``deciding`` the shortest-lived set.
    """

    row: str
    set_labels: tuple[str, ...]
    set_rating_N: tuple[float, ...]
    set_equivalent_load_N: tuple[float, ...]
    set_life_Mrev: tuple[float, ...]
    life_Mrev: float
    deciding: str


@dataclass(frozen=True)
class BearingLife:
    """Rows' lives and the bearing's: L = (Σ_rows L_row^(−e))^(−1/e), 10^6 revolutions."""

    rows: tuple[RowLife, ...]
    life_Mrev: float
    rotating_ring: str
    a_iso: float


def ball_contact_rating_N(ball_diameter_m: float, conformity: float, pitch_diameter_m: float,
                          contact_angle_rad: float, n_balls: int, raceway: Literal["inner", "outer"],
                          bm: float = 1.3) -> float:
    """Basic dynamic load rating Q_c of a ball–raceway contact, N (module docstring)."""
    if raceway not in ("inner", "outer"):
        raise ValueError(f"raceway must be 'inner' or 'outer', got {raceway!r}")
    D_mm = 1e3 * ball_diameter_m
    cos_a = math.cos(contact_angle_rad)
    if cos_a < 1e-9:
        # thrust (α0 = 90°): (γ/cos α)^0.3 → (D/d_m)^0.3 and γ = 0 (Harris & Kotzalas, vol. 2, ch. 8)
        gamma, ratio = 0.0, ball_diameter_m / pitch_diameter_m
    else:
        gamma = ball_diameter_m * cos_a / pitch_diameter_m
        ratio = gamma / cos_a
    s = 1.0 if raceway == "inner" else -1.0
    size = D_mm**1.8 if D_mm <= _DW_LIMIT_MM else _LARGE_BALL_CONST * D_mm**1.4
    return (98.1 * bm * (2 * conformity / (2 * conformity - 1)) ** 0.41
            * (1 - s * gamma) ** 1.39 / (1 + s * gamma) ** (1 / 3) * ratio**0.3 * size * n_balls ** (-1 / 3))


def equivalent_contact_load_N(load_N: np.ndarray, rotating: bool) -> float:
    """Q_e = (Σ Q^w / Z)^(1/w), w = 3 (rotating) or 10/3 (stationary relative to the load), N."""
    Q = np.maximum(np.asarray(load_N, dtype=float), 0.0)
    w = _W_ROTATING if rotating else _W_STATIONARY
    return float(np.mean(Q**w) ** (1.0 / w)) if Q.size else 0.0


def combined_life(lives_Mrev: Sequence[float], e: float = BALL_WEIBULL_SLOPE) -> float:
    """(Σ L_k^(−e))^(−1/e): parts in series with Weibull slope e; inf if every part is unloaded."""
    inv = sum(L ** (-e) for L in lives_Mrev if math.isfinite(L))
    return math.inf if inv == 0.0 else inv ** (-1.0 / e)


def _check_rotating(rotating_ring: str) -> None:
    if rotating_ring not in ("moving", "fixed"):
        raise ValueError(f"rotating_ring must be 'moving' or 'fixed' (the ring turning relative to the load), "
                         f"got {rotating_ring!r}")


def _set_rating_N(row, s: ContactSet, bm: float) -> float:
    f = row.conformity_moving if s.raceway == row.moving_raceway else row.conformity_fixed
    return ball_contact_rating_N(row.ball_diameter_m, f, row.pitch_diameter_m, row.contact_angle_rad,
                                 row.n_balls, s.raceway, bm)


def _ball_rows(bearing: Bearing) -> None:
    for row in bearing.rows:
        if not isinstance(row, (BallRow, FourPointRow)):
            raise ValueError(f"row {row.name!r}: rating life from the load distribution is implemented for ball "
                             f"rows only, not {type(row).__name__}")


def _set_lives(bearing: Bearing, dist: LoadDistribution, rotating_ring: str, bm: float, contact_ratings_N):
    """Per row: [(label, Q_c, Q_e, L)] of its contact sets."""
    rows = {r.name: r for r in bearing.rows}
    out: dict[str, list] = {r.name: [] for r in bearing.rows}
    for s in contact_sets(bearing, dist):
        row = rows[s.row]
        on_moving = s.raceway == row.moving_raceway
        rotating = on_moving == (rotating_ring == "moving")
        key = (s.row, s.label)
        qc = contact_ratings_N[key] if contact_ratings_N and key in contact_ratings_N else _set_rating_N(row, s, bm)
        qe = equivalent_contact_load_N(s.load_N, rotating)
        out[s.row].append((s.label, qc, qe, math.inf if qe == 0.0 else (qc / qe) ** _P_BALL))
    return out


def _assemble(per_row: dict, rotating_ring: str, a_iso: float) -> BearingLife:
    rows = []
    for name, sets in per_row.items():
        labels, qc, qe, L = (tuple(v) for v in zip(*sets))
        deciding = labels[int(np.argmin(L))] if any(math.isfinite(x) for x in L) else ""
        rows.append(RowLife(name, labels, qc, qe, L, a_iso * combined_life(L), deciding))
    total = a_iso * combined_life([x for r in per_row.values() for x in (s[3] for s in r)])
    return BearingLife(tuple(rows), total, rotating_ring, a_iso)


def _check_common(rotating_ring: str, bm: float, a_iso: float) -> None:
    _check_rotating(rotating_ring)
    for name, v in (("bm", bm), ("a_iso", a_iso)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0.0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")


def rating_life(bearing: Bearing, dist: LoadDistribution, rotating_ring: Literal["moving", "fixed"] = "moving",
                bm: float = 1.3, a_iso: float = 1.0,
                contact_ratings_N: dict[tuple[str, str], float] | None = None) -> BearingLife:
    """L10 per row and of the bearing from one load distribution, 10^6 revolutions (module docstring).

    Parameters
    ----------
    bearing, dist : the bearing and its load distribution (ball rows)
    rotating_ring : {"moving", "fixed"}
        The ring that turns relative to the load (its raceway gets w = 3, the other w = 10/3).
    bm : float
        ISO 281 Table 1 rating factor in Q_c.
    a_iso : float
        Life modification factor (ISO 281 9.3), given; 1 gives the basic rating life.
    contact_ratings_N : dict, optional
        Q_c per (row name, contact set label) instead of the formula, N.
    """
    _check_common(rotating_ring, bm, a_iso)
    _ball_rows(bearing)
    return _assemble(_set_lives(bearing, dist, rotating_ring, bm, contact_ratings_N), rotating_ring, a_iso)


def spectrum_rating_life(bearing: Bearing, loads: Sequence[RingLoad], time_shares: Sequence[float],
                         rotating_ring: Literal["moving", "fixed"] = "moving", bm: float = 1.3, a_iso: float = 1.0,
                         contact_ratings_N: dict[tuple[str, str], float] | None = None) -> BearingLife:
    """L10 under a load spectrum: Palmgren–Miner per contact set, L = 1/Σ(t_i/L_i) (module docstring).

    ``time_shares`` (≥ 0, one per load) are normalised to sum to 1.
    """
    _check_common(rotating_ring, bm, a_iso)
    _ball_rows(bearing)
    loads, t = list(loads), np.asarray(time_shares, dtype=float)
    if not loads or t.shape != (len(loads),):
        raise ValueError(f"time_shares must give one share per load ({len(loads)} loads), got {len(t)}")
    if not (np.all(np.isfinite(t)) and np.all(t >= 0.0) and t.sum() > 0.0):
        raise ValueError("time_shares must be finite numbers >= 0 with a positive sum")
    t = t / t.sum()
    damage: dict[tuple[str, str], float] = {}
    template = None
    for load, share in zip(loads, t):
        per_row = _set_lives(bearing, solve_load_distribution(bearing, load), rotating_ring, bm, contact_ratings_N)
        template = template or per_row
        for name, sets in per_row.items():
            for label, _, _, L in sets:
                damage[(name, label)] = damage.get((name, label), 0.0) + (share / L if math.isfinite(L) else 0.0)
    per_row = {name: [(label, qc, math.nan, math.inf if damage[(name, label)] == 0.0 else 1.0 / damage[(name, label)])
                      for label, qc, _, _ in sets] for name, sets in template.items()}
    return _assemble(per_row, rotating_ring, a_iso)
