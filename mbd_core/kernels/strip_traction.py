"""Traction of an elliptical contact from the slip distribution across it (strip model).

The Hertz ellipse (semi-axes a along y, the major axis across the rolling direction, and b along
x, the rolling direction) is cut into ``n`` strips along its major axis, as in the DREB program
(README, Sources) and its successors. Along a strip the slip is taken as that of its centre line.
The contact surface of a ball in a groove is curved across the major axis: its points lie at
(0, y, z(y)), z = κ·y² towards body 1 (κ = 1/(2R_d), R_d the radius of the deformed surface,
2·r_groove·r_ball/(r_groove + r_ball) for equal elastic constants: Harris & Kotzalas, *Rolling
Bearing Analysis*, the "Heathcote" slip of conforming contacts). Body 1 slips relative to body 2
there with the rigid-body field v + ω × (0, y, z):

    v(y) = (v_x − ω_z·y + ω_y·z(y),  v_y − ω_x·z(y)),

v_x, v_y the sliding velocity at the contact centre, ω the relative angular velocity (ω_z the spin
about the contact normal z = x × y, ω_y the rolling about the major axis). Spin alone gives one
point of pure rolling; the rolling term over the curved surface gives the two of a conforming
groove. The Hertz pressure p0·√(1 − x²/a'² − y²/a²) integrated over x gives the load
per unit length q(y) = (3Q / 4a)·(1 − y²/a²); each strip carries its exact share

    Q_i = Q·(S(y_i+1) − S(y_i)),   S(y) = ¾·(y/a − y³/(3a³)) + ½,

at its load centroid ȳ_i, where the traction is −μ(|v(ȳ_i)|)·Q_i·v/|v| with μ any law of
:mod:`mbd_core.kernels.laws`. The sums give the tangential force on body 1 and its moment about
the contact centre, the levers (0, ȳ_i, z(ȳ_i)): the spin torque M_z = −Σ ȳ_i·F_x,i and the small
M_x, M_y of the curved surface. The centre-point law −μ(|v(0)|)·Q·v̂(0) is the limit of a narrow
ellipse (a → 0) or of no spin and a flat contact.

Closed forms of the strip model on a flat contact (tests): constant μ and pure spin,
M = −sign(ω)·(3/8)·μ·Q·a; linear law μ = B·u, F_x = −B·Q·v_x and M = −B·ω·Q·a²/5; on a curved
one with the linear law and rolling only, F_x = −B·Q·(v_x + ω_y·κ·a²/5).
"""

from __future__ import annotations

import math

from numba import njit

from .laws import friction_coefficient

__all__ = ["strip_geometry", "strip_table", "strip_traction", "strip_traction_forces"]


@njit(cache=True, inline="always", _nrt=False)
def strip_geometry(i, n_strips):
    """(ȳ/a, Q_i/Q) of strip i of ``n_strips`` across the major axis: its load centroid in units of a,
    ∫ s(1 − s²) ds / ∫ (1 − s²) ds over the strip, and its share of the load, ¾ ∫ (1 − s²) ds =
    S(s1) − S(s0) (module docstring)."""
    width = 2.0 / n_strips
    s0 = -1.0 + width * i
    s1 = -1.0 + width * (i + 1)
    s0_2, s1_2 = s0 * s0, s1 * s1
    m0 = (s1 - s0) - (s1_2 * s1 - s0_2 * s0) / 3.0
    m1 = 0.5 * (s1_2 - s0_2) - 0.25 * (s1_2 * s1_2 - s0_2 * s0_2)
    return m1 / m0, 0.75 * m0


@njit(cache=True, _nrt=False)
def strip_table(n_strips, out):
    """:func:`strip_geometry` of every strip of ``n_strips`` into ``out`` (n_strips, 2): the table
    :func:`strip_traction_forces` reads instead of computing it per contact."""
    for i in range(n_strips):
        out[i, 0], out[i, 1] = strip_geometry(i, n_strips)


@njit(cache=True, inline="always", _nrt=False)
def strip_traction_forces(load_N, a_m, slip_x, slip_y, omega_x, omega_y, omega_z, curvature_per_m, law, p0, p1, p2,
                          p3, n_strips, each=None, table=None):
    """(F_x, F_y N, M_x, M_y, M_z N·m) on body 1 from ``n_strips`` strips over a curved contact surface
    (module docstring); ω the relative angular velocity of body 1 in the contact frame, rad/s. ``each``
    (≥ n_strips, 5), when given: per strip (ȳ, z(ȳ) m, Q_i N, |v| m/s, secant μQ_i/|v| N·s/m; 0 where it
    does not slip), for the damping matrices of implicit friction (:mod:`.friction_damping`). ``table``:
    a :func:`strip_table`, read when it was built for ``n_strips`` strips (the same numbers, without a
    division per strip)."""
    fx, fy, mx, my, mz = 0.0, 0.0, 0.0, 0.0, 0.0
    if load_N <= 0.0:
        return fx, fy, mx, my, mz
    tabled = table is not None and table.shape[0] == n_strips
    for i in range(n_strips):
        if tabled:
            centroid, share = table[i, 0], table[i, 1]
        else:
            centroid, share = strip_geometry(i, n_strips)
        q = load_N * share
        y = a_m * centroid
        z = curvature_per_m * y * y
        vx = slip_x - omega_z * y + omega_y * z
        vy = slip_y - omega_x * z
        u = math.sqrt(vx * vx + vy * vy)
        f = 0.0
        if u > 0.0:
            f = friction_coefficient(law, u, p0, p1, p2, p3) * q / u
            fx -= f * vx
            fy -= f * vy
            # lever (0, y, z) × (−f vx, −f vy, 0)
            mx += z * f * vy
            my -= z * f * vx
            mz += y * f * vx
        if each is not None:
            each[i, 0], each[i, 1], each[i, 2], each[i, 3], each[i, 4] = y, z, q, u, f
    return fx, fy, mx, my, mz


@njit(cache=True, _nrt=False)
def strip_traction(load_N, a_m, slip_x, slip_y, spin_rad_s, law, p0, p1, p2, p3, n_strips, out):
    """F_x, F_y (N) and M_z (N·m) on body 1 into ``out`` (3,) over a flat contact with spin only."""
    fx, fy, _, _, mz = strip_traction_forces(load_N, a_m, slip_x, slip_y, 0.0, 0.0, spin_rad_s, 0.0, law, p0, p1,
                                             p2, p3, n_strips)
    out[0], out[1], out[2] = fx, fy, mz
