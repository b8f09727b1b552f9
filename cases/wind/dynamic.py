"""A dynamic run of the wind main bearing and the figures read from it.

Roller speed: the spin about the roller's own axis relative to the cage frame (for the radial
row the cage speed is taken off the absolute spin about z; a thrust roller's axis is radial, so its
spin needs no correction), against the no-slip value of :func:`.scene.rolling_speeds`. A roller
rolls only while it is loaded: the ``loaded`` figure averages over the samples in which the roller
carries more than ``LOADED_SHARE`` of its row's largest raceway load; ``one roller`` is the most
loaded roller of the row at the start (:func:`watched_roller`) over the whole run (it passes
through the unloaded zone in a long run, as the paper's plots do).

Equilibrium: the force and moment of the rollers' normal forces on the inner ring (raceway slices
and the radial row's guide ribs, in the rigid geometry's directions) against the applied load and
the ring's weight, averaged over the run after ``settle_s`` (the ring's mean acceleration is zero
when it stays in place).
"""

from __future__ import annotations

import math

import numpy as np

from cases.config import CaseError
from cases.integrate import integrate
from cases.results import RPM_PER_RAD_S, plural
from mbd_core.multibody import largest_load_step_error, stable_timestep
from mbd_core.multibody.step_error import richardson
from mbd_core.quasistatic import Bearing, solve_load_distribution
from mbd_core.quasistatic.flexible import FlexibleRing, build_flexible_model
from mbd_core.quasistatic.flexible_solve import solve_flexible_load_distribution

from .bodies import RACEWAYS
from .case import INNER_RING_MASS_KG, WindCase
from .scene import G_M_S2, WindScene, build_scene, inner_ring_load, load_history, rolling_speeds, rows

__all__ = ["LOADED_SHARE", "run", "settled", "step_error", "slice_error", "roller_speeds", "cage_speeds",
           "ring_reaction", "cage_forces", "applied_load"]

#: a roller counts as loaded above this share of its row's largest raceway load at that instant
LOADED_SHARE = 0.05


def run(case: WindCase, progress=None) -> tuple[WindScene, dict]:
    """The case's scene integrated over ``analysis.duration_s``; ``sc.state`` is left at its end."""
    sc = build_scene(case)
    a = case.analysis
    h = None
    if a.step_factor != 1.0:
        h = a.step_factor * stable_timestep(sc.model, sc.state).timestep_s
    # the Adams preset's soft contacts let the ring settle far from the (Hertz) start: loads grow
    return sc, integrate(sc.model, sc.state, a.duration_s, a.record_every, progress,
                         adaptive=case.contact.preset == "adams", timestep_s=h)


def step_error(sc: WindScene, timestep_s: float) -> dict:
    """Time-step error of the largest roller load (:func:`mbd_core.multibody.largest_load_step_error`)
    from ``sc.state`` (the run's end)."""
    return largest_load_step_error(sc.model, sc.state, timestep_s, [p for rb in sc.rows for p in rb.moving_pairs])


def slice_error(case: WindCase, modal=None) -> dict | None:
    """Slicing error of the largest roller load: the quasi-static load distribution under the load
    of the case's history that loads a roller most, with ``rollers.n_slices`` slices and with 2× and
    4× as many, extrapolated as the time step is (:func:`mbd_core.multibody.step_error.richardson`,
    with 1/slices for h). With the case's modal rings (``modal``, the scene's
    :class:`.bodies.ModalBodies`) the rings bend in it as in the run (:func:`_flexible_largest`), so
    their twist, which loads a roller unevenly along its length, is in the estimate; else rigid
    rings. None under the ``adams`` preset, whose contact law takes the whole roller."""
    if case.contact.preset == "adams":
        return None
    _, loads = load_history(case)
    n = case.rollers.n_slices
    flexible = modal is not None and modal.inner is not None and modal.outer is not None

    def largest(k: int, load) -> float:
        c = case.with_(rollers={"n_slices": k * n})
        if flexible:
            return _flexible_largest(c, modal, load)
        res = solve_load_distribution(Bearing("three-row roller", rows(c)), inner_ring_load(load))
        return max(float(r.load_N.max()) for r in res.rows)

    worst = max(np.unique(loads, axis=0), key=lambda f: largest(1, f))
    est = richardson(*(largest(k, worst) for k in (1, 2, 4)))
    rings = "the case's modal rings" if flexible else "rigid rings"
    return {"max_load": est.relative, "max_load_N": est.value, "order": est.order,
            "order_observed": est.order_observed, "rings": "modal" if flexible else "rigid",
            "what": f"relative slicing error of the largest roller load at {n} slices per roller: quasi-static "
                    f"({rings}) with {n}, {2 * n} and {4 * n} slices under the most loading load of the history "
                    "(Richardson)"}


def _flexible_largest(case: WindCase, modal, load) -> float:
    """Largest roller load of the flexible quasi-static equilibrium
    (:func:`mbd_core.quasistatic.flexible_solve.solve_flexible_load_distribution`): the inner ring
    (free–free modes) rides on the rigid displacement, the outer ring is held at its bolts; each
    row's raceway fields are those of the middle circle of its (θ, s) grid (of an even count, the
    one just below the middle), the section's rotation carrying them along the roller."""
    row_defs = rows(case)
    mid = (case.bodies.n_across - 1) // 2
    names = {r.name: f"{segment}@s{mid}" for r, segment in zip(row_defs, RACEWAYS)}
    rings = (FlexibleRing("inner ring", modal.inner, "moving", names), FlexibleRing("outer ring", modal.outer, "fixed", names))
    res = solve_flexible_load_distribution(build_flexible_model(Bearing("three-row roller", row_defs), rings),
                                           inner_ring_load(load))
    return max(float(r.load_N.max()) for r in res.rows)


#: fewest recorded samples after the settling time that the averages of a run are taken over
MIN_SETTLED_SAMPLES = 2


def settled(case: WindCase, rec: dict) -> np.ndarray:
    """Mask of the samples after ``analysis.settle_s``; too few of them is an error naming the keys."""
    ok = rec["t"] >= case.analysis.settle_s
    if np.count_nonzero(ok) < MIN_SETTLED_SAMPLES:
        a = case.analysis
        raise CaseError(f"analysis.settle_s = {a.settle_s:g} s leaves {plural(int(np.count_nonzero(ok)), 'recorded sample')} "
                        f"before analysis.duration_s = {a.duration_s:g} s (one every analysis.record_every = "
                        f"{a.record_every} steps of {rec['timestep_s']:.3g} s, {len(rec['t'])} in all): "
                        f"lower settle_s or record_every, or lengthen duration_s")
    return ok


def _omega(case: WindCase) -> float:
    return case.analysis.speed_rpm * 2.0 * math.pi / 60.0


def roller_spin_rad_s(sc: WindScene, rec: dict, k: int) -> np.ndarray:
    """(samples, rollers) spin of row k's rollers about their axes relative to the cage, rad/s."""
    rb, row = sc.rows[k], sc.row_defs[k]
    spin = rec["v"][:, list(rb.elements), 5]
    if row.orientation == "radial":
        spin = spin - rec["v"][:, rb.cage, 5][:, None]
    return spin


def watched_roller(sc: WindScene, rec: dict, k: int) -> int:
    """Index within row k of the roller with the largest raceway load at the first sample."""
    return int(np.argmax(rec["fn"][0, list(sc.rows[k].moving_pairs)]))


def roller_speeds(case: WindCase, sc: WindScene, rec: dict) -> dict:
    """Per row: kinematic spin, mean spin of loaded rollers and of roller 0, their errors, rpm."""
    ok = settled(case, rec)
    out = {}
    for k, (rb, row) in enumerate(zip(sc.rows, sc.row_defs)):
        _, w_s = rolling_speeds(row, _omega(case))
        spin = roller_spin_rad_s(sc, rec, k)[ok]
        fn = rec["fn"][ok][:, list(rb.moving_pairs)]
        loaded = fn > LOADED_SHARE * fn.max(axis=1, keepdims=True)
        j = watched_roller(sc, rec, k)
        one = spin[:, j]
        to_rpm = RPM_PER_RAD_S
        out[row.name] = {
            "kinematic_rpm": abs(w_s) * to_rpm,
            "loaded_mean_rpm": abs(spin[loaded].mean()) * to_rpm,
            "loaded_error": float(spin[loaded].mean() / w_s - 1.0),
            "one_roller": j + 1,  # numbered from 1, as in the plots
            "one_roller_mean_rpm": abs(one.mean()) * to_rpm,
            "one_roller_error": float(one.mean() / w_s - 1.0),
            "one_roller_fluctuation_rpm": float(one.std() * to_rpm),
            "loaded_share_of_samples": float(loaded.mean()),
        }
    return out


def cage_speeds(case: WindCase, sc: WindScene, rec: dict) -> dict:
    """Per row: mean cage speed about z against the no-slip orbit speed, rad/s (r/min in the outputs)."""
    ok = settled(case, rec)
    out = {}
    for rb, row in zip(sc.rows, sc.row_defs):
        w_c, _ = rolling_speeds(row, _omega(case))
        w = rec["v"][ok, rb.cage, 5]
        out[row.name] = {"kinematic_rad_s": w_c, "mean_rad_s": float(w.mean()), "error": float(w.mean() / w_c - 1.0)}
    return out


def applied_load(sc: WindScene, t_s: np.ndarray) -> np.ndarray:
    """(samples, 6) load on the inner ring at times t: the spline of the load history (as the
    builder applies it) plus the ring's weight, N and N·m."""
    from scipy.interpolate import CubicSpline

    f = CubicSpline(sc.times_s, sc.loads, axis=0)(np.clip(t_s, sc.times_s[0], sc.times_s[-1]))
    f[:, 1] -= INNER_RING_MASS_KG * G_M_S2
    return f


def ring_reaction(sc: WindScene, rec: dict) -> np.ndarray:
    """(samples, 6) force and moment about the ring centre of the rollers' normal forces on the
    inner ring, N and N·m (normals: −e_r on the inner raceway, ∓z on the thrust raceways, ±z at the radial
    row's guide ribs)."""
    q, fn = rec["q"], rec["fn"]
    c = q[:, sc.inner, :3]
    total = np.zeros((len(rec["t"]), 6))
    for rb, row in zip(sc.rows, sc.row_defs):
        x = q[:, list(rb.elements), :3]
        e_r = x.copy()
        e_r[..., 2] = 0.0
        e_r /= np.linalg.norm(e_r, axis=-1, keepdims=True)
        z = np.zeros_like(x)
        z[..., 2] = 1.0
        r = row.roller_diameter_m / 2
        if row.orientation == "radial":
            n = -e_r
        else:
            n = -row.load_sign * z
        f = fn[:, list(rb.moving_pairs)][..., None] * n
        p = x + r * n - c[:, None, :]
        total[:, :3] += f.sum(axis=1)
        total[:, 3:] += np.cross(p, f).sum(axis=1)
        if rb.other_pairs and row.orientation == "radial":  # ribs: the + end pushes the ring along +z
            a = z  # (thrust rollers' end guides are on their cage)
            half = 0.5 * row.roller_length_m
            ribs = fn[:, list(rb.other_pairs)].reshape(len(rec["t"]), len(rb.elements), 2)
            for j, sign in enumerate((1.0, -1.0)):
                f = (sign * ribs[..., j])[..., None] * a
                total[:, :3] += f.sum(axis=1)
                total[:, 3:] += np.cross(x + sign * half * a - c[:, None, :], f).sum(axis=1)
    return total


def equilibrium_error(case: WindCase, sc: WindScene, rec: dict) -> dict:
    """Mean residual of the inner ring's equilibrium after settling, relative to the load."""
    ok = settled(case, rec)
    react = ring_reaction(sc, rec)[ok].mean(axis=0)
    load = applied_load(sc, rec["t"][ok]).mean(axis=0)
    load[5] = react[5] = 0.0  # the drive holds the spin
    res = react + load
    return {"reaction": react.tolist(), "applied": load.tolist(),
            "force_error": float(np.linalg.norm(res[:3]) / np.linalg.norm(load[:3])),
            "moment_error": float(np.linalg.norm(res[3:5]) / max(np.linalg.norm(load[3:5]), 1e-9))}


def cage_forces(case: WindCase, sc: WindScene, rec: dict) -> dict:
    """Per row: mean roller–pocket force over contacts in touch, mean over all pockets and time, peak, N."""
    ok = settled(case, rec)
    out = {}
    for rb, row in zip(sc.rows, sc.row_defs):
        f = rec["fn"][ok][:, list(rb.pocket_pairs)]
        touching = f > 0
        out[row.name] = {"mean_in_contact_N": float(f[touching].mean()) if touching.any() else 0.0,
                         "mean_N": float(f.mean()), "peak_N": float(f.max())}
        out[row.name]["mean_raceway_N"] = float(rec["fn"][ok][:, list(rb.moving_pairs)].mean())
    return out
