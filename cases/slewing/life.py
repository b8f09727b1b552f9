"""Study (f) of the fast-reactor slewing ring: contact stress and life of the worst ball.

For the normal contact load Q of the most heavily loaded ball (study (f); slewing-ring thesis §4.4,
Tables 7–8) this module evaluates, on both raceways:

* the Hertz contact (semi-axes a ≥ b, maximum pressure p0, mutual approach), exact elliptic
  integrals (:func:`mbd_core.contact.ball_on_groove`); the top race is the "inner" raceway
  (convex in the rolling direction), the bottom race the "outer" one;
* the subsurface shear on the contact axis: peak τ_max and its depth, and the Lundberg–Palmgren
  orthogonal shear τ0 (:mod:`mbd_core.contact.subsurface`);

and, on the worse raceway (the higher p0), the case-depth check of NREL DG03
(:mod:`mbd_core.bearing.case_depth`): the effective case depth h_req at which
τ_max(1.1·h) equals the core shear fatigue strength τ_f, and the life factor
A_cd = min(τ_f / τ_max(1.1·h), 1) for the given case depth h.

ISO 281:2007 thrust-ball rating and basic rating life (:mod:`mbd_core.bearing.rating`)::

    C_a = 3.647 b_m f_c (cos α)^0.7 tan α Z^(2/3) D_w^1.4       (D_w > 25.4 mm, N and mm)
    L10 = (C_a / P)^3 (10^6 rev),  L10h = 10^6 L10 / (60 n)

with P_nominal = F_a (pure axial load of a thrust bearing) and P_worst = Z·Q·sin α, the
equivalent load under which a uniform distribution would load every ball with Q. The corrected
life is L_cd = A_cd·L10_nominal, as in the thesis (12 821 rev = 0.35 × 36 633 rev, §4.4.2): the
ISO life of the bearing times the factor of its most loaded ball.

Defaults are the thesis': D_w = 95.25 mm, f = 0.525, α = 60°, E = 207 GPa, ν = 0.29 (Table 7),
b_m = 1, f_c = 36.635 (§4.4.2); they give C_a = 1 997 045 N for Z = 116 (the
thesis prints 1 950 868 N, the value for Z = 112).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from mbd_core.bearing.case_depth import (
    CASE_DEPTH_STRESS_DEPTH_FACTOR,
    case_depth_corrected_life_Mrev,
    case_depth_life_factor,
    core_shear_fatigue_strength_Pa,
    required_case_depth_m,
)
from mbd_core.bearing.rating import basic_rating_life_Mrev, rating_life_hours, thrust_ball_rating_N
from mbd_core.contact.hertz import ball_on_groove
from mbd_core.contact.subsurface import max_shear_profile_Pa, subsurface_shear
from foundation.materials import BEARING_STEEL
from foundation.validation import check_positive

__all__ = ["WorstBallLife", "worst_ball_life", "plot_subsurface_shear"]

#: ISO 281 Table 4 factor used by the thesis (§4.4.2); with b_m = 1 and Z = 116: 1 997 045 N.
THESIS_FC = 36.635
#: Tensile yield strength of the AISI 4140 race core, Pa (thesis Table 7).
THESIS_CORE_YIELD_PA = 660e6

_RACEWAYS = ("inner", "outer")
#: Standard gravity used by the thesis to convert tonnes of ball load to newtons, m/s².
_G = 9.81


@dataclass(frozen=True)
class WorstBallLife:
    """Contact stresses, case-depth factor and ISO 281 lives for the worst ball load (SI).

    Per raceway (``inner`` = top race, ``outer`` = bottom race): ``p0_*_Pa`` maximum Hertz
    pressure, ``a_*_m``/``b_*_m`` semi-major/semi-minor axes, ``approach_*_m`` mutual approach
    of ball and raceway, ``tau_max_*_Pa``/``depth_tau_max_*_m`` peak Tresca shear on the axis
    and its depth, ``tau_orthogonal_*_Pa``/``depth_tau_orthogonal_*_m`` orthogonal shear.
    The case-depth quantities refer to the worse raceway (:attr:`worse_raceway`):
    ``tau_at_case_Pa`` = τ_max(1.1·h), ``A_cd`` = min(τ_f/τ_at_case, 1) with τ_f =
    ``core_shear_fatigue_Pa`` and ``nu`` the race Poisson ratio. ``*_h`` are hours at ``speed_rpm``;
    ``L_cd_*`` = A_cd·L10_nominal.
    """

    Q_N: float
    p0_inner_Pa: float
    a_inner_m: float
    b_inner_m: float
    approach_inner_m: float
    tau_max_inner_Pa: float
    depth_tau_max_inner_m: float
    tau_orthogonal_inner_Pa: float
    depth_tau_orthogonal_inner_m: float
    p0_outer_Pa: float
    a_outer_m: float
    b_outer_m: float
    approach_outer_m: float
    tau_max_outer_Pa: float
    depth_tau_max_outer_m: float
    tau_orthogonal_outer_Pa: float
    depth_tau_orthogonal_outer_m: float
    nu: float
    core_shear_fatigue_Pa: float
    required_case_depth_m: float
    case_depth_m: float
    tau_at_case_Pa: float
    A_cd: float
    C_a_N: float
    P_nominal_N: float
    P_worst_N: float
    speed_rpm: float
    L10_nominal_Mrev: float
    L10_nominal_h: float
    L10_worst_Mrev: float
    L10_worst_h: float
    L_cd_Mrev: float
    L_cd_h: float

    @property
    def worse_raceway(self) -> str:
        """``"inner"`` or ``"outer"``: the raceway with the higher p0 (governs the case depth)."""
        return "inner" if self.p0_inner_Pa >= self.p0_outer_Pa else "outer"

    def raceway(self, name: str) -> dict[str, float]:
        """Contact quantities of one raceway with the raceway tag removed from the names."""
        if name not in _RACEWAYS:
            raise ValueError(f"raceway must be 'inner' or 'outer', got {name!r}")
        tag = f"_{name}_"
        return {k.replace(tag, "_"): v for k, v in self.to_dict().items() if tag in k}

    def to_dict(self) -> dict[str, float]:
        """All fields as plain floats (JSON-ready)."""
        return {k: float(v) for k, v in asdict(self).items()}


def _contact_fields(Q_N: float, raceway: str, ball_diameter_m: float, conformity: float,
                    pitch_diameter_m: float, alpha_rad: float) -> dict[str, float]:
    """Hertz and subsurface-shear fields of one raceway, named as in :class:`WorstBallLife`."""
    mat = BEARING_STEEL
    c = ball_on_groove(ball_diameter_m, conformity, pitch_diameter_m, alpha_rad, raceway, mat, mat)
    a, b = (float(x) for x in c.semi_axes_m(Q_N))
    p0 = float(c.max_pressure_Pa(Q_N))
    s = subsurface_shear(p0, a, b, mat.nu)
    r = raceway
    return {f"p0_{r}_Pa": p0, f"a_{r}_m": a, f"b_{r}_m": b, f"approach_{r}_m": float(c.approach_m(Q_N)),
            f"tau_max_{r}_Pa": s.tau_max_Pa, f"depth_tau_max_{r}_m": s.depth_tau_max_m,
            f"tau_orthogonal_{r}_Pa": s.tau_orthogonal_Pa,
            f"depth_tau_orthogonal_{r}_m": s.depth_tau_orthogonal_m}


def worst_ball_life(
    Q_N: float,
    *,
    pitch_diameter_m: float,
    n_balls: int,
    axial_load_N: float,
    speed_rpm: float,
    case_depth_m: float = 6.0e-3,
    ball_diameter_m: float = 95.25e-3,
    conformity: float = 0.525,
    contact_angle_deg: float = 60.0,
    fc: float = THESIS_FC,
    bm: float = 1.0,
    core_yield_Pa: float = THESIS_CORE_YIELD_PA,
) -> WorstBallLife:
    """Hertz and subsurface stress, case-depth factor and ISO 281 lives for the worst ball.

    Parameters
    ----------
    Q_N : float
        Normal contact load of the worst ball, N.
    pitch_diameter_m : float
        Pitch diameter d_m, m.
    n_balls : int
        Number of load balls Z.
    axial_load_N : float
        Axial load F_a of the bearing (dead load), N; the nominal equivalent load P_a.
    speed_rpm : float
        Speed of the rotating race, r/min (for the lives in hours).
    case_depth_m : float
        Effective case depth h of the raceways, m.
    ball_diameter_m, conformity, contact_angle_deg : float
        D_w (m), groove radius over D_w, nominal contact angle α (deg, 45 < α ≤ 90).
    fc, bm : float
        ISO 281 factors f_c and b_m.
    core_yield_Pa : float
        Tensile yield strength of the race core, Pa. τ_f = 0.6·0.5·σ_y, the route of the thesis
        (§4.4.2: 660 → 330 → 198 MPa); the UTS route 0.6·0.425·800 MPa would give 204 MPa.

    Returns
    -------
    WorstBallLife
    """
    check_positive(Q_N=Q_N, pitch_diameter_m=pitch_diameter_m, axial_load_N=axial_load_N,
                   speed_rpm=speed_rpm, case_depth_m=case_depth_m, ball_diameter_m=ball_diameter_m,
                   fc=fc, bm=bm, core_yield_Pa=core_yield_Pa)
    if isinstance(n_balls, bool) or not isinstance(n_balls, numbers.Integral) or n_balls < 1:
        raise ValueError(f"n_balls must be an integer >= 1, got {n_balls!r}")
    if not (isinstance(conformity, numbers.Real) and 0.5 < conformity < math.inf):
        raise ValueError(f"conformity must be a finite number > 0.5, got {conformity!r}")
    if not (isinstance(contact_angle_deg, numbers.Real) and 45.0 < contact_angle_deg <= 90.0):
        raise ValueError(f"contact_angle_deg must lie in (45, 90] (thrust bearing), got {contact_angle_deg!r}")
    if not pitch_diameter_m > ball_diameter_m:
        raise ValueError(f"pitch_diameter_m ({pitch_diameter_m}) must exceed ball_diameter_m ({ball_diameter_m})")
    alpha = math.radians(contact_angle_deg)
    Q = float(Q_N)

    fields: dict[str, float] = {}
    for raceway in _RACEWAYS:
        fields.update(_contact_fields(Q, raceway, ball_diameter_m, conformity, pitch_diameter_m, alpha))
    w = "inner" if fields["p0_inner_Pa"] >= fields["p0_outer_Pa"] else "outer"
    p0, a, b, nu = fields[f"p0_{w}_Pa"], fields[f"a_{w}_m"], fields[f"b_{w}_m"], BEARING_STEEL.nu
    tau_f = core_shear_fatigue_strength_Pa(core_yield_Pa=core_yield_Pa)
    tau_case = float(max_shear_profile_Pa(p0, a, b, CASE_DEPTH_STRESS_DEPTH_FACTOR * case_depth_m, nu))
    a_cd = case_depth_life_factor(p0, a, b, case_depth_m, nu, tau_f)

    C_a = thrust_ball_rating_N(ball_diameter_m, n_balls, alpha, fc, bm=bm)
    P_nom, P_worst = float(axial_load_N), n_balls * Q * math.sin(alpha)
    L_nom = basic_rating_life_Mrev(C_a, P_nom, "ball")
    L_worst = basic_rating_life_Mrev(C_a, P_worst, "ball")
    L_cd = case_depth_corrected_life_Mrev(L_nom, a_cd)
    return WorstBallLife(
        Q_N=Q, **fields, nu=nu, core_shear_fatigue_Pa=tau_f,
        required_case_depth_m=required_case_depth_m(p0, a, b, nu, tau_f),
        case_depth_m=float(case_depth_m), tau_at_case_Pa=tau_case, A_cd=a_cd,
        C_a_N=C_a, P_nominal_N=P_nom, P_worst_N=P_worst, speed_rpm=float(speed_rpm),
        L10_nominal_Mrev=L_nom, L10_nominal_h=rating_life_hours(L_nom, speed_rpm),
        L10_worst_Mrev=L_worst, L10_worst_h=rating_life_hours(L_worst, speed_rpm),
        L_cd_Mrev=L_cd, L_cd_h=rating_life_hours(L_cd, speed_rpm),
    )


def plot_subsurface_shear(life: WorstBallLife, path) -> Path:
    """PNG of τ_max(z) below the worse raceway, depth axis pointing down (thesis Figs 45–49).

    Marks the peak τ_max, the case depth h and the check depth 1.1·h (horizontal lines), the
    core shear fatigue strength τ_f (vertical line) and the required case depth.

    Parameters
    ----------
    life : WorstBallLife
        Result of :func:`worst_ball_life`.
    path : str or os.PathLike
        Output file (.png); its folder must exist.

    Returns
    -------
    pathlib.Path
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    w = life.worse_raceway
    r = life.raceway(w)
    h, h_req = life.case_depth_m, life.required_case_depth_m
    z_max = max(4.0 * r["depth_tau_max_m"], 1.3 * CASE_DEPTH_STRESS_DEPTH_FACTOR * h, 1.2 * h_req)
    z = np.linspace(0.0, z_max, 600)
    tau = max_shear_profile_Pa(r["p0_Pa"], r["a_m"], r["b_m"], z, life.nu)

    fig, ax = plt.subplots(figsize=(7.5, 6.0), constrained_layout=True)
    ax.plot(tau / 1e6, z * 1e3, color="C0", lw=2, label="max shear stress τ_max(z)")
    ax.plot(r["tau_max_Pa"] / 1e6, r["depth_tau_max_m"] * 1e3, "o", color="C3", ms=8,
            label=f"peak {r['tau_max_Pa'] / 1e6:.1f} MPa at {r['depth_tau_max_m'] * 1e3:.2f} mm")
    ax.axvline(life.core_shear_fatigue_Pa / 1e6, color="k", ls=":", lw=1.5,
               label=f"core shear fatigue strength τ_f = {life.core_shear_fatigue_Pa / 1e6:.0f} MPa")
    ax.axhline(h * 1e3, color="C2", ls="--", lw=1.5, label=f"case depth h = {h * 1e3:.2f} mm")
    z_check_mm = CASE_DEPTH_STRESS_DEPTH_FACTOR * h * 1e3
    ax.axhline(z_check_mm, color="C1", ls="--", lw=1.5,
               label=f"1.1·h = {z_check_mm:.2f} mm: τ = {life.tau_at_case_Pa / 1e6:.1f} MPa, "
                     f"A_cd = {life.A_cd:.3f}")
    ax.plot(life.tau_at_case_Pa / 1e6, z_check_mm, "s", color="C1", ms=7)
    if h_req > 0.0:
        ax.axhline(h_req * 1e3, color="C4", ls="-.", lw=1.2,
                   label=f"required case depth (A_cd = 1) = {h_req * 1e3:.2f} mm")
    ax.set_xlim(0.0, 1.08 * max(r["tau_max_Pa"], life.core_shear_fatigue_Pa) / 1e6)
    ax.set_ylim(z_max * 1e3, 0.0)
    ax.set_xlabel("maximum shear stress τ_max (MPa)")
    ax.set_ylabel("depth below raceway surface z (mm)")
    race = "top race (inner)" if w == "inner" else "bottom race (outer)"
    ax.set_title(f"Subsurface shear, {race}: Q = {life.Q_N:.0f} N, "
                 f"p0 = {r['p0_Pa'] / 1e6:.0f} MPa")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize=9)
    out = Path(path)
    fig.savefig(out, dpi=120)
    plt.close(fig)
    return out
