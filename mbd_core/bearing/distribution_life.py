"""Basic rating life per row and of the bearing from a load distribution (ISO/TS 16281:2008).

Lundberg–Palmgren, as ISO/TS 16281:2008 (*Rolling bearings — Methods for calculating the modified
reference rating life for universally loaded bearings*) and ISO/TR 1281-1 (explanatory notes on
ISO 281) apply it to a computed load distribution; Harris & Kotzalas, *Rolling Bearing Analysis*,
5th ed., 2007, vol. 2, ch. 8. Lives in 10^6 revolutions of the ring turning relative to the load.

Ball rows, per raceway contact family (a contact set, :mod:`..quasistatic.contacts`) of Z balls,
unloaded ones counting zero:

* dynamic equivalent load Q_e = (Σ Q_j^w / Z)^(1/w), w = 3 on the ring rotating relative to the
  load (every point of its raceway passes every ball), w = 10/3 on the ring stationary relative
  to the load;
* life L = (Q_c/Q_e)^3 with the basic dynamic load rating of the raceway contact, N and mm::

      Q_c = 98.1·b_m·(2f/(2f − 1))^0.41·(1 ∓ γ)^1.39/(1 ± γ)^(1/3)·(γ/cos α0)^0.3·D^1.8·Z^(−1/3)

  upper signs for the inner, lower for the outer raceway, γ = D·cos α0/d_m, f the groove
  conformity, D^1.8 → 3.647·D^1.4 above D = 25.4 mm (as ISO 281, :mod:`.rating`).

Roller rows, per raceway, by ISO/TS 16281's laminae (the row's n_s slices, :mod:`..quasistatic.rows`):

* Q_c = 552·b_m·(1 ∓ γ)^(29/27)/(1 ± γ)^(1/4)·(γ/cos α)^(2/9)·D_we^(29/27)·L_we^(7/9)·Z^(−1/4)
  (N, mm) for the whole roller, q_c = Q_c·n_s^(−7/9) per lamina (Q_c ∝ L^(7/9));
* per lamina k: q_e,k = (Σ_j q_jk^w / Z)^(1/w), w = 4 (rotating) or 9/2 (stationary), and
  L_k = (q_c/q_e,k)^4; the raceway's life (Σ_k L_k^(−9/8))^(−8/9).

Crossed roller rows: the rollers of each diagonal (±α0) roll on their own flank of each ring's
V-groove, so each diagonal is a row of its own of Z_d rollers at α0 (the laminae above with
Z = Z_d, γ = D·cos α0/d_m and the equivalent loads over those Z_d rollers): four raceways, each
passed Z_d times per revolution. The crossed roller bearing is taken as two angular-contact
roller rows of Z_d (about Z/2) rollers, as ISO 281's radial roller formula would rate it with
i = 2 rows of Z/2 rollers (:func:`.rating.radial_roller_rating_N`), not as one row of Z rollers on
each raceway: a point of a flank is rolled over only by the rollers of its diagonal. b_m: radial roller (1.1) for
α0 ≤ 45°, thrust roller (1.0) above.

Thrust rows (α = 90°): γ = 0 and γ/cos α → D/d_m. b_m of ISO 281 Table 1 (defaults 1.3 ball, 1.1
radial roller, 1.0 thrust roller); ISO 281's reduction factors (λ, ν) for edge stresses are not
applied (1): give ``contact_ratings_N`` to use other Q_c.

Rows and the bearing: the contact families (laminae) in series, L = (Σ L_k^(−e))^(−1/e) with the
Weibull slope e = 10/9 (ball) or 9/8 (roller); a bearing with both kinds of rows combines its rows
with 10/9. ISO 281's catalogue rating is this calibrated for a radial ball bearing without
clearance under a radial load (Stribeck's load zone ε = 0.5): C_r = 0.407·Q_ci·Z·cos α·(1 +
(1.04·Q_ci/Q_ce)^(10/3))^(−0.3) (ISO/TR 1281-1), which the tests reproduce; for rollers ISO 281
uses p = 10/3 where the laminae use 4, so catalogue and lamina lives agree only near the
calibration load. The modified life multiplies by a_ISO (ISO 281:2007, 9.3), here a number given
by the user (default 1: the basic rating life); κ, e_C and C_u are not evaluated.

Load spectra: Palmgren–Miner per contact family (lamina), L = 1/Σ(t_i/L_i) with time shares t_i
(summing to 1; ISO 281:2007, 9.5), then combined as above.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..quasistatic.contacts import contact_sets
from ..quasistatic.results import LoadDistribution, RingLoad
from ..quasistatic.rows import Bearing, RollerRow
from ..quasistatic.solver import solve_load_distribution
from .rating import BM_DEFAULTS

__all__ = ["RowLife", "BearingLife", "ball_contact_rating_N", "roller_contact_rating_N", "equivalent_contact_load_N",
           "combined_life", "bearing_weibull_slope", "rating_life", "spectrum_rating_life", "BALL_WEIBULL_SLOPE",
           "ROLLER_WEIBULL_SLOPE"]

#: Weibull slope e of ball bearings (ISO 281; Lundberg–Palmgren).
BALL_WEIBULL_SLOPE = 10.0 / 9.0
#: Weibull slope e of roller bearings.
ROLLER_WEIBULL_SLOPE = 9.0 / 8.0
#: Life exponent p of a point contact and of a line-contact lamina (Lundberg–Palmgren).
_P_BALL, _P_LAMINA = 3.0, 4.0
#: Equivalent-load exponents w of the ring rotating / stationary relative to the load: ball, lamina.
_W_BALL = {True: 3.0, False: 10.0 / 3.0}
_W_LAMINA = {True: 4.0, False: 4.5}
_DW_LIMIT_MM = 25.4
_LARGE_BALL_CONST = 3.647


@dataclass(frozen=True)
class RowLife:
    """Life of one row: per contact set its Q_c, Q_e, life, and the row's combined life.

    ``set_labels``, ``set_rating_N``, ``set_equivalent_load_N``, ``set_life_Mrev``: per contact set
    (ball: a raceway contact family; roller: a raceway, its laminae combined), N, N, 10^6 rev. For
    rollers Q_c is the whole roller's and Q_e the largest lamina equivalent load times n_s (NaN
    for a spectrum). ``life_Mrev`` = a_ISO·(Σ L_k^(−e))^(−1/e); ``deciding`` the shortest-lived set.
    """

    row: str
    set_labels: tuple[str, ...]
    set_rating_N: tuple[float, ...]
    set_equivalent_load_N: tuple[float, ...]
    set_life_Mrev: tuple[float, ...]
    life_Mrev: float
    deciding: str

    def to_dict(self) -> dict:
        sets = [{"label": lab, "rating_N": qc, "equivalent_load_N": qe, "life_Mrev": L} for lab, qc, qe, L in
                zip(self.set_labels, self.set_rating_N, self.set_equivalent_load_N, self.set_life_Mrev)]
        return {"row": self.row, "life_Mrev": self.life_Mrev, "deciding": self.deciding, "contact_sets": sets}


@dataclass(frozen=True)
class BearingLife:
    """Rows' lives and the bearing's: L = (Σ_rows L_row^(−e))^(−1/e), 10^6 revolutions."""

    rows: tuple[RowLife, ...]
    life_Mrev: float
    rotating_ring: str
    a_iso: float

    def to_dict(self) -> dict:
        return {"life_Mrev": self.life_Mrev, "rotating_ring": self.rotating_ring, "a_iso": self.a_iso,
                "rows": [r.to_dict() for r in self.rows]}


def ball_contact_rating_N(ball_diameter_m: float, conformity: float, pitch_diameter_m: float,
                          contact_angle_rad: float, n_balls: int, raceway: Literal["inner", "outer"],
                          bm: float = 1.3) -> float:
    """Basic dynamic load rating Q_c of a ball–raceway contact, N (module docstring)."""
    gamma, ratio, s = _geometry(ball_diameter_m, pitch_diameter_m, contact_angle_rad, raceway)
    D_mm = 1e3 * ball_diameter_m
    size = D_mm**1.8 if D_mm <= _DW_LIMIT_MM else _LARGE_BALL_CONST * D_mm**1.4
    return (98.1 * bm * (2 * conformity / (2 * conformity - 1)) ** 0.41
            * (1 - s * gamma) ** 1.39 / (1 + s * gamma) ** (1 / 3) * ratio**0.3 * size * n_balls ** (-1 / 3))


def _geometry(diameter_m: float, pitch_diameter_m: float, contact_angle_rad: float,
              raceway: str) -> tuple[float, float, float]:
    """(γ, γ/cos α, s) = (D cos α/d_m, D/d_m, +1 inner / −1 outer raceway); thrust (α = 90°): γ = 0,
    ratio D/d_m (Harris & Kotzalas, vol. 2, ch. 8). ValueError for another raceway name."""
    if raceway not in ("inner", "outer"):
        raise ValueError(f"raceway must be 'inner' or 'outer', got {raceway!r}")
    cos_a = math.cos(contact_angle_rad)
    gamma = 0.0 if cos_a < 1e-9 else diameter_m * cos_a / pitch_diameter_m
    return gamma, diameter_m / pitch_diameter_m, 1.0 if raceway == "inner" else -1.0


def roller_contact_rating_N(roller_diameter_m: float, roller_length_m: float, pitch_diameter_m: float,
                            contact_angle_rad: float, n_rollers: int, raceway: Literal["inner", "outer"],
                            bm: float = 1.1) -> float:
    """Basic dynamic load rating Q_c of a whole roller–raceway line contact, N (module docstring)."""
    gamma, ratio, s = _geometry(roller_diameter_m, pitch_diameter_m, contact_angle_rad, raceway)
    D_mm, L_mm = 1e3 * roller_diameter_m, 1e3 * roller_length_m
    return (552.0 * bm * (1 - s * gamma) ** (29 / 27) / (1 + s * gamma) ** 0.25 * ratio ** (2 / 9)
            * D_mm ** (29 / 27) * L_mm ** (7 / 9) * n_rollers**-0.25)


def equivalent_contact_load_N(load_N: np.ndarray, rotating: bool) -> float:
    """Q_e = (Σ Q^w / Z)^(1/w), w = 3 (rotating) or 10/3 (stationary relative to the load), N."""
    return float(_w_mean(load_N, _W_BALL[rotating]))


def _w_mean(load_N, w: float, axis=None):
    """(Σ Q^w / Z)^(1/w) over the elements (axis 0 of a (Z, n_s) array), unloaded = 0."""
    Q = np.maximum(np.asarray(load_N, dtype=float), 0.0)
    if Q.size == 0:
        return 0.0
    return np.mean(Q**w, axis=axis) ** (1.0 / w)


def combined_life(lives_Mrev, e: float = BALL_WEIBULL_SLOPE) -> float:
    """(Σ L_k^(−e))^(−1/e): parts in series with Weibull slope e; inf if every part is unloaded."""
    inv = sum(L ** (-e) for L in np.ravel(lives_Mrev) if math.isfinite(L))
    return math.inf if inv == 0.0 else inv ** (-1.0 / e)


def _slope(row) -> float:
    return ROLLER_WEIBULL_SLOPE if isinstance(row, RollerRow) else BALL_WEIBULL_SLOPE


def _default_bm(row) -> float:
    if isinstance(row, RollerRow):
        radial = row.nominal_contact_angle_rad <= math.pi / 4 + 1e-12
        return BM_DEFAULTS["radial_roller" if radial else "thrust_roller"]
    return BM_DEFAULTS["radial_ball"]


def _rotating_raceways(row, rotating_ring: str) -> str:
    """The raceway ("inner"/"outer") of the ring that turns relative to the load."""
    if isinstance(row, RollerRow):
        # radial, crossed: load_sign +1 means the moving ring carries the inner raceway; thrust: "inner" is the moving ring's
        moving = "inner" if row.orientation == "thrust" or row.load_sign == 1 else "outer"
    else:
        moving = row.moving_raceway
    fixed = "outer" if moving == "inner" else "inner"
    return moving if rotating_ring == "moving" else fixed


#: one part of a row: (label, Q_c N, Q_e N, lives (n,) 10^6 rev — one per lamina for rollers)
_Part = tuple[str, float, float, np.ndarray]


def _ball_parts(row, sets, rotating_ring: str, bm: float, ratings) -> list[_Part]:
    """One part per contact set of a ball row: Q_c, Q_e and its life (Q_c/Q_e)^3."""
    out = []
    for s in sets:
        f = row.conformity_moving if s.raceway == row.moving_raceway else row.conformity_fixed
        qc = ratings.get((row.name, s.label)) or ball_contact_rating_N(
            row.ball_diameter_m, f, row.pitch_diameter_m, row.contact_angle_rad, row.n_balls, s.raceway, bm)
        qe = equivalent_contact_load_N(s.load_N, s.raceway == _rotating_raceways(row, rotating_ring))
        out.append((s.label, qc, qe, np.array([math.inf if qe == 0.0 else (qc / qe) ** _P_BALL])))
    return out


def _roller_groups(row: RollerRow) -> list[tuple[str, np.ndarray]]:
    """(label suffix, mask (Z,) of the rollers) of each group rolling on its own raceways: the whole
    row, or each diagonal of a crossed row (module docstring)."""
    if row.orientation != "crossed":
        return [("", np.ones(row.n_rollers, dtype=bool))]
    sig = row.diagonal_signs
    return [(f", diagonal {label}", sig == s) for s, label in zip((1.0, -1.0), ("+α", "−α")) if np.any(sig == s)]


def _roller_parts(row: RollerRow, dist: LoadDistribution, rotating_ring: str, bm: float, ratings) -> list[_Part]:
    """One part per raceway of a roller row (per raceway and diagonal of a crossed row), with the
    lives (q_c/q_e,k)^4 of its n_s laminae."""
    q_all = np.asarray(dist.row(row.name).slice_load_N, dtype=float)  # (Z, n_s) lamina loads, N
    alpha = row.nominal_contact_angle_rad
    out = []
    for suffix, on in _roller_groups(row):
        q, Z = q_all[on], int(np.sum(on))
        for raceway in ("inner", "outer"):
            label = f"{raceway} raceway{suffix}"
            Qc = ratings.get((row.name, label)) or roller_contact_rating_N(
                row.roller_diameter_m, row.roller_length_m, row.pitch_diameter_m, alpha, Z, raceway, bm)
            qc = Qc * row.n_slices ** (-7.0 / 9.0)
            qe = _w_mean(q, _W_LAMINA[raceway == _rotating_raceways(row, rotating_ring)], axis=0)
            with np.errstate(divide="ignore"):
                lives = np.where(qe > 0.0, (qc / np.where(qe > 0.0, qe, 1.0)) ** _P_LAMINA, math.inf)
            out.append((label, Qc, float(np.max(qe)) * row.n_slices, lives))
    return out


def _row_parts(bearing: Bearing, dist: LoadDistribution, rotating_ring: str, bm, ratings) -> dict[str, list[_Part]]:
    """Per row its parts (module docstring)."""
    sets = contact_sets(bearing, dist)
    ratings = ratings or {}
    out = {}
    for row in bearing.rows:
        b = _default_bm(row) if bm is None else bm
        if isinstance(row, RollerRow):
            out[row.name] = _roller_parts(row, dist, rotating_ring, b, ratings)
        else:
            out[row.name] = _ball_parts(row, [s for s in sets if s.row == row.name], rotating_ring, b, ratings)
    return out


def _assemble(bearing: Bearing, per_row: dict[str, list[_Part]], rotating_ring: str, a_iso: float) -> BearingLife:
    rows, row_lives = [], []
    for row in bearing.rows:
        e = _slope(row)
        labels, qc, qe, lives = zip(*per_row[row.name])
        set_life = tuple(combined_life(L, e) for L in lives)
        deciding = labels[int(np.argmin(set_life))] if any(math.isfinite(x) for x in set_life) else ""
        row_life = combined_life(np.concatenate(lives), e)
        row_lives.append(row_life)
        rows.append(RowLife(row.name, labels, qc, qe, set_life, a_iso * row_life, deciding))
    return BearingLife(tuple(rows), a_iso * combined_life(row_lives, bearing_weibull_slope(bearing)), rotating_ring,
                       a_iso)


def bearing_weibull_slope(bearing: Bearing) -> float:
    """e that combines the rows of a bearing: 9/8 if every row is a roller row, else 10/9 (module docstring)."""
    return ROLLER_WEIBULL_SLOPE if all(isinstance(r, RollerRow) for r in bearing.rows) else BALL_WEIBULL_SLOPE


def _check_common(rotating_ring: str, bm: float | None, a_iso: float) -> None:
    if rotating_ring not in ("moving", "fixed"):
        raise ValueError(f"rotating_ring must be 'moving' or 'fixed' (the ring turning relative to the load), "
                         f"got {rotating_ring!r}")
    for name, v in (("bm", 1.0 if bm is None else bm), ("a_iso", a_iso)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0.0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")


def rating_life(bearing: Bearing, dist: LoadDistribution, rotating_ring: Literal["moving", "fixed"] = "moving",
                bm: float | None = None, a_iso: float = 1.0,
                contact_ratings_N: dict[tuple[str, str], float] | None = None) -> BearingLife:
    """L10 per row and of the bearing from one load distribution, 10^6 revolutions (module docstring).

    Parameters
    ----------
    bearing, dist : the bearing and its rigid-ring load distribution
    rotating_ring : {"moving", "fixed"}
        The ring that turns relative to the load (its raceway gets w = 3 or 4, the other 10/3 or 9/2).
    bm : float, optional
        ISO 281 Table 1 rating factor in Q_c (default per row type, :data:`.rating.BM_DEFAULTS`).
    a_iso : float
        Life modification factor (ISO 281 9.3), given; 1 gives the basic rating life.
    contact_ratings_N : dict, optional
        Q_c per (row name, contact set label), e.g. ``("balls", "inner groove")`` or
        ``("rollers", "outer raceway")`` (whole roller), instead of the formula, N.
    """
    _check_common(rotating_ring, bm, a_iso)
    return _assemble(bearing, _row_parts(bearing, dist, rotating_ring, bm, contact_ratings_N), rotating_ring, a_iso)


def spectrum_rating_life(bearing: Bearing, loads: Sequence[RingLoad | LoadDistribution], time_shares: Sequence[float],
                         rotating_ring: Literal["moving", "fixed"] = "moving", bm: float | None = None,
                         a_iso: float = 1.0,
                         contact_ratings_N: dict[tuple[str, str], float] | None = None) -> BearingLife:
    """L10 under a load spectrum: Palmgren–Miner per contact set (lamina), L = 1/Σ(t_i/L_i), then
    combined as for one load (module docstring). ``loads``: a RingLoad per case, or its already
    solved LoadDistribution; ``time_shares`` (≥ 0, one per load) are normalised to sum to 1; the
    other parameters as :func:`rating_life`.
    """
    _check_common(rotating_ring, bm, a_iso)
    loads, t = list(loads), np.asarray(time_shares, dtype=float)
    if not loads or t.shape != (len(loads),):
        raise ValueError(f"time_shares must give one share per load ({len(loads)} loads), got {t.size}")
    if not (np.all(np.isfinite(t)) and np.all(t >= 0.0) and t.sum() > 0.0):
        raise ValueError("time_shares must be finite numbers >= 0 with a positive sum")
    t = t / t.sum()
    damage: dict[tuple[str, str], np.ndarray] = {}
    template = None
    for load, share in zip(loads, t):
        dist = load if isinstance(load, LoadDistribution) else solve_load_distribution(bearing, load)
        per_row = _row_parts(bearing, dist, rotating_ring, bm, contact_ratings_N)
        template = template or per_row
        for name, parts in per_row.items():
            for label, _, _, L in parts:
                damage[(name, label)] = damage.get((name, label), 0.0) + share / L  # 1/inf = 0: unloaded
    with np.errstate(divide="ignore"):
        per_row = {name: [(label, qc, math.nan, 1.0 / damage[(name, label)]) for label, qc, _, _ in parts]
                   for name, parts in template.items()}
    return _assemble(bearing, per_row, rotating_ring, a_iso)
