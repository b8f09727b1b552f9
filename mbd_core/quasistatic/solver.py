"""Quasi-static load distribution of a bearing with rigid rings.

The equilibrium of the moving ring,

    Σ_i F_i(q) + F_ext = 0,   Σ_i (p_i × F_i(q))_{x,y} + M_ext = 0,

for q = (x, y, z, θx, θy) (the spin θz has no stiffness and is not an unknown). F_i are the
forces of the balls and roller slices on the moving ring (see :mod:`.rows`). It is solved as the
minimum of the ring's convex potential energy (:mod:`.newton`): a start that closes the
clearances along the linear-spring estimate, then Newton steps with the analytic Jacobian,
Levenberg–Marquardt regularised where elements have lost contact, and a line search on the
energy — convergent from any start for any load the rows can carry, whatever the clearance.
The potential is convex while the grooves are taken as full tori; the groove edges (beyond
which a ball is unloaded, :mod:`.rows`) make it discontinuous. So the first stage solves on full
tori and the second, from there, lets the balls that ran over an edge drop out.
Moments and rotations are scaled by the largest pitch radius so that the system is well
balanced. Convergence is relative: |residual| ≤ tolerance·max(|load|, Σ element loads) plus the
rounding level of the approaches, never an absolute force. Degrees of freedom in which the
bearing has no stiffness and no load (the axial direction of a purely radial roller row, say)
are held at zero; a load on such a degree of freedom is an error.

Reference: Harris & Kotzalas, *Advanced Concepts of Bearing Technology*, 5th ed., ch. 1
("rigid rings" load distribution), and ISO/TS 16281:2008 for the slice model.
"""

from __future__ import annotations

import logging
from dataclasses import replace

import numpy as np

from .elements import BallGroup, SliceGroup, build_groups, displacement_matrix
from .newton import Evaluation, minimise_potential, ray_start, safe_norm
from .results import DOF_NAMES, LOAD_NAMES, LoadDistribution, LoadDistributionError, RingLoad, RowLoads
from .rows import BallRow, Bearing, FourPointRow
from .validity import approach_limit_error, load_distribution_warnings

__all__ = ["RingLoad", "RowLoads", "LoadDistribution", "LoadDistributionError", "solve_load_distribution",
           "stiffness_matrix", "DOF_NAMES"]

log = logging.getLogger(__name__)

#: Relative equilibrium error above which a result converged to the rounding level is flagged,
#: and above which it is refused (LoadDistributionError).
ROUNDING_WARNING_LIMIT = 1e-6
ROUNDING_ERROR_LIMIT = 1e-2
#: Rounding level of an approach δ = |s| − A (or w·q − offset), in units of the lengths involved.
_ROUNDING = 8.0 * np.finfo(float).eps

# --------------------------------------------------------------------------- element forces
# The generalised force of a point force F at p is Bᵀ(p)·F (virtual work with u = B(p)·q).

def ball_forces(g: BallGroup, B: np.ndarray, q: np.ndarray, jacobian: bool = True, groove_edges: bool = True):
    """Ball loads and their resultant on the moving ring.

    ``groove_edges=False`` takes the grooves as full tori (no ball runs over an edge): the convex
    problem of the first solver stage.

    Returns
    -------
    Q : (n,) normal loads, N;  delta : (n,) approaches, m;  s : (n, 3) centre-distance vectors, m;
    r : (5,) generalised force (Fx, Fy, Fz, Mx, My) of the balls on the moving ring, N and N·m;
    J : (5, 5) dr/dq, or None.
    """
    u = B @ q
    u = u - np.sum(u * g.t, axis=1)[:, None] * g.t
    s = g.s0_m + u
    L = np.linalg.norm(s, axis=1)
    s_hat = s / L[:, None]
    # δ = |s| − A without the cancellation: (|s0|² − A² + 2 s0·u + |u|²)/(|s| + A)
    delta = (g.s0_excess_m2 + np.einsum("ij,ij->i", 2.0 * g.s0_m + u, u)) / (L + g.free_length_m)
    alpha = np.arctan2(g.axial_sign * s[:, 2], g.radial_sign * np.sum(s * g.e_r, axis=1))
    on_groove = (alpha >= g.angle_min_rad) & (alpha <= g.angle_max_rad) if groove_edges else True
    dpos = np.where(on_groove, np.maximum(delta, 0.0), 0.0)
    sq = np.sqrt(dpos)
    Q = g.K * dpos * sq
    r = -np.einsum("nji,nj->i", B, Q[:, None] * s_hat)
    if not jacobian:
        return Q, delta, s, r, None
    dQ = 1.5 * g.K * sq
    ss = s_hat[:, :, None] * s_hat[:, None, :]
    eye = np.eye(3)[None]
    G = -(dQ[:, None, None] * ss + (Q / L)[:, None, None] * (eye - ss))
    P = eye - g.t[:, :, None] * g.t[:, None, :]
    J = np.einsum("nji,njk->ik", B, G @ P @ B)
    return Q, delta, s, r, J


def slice_forces(g: SliceGroup, w: np.ndarray, q: np.ndarray, jacobian: bool = True):
    """Slice loads and their resultant on the moving ring.

    ``w`` (n, 5) is Bᵀ(p)·normal of every slice: δ = w·q − offset and r = −Σ Q·w.
    Returns Q (n,), delta (n,), r (5,), J (5, 5) or None.
    """
    delta = w @ q - g.offset_m
    dpos = np.maximum(delta, 0.0)
    Q = g.K * dpos**g.exponent
    r = -(Q @ w)
    if not jacobian:
        return Q, delta, r, None
    with np.errstate(divide="ignore", invalid="ignore"):
        dQ = np.where(dpos > 0.0, g.exponent * g.K * dpos ** (g.exponent - 1.0), 0.0)
    return Q, delta, r, -(w.T * dQ) @ w


def _row_norm(v: np.ndarray) -> np.ndarray:
    return np.sqrt(np.einsum("ij,ij->i", v, v))


class _Problem:
    """Bearing geometry flattened once; evaluates the residual and Jacobian of q."""

    def __init__(self, bearing: Bearing):
        self.bearing = bearing
        self.balls, self.slices = build_groups(bearing)
        self.B_balls = displacement_matrix(self.balls.p_m)
        self.w_slices = np.einsum("nji,nj->ni", displacement_matrix(self.slices.p_m), self.slices.normal)
        self.w_norm = _row_norm(self.w_slices)

    def reaction(self, q: np.ndarray, jacobian: bool = True):
        _, _, _, rb, Jb = ball_forces(self.balls, self.B_balls, q, jacobian)
        _, _, rs, Js = slice_forces(self.slices, self.w_slices, q, jacobian)
        return rb + rs, (None if not jacobian else Jb + Js)

    def evaluate(self, q: np.ndarray, f_ext: np.ndarray, S: np.ndarray, tolerance: float,
                 jacobian: bool = True, groove_edges: bool = True) -> Evaluation:
        """Scaled residual (r + f)/S, its Jacobian, the potential Π and the convergence threshold at q.

        Π = Σ Q·δ/(n + 1) − f·q (elastic energy K·δ^(n+1)/(n+1) of each loaded element). The
        threshold is ``tolerance``·max(|f/S|, Σ Q) plus the rounding level of the residual,
        Σ (dQ/dδ)·ε·ℓ with ℓ the size of the terms whose sum is δ
        ((| |s0|² − A² | + |2s0 + u|·|u|)/(|s| + A) of a ball, |w|·|q| + |offset| of a slice):
        below it the residual is noise.
        """
        with np.errstate(over="ignore", invalid="ignore"):
            Qb, db, s, rb, Jb = ball_forces(self.balls, self.B_balls, q, jacobian, groove_edges)
            Qs, ds, rs, Js = slice_forces(self.slices, self.w_slices, q, jacobian)
            lb, ls = Qb > 0.0, Qs > 0.0
            elastic_b = float(np.sum(Qb[lb] * db[lb])) / 2.5
            elastic_s = float(np.sum(Qs[ls] * ds[ls] / (self.slices.exponent[ls] + 1.0)))
            energy = elastic_b + elastic_s - float(f_ext @ q)
            g = self.balls
            u = s[lb] - g.s0_m[lb]
            ell_b = ((np.abs(g.s0_excess_m2[lb]) + _row_norm(2.0 * g.s0_m[lb] + u) * _row_norm(u))
                     / (_row_norm(s[lb]) + g.free_length_m[lb]))
            ell_s = self.w_norm[ls] * safe_norm(q) + np.abs(self.slices.offset_m[ls])
            noise = _ROUNDING * (float(np.sum(1.5 * Qb[lb] / db[lb] * ell_b))
                                 + float(np.sum(self.slices.exponent[ls] * Qs[ls] / ds[ls] * ell_s)))
            load_sum = float(np.sum(Qb) + np.sum(Qs))
            R = (rb + rs + f_ext) / S
            J = None if not jacobian else (Jb + Js) / S[:, None] / S[None, :]
        return Evaluation(R, J, energy, tolerance * max(safe_norm(f_ext / S), load_sum) + noise)

    def resolution_force_N(self) -> float:
        """Largest element force at an approach equal to the rounding of the lengths it is computed
        from (|s0|² − A² over 2A of a ball, the gap of a slice), N: loads near it are not resolved."""
        g, sl = self.balls, self.slices
        eps = _ROUNDING
        ball = g.K * (eps * np.abs(g.s0_excess_m2) / (2.0 * g.free_length_m)) ** 1.5
        sli = sl.K * (eps * np.abs(sl.offset_m)) ** sl.exponent
        return float(max(ball.max(initial=0.0), sli.max(initial=0.0)))

    def linear_stiffness(self, load_scale_N: float) -> np.ndarray:
        """Secant stiffness (5, 5) with every element loaded to an equal share of the load.

        Used only for the starting point and to find unsupported degrees of freedom: each
        element acts as a two-sided linear spring along its contact direction (plus the
        transverse geometric stiffness Q/A of a ball in its groove).
        """
        n_el = len(self.balls.K) + len(self.slices.K)
        # a direction and a pattern are all that is used: keep the springs clear of underflow
        Q_ref = (max(load_scale_N, 1e-30) if load_scale_N > 0.0 else 1.0) / max(n_el, 1)
        K = np.zeros((5, 5))
        g = self.balls
        if len(g.K):
            k = Q_ref / (Q_ref / g.K) ** (2.0 / 3.0)
            n_hat = g.s0_m / np.linalg.norm(g.s0_m, axis=1)[:, None]
            nn = n_hat[:, :, None] * n_hat[:, None, :]
            P = np.eye(3)[None] - g.t[:, :, None] * g.t[:, None, :]
            G = k[:, None, None] * nn + (Q_ref / g.free_length_m.clip(min=1e-12))[:, None, None] * (P - nn)
            K += np.einsum("nji,njk->ik", self.B_balls, G @ self.B_balls)
        s = self.slices
        if len(s.K):
            k = Q_ref / (Q_ref / s.K) ** (1.0 / s.exponent)
            K += (self.w_slices.T * k) @ self.w_slices
        return K


def _scaling(bearing: Bearing) -> np.ndarray:
    L = bearing.reference_length_m
    return np.array([1.0, 1.0, 1.0, L, L])


def supported_dofs(prob: _Problem, bearing_name: str, f_ext: np.ndarray, S: np.ndarray):
    """Degrees of freedom of the moving ring in which the rows have stiffness.

    Returns the mask (5,) of supported DOFs and the scaled secant stiffness (5, 5) of
    :meth:`_Problem.linear_stiffness`. A load on an unsupported DOF is a
    :class:`LoadDistributionError` naming the load component.
    """
    load_scale = safe_norm(f_ext / S)
    K_lin = prob.linear_stiffness(load_scale) / S[:, None] / S[None, :]
    diag = np.diag(K_lin)
    supported = diag > 1e-12 * diag.max()
    for i in np.flatnonzero(~supported):
        if abs(f_ext[i] / S[i]) > 1e-12 * load_scale:
            raise LoadDistributionError(
                f"load: {LOAD_NAMES[i]} = {f_ext[i]:.6g} acts on a degree of freedom ({DOF_NAMES[i]}) "
                f"in which bearing {bearing_name!r} has no stiffness"
            )
    return supported, K_lin


def damped_newton(residual, y: np.ndarray, free: np.ndarray, tolerance_abs: float, max_iterations: int,
                  fallback_stiffness: np.ndarray):
    """Newton's method on the ``free`` unknowns with backtracking on the residual norm.

    ``residual(y, jac)`` returns the scaled residual R(y) and its Jacobian dR/dy; the rest of y is
    held. A step is halved until |R| decreases (Armijo factor 1e-4). Where the Jacobian is singular
    (every element has lost contact) ``1e-3·fallback_stiffness`` is added to −J.

    Returns
    -------
    y, R, |R_free|, iterations — converged when |R_free| ≤ ``tolerance_abs``.
    """
    y = np.array(y, dtype=float)
    r, J = residual(y)
    norm = safe_norm(r[free])
    it = 0
    while norm > tolerance_abs and it < max_iterations:
        it += 1
        Kf = -J[np.ix_(free, free)]
        if not np.all(np.isfinite(Kf)) or np.linalg.cond(Kf) > 1e12:
            Kf = Kf + 1e-3 * fallback_stiffness[np.ix_(free, free)]  # all elements lost contact: lean on the springs
        step = np.zeros_like(y)
        step[free] = np.linalg.solve(Kf, r[free])
        lam, accepted = 1.0, False
        while lam > 1e-8:
            y_try = y + lam * step
            r_try, J_try = residual(y_try)
            n_try = safe_norm(r_try[free])
            if n_try < (1.0 - 1e-4 * lam) * norm:
                accepted = True
                break
            lam *= 0.5
        if not accepted:
            break
        y, r, J, norm = y_try, r_try, J_try, n_try
        log.debug("iteration %d: |residual| = %.3e (step %.3g)", it, norm, lam)
    return y, r, float(norm), it


def no_equilibrium_error(bearing_name: str, iterations: int, r: np.ndarray, S: np.ndarray,
                         f_ext: np.ndarray, resolution_N: float = 0.0, too_small: bool = False) -> LoadDistributionError:
    """The error of an unconverged solve, naming the worst unbalanced load component.

    ``resolution_N``: the smallest element force the geometry resolves in double precision
    (:meth:`_Problem.resolution_force_N`); a load not far above it (or ``too_small``) is named as
    the cause.
    """
    worst = int(np.argmax(np.abs(r[:5])))
    cause = ("the rows cannot carry this load (does it lift the moving ring off every element, or exceed what "
             "the contact angles allow?)")
    if too_small or safe_norm(f_ext / S) < 1e6 * resolution_N:
        cause = (f"the load is too small for the clearances: the approaches it causes are below the rounding of "
                 f"the geometry in double precision (an element force at the rounding level of its approach "
                 f"is ~{resolution_N:.1e} N)")
    return LoadDistributionError(
        f"no converged equilibrium for bearing {bearing_name!r} after {iterations} iterations: "
        f"unbalanced {LOAD_NAMES[worst]} = {r[worst] * S[worst]:.6g} of the applied {f_ext[worst]:.6g}; {cause}"
    )


def solve_load_distribution(
    bearing: Bearing,
    load: RingLoad,
    *,
    tolerance: float = 1e-10,
    max_iterations: int = 100,
    initial_displacement: np.ndarray | None = None,
) -> LoadDistribution:
    """Equilibrium of the moving ring under ``load`` and the load of every rolling element.

    Parameters
    ----------
    bearing : Bearing
        Rows between the fixed and the moving ring.
    load : RingLoad
        External load on the moving ring, N and N·m.
    tolerance : float
        Convergence when |residual| ≤ tolerance·max(|F, M/R_ref|, Σ element loads) plus the
        rounding level of the element approaches (moments scaled by the largest pitch radius
        R_ref); relative at every load, never an absolute force.
    max_iterations : int
        Newton iterations before giving up.
    initial_displacement : (5,) array, optional
        Starting point (x, y, z, θx, θy), m and rad; default: the minimum of the potential along
        the linear-spring estimate (which closes the clearances).

    Returns
    -------
    LoadDistribution
        With ``warnings`` where the result lies outside the model's validity (:mod:`.validity`).

    Raises
    ------
    LoadDistributionError
        If the load acts on a degree of freedom without stiffness, or there is no equilibrium
        (the rows cannot carry the load: it lifts the moving ring off every element, exceeds what
        the contact angles allow, overflows, or needs approaches beyond the elements' size).
    """
    if not isinstance(bearing, Bearing):
        raise TypeError(f"bearing must be a Bearing, got {type(bearing).__name__}")
    if not isinstance(load, RingLoad):
        raise TypeError(f"load must be a RingLoad, got {type(load).__name__}")
    if not (isinstance(tolerance, (int, float)) and 0.0 < tolerance < 1.0):
        raise ValueError(f"tolerance must lie in (0, 1), got {tolerance!r}")
    prob = _Problem(bearing)
    S = _scaling(bearing)  # q_scaled = S·q, r_scaled = r / S
    f_ext = load.as_array()
    supported, K_lin = supported_dofs(prob, bearing.name, f_ext, S)
    free = np.flatnonzero(supported)
    held = tuple(DOF_NAMES[i] for i in np.flatnonzero(~supported))

    def on_tori(y_scaled: np.ndarray, jac: bool = True) -> Evaluation:
        return prob.evaluate(y_scaled / S, f_ext, S, tolerance, jac, groove_edges=False)

    def on_grooves(y_scaled: np.ndarray, jac: bool = True) -> Evaluation:
        return prob.evaluate(y_scaled / S, f_ext, S, tolerance, jac)

    if initial_displacement is None:
        y = np.zeros(5)
        try:
            y[free] = np.linalg.solve(K_lin[np.ix_(free, free)], f_ext[free] / S[free])
        except np.linalg.LinAlgError:
            y[free] = f_ext[free] / S[free] / np.diag(K_lin)[free]
        y = ray_start(on_tori, y, free)
    else:
        y = np.asarray(initial_displacement, dtype=float).reshape(5) * S
        y[~supported] = 0.0
    # stage 1: grooves as full tori, a convex potential (global convergence); stage 2: the balls that
    # ran over a groove edge drop out (nothing to do when none did)
    D = np.diag(K_lin)[free]
    y, _, _, it1 = minimise_potential(on_tori, y, free, max_iterations, D)
    y, ev, norm, it2 = minimise_potential(on_grooves, y, free, max_iterations, D)
    it = it1 + it2
    if not norm <= ev.tolerance:
        raise no_equilibrium_error(bearing.name, it, ev.R, S, f_ext, prob.resolution_force_N())
    res = _collect(prob, bearing, load, y / S, it, norm, held)
    if res.equilibrium_error > ROUNDING_ERROR_LIMIT:  # converged to the rounding level, which is no answer
        raise no_equilibrium_error(bearing.name, it, ev.R, S, f_ext, prob.resolution_force_N(), too_small=True)
    if res.equilibrium_error > ROUNDING_WARNING_LIMIT:
        note = (f"equilibrium only to {res.equilibrium_error:.1e} of the load: the approaches are near the "
                "rounding of the geometry in double precision (a load this small against the clearances)")
        res = replace(res, warnings=res.warnings + (note,))
    return res


def _collect(prob: _Problem, bearing: Bearing, load: RingLoad, q: np.ndarray, iterations: int,
             residual_norm: float, held: tuple[str, ...]) -> LoadDistribution:
    Qb, db, s, rb, _ = ball_forces(prob.balls, prob.B_balls, q, jacobian=False)
    Qs, ds, rs, _ = slice_forces(prob.slices, prob.w_slices, q, jacobian=False)
    scale = max(safe_norm(load.as_array() / _scaling(bearing)), float(Qb.sum() + Qs.sum()))
    error = residual_norm / scale if scale > 0.0 else 0.0
    rows = row_loads(bearing, prob.balls, prob.slices, (Qb, db, s), (Qs, ds))
    err = approach_limit_error(bearing, rows)
    if err:
        raise LoadDistributionError(f"no converged equilibrium within the model for bearing {bearing.name!r}: {err}")
    warnings = load_distribution_warnings(bearing, rows, q)
    if warnings:
        log.info("bearing %r: %d validity warnings, the first: %s", bearing.name, len(warnings), warnings[0])
    return LoadDistribution(bearing.name, load.as_array(), q, rb + rs, rows, iterations, error, held, warnings,
                            tangent_stiffness(prob, q))


def tangent_stiffness(prob: _Problem, q: np.ndarray) -> np.ndarray:
    """K = dF/dq (5, 5) at q: minus the analytic Jacobian of the element reaction (the load F that
    holds the ring at q is −reaction(q)), balls past a groove edge or shoulder left out."""
    return -prob.reaction(q, jacobian=True)[1]


def stiffness_matrix(bearing: Bearing, dist: LoadDistribution) -> np.ndarray:
    """Tangent stiffness of ``bearing`` at the equilibrium ``dist`` (rigid rings), (5, 5).

    K[i, j] = dF_i/dq_j, F = (Fx, Fy, Fz, Mx, My) the load on the moving ring (N, N·m) that holds
    it at q = (x, y, z, θx, θy) (m, rad): units N/m, N/rad, N·m/m, N·m/rad
    (:data:`.results.STIFFNESS_UNITS`). From the analytic Jacobian of the element forces
    (:func:`ball_forces`, :func:`slice_forces`): K = Σ Bᵀ·(dQ/dδ·n·nᵀ + Q/|s|·(I − n·nᵀ − t·tᵀ))·B
    over the balls (the second term the geometric stiffness of the turning line of centres,
    Harris & Kotzalas, *Advanced Concepts of Bearing Technology*, 5th ed., ch. 1) plus Σ dq/dδ·w·wᵀ
    over the roller slices; symmetric. A held degree of freedom (:attr:`LoadDistribution.held_dofs`)
    has a zero row and column. Also in ``dist.stiffness`` of a :func:`solve_load_distribution` result.
    """
    if not isinstance(dist, LoadDistribution):
        raise TypeError(f"dist must be a LoadDistribution, got {type(dist).__name__}")
    if not isinstance(bearing, Bearing):
        raise TypeError(f"bearing must be a Bearing, got {type(bearing).__name__}")
    names = [r.name for r in bearing.rows]
    if dist.bearing_name != bearing.name or [r.name for r in dist.rows] != names:
        raise ValueError(f"dist: the load distribution of bearing {dist.bearing_name!r} (rows "
                         f"{[r.name for r in dist.rows]}) is not one of bearing {bearing.name!r} (rows {names})")
    return tangent_stiffness(_Problem(bearing), np.asarray(dist.displacement, dtype=float))


def _ball_angles(bg: BallGroup, m: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Loaded contact angle atan2(s_z·s·e_z, s_r·s·e_r) of the ball entries ``m``, rad."""
    s_r = np.sum(s[m] * bg.e_r[m], axis=1) * bg.radial_sign[m]
    return np.arctan2(s[m, 2] * bg.axial_sign[m], s_r)


def _four_point_loads(row: FourPointRow, psi: np.ndarray, Q: np.ndarray, delta: np.ndarray,
                      alpha: np.ndarray) -> RowLoads:
    """RowLoads of a four-point row from its entries (two per ball, interleaved by diagonal)."""
    Z, k = row.n_balls, len(row.DIAGONAL_SIGNS)
    Q, delta, alpha = (np.asarray(v).reshape(Z, k) for v in (Q, delta, alpha))
    # the more loaded diagonal of each ball; where neither is loaded, the one pressed the further
    pick = np.where(Q[:, 0] != Q[:, 1], np.argmax(Q, axis=1), np.argmax(delta, axis=1))
    rows_ = np.arange(Z)
    n_points = 2 * np.count_nonzero(Q > 0.0, axis=1)
    return RowLoads(row.name, "ball", psi, Q[rows_, pick], delta[rows_, pick], alpha[rows_, pick],
                    Q[rows_, pick] <= 0.0, contact_load_N=Q, contact_angles_rad=alpha,
                    contact_approach_m=delta, n_contact_points=n_points)


def row_loads(bearing: Bearing, bg: BallGroup, sg: SliceGroup, balls, slices) -> tuple[RowLoads, ...]:
    """Per-row loads from the element results ``balls`` = (Q, δ, s) of :func:`ball_forces` and
    ``slices`` = (Q, δ) of :func:`slice_forces`."""
    Qb, db, s = balls
    Qs, ds = slices
    rows = []
    for i, row in enumerate(bearing.rows):
        psi = row.azimuths_rad()
        if isinstance(row, FourPointRow):
            m = bg.row == i
            rows.append(_four_point_loads(row, psi, Qb[m], db[m], _ball_angles(bg, m, s)))
        elif isinstance(row, BallRow):
            m = bg.row == i
            rows.append(RowLoads(row.name, "ball", psi, Qb[m], db[m], _ball_angles(bg, m, s), Qb[m] <= 0.0))
        else:
            m = sg.row == i
            ns = row.n_slices
            q_sl = Qs[m].reshape(row.n_rollers, ns)
            d_sl = ds[m].reshape(row.n_rollers, ns)
            total = q_sl.sum(axis=1)
            rows.append(RowLoads(row.name, "roller", psi, total, d_sl.max(axis=1),
                                 row.contact_angles_rad, total <= 0.0, q_sl))
    return tuple(rows)
