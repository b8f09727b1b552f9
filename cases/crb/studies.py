"""The studies of a cylindrical roller bearing's friction torque (:mod:`cases.crb.case`): one
operating point roller by roller, and the torque map over speed and axial load beside the catalogue
model."""

from __future__ import annotations

import math

import numpy as np

from mbd_core.bearing.catalogue_friction import catalogue_cylindrical_roller_moment
from mbd_core.bearing.roller_friction import RollerFriction, roller_bearing_friction

from ..overrides import StudyEntry, unused_keys
from .case import CrbCase
from .plots import plot_rib_film, plot_rollers, plot_torque_speed

__all__ = ["STUDIES", "case_unused_keys", "run_study", "uses_dynamics", "operating_point"]

# below this film parameter the raceways run in mixed lubrication, which the contact model does not count
_MIXED_RACEWAY_LAMBDA = 1.0


def operating_point(case: CrbCase, speed_rpm: float, axial_load_N: float) -> tuple[RollerFriction, dict]:
    """Our losses and the catalogue model's moment at one speed and axial load (the case's radial load)."""
    lub, op = case.lubrication, case.operation
    oil = lub.oil()
    ours = roller_bearing_friction(case.bearing.model(), oil, lub.temperature_C, speed_rpm, op.radial_load_N,
                                   axial_load_N, case.surfaces)
    catalogue = catalogue_cylindrical_roller_moment(case.bearing.bore_m, case.bearing.outside_diameter_m,
                                                    op.radial_load_N, axial_load_N, speed_rpm,
                                                    oil.kinematic_viscosity_m2_s(lub.temperature_C),
                                                    case.catalogue)
    return ours, catalogue


def _validity(out, run: RollerFriction) -> None:
    lam = run.summary()["min_raceway_lambda"]
    if lam < _MIXED_RACEWAY_LAMBDA:
        out.warn([f"raceway film parameter Λ = {lam:.2f} < {_MIXED_RACEWAY_LAMBDA:g} at {run.speed_rpm:g} rev/min: the "
                  "raceways run in mixed lubrication, whose asperity friction the contact model does not count "
                  "(its torque is low there)"])


def _point(case: CrbCase, out, progress=None) -> None:
    op = case.operation
    run, catalogue = operating_point(case, op.speed_rpm, op.axial_load_N)
    header = ("roller", "angle_rad", "roller_load_N", "rib_load_N", "raceway_lambda", "rib_lambda", "outer_rib_lambda",
              "rib_asperity_share", "rib_friction", "rolling_power_W", "rib_power_W")
    out.write_csv("roller_losses.csv", header, zip(range(1, len(run.angles_rad) + 1), run.angles_rad, run.roller_load_N,
                                                   run.rib_load_N, run.raceway_lambda, run.rib_lambda,
                                                   run.outer_rib_lambda, run.rib_asperity_share, run.rib_friction,
                                                   run.rolling_power_W, run.rib_power_W))
    title = (f"{case.name}: {op.radial_load_N / 1e3:g} kN radial, {op.axial_load_N / 1e3:g} kN axial, "
             f"{op.speed_rpm:g} rev/min, {run.torque_Nm:.3g} N·m")
    out.save_figure(plot_rollers(run, title), "rollers.png")
    out.summary.update(run.summary(), catalogue=catalogue, torque_to_catalogue=run.torque_Nm / catalogue["torque_Nm"])
    _validity(out, run)
    out.note(f"friction torque {run.torque_Nm:.3g} N·m (raceway rolling {run.rolling_torque_Nm:.3g}, ribs "
             f"{run.rib_torque_Nm:.3g}); catalogue model {catalogue['torque_Nm']:.3g} N·m")


def _speed_axial(case: CrbCase, out, progress=None) -> None:
    speeds, axials = case.study.speeds_rpm, case.study.axial_loads_N
    points = [(fa, n) for fa in axials for n in speeds]
    rows, ours, ref, lambdas, shares = [], {}, {}, {}, {}
    for fa, n in (progress(points, "speed and axial load points") if progress else points):
        run, cat = operating_point(case, n, fa)
        s = run.summary()
        rows.append((n, fa, run.torque_Nm, run.rolling_torque_Nm, run.rib_torque_Nm, s["min_raceway_lambda"],
                     s["min_rib_lambda"] if s["min_rib_lambda"] is not None else math.nan,
                     s["max_rib_asperity_share"], cat["torque_Nm"], cat["rolling_Nm"], cat["sliding_Nm"],
                     run.torque_Nm / cat["torque_Nm"]))
        total, rolling = ours.setdefault(fa, ([], []))
        total.append(run.torque_Nm)
        rolling.append(run.rolling_torque_Nm)
        ref.setdefault(fa, []).append(cat["torque_Nm"])
        if fa > 0.0:
            lambdas.setdefault(fa, []).append(s["min_rib_lambda"])
            shares.setdefault(fa, []).append(s["max_rib_asperity_share"])
        _validity(out, run)
    out.write_csv("friction_torque.csv", ("speed_rpm", "axial_load_N", "torque_Nm", "rolling_torque_Nm", "rib_torque_Nm",
                                          "min_raceway_lambda", "min_rib_lambda", "max_rib_asperity_share",
                                          "catalogue_torque_Nm", "catalogue_rolling_Nm", "catalogue_sliding_Nm",
                                          "torque_to_catalogue"), rows)
    op, lub = case.operation, case.lubrication
    what = (f"{case.name}: F_r = {op.radial_load_N / 1e3:g} kN, ISO VG {lub.iso_vg} at {lub.temperature_C:g} °C")
    out.save_figure(plot_torque_speed(list(speeds), ours, ref, what), "friction_torque.png")
    if lambdas:
        out.save_figure(plot_rib_film(list(speeds), lambdas, shares, f"{what}: rib contacts"), "rib_film.png")
    ratios = np.array([r[-1] for r in rows])
    least = {f"{fa:g}": float(speeds[int(np.argmin(ours[fa][0]))]) for fa in axials}
    out.summary.update(
        points=[dict(zip(("speed_rpm", "axial_load_N", "torque_Nm", "rolling_torque_Nm", "rib_torque_Nm",
                          "min_raceway_lambda", "min_rib_lambda", "max_rib_asperity_share", "catalogue_torque_Nm"),
                         r[:9])) for r in rows],
        speed_of_least_torque_rpm=least, torque_to_catalogue_min=float(ratios.min()),
        torque_to_catalogue_max=float(ratios.max()))
    out.note(f"{len(rows)} points: torque {min(r[2] for r in rows):.3g} … {max(r[2] for r in rows):.3g} N·m, "
             f"{ratios.min():.2f} … {ratios.max():.2f}× the catalogue model")
    out.note("least torque at " + ", ".join(f"{n:g} rev/min (F_a = {float(fa) / 1e3:g} kN)" for fa, n in least.items()))


STUDIES = {
    "point": StudyEntry(run=_point, sweeps=()),
    "speed-axial": StudyEntry(run=_speed_axial, sweeps=("speeds_rpm", "axial_loads_N"),
                              unused={"operation.axial_load_N": "set study.axial_loads_N",
                                      "operation.speed_rpm": "set study.speeds_rpm"}),
}


def case_unused_keys(case: CrbCase) -> dict[str, str]:
    """Every key of ``case`` its study does not read → what does its job."""
    return unused_keys(case.study.kind, STUDIES, {}, ())


def uses_dynamics(case: CrbCase) -> bool:
    return False


#: ``error_estimates`` of every run: the model has no discretisation whose error a run could estimate
ERROR_ESTIMATES = {"why_none": "closed form contact by contact (roller loads from one root solve to 1e-13, films "
                               "and losses from fitted formulas): no mesh, modes, slices or step to estimate an "
                               "error of; its model error is the comparison with the catalogue model"}


def run_study(case: CrbCase, out, progress=None) -> None:
    STUDIES[case.study.kind].run(case, out, progress)
    out.summary["error_estimates"] = dict(ERROR_ESTIMATES)
