"""Rolling kinematics of a bearing without slip: cage and element speeds, defect frequencies.

Notation (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., vol. 1, ch. 8; the defect
frequencies as in Randall & Antoni, "Rolling element bearing diagnostics — a tutorial",
MSSP 25 (2011) 485–520):

* pitch diameter d_m, rolling-element diameter D (ball diameter, or mean roller diameter),
  contact angle α (0 = radial, π/2 = thrust), number of rolling elements Z;
* pitch ratio γ = D·cos α / d_m (0 ≤ γ < 1);
* angular speeds of the inner ring ω_i and the outer ring ω_o, rad/s, both about the bearing
  axis with the same positive sense; either or both may rotate.

Pure rolling at both raceway contacts (the element rolls about an axis perpendicular to the
line of contact, so its contact points lie D/2 from that axis, while the raceway contact
points lie at the radii d_m(1 ∓ γ)/2 from the bearing axis) gives::

    ω_c = [ω_i (1 − γ) + ω_o (1 + γ)] / 2                    (cage = element orbital speed)
    ω_R = (d_m / (2 D)) (1 − γ²) (ω_o − ω_i)                  (element about its own axis,
                                                               relative to the cage)

Sign of ω_R: it is measured about the element's own axis oriented with the same positive
sense as the bearing axis (for α = 0 the two axes are parallel). With the inner ring driving
in the positive sense and the outer ring fixed, ω_R < 0: the element spins opposite to the
inner ring, as a gear meshing with it would.

Defect frequencies, Hz (all non-negative)::

    FTF  = |ω_c| / 2π                  cage rotation frequency in the fixed (ground) frame
    BPFO = Z |ω_c − ω_o| / 2π          elements passing a point of the outer raceway
    BPFI = Z |ω_i − ω_c| / 2π          elements passing a point of the inner raceway
    BSF  = |ω_R| / 2π                  element rotation frequency relative to the cage

BSF is here the element spin frequency itself (Harris & Kotzalas). A defect on an element
strikes the inner and the outer raceway once each per element revolution, so many
condition-monitoring references (e.g. the Case Western Reserve University bearing data
centre tables) quote 2·BSF; that variant is the field ``bsf_2x_Hz``.

For thrust bearings (α = π/2, γ = 0) "inner ring" and "outer ring" stand for the shaft and
housing washers. For rollers with α ≠ 0 (tapered rollers) D is the mean roller diameter
and the results are those of the mean section.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from foundation.validation import check_positive

__all__ = [
    "RollingKinematics",
    "rolling_kinematics",
    "pitch_ratio",
    "cage_speed_rad_s",
    "element_speed_rad_s",
    "element_speed_magnitude_rad_s",
    "rpm_to_rad_s",
    "rad_s_to_rpm",
]

_RAD_S_PER_RPM = 2.0 * math.pi / 60.0


def rpm_to_rad_s(speed_rpm):
    """Convert a speed (float or array) from revolutions per minute to rad/s, ω = 2π n / 60."""
    out = np.asarray(speed_rpm, dtype=float) * _RAD_S_PER_RPM
    return float(out) if out.ndim == 0 else out


def rad_s_to_rpm(speed_rad_s):
    """Convert a speed (float or array) from rad/s to revolutions per minute, n = 60 ω / 2π."""
    out = np.asarray(speed_rad_s, dtype=float) / _RAD_S_PER_RPM
    return float(out) if out.ndim == 0 else out


def _check_geometry(element_diameter_m: float, pitch_diameter_m: float, contact_angle_rad: float) -> None:
    check_positive(element_diameter_m=element_diameter_m, pitch_diameter_m=pitch_diameter_m)
    if not element_diameter_m < pitch_diameter_m:
        raise ValueError(
            f"element_diameter_m ({element_diameter_m} m) must be smaller than "
            f"pitch_diameter_m ({pitch_diameter_m} m)"
        )
    if not (math.isfinite(contact_angle_rad) and 0.0 <= contact_angle_rad <= math.pi / 2 + 1e-12):
        raise ValueError(
            f"contact_angle_rad must lie in [0, pi/2] (0 to 90 deg), got {contact_angle_rad} rad"
        )


def _check_speeds(inner_speed_rad_s: float, outer_speed_rad_s: float) -> None:
    for name, v in (("inner_speed_rad_s", inner_speed_rad_s), ("outer_speed_rad_s", outer_speed_rad_s)):
        if not math.isfinite(v):
            raise ValueError(f"{name} must be finite, got {v}")


def pitch_ratio(element_diameter_m: float, pitch_diameter_m: float, contact_angle_rad: float) -> float:
    """Pitch ratio γ = D·cos α / d_m (dimensionless, 0 ≤ γ < 1).

    Parameters
    ----------
    element_diameter_m : float
        Rolling-element diameter D, m (0 < D < d_m).
    pitch_diameter_m : float
        Pitch diameter d_m, m.
    contact_angle_rad : float
        Contact angle α, rad, 0 ≤ α ≤ π/2.
    """
    _check_geometry(element_diameter_m, pitch_diameter_m, contact_angle_rad)
    alpha = min(contact_angle_rad, math.pi / 2)
    # cos(π/2) is 6e-17 in floating point; a thrust bearing has γ = 0 exactly
    cos_a = 0.0 if alpha == math.pi / 2 else math.cos(alpha)
    return element_diameter_m * cos_a / pitch_diameter_m


def cage_speed_rad_s(
    element_diameter_m: float,
    pitch_diameter_m: float,
    contact_angle_rad: float,
    inner_speed_rad_s: float = 0.0,
    outer_speed_rad_s: float = 0.0,
) -> float:
    """Cage speed in the fixed frame, ω_c = [ω_i (1 − γ) + ω_o (1 + γ)]/2, rad/s (signed).

    Harris & Kotzalas, vol. 1, ch. 8 (pure rolling, no slip). Parameters as in
    :func:`rolling_kinematics`.
    """
    gamma = pitch_ratio(element_diameter_m, pitch_diameter_m, contact_angle_rad)
    _check_speeds(inner_speed_rad_s, outer_speed_rad_s)
    return 0.5 * (inner_speed_rad_s * (1.0 - gamma) + outer_speed_rad_s * (1.0 + gamma))


def element_speed_rad_s(
    element_diameter_m: float,
    pitch_diameter_m: float,
    contact_angle_rad: float,
    inner_speed_rad_s: float = 0.0,
    outer_speed_rad_s: float = 0.0,
) -> float:
    """Element speed about its own axis relative to the cage, rad/s (signed).

    ω_R = (d_m/(2D))(1 − γ²)(ω_o − ω_i) (Harris & Kotzalas, vol. 1, ch. 8). Positive in
    the sense of the bearing axis; negative when the inner ring drives positively and the
    outer ring is fixed. Parameters as in :func:`rolling_kinematics`.
    """
    gamma = pitch_ratio(element_diameter_m, pitch_diameter_m, contact_angle_rad)
    _check_speeds(inner_speed_rad_s, outer_speed_rad_s)
    ratio = pitch_diameter_m / (2.0 * element_diameter_m)
    return ratio * (1.0 - gamma * gamma) * (outer_speed_rad_s - inner_speed_rad_s)


def element_speed_magnitude_rad_s(
    element_diameter_m: float,
    pitch_diameter_m: float,
    contact_angle_rad: float,
    inner_speed_rad_s: float = 0.0,
    outer_speed_rad_s: float = 0.0,
) -> float:
    """|ω_R|: magnitude of the element speed relative to the cage, rad/s (≥ 0)."""
    return abs(
        element_speed_rad_s(
            element_diameter_m, pitch_diameter_m, contact_angle_rad, inner_speed_rad_s, outer_speed_rad_s
        )
    )


@dataclass(frozen=True)
class RollingKinematics:
    """Rolling kinematics of a bearing without slip (see the module docstring for the formulas).

    Attributes
    ----------
    pitch_ratio : float
        γ = D·cos α / d_m.
    cage_speed_rad_s : float
        ω_c, cage (element orbital) speed in the fixed frame, rad/s, signed.
    element_speed_rad_s : float
        ω_R, element speed about its own axis relative to the cage, rad/s, signed
        (negative for a positively driven inner ring and a fixed outer ring).
    ftf_Hz : float
        Fundamental train frequency |ω_c|/2π: cage rotation frequency in the fixed frame, Hz.
    bpfo_Hz : float
        Ball-pass frequency of the outer race Z·|ω_c − ω_o|/2π, Hz.
    bpfi_Hz : float
        Ball-pass frequency of the inner race Z·|ω_i − ω_c|/2π, Hz.
    bsf_Hz : float
        Ball (element) spin frequency |ω_R|/2π relative to the cage, Hz.
    bsf_2x_Hz : float
        2·BSF, the rate at which an element defect strikes the two raceways, Hz (the
        "rolling element" defect frequency of many condition-monitoring tables).
    """

    pitch_ratio: float
    cage_speed_rad_s: float
    element_speed_rad_s: float
    ftf_Hz: float
    bpfo_Hz: float
    bpfi_Hz: float
    bsf_Hz: float
    bsf_2x_Hz: float

    @property
    def element_speed_magnitude_rad_s(self) -> float:
        """|ω_R|, rad/s."""
        return abs(self.element_speed_rad_s)


def rolling_kinematics(
    element_diameter_m: float,
    pitch_diameter_m: float,
    contact_angle_rad: float,
    n_elements: int,
    inner_speed_rad_s: float = 0.0,
    outer_speed_rad_s: float = 0.0,
) -> RollingKinematics:
    """Cage and element speeds and the defect frequencies of a bearing rolling without slip.

    Parameters
    ----------
    element_diameter_m : float
        Rolling-element diameter D, m (ball diameter; mean diameter of a roller), 0 < D < d_m.
    pitch_diameter_m : float
        Pitch diameter d_m, m.
    contact_angle_rad : float
        Contact angle α, rad, 0 (radial) ≤ α ≤ π/2 (thrust).
    n_elements : int
        Number of rolling elements Z in the row, ≥ 1.
    inner_speed_rad_s, outer_speed_rad_s : float
        Angular speeds ω_i and ω_o of the inner and outer ring about the bearing axis, rad/s,
        same positive sense (0 for a fixed ring).

    Returns
    -------
    RollingKinematics
    """
    if isinstance(n_elements, bool) or not isinstance(n_elements, numbers.Integral) or n_elements < 1:
        raise ValueError(f"n_elements must be an integer >= 1, got {n_elements!r}")
    gamma = pitch_ratio(element_diameter_m, pitch_diameter_m, contact_angle_rad)
    args = (element_diameter_m, pitch_diameter_m, contact_angle_rad, inner_speed_rad_s, outer_speed_rad_s)
    w_c = cage_speed_rad_s(*args)
    w_r = element_speed_rad_s(*args)
    two_pi = 2.0 * math.pi
    z = int(n_elements)
    bsf = abs(w_r) / two_pi
    return RollingKinematics(
        pitch_ratio=gamma,
        cage_speed_rad_s=w_c,
        element_speed_rad_s=w_r,
        ftf_Hz=abs(w_c) / two_pi,
        bpfo_Hz=z * abs(w_c - outer_speed_rad_s) / two_pi,
        bpfi_Hz=z * abs(inner_speed_rad_s - w_c) / two_pi,
        bsf_Hz=bsf,
        bsf_2x_Hz=2.0 * bsf,
    )
