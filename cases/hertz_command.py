"""``flexbearing hertz``: one Hertz contact (ball in a groove, two spheres, a roller on a raceway):
dimensions, pressure, approach and subsurface shear, in engineering units on the command line."""

from __future__ import annotations

import argparse
import math

from foundation.materials import ElasticMaterial, effective_modulus_Pa
from mbd_core.contact import ball_on_groove, line_contact, sphere_on_sphere, subsurface_shear
from mbd_core.contact.limits import line_contact_warnings, point_contact_warnings
from mbd_core.contact.line import iso16281_stiffness, palmgren_stiffness

from .cli_input import UserError, require_positive
from .report import format_table

__all__ = ["add_hertz_parser", "cmd_hertz_ball", "cmd_hertz_spheres", "cmd_hertz_line"]


def _material(args, which: str = "") -> ElasticMaterial:
    E = getattr(args, f"E{which}_GPa")
    nu = getattr(args, f"nu{which}")
    require_positive(**{f"E{which}_GPa": E})
    try:
        return ElasticMaterial(f"material{which}", E * 1e9, nu)
    except ValueError as e:
        raise UserError(str(e).replace("E_Pa", f"--E{which}-GPa").replace("nu ", f"--nu{which} ")) from None


def _point_report(contact, Q_N: float, nu: float) -> dict:
    a, b = (float(x) for x in contact.semi_axes_m(Q_N))
    p0 = float(contact.max_pressure_Pa(Q_N))
    sub = subsurface_shear(p0, a, b, nu)
    return {
        "load_N": Q_N,
        "method": contact.method,
        "curvature_sum_per_m": contact.curvature_sum_per_m,
        "curvature_difference": contact.curvature_difference,
        "ellipticity_a_over_b": contact.ellipticity,
        "semi_major_axis_a_m": a,
        "semi_minor_axis_b_m": b,
        "max_pressure_p0_Pa": p0,
        "approach_m": float(contact.approach_m(Q_N)),
        "stiffness_N_per_m1p5": contact.stiffness_N_per_m1p5,
        "tau_max_Pa": sub.tau_max_Pa,
        "depth_tau_max_m": sub.depth_tau_max_m,
        "tau_orthogonal_Pa": sub.tau_orthogonal_Pa,
        "depth_tau_orthogonal_m": sub.depth_tau_orthogonal_m,
    }


_POINT_ROWS = (
    ("ellipticity a/b", "ellipticity_a_over_b", 1.0, "-", "{:.4f}"),
    ("semi-major axis a", "semi_major_axis_a_m", 1e3, "mm", "{:.4f}"),
    ("semi-minor axis b", "semi_minor_axis_b_m", 1e3, "mm", "{:.4f}"),
    ("max pressure p0", "max_pressure_p0_Pa", 1e-6, "MPa", "{:.1f}"),
    ("approach delta", "approach_m", 1e3, "mm", "{:.5f}"),
    ("stiffness K (Q=K d^1.5)", "stiffness_N_per_m1p5", 1.0, "N/m^1.5", "{:.5g}"),
    ("max shear tau_max", "tau_max_Pa", 1e-6, "MPa", "{:.1f}"),
    ("depth of tau_max", "depth_tau_max_m", 1e3, "mm", "{:.4f}"),
    ("orthogonal shear tau_0", "tau_orthogonal_Pa", 1e-6, "MPa", "{:.1f}"),
    ("depth of tau_0", "depth_tau_orthogonal_m", 1e3, "mm", "{:.4f}"),
)


def _print_quantities(title: str, d: dict, spec) -> None:
    print(title)
    rows = [(label, fmt.format(d[key] * scale), unit) for label, key, scale, unit, fmt in spec if key in d]
    print(format_table(rows, ("quantity", "value", "unit")))


def _print_warnings(d: dict) -> None:
    for w in d.get("warnings", ()):
        print(f"WARNING: {w}")


def cmd_hertz_ball(args) -> dict:
    require_positive(ball_diameter_mm=args.ball_diameter_mm, pitch_diameter_mm=args.pitch_diameter_mm,
                      load_N=args.load_N)
    mat = _material(args)
    try:
        c = ball_on_groove(args.ball_diameter_mm * 1e-3, args.conformity, args.pitch_diameter_mm * 1e-3,
                           math.radians(args.contact_angle_deg), args.raceway, mat, mat, args.method)
    except ValueError as e:
        msg = str(e)
        for field in ("conformity", "ball_diameter", "pitch_diameter", "contact_angle"):
            msg = msg.replace(field, "--" + field.replace("_", "-") + ("" if field == "conformity" else
                                                                         "-deg" if "angle" in field else "-mm"), 1)
        raise UserError(msg) from None
    d = _point_report(c, args.load_N, mat.nu)
    alpha = math.radians(args.contact_angle_deg)
    groove = (args.conformity * args.ball_diameter_mm * 1e-3, alpha, -math.pi / 2 if alpha == 0.0 else 0.0, math.pi / 2)
    d["warnings"] = point_contact_warnings(c, args.load_N, args.ball_diameter_mm * 0.5e-3, groove=groove)
    if not args.json:
        _print_quantities(
            f"ball Ø{args.ball_diameter_mm:g} mm on the {args.raceway} groove (f = {args.conformity:g}, "
            f"pitch Ø{args.pitch_diameter_mm:g} mm, α = {args.contact_angle_deg:g}°), Q = {args.load_N:g} N",
            d, _POINT_ROWS)
        _print_warnings(d)
    return d


def cmd_hertz_spheres(args) -> dict:
    require_positive(diameter_1_mm=args.diameter_1_mm, diameter_2_mm=args.diameter_2_mm, load_N=args.load_N)
    mat = _material(args)
    c = sphere_on_sphere(args.diameter_1_mm * 1e-3, args.diameter_2_mm * 1e-3, mat, mat)
    d = _point_report(c, args.load_N, mat.nu)
    d["warnings"] = point_contact_warnings(c, args.load_N, min(args.diameter_1_mm, args.diameter_2_mm) * 0.5e-3)
    if not args.json:
        _print_quantities(f"spheres Ø{args.diameter_1_mm:g} and Ø{args.diameter_2_mm:g} mm, Q = {args.load_N:g} N",
                          d, _POINT_ROWS)
        _print_warnings(d)
    return d


def cmd_hertz_line(args) -> dict:
    require_positive(roller_diameter_mm=args.roller_diameter_mm, length_mm=args.length_mm, load_N=args.load_N)
    if not args.raceway_diameter_mm > 0:
        raise UserError(f"--raceway-diameter-mm must be > 0 (inf for a flat raceway), got {args.raceway_diameter_mm}")
    if args.raceway_diameter_mm != math.inf:
        require_positive(raceway_diameter_mm=args.raceway_diameter_mm)
    mat = _material(args)
    try:
        c = line_contact(args.roller_diameter_mm * 1e-3, args.raceway_diameter_mm * 1e-3, args.length_mm * 1e-3,
                         mat, mat, concave=args.concave)
    except ValueError as e:
        raise UserError(str(e)) from None
    Q = args.load_N
    b = float(c.half_width_m(Q))
    p0 = float(c.max_pressure_Pa(Q))
    L = args.length_mm * 1e-3
    e_eff = effective_modulus_Pa(mat, mat)
    # plane strain: τ_max = 0.300·p0 at z = 0.786·b (Johnson §4.3), from the elliptical solution at b/a → 0
    sub = subsurface_shear(p0, b * 1e4, b, mat.nu)
    d = {
        "load_N": Q,
        "half_width_b_m": b,
        "max_pressure_p0_Pa": p0,
        "tau_max_Pa": sub.tau_max_Pa,
        "depth_tau_max_m": sub.depth_tau_max_m,
        "palmgren_approach_one_contact_m": (Q / palmgren_stiffness(L, e_eff)) ** 0.9,
        "iso16281_approach_roller_m": (Q / iso16281_stiffness(L, e_eff)) ** 0.9,
        "warnings": line_contact_warnings(c, Q, args.roller_diameter_mm * 0.5e-3),
    }
    if not args.json:
        spec = (
            ("half-width b", "half_width_b_m", 1e3, "mm", "{:.4f}"),
            ("max pressure p0", "max_pressure_p0_Pa", 1e-6, "MPa", "{:.1f}"),
            ("max shear tau_max", "tau_max_Pa", 1e-6, "MPa", "{:.1f}"),
            ("depth of tau_max", "depth_tau_max_m", 1e3, "mm", "{:.4f}"),
            ("approach, one contact (Palmgren)", "palmgren_approach_one_contact_m", 1e3, "mm", "{:.5f}"),
            ("approach, roller (ISO/TS 16281)", "iso16281_approach_roller_m", 1e3, "mm", "{:.5f}"),
        )
        _print_quantities(f"roller Ø{args.roller_diameter_mm:g} × {args.length_mm:g} mm on raceway "
                          f"Ø{args.raceway_diameter_mm:g} mm{' (concave)' if args.concave else ''}, Q = {Q:g} N",
                          d, spec)
        _print_warnings(d)
    return d


def _add_material(p: argparse.ArgumentParser) -> None:
    p.add_argument("--E-GPa", dest="E_GPa", type=float, default=207.0, help="Young's modulus of both bodies (GPa)")
    p.add_argument("--nu", type=float, default=0.29, help="Poisson's ratio of both bodies")


def add_hertz_parser(sub) -> None:
    h = sub.add_parser("hertz", help="Hertz contact: dimensions, pressure, approach, subsurface shear")
    hs = h.add_subparsers(dest="geometry", required=True)
    b = hs.add_parser("ball", help="ball in a raceway groove")
    b.add_argument("--ball-diameter-mm", type=float, required=True)
    b.add_argument("--conformity", type=float, required=True, help="groove radius / ball diameter (> 0.5)")
    b.add_argument("--pitch-diameter-mm", type=float, required=True)
    b.add_argument("--contact-angle-deg", type=float, default=0.0)
    b.add_argument("--raceway", choices=("inner", "outer"), default="inner")
    b.add_argument("--method", choices=("exact", "hamrock-brewe"), default="exact")
    b.add_argument("--load-N", type=float, required=True)
    _add_material(b)
    b.set_defaults(func=cmd_hertz_ball)
    s = hs.add_parser("spheres", help="two convex spheres (e.g. load ball on spacer ball)")
    s.add_argument("--diameter-1-mm", type=float, required=True)
    s.add_argument("--diameter-2-mm", type=float, required=True)
    s.add_argument("--load-N", type=float, required=True)
    _add_material(s)
    s.set_defaults(func=cmd_hertz_spheres)
    ln = hs.add_parser("line", help="roller on a cylindrical or flat raceway")
    ln.add_argument("--roller-diameter-mm", type=float, required=True)
    ln.add_argument("--raceway-diameter-mm", type=float, default=math.inf, help="inf for a flat raceway")
    ln.add_argument("--concave", action="store_true", help="the raceway wraps around the roller (outer ring)")
    ln.add_argument("--length-mm", type=float, required=True)
    ln.add_argument("--load-N", type=float, required=True)
    _add_material(ln)
    ln.set_defaults(func=cmd_hertz_line)
    for p in (b, s, ln):
        p.add_argument("--json", action="store_true", help="print SI results as JSON")
