"""What a model is built from, as a user names it: the motion of a body (free, fixed, driven), the
penalty law of a contact pair, and the quaternions that place bodies."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..contact.friction import Coulomb, DrebConstant, DrebFalling, DrebLinear, Kragelskii, LimitingShear, MixedFriction

__all__ = ["ContactLaw", "StripTraction", "Free", "Fixed", "Driven", "FRICTION_TYPES", "quat_from_axis_angle", "quat_z_to"]

FRICTION_TYPES = (Coulomb, DrebLinear, DrebConstant, DrebFalling, Kragelskii, LimitingShear, MixedFriction)


def quat_from_axis_angle(axis, angle_rad: float) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a rotation by ``angle_rad`` about ``axis``."""
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    return np.concatenate([[math.cos(angle_rad / 2)], math.sin(angle_rad / 2) * a])


def quat_z_to(direction) -> np.ndarray:
    """Unit quaternion turning the body z axis onto ``direction`` (shortest rotation)."""
    d = np.asarray(direction, float)
    d = d / np.linalg.norm(d)
    axis = np.cross([0.0, 0.0, 1.0], d)
    s = np.linalg.norm(axis)
    if s < 1e-15:
        return np.array([1.0, 0, 0, 0]) if d[2] > 0 else np.array([0.0, 1, 0, 0])
    return quat_from_axis_angle(axis / s, math.atan2(s, d[2]))


@dataclass(frozen=True)
class Free:
    """All six velocity components integrated."""


@dataclass(frozen=True)
class Fixed:
    """Held at its initial pose (a housing, a ring bolted to the structure)."""


@dataclass(frozen=True)
class Driven:
    """Spin about the body's own z axis held at ``omega_rad_s``.

    ``translation_free``: the centre moves under the forces (else it is held);
    ``tilt_free``: the rotations about body x and y are integrated (else held at zero rate).
    """

    omega_rad_s: float
    translation_free: bool = False
    tilt_free: bool = False

    def __post_init__(self) -> None:
        if not math.isfinite(self.omega_rad_s):
            raise ValueError(f"Driven: omega_rad_s must be finite, got {self.omega_rad_s!r}")


@dataclass(frozen=True)
class StripTraction:
    """Traction of a ball contact integrated over its Hertz ellipse in strips
    (:mod:`mbd_core.kernels.strip_traction`) instead of the slip at the contact centre alone, so that
    the spin of the ball about the contact normal gives a spin moment and points of pure rolling.

    Parameters
    ----------
    n_strips : int
        Strips across the ellipse's major axis (1: the centre-point law with the spin ignored).
    semi_major_m_per_N3 : float
        c in a = c·F_n^(1/3): the semi-major axis of the contact ellipse at 1 N, m/N^(1/3) (Hertz,
        :meth:`mbd_core.contact.hertz.HertzPointContact.semi_axes_m`).
    deformed_radius_m : float
        Radius R_d of the deformed contact surface across the major axis, its centre on the ball's
        side (a groove: 2·r_groove·r_ball/(r_groove + r_ball)); inf for a flat contact surface.
    """

    n_strips: int
    semi_major_m_per_N3: float
    deformed_radius_m: float = math.inf

    def __post_init__(self) -> None:
        if not (isinstance(self.n_strips, (int, np.integer)) and 1 <= self.n_strips <= 1000):
            raise ValueError(f"strip traction: n_strips must be an integer in [1, 1000], got {self.n_strips!r}")
        if not (math.isfinite(self.semi_major_m_per_N3) and self.semi_major_m_per_N3 > 0):
            raise ValueError(f"strip traction: semi_major_m_per_N3 must be a positive number, got "
                             f"{self.semi_major_m_per_N3!r}")
        if not self.deformed_radius_m > 0:
            raise ValueError(f"strip traction: deformed_radius_m must be > 0 (inf: flat), got {self.deformed_radius_m!r}")

    @property
    def curvature_per_m(self) -> float:
        """κ = 1/(2R_d) of z(y) = κ·y², 1/m (0 for a flat surface)."""
        return 0.5 / self.deformed_radius_m


@dataclass(frozen=True)
class ContactLaw:
    """Penalty law of a contact pair.

    Parameters
    ----------
    stiffness : float
        K of F = K δⁿ (N/m^n); for roller–raceway pairs the stiffness of one slice.
    exponent : float
        n (1.5 point contact, 10/9 line contact slices, 1 linear).
    damping : float
        IMPACT: c in N·s/m reached at δ = d_max; Hunt–Crossley: c in s/m.
    d_max_m : float
        Penetration over which the IMPACT damping ramps from 0 to c.
    model : {"impact", "hunt_crossley"}
    friction : friction law object or None
        One of :mod:`mbd_core.contact.friction` (None: frictionless).
    max_penetration_m : float or None
        Divergence bound: a run stops when this pair penetrates deeper. Default: 2 % of the
        element radius (far beyond the range where Hertz theory holds).
    strips : StripTraction or None
        Ball–groove pairs on rigid rings: the friction law applied strip by strip over the contact
        ellipse (None: at the contact centre only). Needs ``friction``.
    """

    stiffness: float
    exponent: float = 1.5
    damping: float = 0.0
    d_max_m: float = 1e-6
    model: str = "impact"
    friction: object | None = None
    max_penetration_m: float | None = None
    strips: StripTraction | None = None

    def __post_init__(self) -> None:
        for name in ("stiffness", "exponent", "d_max_m"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"contact law: {name} must be a positive number, got {v!r}")
        if not (math.isfinite(self.damping) and self.damping >= 0):
            raise ValueError(f"contact law: damping must be ≥ 0, got {self.damping!r}")
        if self.model not in ("impact", "hunt_crossley"):
            raise ValueError(f"contact law: model must be 'impact' or 'hunt_crossley', got {self.model!r}")
        if self.friction is not None and not isinstance(self.friction, FRICTION_TYPES):
            raise TypeError(f"contact law: friction must be one of {[t.__name__ for t in FRICTION_TYPES]}")
        if self.max_penetration_m is not None and not self.max_penetration_m > 0:
            raise ValueError(f"contact law: max_penetration_m must be > 0, got {self.max_penetration_m!r}")
        if self.strips is not None:
            if not isinstance(self.strips, StripTraction):
                raise TypeError("contact law: strips must be a StripTraction")
            if self.friction is None:
                raise ValueError("contact law: strips integrate a friction law over the contact: give friction")

    def without_friction(self) -> "ContactLaw":
        return ContactLaw(self.stiffness, self.exponent, self.damping, self.d_max_m, self.model, None,
                          self.max_penetration_m)
