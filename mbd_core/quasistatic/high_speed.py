"""Load distribution of a ball row at speed: centrifugal force and gyroscopic moment of the balls.

At rest both contacts of a ball lie on one line and carry one load. At speed the ball's centrifugal
force F_c pushes it outwards and its gyroscopic moment must be held by friction, so each ball has its
own equilibrium: the outer contact carries more than the inner one and the two contact angles part
(α_o < α_i). This is Jones' quasi-static model (A. B. Jones, "A general theory for elastically
constrained ball and radial roller bearings under arbitrary load and speed conditions", Trans. ASME
J. Basic Eng. 82 (1960) 309–320; Harris & Kotzalas, Advanced Concepts of Bearing Technology, 5th ed.,
ch. 3), written here for a row whose inner ring turns at ω_i and whose outer ring is fixed.

Each ball j at azimuth ψ_j moves in its plane (e_r, e_z). With O_o the outer groove's curvature
centre (fixed) and O_i the inner one's (moved by the inner ring's displacement q = (x, y, z, θx, θy),
as in :mod:`.elements`), its centre b gives

    δ_o = |b − O_o| − (f_o − ½)D,   n_o = (b − O_o)/|b − O_o|,   Q_o = K_o δ_o^{3/2}   (contact at b + (D/2) n_o)
    δ_i = |b − O_i| − (f_i − ½)D,   n_i = (b − O_i)/|b − O_i|,   Q_i = K_i δ_i^{3/2}   (contact at b + (D/2) n_i)

(K_o, K_i of each Hertz contact, :func:`mbd_core.contact.hertz.ball_on_groove`).

**Kinematics** (race control, the contacts' centres rolling without slip): the orbit speed ω_m and
the ball's angular velocity Ω = Ω_r e_r + Ω_z e_z (inertial) solve three linear conditions, with r_b
the radius of the ball centre:

    (ω_m r_b e_t + Ω × ρ_o)·e_t = 0                    rolling on the fixed outer race,
    (ω_m r_b e_t + Ω × ρ_i)·e_t = ω_i (r_b + ρ_i·e_r)   rolling on the inner race,
    Ω·n_o = 0 (outer race control) or (Ω − ω_i e_z)·n_i = 0 (inner race control)   no spin there,

ρ = (D/2) n the contact points. For outer control this gives Jones' spin-axis angle
tan β = sin α_o/(cos α_o + D/d_m) of the ball relative to the cage (checked in the tests).

**Loads on the ball**: F_c = m ω_m² r_b outwards; the gyroscopic moment the contacts must supply,
M = ω_m e_z × (J Ω) = J ω_m Ω_r e_t (J = m D²/10, steady precession), held by friction at the
controlling race: a force (2M/D) along t = (n_z, −n_r) in the ball plane there, so that
(ρ × t)·e_t = D/2 ("none": half at each race, λ_i = λ_o = 1 in Harris' notation). A contact holds
at most ``TRACTION_LIMIT``·Q of it (a contact without load holds none; a loaded one in the tests
holds it all). The ball's equilibrium

    −Q_o n_o − Q_i n_i + F_c e_r + friction = 0

is solved per ball (2 unknowns, pseudo-transient continuation, :func:`_settle_balls`) inside a Newton
iteration on the ring's equilibrium f_ext + Σ (forces of the balls on the inner ring) = 0 (5 unknowns,
finite-difference Jacobian), and the speed is raised from rest in steps (halved where one fails). A
ball that loses its inner contact sits at the bottom of the outer groove under F_c, carried by the
cage (:func:`_kinematics`). The first step is the static load distribution
(:func:`.solver.solve_load_distribution`), so a load the row cannot carry at rest is refused with that
solver's message.

Checks (``tests/test_high_speed_rows.py``): at rest, the static distribution; under thrust, a
Jones/Harris solution in its classical form; and the multibody dynamics of the same bearing (friction at
both contacts) settles between the inner- and outer-control solutions, which fixes the sign of the
friction couple independently.

Left out: the balls' drag and the friction of spin and sliding beyond the gyroscopic couple
(Harris' "Q-S" refinements), the rings' hoop growth and their own centrifugal expansion, cage forces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from foundation.validation import check_positive
from .elements import build_groups, displacement_matrix
from .results import LoadDistributionError, RingLoad
from .row_common import ball_contact_stiffnesses, ball_mass_kg
from .rows import BallRow, Bearing
from .solver import solve_load_distribution

__all__ = ["RACE_CONTROL", "HighSpeedRow", "solve_high_speed_row"]

#: which race holds the gyroscopic moment (no spin there)
RACE_CONTROL = ("outer", "inner", "none")
#: the largest traction coefficient with which a contact holds the gyroscopic couple (an EHL film's
#: limiting traction, 0.05–0.1; beyond it the ball would pivot)
TRACTION_LIMIT = 0.1
#: a ball rolls on its own when both its contacts carry more than this fraction of the load at an
#: approach of 1e-3·D; below, the cage carries it (continuity of the orbit speed, :func:`_kinematics`)
BLEND_LOAD_FRACTION = 1e-3
#: most steps of the continuation in speed (one per quarter of the load in the balls' centrifugal force)
MAX_SPEED_STEPS = 40
#: a failed step in speed is halved at most this many times
MAX_HALVINGS = 6
#: passes of the balls' equilibria with the cage speed updated between them
MAX_CAGE_PASSES = 20
#: a ball's equilibrium is accepted within this fraction of the load scale when Newton stalls (the
#: cage-carried blend of a barely loaded ball is only piecewise smooth); well-posed balls reach 1e-10
BALL_TOLERANCE = 1e-5


@dataclass(frozen=True)
class HighSpeedRow:
    """Equilibrium of a ball row at speed (module docstring). Arrays are (Z,) per ball.

    displacement : (5,) inner ring (x, y, z m, θx, θy rad)
    azimuth_rad; inner_load_N, outer_load_N : Q_i, Q_o; inner_angle_rad, outer_angle_rad : α_i, α_o
    (atan2 of the axial component, on the loaded side, and the radial one of each contact normal);
    orbit_speed_rad_s : ω_m; spin_rad_s : (Z, 2) Ω_r, Ω_z (inertial); centrifugal_N : F_c;
    gyroscopic_moment_Nm : M; iterations : of the ring's Newton iterations (all speed steps)
    ball_centre_rz_m : (Z, 2) each ball centre's radius and height (the row's frame), m — with
    ``displacement`` a start for a dynamic run without start-up shock
    stiffness : (5, 5) the row's tangent stiffness at the operating point, K[i, j] = dF_i/dq_j with F
    the load on the inner ring that holds it at q (N/m, N/rad, N·m/m, N·m/rad, as
    :func:`.solver.stiffness_matrix`), by central differences with every ball settled again
    """

    displacement: np.ndarray
    azimuth_rad: np.ndarray
    inner_load_N: np.ndarray
    outer_load_N: np.ndarray
    inner_angle_rad: np.ndarray
    outer_angle_rad: np.ndarray
    orbit_speed_rad_s: np.ndarray
    spin_rad_s: np.ndarray
    centrifugal_N: np.ndarray
    gyroscopic_moment_Nm: np.ndarray
    iterations: int
    ball_centre_rz_m: np.ndarray
    stiffness: np.ndarray


@dataclass(frozen=True)
class _Geometry:
    psi: np.ndarray            # (Z,)
    e_r: np.ndarray            # (Z, 3)
    p_inner: np.ndarray        # (Z, 3) inner curvature centres at rest, world
    B: np.ndarray              # (Z, 3, 5) their displacement per unit q
    outer_rz: np.ndarray       # (Z, 2) outer curvature centre (r, z)
    b0_rz: np.ndarray          # (Z, 2) ball centre at rest
    free_i: float              # (f_i − ½)D
    free_o: float
    K_i: float
    K_o: float
    mass: float
    J: float
    cage_ratio: float          # ω_m/ω_i of rolling at the free contact angle
    blend_N: float             # contact load below which a ball is carried by the cage (:func:`_kinematics`)
    D: float
    axial_sign: float


def _geometry(row: BallRow) -> _Geometry:
    """The row's grooves as the static solver has them (:mod:`.elements`: the moving groove's centre
    p and the unloaded vector s0 from the fixed groove's centre to it, clearance included), in each
    ball's (r, z) plane."""
    Z, D = row.n_balls, row.ball_diameter_m
    balls = build_groups(Bearing(row.name, (row,)))[0]
    e_r = balls.e_r

    def rz(v):
        return np.stack([np.sum(v * e_r, axis=1), v[:, 2]], axis=1)

    p_inner = balls.p_m
    centre = np.array([0.5 * row.pitch_diameter_m, row.axial_position_m])
    mass = ball_mass_kg(D, row.ball_material.density_kg_m3)
    K_i, K_o = ball_contact_stiffnesses(row)
    return _Geometry(row.azimuths_rad(), e_r, p_inner,
                     displacement_matrix(p_inner), rz(p_inner - balls.s0_m), np.tile(centre, (Z, 1)),
                     (row.conformity_moving - 0.5) * D, (row.conformity_fixed - 0.5) * D, K_i, K_o, mass,
                     0.1 * mass * D * D, 0.5 * (1.0 - D * math.cos(row.contact_angle_rad) / row.pitch_diameter_m),
                     BLEND_LOAD_FRACTION * row.contact_stiffness() * (1e-3 * D) ** 1.5, D, float(row.axial_sign))


def _inner_centres_rz(g: _Geometry, q: np.ndarray) -> np.ndarray:
    """(Z, 2) inner curvature centres (r, z) in each ball's plane for the ring displacement q."""
    p = g.p_inner + g.B @ q
    return np.stack([np.sum(p * g.e_r, axis=1), p[:, 2]], axis=1)


def _balls_at_rest(g: _Geometry, inner_rz) -> np.ndarray:
    """(Z, 2) ball centres on the line between the curvature centres, the pair's approach δ = L − A
    shared as two Hertz contacts in series share it (δ_i/δ_o = (K_o/K_i)^{2/3}, equal loads); a ball
    with play sits in the middle of it. At rest this is the static equilibrium of every loaded ball."""
    d = inner_rz - g.outer_rz
    L = np.hypot(d[:, 0], d[:, 1])
    delta = L - g.free_o - g.free_i
    share_o = 1.0 / (1.0 + (g.K_o / g.K_i) ** (2.0 / 3.0))
    return g.outer_rz + ((g.free_o + share_o * delta) / L)[:, None] * d


def _contact(centre_rz, b_rz, free_m, K):
    w = b_rz - centre_rz
    L = np.hypot(w[:, 0], w[:, 1])
    n = w / L[:, None]
    delta = L - free_m
    Q = K * np.maximum(delta, 0.0) ** 1.5
    return Q, n


def _kinematics(g: _Geometry, b_rz, n_o, n_i, Q_o, Q_i, omega_i: float, control: str, cage: float | None = None):
    """(ω_m, Ω_r, Ω_z) per ball (module docstring). A ball with both contacts loaded: the three
    linear conditions. A ball that touches one race only is carried by the cage: it orbits at the
    balls' mean orbit speed (weighted by Q_i; with none loaded, the rolling speed at the free contact
    angle, ω_i(1 − γ cos α0)/2) and rolls without spin on the race it touches. In between the two
    are blended by the lesser contact load (``blend_N``)."""
    Z = b_rz.shape[0]
    r_b = b_rz[:, 0]
    h = 0.5 * g.D
    # Ω × ρ · e_t = Ω_z ρ_r − Ω_r ρ_z
    A = np.zeros((Z, 3, 3))
    rhs = np.zeros((Z, 3))
    A[:, 0, 0], A[:, 0, 1], A[:, 0, 2] = r_b, -h * n_o[:, 1], h * n_o[:, 0]
    A[:, 1, 0], A[:, 1, 1], A[:, 1, 2] = r_b, -h * n_i[:, 1], h * n_i[:, 0]
    rhs[:, 1] = omega_i * (r_b + h * n_i[:, 0])
    if control == "inner":
        A[:, 2, 1], A[:, 2, 2] = n_i[:, 0], n_i[:, 1]
        rhs[:, 2] = omega_i * n_i[:, 1]
    else:   # outer control, and the spin axis of "none" (its moment is split between the races)
        A[:, 2, 1], A[:, 2, 2] = n_o[:, 0], n_o[:, 1]
    own = np.linalg.solve(A, rhs[..., None])[..., 0]
    if cage is None:
        weight = np.sum(Q_i)
        cage = float(Q_i @ own[:, 0]) / weight if weight > 0.0 else omega_i * g.cage_ratio
    # carried by the cage: rolling without spin on the race it touches (the outer one unless only the
    # inner one is loaded)
    outer = ~((Q_o == 0.0) & (Q_i > 0.0))
    n = np.where(outer[:, None], n_o, n_i)
    race = np.where(outer, 0.0, omega_i)
    A2 = np.zeros((Z, 2, 2))
    A2[:, 0, 0], A2[:, 0, 1] = -h * n[:, 1], h * n[:, 0]
    A2[:, 1, 0], A2[:, 1, 1] = n[:, 0], n[:, 1]
    rhs2 = np.stack([race * (r_b + h * n[:, 0]) - cage * r_b, race * n[:, 1]], axis=1)
    carried = np.concatenate([np.full((Z, 1), cage), np.linalg.solve(A2, rhs2[..., None])[..., 0]], axis=1)
    # blended by the lesser contact load, so that the speeds (and F_c) stay continuous as a contact
    # opens: a ball loaded on both sides by more than g.blend_N rolls on its own, independent of the others
    w = np.minimum(np.minimum(Q_o, Q_i) / g.blend_N, 1.0)[:, None]
    return w * own + (1.0 - w) * carried, cage


def _ball_state(g: _Geometry, b_rz, inner_rz, omega_i: float, control: str, cage: float | None = None):
    """Forces on each ball and what makes them: (residual (Z, 2), Q_i, Q_o, n_i, n_o, kin, F_c, M, friction
    force on the inner ring (Z, 2), cage speed); ``cage`` given: the speed of the cage-carried balls
    held at it."""
    Q_o, n_o = _contact(g.outer_rz, b_rz, g.free_o, g.K_o)
    Q_i, n_i = _contact(inner_rz, b_rz, g.free_i, g.K_i)
    kin, cage = _kinematics(g, b_rz, n_o, n_i, Q_o, Q_i, omega_i, control, cage)
    w_m = kin[:, 0]
    F_c = g.mass * w_m**2 * b_rz[:, 0]
    M = g.J * w_m * kin[:, 1]
    share_o = {"outer": 1.0, "inner": 0.0, "none": 0.5}[control]
    # the controlling contact holds the couple as far as its traction allows (continuous in Q at 0)
    f_o = np.clip(2.0 * share_o * M / g.D, -TRACTION_LIMIT * Q_o, TRACTION_LIMIT * Q_o)
    f_i = np.clip(2.0 * (1.0 - share_o) * M / g.D, -TRACTION_LIMIT * Q_i, TRACTION_LIMIT * Q_i)
    t_o = np.stack([n_o[:, 1], -n_o[:, 0]], axis=1)
    t_i = np.stack([n_i[:, 1], -n_i[:, 0]], axis=1)
    res = -Q_o[:, None] * n_o - Q_i[:, None] * n_i + f_o[:, None] * t_o + f_i[:, None] * t_i
    res[:, 0] += F_c
    return res, Q_i, Q_o, n_i, n_o, kin, F_c, M, -f_i[:, None] * t_i, cage


def _settle_balls(g: _Geometry, b_rz, inner_rz, omega_i: float, control: str, scale_N: float):
    """Each ball's centre at its equilibrium, by pseudo-transient continuation per ball (Kelley & Keyes,
    SIAM J. Numer. Anal. 35 (1998) 508): (μ I − J) d = r with J = ∂r/∂b (finite differences) and μ
    reduced as the residual falls (switched evolution relaxation, μ ← μ·|r_new|/|r_old|). A large μ
    moves a ball along its net force, as a damped ball would (a ball touching no race, pushed out by
    F_c, whose ∂r/∂b = m ω_m² > 0 would send plain Newton inwards); a small μ is Newton's step.
    μ stays above 10·m·ω_i² and every step changes the contacts' approaches by at most 1e-3·D. The
    cage speed that carries the barely loaded balls is held during a pass and updated between passes
    (so each ball's problem is its own)."""
    cage = _ball_state(g, b_rz, inner_rz, omega_i, control)[9]
    for _ in range(MAX_CAGE_PASSES):
        b_rz = _settle_at_cage(g, b_rz, inner_rz, omega_i, control, scale_N, cage)
        new = _ball_state(g, b_rz, inner_rz, omega_i, control)[9]
        if abs(new - cage) <= 1e-12 * max(abs(omega_i), 1e-300):
            return b_rz
        cage = new
    return b_rz


def _settle_at_cage(g: _Geometry, b_rz, inner_rz, omega_i: float, control: str, scale_N: float, cage: float):
    """:func:`_settle_balls` with the cage speed held (each ball's equilibrium then its own)."""
    h = 1e-9 * g.D
    mu_floor = 1e-9 * g.K_o * math.sqrt(g.D) + 10.0 * g.mass * omega_i**2
    mu = np.full(b_rz.shape[0], mu_floor)
    limit = 1e-3 * g.D

    def residual(b):
        return _ball_state(g, b, inner_rz, omega_i, control, cage)

    st = residual(b_rz)
    r = st[0]
    norm = np.hypot(r[:, 0], r[:, 1])
    for _ in range(400):
        if np.max(norm) <= 1e-10 * scale_N:
            return b_rz
        J = np.empty((b_rz.shape[0], 2, 2))
        for k in range(2):
            bp = b_rz.copy()
            bp[:, k] += h
            J[:, :, k] = (residual(bp)[0] - r) / h
        step = np.linalg.solve(mu[:, None, None] * np.eye(2) - J, r[..., None])[..., 0]
        normal = np.maximum(np.abs(np.sum(step * st[4], axis=1)), np.abs(np.sum(step * st[3], axis=1)))
        step *= np.minimum(1.0, limit / np.maximum(normal, 1e-300))[:, None]
        b_rz = b_rz + step
        st = residual(b_rz)
        r = st[0]
        new = np.hypot(r[:, 0], r[:, 1])
        mu = np.clip(mu * new / np.maximum(norm, 1e-300), mu_floor, 1e3 * mu)
        norm = new
    if np.max(norm) <= BALL_TOLERANCE * scale_N:
        return b_rz       # settled as far as the blend of a ball's kinematics (:func:`_kinematics`) allows
    k = int(np.argmax(norm))
    raise LoadDistributionError(
        f"high-speed ball equilibrium: ball {k} did not settle in 400 iterations at "
        f"{omega_i * 30 / math.pi:.6g} rev/min (residual {norm[k]:.3g} N, contact loads {st[1][k]:.3g} N inner, "
        f"{st[2][k]:.3g} N outer)")


def _ring_residual(g: _Geometry, q, b_rz, f_ext, omega_i, control, scale_N):
    inner_rz = _inner_centres_rz(g, q)
    b_rz = _settle_balls(g, b_rz, inner_rz, omega_i, control, scale_N)
    state = _ball_state(g, b_rz, inner_rz, omega_i, control)
    Q_i, n_i, fric = state[1], state[3], state[8]
    # force of ball on the inner ring: +Q_i n_i (the ball gets −Q_i n_i) and the reaction of the friction
    f_rz = Q_i[:, None] * n_i + fric
    f = f_rz[:, :1] * g.e_r + f_rz[:, 1:] * np.array([0.0, 0.0, 1.0])
    r = f_ext + np.einsum("nji,nj->i", g.B, f)
    return r, b_rz, state


def _ring_equilibrium(g: _Geometry, row: BallRow, q, b_rz, f_ext, omega_i: float, control: str, scale_N: float, S,
                      tolerance: float, max_iterations: int):
    """Newton on the ring's 5 coordinates (finite-difference Jacobian) with every ball settled at each
    evaluation; steps of at most 5e-4·D, halved while the residual grows or a ball cannot settle
    there. Returns (q, ball centres, ball state, iterations)."""
    h_q = np.array([1e-10, 1e-10, 1e-10, 1e-10 / S[3], 1e-10 / S[4]]) * max(1.0, 1e3 * row.ball_diameter_m)
    weights = np.array([1.0, 1.0, 1.0, 1.0 / S[3], 1.0 / S[4]])
    r, b_rz, state = _ring_residual(g, q, b_rz, f_ext, omega_i, control, scale_N)
    for it in range(1, max_iterations + 1):
        norm = float(np.max(np.abs(r * weights)))
        if norm <= tolerance * scale_N:
            return q, b_rz, state, it
        J = np.empty((5, 5))
        for k in range(5):
            dq = np.zeros(5)
            dq[k] = h_q[k]
            J[:, k] = (_ring_residual(g, q + dq, b_rz, f_ext, omega_i, control, scale_N)[0] - r) / h_q[k]
        free = np.abs(np.diag(J)) > 0.0
        step = np.zeros(5)
        step[free] = np.linalg.lstsq(J[np.ix_(free, free)], -r[free], rcond=None)[0]
        big = max(np.max(np.abs(step[:3])), np.max(np.abs(step[3:])) * S[3])
        step *= min(1.0, 5e-4 * g.D / max(big, 1e-300))
        for _ in range(12):
            try:
                trial = _ring_residual(g, q + step, b_rz, f_ext, omega_i, control, scale_N)
            except LoadDistributionError:
                step *= 0.5
                continue
            if float(np.max(np.abs(trial[0] * weights))) < norm:
                break
            step *= 0.5
        else:
            break
        q = q + step
        r, b_rz, state = trial
    raise LoadDistributionError(
        f"high-speed ball row {row.name!r}: no equilibrium of the inner ring in {max_iterations} iterations at "
        f"{omega_i * 30 / math.pi:.6g} rev/min (residual {np.max(np.abs(r)):.3g} N): the row cannot carry the load "
        "at this speed")


def solve_high_speed_row(row: BallRow, load: RingLoad, inner_speed_rad_s: float, control: str = "outer",
                         tolerance: float = 1e-6, max_iterations: int = 60) -> HighSpeedRow:
    """The inner ring's and each ball's equilibrium at speed (module docstring).

    Parameters
    ----------
    row : BallRow
        With ``moving_raceway = "inner"``: the inner ring turns and carries ``load``.
    load : RingLoad
        On the inner ring, N and N·m; its axial component must push the ring the way the row carries.
    inner_speed_rad_s : the inner ring's speed ω_i, rad/s (0: the static distribution)
    control : "outer", "inner" or "none" (:data:`RACE_CONTROL`)
    tolerance : equilibrium of the ring, relative to the largest of the load and Z·F_c
    """
    if not isinstance(row, BallRow) or row.moving_raceway != "inner":
        raise ValueError("solve_high_speed_row: give a BallRow whose moving raceway is the inner one (the turning ring)")
    if control not in RACE_CONTROL:
        raise ValueError(f"control must be one of {', '.join(RACE_CONTROL)}, got {control!r}")
    if not math.isfinite(inner_speed_rad_s):
        raise ValueError(f"inner_speed_rad_s must be finite, got {inner_speed_rad_s!r}")
    check_positive("solve_high_speed_row", tolerance=tolerance)
    g = _geometry(row)
    f_ext = load.as_array()
    # the moment's lever: the pitch radius (moments and forces alike in the tolerance)
    S = np.array([1.0, 1.0, 1.0, 0.5 * row.pitch_diameter_m, 0.5 * row.pitch_diameter_m])
    w_guess = 0.5 * inner_speed_rad_s * (1.0 - row.ball_diameter_m * math.cos(row.contact_angle_rad) / row.pitch_diameter_m)
    scale_N = max(float(np.max(np.abs(f_ext / np.array([1, 1, 1, S[3], S[4]])))),
                  row.n_balls * g.mass * w_guess**2 * 0.5 * row.pitch_diameter_m, 1e-6)
    # continuation in speed from the static equilibrium: the balls' centres move continuously as F_c
    # grows, so each step starts near its answer (a ball wedged between the grooves at speed is reached
    # without jumping over the corner where its two contacts meet)
    q = solve_load_distribution(Bearing(row.name, (row,)), load).displacement.copy()
    b_rz = _balls_at_rest(g, _inner_centres_rz(g, q))
    f_c = row.n_balls * g.mass * w_guess**2 * 0.5 * row.pitch_diameter_m
    load_N = max(float(np.max(np.abs(f_ext[:3]))), float(np.max(np.abs(f_ext[3:]))) / S[3], 1e-6)
    n_steps = int(np.clip(math.ceil(4.0 * f_c / load_N), 1, MAX_SPEED_STEPS))
    iterations, done, step = 0, 0.0, inner_speed_rad_s / n_steps
    while done < inner_speed_rad_s:
        speed = min(done + step, inner_speed_rad_s)
        try:
            q_new, b_new, state, it = _ring_equilibrium(g, row, q, b_rz, f_ext, float(speed), control, scale_N, S,
                                                        tolerance, max_iterations)
        except LoadDistributionError:
            if step < inner_speed_rad_s / (n_steps * 2**MAX_HALVINGS):
                raise
            step *= 0.5     # a smaller step in speed from the last equilibrium
            continue
        q, b_rz, done = q_new, b_new, speed
        iterations += it
    if inner_speed_rad_s == 0.0:
        q, b_rz, state, iterations = _ring_equilibrium(g, row, q, b_rz, f_ext, 0.0, control, scale_N, S, tolerance,
                                                       max_iterations)
    it = iterations
    _, Q_i, Q_o, n_i, n_o, kin, F_c, M, _, _ = state
    sa = g.axial_sign
    K = _stiffness(g, row, q, b_rz, inner_speed_rad_s, control, scale_N, S)
    return HighSpeedRow(q, g.psi, Q_i, Q_o, np.arctan2(-sa * n_i[:, 1], -n_i[:, 0]), np.arctan2(sa * n_o[:, 1], n_o[:, 0]),
                        kin[:, 0], kin[:, 1:], F_c, M, it, b_rz, K)


def _stiffness(g: _Geometry, row: BallRow, q, b_rz, omega_i: float, control: str, scale_N: float, S) -> np.ndarray:
    """K = −∂(ball forces on the ring)/∂q at q, central differences (steps 1e-7·D, 1e-7·D/R), balls settled."""
    K = np.zeros((5, 5))
    zero = np.zeros(5)
    for k in range(5):
        h = 1e-7 * g.D / (1.0 if k < 3 else S[k])
        dq = np.zeros(5)
        dq[k] = h
        plus = _ring_residual(g, q + dq, b_rz, zero, omega_i, control, scale_N)[0]
        minus = _ring_residual(g, q - dq, b_rz, zero, omega_i, control, scale_N)[0]
        K[:, k] = -(plus - minus) / (2.0 * h)
    return K
