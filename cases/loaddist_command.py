"""``flexbearing loaddist``: its options, which bearing the argument names, and what it prints and writes."""

from __future__ import annotations

import logging
import math
import os
from dataclasses import dataclass

from mbd_core.bearing.distribution_case_depth import case_depth_bearing_life_Mrev, row_case_depth_factors
from mbd_core.bearing.distribution_life import rating_life, spectrum_rating_life
from mbd_core.quasistatic import RingLoad
from mbd_core.quasistatic.results import LOAD_NAMES

from .bearing_file import BUILTIN_DIR, BearingDescription, read_bearing_file
from .bearing_report import (bearing_checks, bearing_checks_lines, curve_comparison, stiffness_lines, write_contacts_csv,
                             write_limiting_curve)
from .bearing_solver import BearingSolver
from .catalog import BUILTIN_BEARINGS
from .edge_stress_report import EDGE_STRESS_FILES, edge_stress_lines, edge_stresses, write_edge_stress
from .report import format_table, load_distribution_table, write_load_distribution
from .results import output_units

__all__ = ["LOAD_NAMES", "LoaddistOptions", "add_loaddist_parser", "bearing_description", "cases_table", "check_loaddist_options",
           "chosen_loads", "loaddist_outputs"]


@dataclass(frozen=True)
class LoaddistOptions:
    """The options of ``loaddist`` that shape its outputs (the parsed command line has the same
    attributes; a ``flexbearing run`` of a described bearing builds these from its case)."""

    out: str | None = None
    limiting_curve: bool = False
    s0: float = 1.0
    p0_limit_MPa: float | None = None
    rotating_ring: str | None = None
    speed_rpm: float | None = None
    json: bool = False
    edge_stress: bool = False


def add_loaddist_parser(sub, func) -> None:
    """The ``loaddist`` sub-command and its options."""
    ld = sub.add_parser("loaddist", help="quasi-static load distribution with rigid rings, or with the modal rings "
                        "of a description file's [rings] tables")
    ld.add_argument("bearing", nargs="?", default="slewing-ring",
                    help=f"built-in bearing ({', '.join(sorted(BUILTIN_BEARINGS))}; default: slewing-ring) or a "
                    "bearing description file .toml (format: cases/bearings/README.md)")
    for name, unit in (("Fx", "N"), ("Fy", "N"), ("Fz", "N"), ("Mx", "Nm"), ("My", "Nm")):
        ld.add_argument(f"--{name}-{unit}", dest=f"{name}_{unit}", type=float, default=None,
                        help=f"load on the moving ring ({'N' if unit == 'N' else 'N·m'}); "
                        "all omitted = the load of the bearing's file (every case of its spectrum)")
    ld.add_argument("--limiting-curve", action="store_true",
                    help="also compute the limiting load curve (axial force vs tilting moment at the static "
                    "criterion; needs --out; takes seconds)")
    ld.add_argument("--s0", type=float, default=1.0,
                    help="static safety factor of the limiting load curve's criterion (default 1: p0 at the ISO 76 limit)")
    ld.add_argument("--p0-limit-MPa", dest="p0_limit_MPa", type=float, default=None,
                    help="allowed contact pressure p0 of the limiting load curve instead of ISO 76 over --s0 (MPa)")
    ld.add_argument("--rotating-ring", dest="rotating_ring", choices=("moving", "fixed"), default=None,
                    help="ring that turns relative to the load; with --speed-rpm gives the L10 rating life")
    ld.add_argument("--speed-rpm", dest="speed_rpm", type=float, default=None,
                    help="relative speed of the rings, rev/min (with --rotating-ring: L10 in hours)")
    ld.add_argument("--edge-stress", dest="edge_stress", action="store_true",
                    help="raceway pressures along the most loaded roller of each roller row with the slices coupled "
                    "through the elastic half-space (edge stresses), beside the ISO/TS 16281 slices")
    ld.add_argument("--rigid-rings", dest="rigid_rings", action="store_true",
                    help="solve with rigid rings even where the description file makes rings modal ([rings.X])")
    ld.add_argument("--out", default=None,
                    help="write summary.json, element_loads.csv, contacts.csv and plots here")
    ld.add_argument("--json", action="store_true", help="print SI results as JSON")
    ld.set_defaults(func=func)


def check_loaddist_options(args) -> None:
    """ValueError naming the option for an unusable limiting-curve option (before any work)."""
    if not (math.isfinite(args.s0) and args.s0 > 0.0):
        raise ValueError(f"--s0 must be a positive number, got {args.s0}")
    if args.p0_limit_MPa is not None and not (math.isfinite(args.p0_limit_MPa) and args.p0_limit_MPa > 0.0):
        raise ValueError(f"--p0-limit-MPa must be a positive number, got {args.p0_limit_MPa}")
    if args.speed_rpm is not None and not (math.isfinite(args.speed_rpm) and args.speed_rpm > 0.0):
        raise ValueError(f"--speed-rpm must be a positive number, got {args.speed_rpm}")
    if (args.rotating_ring is None) != (args.speed_rpm is None):
        raise ValueError("--rotating-ring and --speed-rpm give the rating life together: give both")
    if args.limiting_curve and not args.out:
        raise ValueError("--limiting-curve writes limiting_load_curve.csv and .png: give --out")
    if not args.limiting_curve and (args.s0 != 1.0 or args.p0_limit_MPa is not None):
        raise ValueError("--s0 and --p0-limit-MPa set the limiting load curve's criterion: give --limiting-curve")


def loaddist_outputs(args, name: str, desc: BearingDescription, results, time_share, solver: BearingSolver) -> dict:
    """Print and (with ``--out``) write the results of ``loaddist``; the summary in output units."""
    checks = [bearing_checks(desc.bearing, r) for r in results]
    extra = {"case": name, "description": desc.description, **solver.summary(),
             "rating_life": life_summary(args, desc, results, time_share)}
    written = ["summary.json", "element_loads.csv", "contacts.csv", "element_loads.png"]
    if any(r.kind == "ball" for r in results[0].rows):
        written.append("contact_angles.png")
    edges = edge_stresses(desc.bearing, results) if args.edge_stress else None
    if edges is not None:
        extra["edge_stress"] = [{**e.to_dict(), **({"load_case": case + 1} if len(results) > 1 else {})}
                                for case, e in edges]
        written.extend(EDGE_STRESS_FILES)
    if args.out:
        def more(folder):
            write_contacts_csv(desc.bearing, results, folder / "contacts.csv")
            if edges is not None:
                write_edge_stress(edges, folder, len(results) > 1)
            if args.limiting_curve:
                p0 = None if args.p0_limit_MPa is None else args.p0_limit_MPa * 1e6
                curve, rigid = write_limiting_curve(desc.bearing, folder, results, s0=args.s0, pressure_limit_Pa=p0,
                                                    solve=solver.solve if solver.flexible else None)
                extra["limiting_load_curve"] = curve.to_dict()
                written.extend(["limiting_load_curve.csv", "limiting_load_curve.png"])
                if rigid is not None:
                    extra["limiting_load_curve_rigid"] = rigid.to_dict()
                    extra["limiting_load_curve_modal_over_rigid"] = curve_comparison(curve, rigid)
                    written.append("limiting_load_curve_rigid.csv")

        path = write_load_distribution(results if len(results) > 1 else results[0], args.out, extra, time_share,
                                       case_extra=checks, more=more)
        logging.getLogger(__name__).info("wrote %s", path)
    if not args.json:
        if desc.description:
            print(desc.description)
        print(solver.label)
        if len(results) == 1:
            print("\n".join([load_distribution_table(results[0]), *bearing_checks_lines(checks[0]),
                             *stiffness_lines(results[0])]))
        else:
            print(cases_table(results, time_share, checks))
        if edges is not None:
            print("\n".join(edge_stress_lines(edges, len(results) > 1)))
        print("\n".join(life_lines(extra["rating_life"])))
        if args.out:
            print(f"\nresults: {args.out}/{', '.join(written)}")
    if len(results) == 1:
        d = results[0].to_dict()
        d.update({k: v for k, v in checks[0].items() if k != "warnings"})
        d["warnings"] = d["warnings"] + checks[0]["warnings"]
        d["rating_life"] = extra["rating_life"]
        if edges is not None:
            d["edge_stress"] = extra["edge_stress"]
        return output_units(d)
    return output_units({"bearing": desc.name, "rating_life": extra["rating_life"],
                         **({"edge_stress": extra["edge_stress"]} if edges is not None else {}), "load_cases": [
        {"case": k + 1, **r.to_dict(), **{k2: v for k2, v in c.items() if k2 != "warnings"},
         "warnings": r.to_dict()["warnings"] + c["warnings"]} for k, (r, c) in enumerate(zip(results, checks))]})


def chosen_loads(desc: BearingDescription, given: dict) -> tuple[tuple[RingLoad, ...], tuple[float, ...] | None]:
    """(load cases, time shares) to solve: the file's, or one case of the ``given`` components
    (None: not given, 0) when any is given."""
    if all(v is None for v in given.values()):
        return desc.load_cases, desc.time_share
    return (RingLoad(**{k: (0.0 if v is None else v) for k, v in given.items()}),), None


def bearing_description(name: str) -> tuple[str, BearingDescription]:
    """(name, description) of a built-in bearing by name, or of a description file by path
    (:mod:`cases.bearing_file`; the built-ins are files too, read alike). ValueError naming the
    argument when it is neither."""
    if name in BUILTIN_BEARINGS:
        return name, read_bearing_file(BUILTIN_DIR / f"{name}.toml")
    if name.endswith(".toml") or os.sep in name or "/" in name or os.path.exists(name):
        return os.path.splitext(os.path.basename(name.rstrip("/" + os.sep)))[0] or name, read_bearing_file(name)
    raise ValueError(f"bearing: unknown built-in bearing {name!r}; one of {', '.join(sorted(BUILTIN_BEARINGS))}, "
                    "or a bearing description file (.toml)")


def cases_table(results, time_share, checks=None) -> str:
    """One line per load case: the load, each row's largest element load and the bearing's s0."""
    names = [r.name for r in results[0].rows]
    lines = []
    for k, res in enumerate(results):
        share = [] if time_share is None else [f"{time_share[k]:.4g}"]
        s0 = [] if checks is None else [_s0_text(checks[k]["static_safety"]["s0"])]
        lines.append((k + 1, *share, *(f"{v:.4g}" for v in res.load), *(f"{r.max_load_N:.0f}" for r in res.rows), *s0))
    head = ("case", *(["time_share"] if time_share is not None else []), "Fx N", "Fy N", "Fz N", "Mx N·m",
            "My N·m", *(f"Q_max {n} N" for n in names), *([] if checks is None else ["s0"]))
    warnings = [f"WARNING: case {k + 1}: {w}" for k, res in enumerate(results) for w in res.warnings]
    if checks is not None:
        warnings += [f"WARNING: case {k + 1}: {w}" for k, c in enumerate(checks) for w in c["warnings"]]
    return "\n".join([f"bearing: {results[0].bearing_name}", format_table(lines, head), *warnings])


def _s0_text(s0) -> str:
    return "unloaded" if s0 is None else f"{s0:.3g}"


def life_summary(args, desc: BearingDescription, results, time_share) -> dict:
    """L10 per row and of the bearing (:mod:`mbd_core.bearing.distribution_life`, ISO 281 / ISO/TS 16281
    lamina method), in 10^6 rev and hours: L10h = L10·10^6/(60·n) (ISO 281:2007, eq. 4 note: hours at
    constant speed n in rev/min). A spectrum is combined by Palmgren–Miner with its time shares.
    Rows given a case depth add ``case_depth`` (the DG03 factor A_cd and the contact it was evaluated
    at, :mod:`mbd_core.bearing.distribution_case_depth`) and ``life_cd_Mrev``/``life_cd_h`` = A_cd·L10;
    the bearing then adds its ``life_cd_Mrev``/``life_cd_h`` (rows in series, A_cd = 1 for the others).
    Without --rotating-ring and --speed-rpm: ``computed`` False and the reason."""
    if args.rotating_ring is None:
        return {"computed": False, "reason": "give --rotating-ring and --speed-rpm to compute the L10 rating life"}
    if len(results) == 1:
        life = rating_life(desc.bearing, results[0], rotating_ring=args.rotating_ring)
    else:
        shares = time_share if time_share is not None else [1.0] * len(results)
        life = spectrum_rating_life(desc.bearing, list(results), shares,
                                    rotating_ring=args.rotating_ring)
    hours = 1e6 / (60.0 * args.speed_rpm)
    d = life.to_dict()
    d.update({"computed": True, "speed_rpm": args.speed_rpm, "life_h": life.life_Mrev * hours,
              "time_share": None if len(results) == 1 else list(shares)})
    for r in d["rows"]:
        r["life_h"] = r["life_Mrev"] * hours
    if desc.case_depths:
        _add_case_depth(d, desc, life, results, hours)
    return d


def _add_case_depth(d: dict, desc: BearingDescription, life, results, hours: float) -> None:
    """The case-depth factor and the corrected lives A_cd·L10 in the life summary ``d``."""
    factors = row_case_depth_factors(desc.bearing, list(results), desc.case_depths)
    by_row = {f.row: f for f in factors}
    for r in d["rows"]:
        f = by_row.get(r["row"])
        if f is not None:
            r["case_depth"] = f.to_dict()
            r["life_cd_Mrev"] = f.factor * r["life_Mrev"]
            r["life_cd_h"] = r["life_cd_Mrev"] * hours
    d["life_cd_Mrev"] = case_depth_bearing_life_Mrev(desc.bearing, life, factors)
    d["life_cd_h"] = d["life_cd_Mrev"] * hours


def life_lines(life: dict) -> list[str]:
    """Screen lines of :func:`life_summary`."""
    if not life["computed"]:
        return [f"rating life: not computed ({life['reason']})"]
    rows = []
    for r in life["rows"]:
        rows.append(f"  {r['row']}: L10 = {r['life_Mrev']:.4g} Mrev = {r['life_h']:.4g} h (deciding: {r['deciding']})")
        if "case_depth" in r:
            rows.extend(_case_depth_lines(r, spectrum=life["time_share"] is not None))
    bearing = [f"  bearing: L10 = {life['life_Mrev']:.4g} Mrev = {life['life_h']:.4g} h"]
    if "life_cd_Mrev" in life:
        bearing.append(f"  bearing: L10·A_cd = {life['life_cd_Mrev']:.4g} Mrev = {life['life_cd_h']:.4g} h")
    return [f"rating life L10 ({life['rotating_ring']} ring rotating, {life['speed_rpm']:g} rpm):", *rows, *bearing]


def _case_depth_lines(r: dict, spectrum: bool) -> list[str]:
    """Screen lines of a row's case-depth factor (from the SI values of :func:`life_summary`)."""
    c = r["case_depth"]
    if c["element"] is None:
        at = "unloaded"
    else:
        at = f"{c['contact']}, element {c['element']}" + (f", case {c['load_case']}" if spectrum else "")
    return [f"    case depth {c['case_depth_m'] * 1e3:.3g} mm: A_cd = {c['factor']:.3g} at {at} (τ_max(1.1·h) = "
            f"{c['shear_at_check_depth_Pa'] / 1e6:.0f} MPa, τ_f = {c['core_shear_fatigue_Pa'] / 1e6:.0f} MPa)",
            f"    L10·A_cd = {r['life_cd_Mrev']:.4g} Mrev = {r['life_cd_h']:.4g} h"]
