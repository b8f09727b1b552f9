"""Synthetic load spectrum of the 12 MW main bearing: 32 load cases at the inner-ring centre.

The measured spectrum is not published, so a deterministic one is built from a Weibull wind climate,
thrust and torque curves and the weights of rotor and shaft. Axes (SI units): z is the shaft axis
from the rotor (front) to the rear, y vertical up, x horizontal (x = y × z); moments are positive
by the right-hand rule about the bearing centre (origin). The rotor centre is at
z = −``rotor_overhang_m``, the shaft centre of gravity at z = ``shaft_cg_m`` (positive: behind the
bearing). Per case k of n, with thrust T and phase φ_k = 2π·``asymmetry_cycles``·k/n:

    Fx = ε T sin φ_k,  Fy = −(m_r + m_s) g,  Fz = T,
    Mx = g (−a m_r + c m_s),  My = e T cos φ_k − a Fx,  Mz = Q,

ε = ``lateral_force_ratio``, e = ``thrust_eccentricity_m``, a = overhang, c = ``shaft_cg_m``.
Fx and e T stand for the asymmetric inflow of the rotor (yaw misalignment, shear); −a Fx moves
the lateral force from the rotor centre to the bearing. The thrust acts on the axis and adds no
moment. Q is the aerodynamic torque on the rotor about +z (clockwise seen from upwind); the
bearing does not carry it (it passes to the generator) and ``include_torque=False`` drops it.

References: IEC 61400-1:2019 §6.3.2.2 (Rayleigh = Weibull k = 2 wind speeds); T. Burton et al.,
Wind Energy Handbook, 2nd ed., Wiley 2011, §3.3, §8.2 (thrust and power of pitch-regulated turbines).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicSpline

from cases.results import plt

__all__ = ["LOAD_COLUMNS", "CSV_HEADER", "SpectrumError", "SpectrumModel", "bin_edges", "load_cases", "sequence",
           "spline", "write_csv", "read_csv", "plot_spectrum"]

LOAD_COLUMNS = ("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm", "Mz_Nm")
CSV_HEADER = ("time", "Fx", "Fy", "Fz", "Mx", "My", "Mz")
_SI_UNITS = ("s", "N", "N", "N", "N*m", "N*m", "N*m")
_FORCE_UNITS = {"N": 1.0, "kN": 1e3, "MN": 1e6}
_MOMENT_UNITS = {"N*m": 1.0, "Nm": 1.0, "kN*m": 1e3, "kNm": 1e3, "MN*m": 1e6, "MNm": 1e6}


class SpectrumError(ValueError):
    """A load-spectrum CSV file that cannot be read; the message names file, row and column."""


@dataclass(frozen=True)
class SpectrumModel:
    """Wind climate, turbine curves and weights that define the load cases (SI units).

    Wind: Weibull scale 10.5 m/s, shape 2 (mean 9.3 m/s at hub height, a typical offshore site).
    Thrust T(v) = T_r (v/v_r)² for cut-in ≤ v < v_r and T_r (v_r/v)^p above (pitch regulation).
    Torque Q(v) = Q_r (v/v_r)^q below rated, Q_r = P_r/ω_r at and above; q = 2 follows from P ∝ v³
    at constant tip-speed ratio (ω ∝ v). Idle (v < cut-in): T = Q = 0; parked (v ≥ cut-out,
    feathered): T = r_p T_r, Q = 0. Gravity acts in every case.
    """

    weibull_scale_m_s: float = 10.5
    weibull_shape: float = 2.0
    cut_in_m_s: float = 3.0
    rated_m_s: float = 11.0
    cut_out_m_s: float = 25.0
    rated_thrust_N: float = 1.5e6
    thrust_decay_exponent: float = 1.0  # p
    parked_thrust_ratio: float = 0.1  # r_p
    rated_power_W: float = 12e6
    rated_speed_rpm: float = 7.8
    torque_exponent: float = 2.0  # q
    include_torque: bool = True
    rotor_mass_kg: float = 1.1e5  # rotor and hub
    shaft_mass_kg: float = 2.0e4
    rotor_overhang_m: float = 2.0  # rotor centre at z = −overhang (in front of the bearing)
    shaft_cg_m: float = 0.8  # shaft centre of gravity at z = shaft_cg_m (negative: in front)
    gravity_m_s2: float = 9.81
    lateral_force_ratio: float = 0.05  # ε
    thrust_eccentricity_m: float = 0.3  # e
    asymmetry_cycles: float = 3.0
    n_cases: int = 32

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if isinstance(v, bool) != (f.name == "include_torque") or not isinstance(v, (int, float)) \
                    or not math.isfinite(v):
                raise ValueError(f"SpectrumModel: {f.name} must be a finite {f.type}, got {v!r}")
        for names, ok, text in (
                ("weibull_scale_m_s weibull_shape cut_in_m_s rated_thrust_N rated_power_W rated_speed_rpm "
                 "gravity_m_s2", lambda v: v > 0, "> 0"),
                ("thrust_decay_exponent torque_exponent rotor_mass_kg shaft_mass_kg lateral_force_ratio",
                 lambda v: v >= 0, "≥ 0"),
                ("parked_thrust_ratio", lambda v: 0 <= v <= 1, "in [0, 1]"),
                ("n_cases", lambda v: isinstance(v, int) and v >= 3, "an integer ≥ 3")):
            for name in names.split():
                if not ok(getattr(self, name)):
                    raise ValueError(f"SpectrumModel: {name} must be {text}, got {getattr(self, name)!r}")
        if not self.cut_in_m_s < self.rated_m_s < self.cut_out_m_s:
            raise ValueError(f"SpectrumModel: need cut_in_m_s < rated_m_s < cut_out_m_s, got {self.cut_in_m_s}, "
                             f"{self.rated_m_s}, {self.cut_out_m_s}")

    @property
    def rated_torque_Nm(self) -> float:
        """Q_r = P_r/ω_r, N·m (aerodynamic torque; drive-train losses neglected)."""
        return self.rated_power_W / (self.rated_speed_rpm * 2.0 * math.pi / 60.0)


def bin_edges(model: SpectrumModel = SpectrumModel()) -> np.ndarray:
    """Wind-speed bin edges (n_cases + 1,), m/s: [0, cut-in, …(n−2 equal bins)…, cut-out, ∞].

    Case 0 is idle (v < cut-in), cases 1…n−2 operate at their bin midpoints, case n−1 is parked.
    """
    return np.concatenate(([0.0], np.linspace(model.cut_in_m_s, model.cut_out_m_s, model.n_cases - 1), [np.inf]))


def load_cases(model: SpectrumModel = SpectrumModel()) -> tuple[np.ndarray, np.ndarray]:
    """The load cases: loads (n_cases, 6) in :data:`LOAD_COLUMNS` order, N and N·m, and their time
    shares (n_cases,), the Weibull probabilities of the bins of :func:`bin_edges` (sum 1)."""
    m, n, edges = model, model.n_cases, bin_edges(model)
    share = np.diff(-np.expm1(-(edges / m.weibull_scale_m_s) ** m.weibull_shape))  # F(v) = 1 − exp(−(v/λ)^k)
    ratio = 0.5 * (edges[1:-2] + edges[2:-1]) / m.rated_m_s  # operating bin midpoints / rated speed
    below = ratio < 1.0
    thrust = np.concatenate(([0.0], m.rated_thrust_N * np.where(below, ratio**2, ratio ** -m.thrust_decay_exponent),
                             [m.parked_thrust_ratio * m.rated_thrust_N]))  # idle, operating, parked
    q = m.include_torque * m.rated_torque_Nm * np.where(below, ratio**m.torque_exponent, 1.0)
    torque = np.concatenate(([0.0], q, [0.0]))
    phase = 2.0 * math.pi * m.asymmetry_cycles * np.arange(n) / n
    g, a = m.gravity_m_s2, m.rotor_overhang_m
    fx = m.lateral_force_ratio * thrust * np.sin(phase)
    fy = np.full(n, -(m.rotor_mass_kg + m.shaft_mass_kg) * g)
    mx = np.full(n, g * (-a * m.rotor_mass_kg + m.shaft_cg_m * m.shaft_mass_kg))
    my = m.thrust_eccentricity_m * thrust * np.cos(phase) - a * fx
    return np.column_stack((fx, fy, thrust, mx, my, torque)), share


def sequence(loads, time_share, duration_s: float = 8.0, order="as_given") -> tuple[np.ndarray, np.ndarray]:
    """Lay the n cases out as equally spaced knots t_k = duration·(k + ½)/n, s.

    The time shares are not dwell times (the simulated span is far shorter than the climate);
    they stay data for weighting results. ``order``: "as_given", "by_share" (largest share
    first) or a permutation of range(n). Returns times (n,) s and the reordered loads (n, 6).
    """
    f, w = np.asarray(loads, float), np.asarray(time_share, float)
    n = f.shape[0]
    if f.ndim != 2 or f.shape[1] != 6 or w.shape != (n,) or n < 2 or not 0 < duration_s < math.inf:
        raise ValueError(f"sequence: need loads (n, 6), time_share (n,), n ≥ 2 and duration_s > 0; got {f.shape}, "
                         f"{w.shape} and {duration_s!r}")
    named = {"as_given": np.arange(n), "by_share": np.argsort(-w, kind="stable")}
    idx = named.get(order) if isinstance(order, str) else np.asarray(order)
    if idx is None or idx.shape != (n,) or not np.array_equal(np.sort(idx), np.arange(n)):
        raise ValueError(f"sequence: order must be 'as_given', 'by_share' or a permutation of range({n})")
    return duration_s * (np.arange(n) + 0.5) / n, f[idx].copy()


def spline(times_s, loads, bc_type="natural"):
    """Cubic spline f(t) → (len(t), 6) through the knots (times_s (k,), loads (k, 6)); end values held.

    ``ModelBuilder.add_load_history`` (mbd_core/multibody/builder.py) uses ``CubicSpline`` with its
    default "not-a-knot" ends and the same end-value hold: the two agree at the knots and outside
    the range but differ between knots, most in the end intervals. Pass bc_type="not-a-knot" for
    the curve the multibody model applies.
    """
    t = np.asarray(times_s, float)
    pp = CubicSpline(t, np.asarray(loads, float), axis=0, bc_type=bc_type)
    return lambda tq: pp(np.clip(np.atleast_1d(np.asarray(tq, float)), t[0], t[-1]))


def write_csv(path, times_s, loads) -> Path:
    """Write header ``time,Fx,…,Mz``, units row ``s,N,…,N*m`` and one row per knot (exact floats)."""
    t, f = np.asarray(times_s, float), np.asarray(loads, float)
    if t.ndim != 1 or f.shape != (t.size, 6):
        raise ValueError(f"write_csv: need times (k,) and loads (k, 6), got {t.shape} and {f.shape}")
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerows([CSV_HEADER, _SI_UNITS])
        w.writerows([repr(float(x)) for x in (ti, *fi)] for ti, fi in zip(t, f))
    return Path(path)


def read_csv(path) -> tuple[np.ndarray, np.ndarray]:
    """Read a file of :func:`write_csv` layout; returns times (k,) s and loads (k, 6) in N and N·m.

    Units accepted: time s; forces N, kN, MN; moments N*m, Nm, kN*m, kNm, MN*m, MNm (converted
    to SI). Errors raise :class:`SpectrumError` naming the file, the row — the 1-based line
    number in the file, header = row 1, units = row 2 — and the column.
    """
    def fail(row, col, what):
        raise SpectrumError(f"{path}: row {row}" + (f", column {col}" if col else "") + f": {what}")

    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        rows = [(reader.line_num, [c.strip() for c in r]) for r in reader if r]
    if not rows or rows[0][1] != list(CSV_HEADER):
        got = rows[0][1] if rows else []
        col = next((h for i, h in enumerate(CSV_HEADER) if i >= len(got) or got[i] != h), None)
        fail(rows[0][0] if rows else 1, col, f"header must be {','.join(CSV_HEADER)}, got {','.join(got)!r}")
    line, units = rows[1] if len(rows) > 1 else (2, [])
    if len(units) != 7:
        fail(line, None, f"missing units row or {len(units)} units, expected 7 ({','.join(_SI_UNITS)})")
    scale = []
    for i, (col, u) in enumerate(zip(CSV_HEADER, units)):
        table = {"s": 1.0} if i == 0 else _FORCE_UNITS if i <= 3 else _MOMENT_UNITS
        if u not in table:
            fail(line, col, f"unit {u!r} not one of {', '.join(table)}")
        scale.append(table[u])
    data = []
    for line, cells in rows[2:]:
        if len(cells) != 7:
            fail(line, None, f"{len(cells)} fields, expected 7")
        vals = []
        for col, c in zip(CSV_HEADER, cells):
            if not c:
                fail(line, col, "missing value")
            try:
                x = float(c)
            except ValueError:
                x = None
            if x is None or not math.isfinite(x):
                fail(line, col, f"{c!r} is not a finite number")
            vals.append(x)
        if data and vals[0] <= data[-1][1][0]:
            fail(line, "time", f"time {vals[0]!r} is not greater than {data[-1][1][0]!r} (row {data[-1][0]})")
        data.append((line, vals))
    if len(data) < 2:
        fail(rows[-1][0], None, f"needs at least 2 data rows, found {len(data)}")
    a = np.array([v for _, v in data]) * np.array(scale)
    return a[:, 0], a[:, 1:]


def plot_spectrum(times_s, loads, time_share, path, bc_type="not-a-knot") -> Path:
    """PNG: top, the six components vs time (N, N·m; spline and knots); bottom, time shares of
    the load cases, numbered from 1.

    The default ``bc_type`` draws the curve ``ModelBuilder.add_load_history`` applies.
    """
    pyplot = plt()
    t, f = np.asarray(times_s, float), np.asarray(loads, float)
    dense = np.linspace(t[0], t[-1], 40 * t.size)
    curve = spline(t, f, bc_type=bc_type)(dense)
    fig, (top, bottom) = pyplot.subplots(2, 1, figsize=(9, 7), constrained_layout=True)
    for j, name in enumerate(CSV_HEADER[1:]):  # forces solid, moments dashed
        line, = top.plot(dense, curve[:, j], "-" if j < 3 else "--", label=name)
        top.plot(t, f[:, j], "o", ms=3, color=line.get_color())
    top.set(xlabel="time (s)", ylabel="force (N), moment (N·m)")
    top.legend(ncol=3, fontsize=8, loc="upper left")
    top.grid(alpha=0.3)
    bottom.bar(np.arange(1, len(time_share) + 1), 100.0 * np.asarray(time_share, float))
    bottom.set(xlabel="load case", ylabel="time share (%)")
    fig.savefig(path, dpi=120)
    pyplot.close(fig)
    return Path(path)
