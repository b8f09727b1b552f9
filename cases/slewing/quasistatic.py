"""Quasi-static runs of the slewing ring: one equilibrium, or the balls rolling through a turn.

At ≤ 6.55 rpm the inertia of the balls and rings is negligible against the dead load (the
centrifugal force on a load ball at the 2 m ring's orbit speed is 0.3 N against 42 kN), so the
load on the balls at each position of the top race is the equilibrium of that position: the
bottom race fixed, the top race turned by φ with its thermal sector, the balls at ψ_i0 + r·φ
(r the orbit ratio, :func:`.scene.orbit_ratio`), each solved by
:func:`mbd_core.quasistatic.flexible_solve.solve_flexible_load_distribution`, starting from the top
race's displacement at the previous position.
The balls are held at their azimuths (spacer balls and cage carry the circumferential forces).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from mbd_core.contact import ball_on_groove

from mbd_core.quasistatic import Bearing, RingLoad
from mbd_core.quasistatic.estimates import truncation_estimate
from mbd_core.quasistatic.flexible import build_flexible_model
from mbd_core.quasistatic.flexible_solve import solve_flexible_load_distribution

from . import scene
from .case import SlewingCase

__all__ = ["Travel", "equilibrium", "travel", "analytic_ball_load_N", "nominal_ball_load_N", "error_estimates"]


def nominal_ball_load_N(case: SlewingCase) -> float:
    """Q = W / (Z sin α0) at the nominal contact angle (the thesis' check, §3.2.1)."""
    g = case.geometry
    return case.dead_load_N / (g.n_balls * math.sin(math.radians(g.contact_angle_deg)))


def analytic_ball_load_N(case: SlewingCase) -> tuple[float, float]:
    """Normal ball load and loaded contact angle (Q, α) of a ring of Z balls under a pure thrust W.

    Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed. (2007), §7.2 (thrust-loaded angular
    contact ball bearing): with zero clearance the curvature centres stay A = (f_i + f_o − 1)·D
    apart along the contact line, so the ball's approach is δ = A (cos α0 / cos α − 1), its load
    Q = K_n δ^1.5 and the axial balance W = Z Q sin α; K_n is the two contacts in series,
    K_n = (K_i^(−2/3) + K_o^(−2/3))^(−3/2). Solved for α by bracketing.
    """
    row = scene.ball_row(case)
    a0 = row.contact_angle_rad
    A = (row.conformity_moving + row.conformity_fixed - 1.0) * row.ball_diameter_m
    if row.stiffness_N_per_m1p5 is not None:
        k_n = row.stiffness_N_per_m1p5
    else:
        k = [ball_on_groove(row.ball_diameter_m, row.conformity_moving, row.pitch_diameter_m, a0, r,
                            row.ball_material, row.race_material).stiffness_N_per_m1p5 for r in ("inner", "outer")]
        k_n = (k[0] ** (-2 / 3) + k[1] ** (-2 / 3)) ** -1.5

    def load(alpha):
        return k_n * (A * (math.cos(a0) / math.cos(alpha) - 1.0)) ** 1.5

    alpha = brentq(lambda al: row.n_balls * load(al) * math.sin(al) - case.dead_load_N, a0 + 1e-12,
                   0.5 * math.pi - 1e-6, xtol=1e-15)
    return load(alpha), alpha


def equilibrium(case: SlewingCase, bodies: scene.Bodies, top_rotation_rad: float = 0.0, ball_phase_rad: float = 0.0,
                initial_displacement=None, ball_offsets_rad=()):
    """The equilibrium at one position (a :class:`FlexibleLoadDistribution`); ``ball_offsets_rad``:
    each ball's angle from the even spacing (default: evenly spaced)."""
    model = build_flexible_model(Bearing(case.name, (scene.ball_row(case, ball_phase_rad, ball_offsets_rad),)),
                                 scene.flexible_rings(bodies, top_rotation_rad),
                                 scene.groove_offsets(case, top_rotation_rad))
    return solve_flexible_load_distribution(model, RingLoad(Fz_N=-case.dead_load_N),
                                            initial_displacement=initial_displacement)


def error_estimates(case: SlewingCase, bodies: scene.Bodies, res) -> dict:
    """``error_estimates`` of one equilibrium: the top structure's modal truncation at its most
    loaded ball (:func:`mbd_core.quasistatic.estimates.truncation_estimate`, from the residual
    compliance its reduction measured), or why there is none."""
    top = bodies.top
    if top is None:
        return {"modal_truncation": None, "why_none": "rigid top structure (no modes to truncate)"}
    R, C = (top.metadata.get(k) for k in ("residual_compliance_m_per_N", "probe_compliance_m_per_N"))
    if R is None or C is None:
        return {"modal_truncation": None, "why_none": "the top structure's reduction measured no residual compliance"}
    row = res.rows[0]
    groove = case.geometry.section().groove("top", case.geometry.pitch_diameter_m)
    n = np.array([groove.direction(math.degrees(a)) for a in row.contact_angle_rad])
    est = truncation_estimate(C, R, n, row.load_N, row.approach_m)
    est["ball"] = est.pop("element") + 1
    return {"modal_truncation": est, "what": "estimated relative error of the largest ball load from the "
            "top structure's residual flexibility at the most loaded ball: η/(1 + κ), η = 1.5·r/δ the deflection "
            "r its basis misses against the Hertz approach δ, κ the same for the ring's whole deflection "
            "(mbd_core.quasistatic.estimates; its tracking of the true error: flexbearing tradeoff)"}


@dataclass(frozen=True)
class Travel:
    """Equilibria along a turn of the top race (n positions, Z balls).

    top_rotation_rad : (n,) top race angle φ
    ball_azimuth_rad : (n, Z) ball azimuths
    load_N : (n, Z) normal ball loads
    axial_N : (n, Z) their axial components Q sin α_loaded
    displacement : (n, 5) rigid displacement of the top race (x, y, z m, θx, θy rad)
    eta : (n, m) modal coordinates of the top structure (m = 0 when rigid)
    warnings : validity warnings of the equilibria, each naming its position
    """

    top_rotation_rad: np.ndarray
    ball_azimuth_rad: np.ndarray
    load_N: np.ndarray
    axial_N: np.ndarray
    displacement: np.ndarray
    eta: np.ndarray
    warnings: tuple[str, ...] = ()

    @property
    def worst(self) -> tuple[int, int]:
        """(position, ball) of the largest ball load."""
        k = int(np.argmax(self.load_N))
        return divmod(k, self.load_N.shape[1])


def travel(case: SlewingCase, bodies: scene.Bodies, steps: int, revolutions: float, progress=None) -> Travel:
    """Equilibria at ``steps`` positions over ``revolutions`` turns of the top race (start included)."""
    phi = np.linspace(0.0, 2.0 * math.pi * revolutions, steps, endpoint=False)
    ratio = scene.orbit_ratio(case)
    rows, q0, warnings = [], None, []
    for p in (progress(phi, "positions") if progress else phi):
        res = equilibrium(case, bodies, float(p), float(ratio * p), q0)
        q0 = res.displacement
        warnings += [f"top race at {math.degrees(p):.1f}°: {w}" for w in res.warnings]
        r = res.rows[0]
        eta = res.modal("top") if bodies.top is not None else np.zeros(0)
        rows.append((r.azimuth_rad, r.load_N, r.load_N * np.sin(r.contact_angle_rad), res.displacement, eta))
    az, q, ax, disp, eta = (np.array(x) for x in zip(*rows))
    return Travel(phi, az, q, ax, disp, eta, tuple(warnings))
