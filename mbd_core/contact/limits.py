"""Validity limits of Hertz contacts in rolling bearings, and warnings for results beyond them.

* Static limit of the maximum contact pressure (ISO 76:2006, *Rolling bearings — Static load
  ratings*, definitions of the basic static load ratings: the load giving, at the most heavily
  loaded contact, 4 200 MPa for ball bearings (4 600 MPa self-aligning ball bearings) and
  4 000 MPa for roller bearings). Above it the permanent deformation exceeds 10⁻⁴ of the rolling-element
  diameter and the elastic (Hertz) model no longer describes the contact.
* Hertz theory assumes a contact small against the bodies (Johnson, *Contact Mechanics*, 1985,
  §4.1). Conforming grooves give semi-major axes of a good fraction of the ball radius at rated
  loads, so only a semi-axis beyond the convex body's radius (a contact wider than the ball or
  roller, no Hertz contact at all) is flagged here; the pressure limit is met long before.
* A ball contact ellipse must stay on its groove: the semi-major axis a spans the angle a/(f·D)
  on the groove of radius f·D either side of the contact angle α (Harris & Kotzalas, *Rolling
  Bearing Analysis*, 5th ed., 2007, §6: "truncation" of the ellipse at the groove shoulder).
"""

from __future__ import annotations

import math

__all__ = ["P0_STATIC_LIMIT_BALL_PA", "P0_STATIC_LIMIT_ROLLER_PA", "SMALL_CONTACT_RATIO", "pressure_warning",
           "small_contact_warning", "groove_edge_warning", "point_contact_warnings", "line_contact_warnings"]

#: ISO 76 static limit of p0 for ball bearings (except self-aligning), Pa.
P0_STATIC_LIMIT_BALL_PA = 4.2e9
#: ISO 76 static limit of p0 for roller bearings, Pa.
P0_STATIC_LIMIT_ROLLER_PA = 4.0e9
#: Largest contact semi-axis over the convex body's radius before the contact is flagged.
SMALL_CONTACT_RATIO = 1.0


def pressure_warning(p0_Pa: float, limit_Pa: float, kind: str) -> str | None:
    """Warning if p0 exceeds the ISO 76 static limit of a ``kind`` ("ball" or "roller") bearing."""
    if not p0_Pa > limit_Pa:
        return None
    return (f"max contact pressure p0 = {p0_Pa / 1e9:.4g} GPa exceeds the ISO 76 static limit "
            f"{limit_Pa / 1e9:.3g} GPa of {kind} bearings: plastic deformation, beyond the elastic (Hertz) model")


def small_contact_warning(semi_axis_m: float, radius_m: float) -> str | None:
    """Warning if the contact semi-axis exceeds SMALL_CONTACT_RATIO of the convex body's radius."""
    if not semi_axis_m > SMALL_CONTACT_RATIO * radius_m:
        return None
    return (f"contact semi-axis {semi_axis_m * 1e3:.4g} mm exceeds the body radius {radius_m * 1e3:.4g} mm: "
            "beyond the small-contact assumption of Hertz theory")


def groove_edge_warning(semi_major_m: float, groove_radius_m: float, contact_angle_rad: float,
                        angle_min_rad: float, angle_max_rad: float) -> str | None:
    """Warning if the contact ellipse, ±a/(groove radius) about α, leaves [angle_min, angle_max]."""
    half = semi_major_m / groove_radius_m
    if angle_min_rad <= contact_angle_rad - half and contact_angle_rad + half <= angle_max_rad:
        return None
    span = f"±{math.degrees(half):.3g}°" if half < math.pi else "more than the whole section"
    return (f"contact ellipse (a = {semi_major_m * 1e3:.4g} mm, {span} on the groove about "
            f"α = {math.degrees(contact_angle_rad):.4g}°) runs over the groove edge at "
            f"[{math.degrees(angle_min_rad):.3g}°, {math.degrees(angle_max_rad):.3g}°]: "
            "truncated, beyond the Hertz model")


def point_contact_warnings(contact, Q_N: float, convex_radius_m: float, limit_Pa: float = P0_STATIC_LIMIT_BALL_PA,
                           groove: tuple[float, float, float, float] | None = None) -> list[str]:
    """Validity warnings of a Hertz point contact under load Q.

    Parameters
    ----------
    contact : HertzPointContact
    Q_N : float
        Normal load, N.
    convex_radius_m : float
        Smallest principal radius of the convex body (the ball radius), m.
    limit_Pa : float
        Static limit of p0, Pa (ISO 76: 4.2 GPa ball bearings).
    groove : (groove radius m, contact angle rad, angle min rad, angle max rad), optional
        For a ball in a groove: check the ellipse stays on the groove.
    """
    a, _ = (float(x) for x in contact.semi_axes_m(Q_N))
    out = [pressure_warning(float(contact.max_pressure_Pa(Q_N)), limit_Pa, "ball"),
           small_contact_warning(a, convex_radius_m)]
    if groove is not None:
        out.append(groove_edge_warning(a, *groove))
    return [w for w in out if w]


def line_contact_warnings(contact, Q_N: float, roller_radius_m: float,
                          limit_Pa: float = P0_STATIC_LIMIT_ROLLER_PA) -> list[str]:
    """Validity warnings of a Hertz line contact (roller) under load Q."""
    out = [pressure_warning(float(contact.max_pressure_Pa(Q_N)), limit_Pa, "roller"),
           small_contact_warning(float(contact.half_width_m(Q_N)), roller_radius_m)]
    return [w for w in out if w]
