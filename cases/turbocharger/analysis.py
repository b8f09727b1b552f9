"""What a turbocharger run gives (:mod:`.studies`): orbits of the rotor's axis at the bearings and
wheels (rigid frame plus modes), damper eccentricity and forces, ball loads, where the drive's power
goes (each race's and the pockets' friction, the dampers, the rotor's modal damping:
:func:`mbd_core.multibody.power_losses.power_losses`), cage whirl, the transmitted force's spectrum
with the bearing's defect frequencies."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from cms_reduction.sampling import sample_points
from mbd_core.bearing.kinematics import rolling_kinematics
from mbd_core.multibody.power_losses import PowerLosses, power_losses
from mbd_core.multibody.ring_torque import hann_spectrum

from .case import TurbochargerCase
from .scene import TurboScene, wheel_points_m

__all__ = ["RunFigures", "analyse", "axis_stations_m", "defect_frequencies_Hz"]


def axis_stations_m(case: TurbochargerCase, scene: TurboScene) -> dict[str, float]:
    """Heights (rotor frame, m) of the axis points whose orbits are reported."""
    wheels = wheel_points_m(case)
    return {"turbine wheel": float(wheels["turbine"][2]), "turbine bearing": scene.row_z_m[0],
            "compressor bearing": scene.row_z_m[1], "compressor wheel": float(wheels["compressor"][2])}


def defect_frequencies_Hz(scene: TurboScene) -> dict[str, float]:
    """Shaft rotation, FTF, BPFO, BPFI and 2×BSF of the turbine-side row at its operating point, Hz:
    the cage at the balls' orbit speed ω_m of the row's quasi-static high-speed solution under the
    preload (its contact angles, centrifugal force and gyroscopic moment: 1 % above the nominal
    kinematics at 50 000 rev/min), FTF = ω_m/2π, BPFO = Z·FTF, BPFI = Z·(f_shaft − FTF); the ball spin
    from the rolling kinematics at the mean of its operating inner and outer contact angles."""
    row, quasi = scene.specs[0], scene.quasi[0]
    shaft = scene.speed_rad_s / (2 * math.pi)
    ftf = float(np.mean(quasi.orbit_speed_rad_s)) / (2 * math.pi)
    alpha = 0.5 * float(np.mean(quasi.inner_angle_rad) + np.mean(quasi.outer_angle_rad))
    k = rolling_kinematics(row.ball_diameter_m, row.pitch_diameter_m, alpha, row.n_balls,
                           inner_speed_rad_s=scene.speed_rad_s)
    return {"1x": shaft, "FTF": ftf, "BPFO": row.n_balls * ftf, "BPFI": row.n_balls * (shaft - ftf),
            "2xBSF": 2.0 * k.bsf_Hz}


def _peaks(f: np.ndarray, amp: np.ndarray, n: int) -> list[float]:
    """The ``n`` highest local maxima of a spectrum above its third bin, by frequency."""
    local = [i for i in range(3, amp.size - 1) if amp[i] > amp[i - 1] and amp[i] >= amp[i + 1]]
    return sorted(float(f[i]) for i in sorted(local, key=lambda i: -amp[i])[:n])


@dataclass
class RunFigures:
    """Time series (settled part of the run) and figures of one run."""

    t_s: np.ndarray
    orbits_m: dict            # station → (k, 2) world x, y of the axis point
    eccentricity: np.ndarray  # (k, 2) ε of each damper
    film_N: np.ndarray        # (k, 2, 2) film force x, y on each outer ring
    housing_N: np.ndarray     # (k, 2, 2) film + centring spring force into the housing, x, y
    inner_loads_N: list       # per row (k, Z) inner contact loads
    outer_loads_N: list
    cage_whirl_m: np.ndarray  # (k, 2) cage centre's distance from its outer ring's centre
    spectrum: tuple           # (f Hz, amplitude N, Hann window) of the turbine-side housing force's x component
    frequencies_Hz: dict
    summary: dict
    losses: PowerLosses


def analyse(case: TurbochargerCase, scene: TurboScene, rec: dict) -> RunFigures:
    t = np.asarray(rec["t"])
    keep = t >= t[0] + case.run.settle_s
    losses = power_losses(scene.model, rec, t[0] + case.run.settle_s)
    q, v, eta = rec["q"][keep], rec["v"][keep], rec["eta"][keep]
    t = t[keep]
    R = Rotation.from_quat(q[:, scene.rotor, 3:], scalar_first=True).as_matrix()
    stations = axis_stations_m(case, scene)
    pts = np.array([[0.0, 0.0, z] for z in stations.values()])
    D = sample_points(scene.body, "axis", pts, np.zeros(len(pts))).displacement        # (n, 3, m)
    local = pts[None, :, :] + np.einsum("pcm,km->kpc", D, eta)
    world = q[:, scene.rotor, None, :3] + np.einsum("kij,kpj->kpi", R, local)
    orbits = {name: world[:, i, :2] for i, name in enumerate(stations)}
    ecc, film, housing = np.zeros((t.size, 2)), np.zeros((t.size, 2, 2)), np.zeros((t.size, 2, 2))
    for j, (outer, table) in enumerate(zip(scene.outers, scene.tables)):
        d, u = q[:, outer, :2], v[:, outer, :2]
        e = np.linalg.norm(d, axis=1)
        ecc[:, j] = e / table.clearance_m
        for k in range(t.size):
            er = d[k] / e[k] if e[k] > 0 else np.array([1.0, 0.0])
            et = np.array([-er[1], er[0]])
            fr, ft = table.force_N(min(ecc[k, j], table.max_eccentricity_ratio), u[k] @ er, u[k] @ et)
            film[k, j] = fr * er + ft * et
        housing[:, j] = -film[:, j] + case.damper.centring_stiffness_N_m * d
    inner = [rec["fn"][keep][:, list(rb.moving_pairs)] for rb in scene.rows]
    outer = [rec["fn"][keep][:, list(rb.fixed_pairs)] for rb in scene.rows]
    cage = q[:, scene.rows[0].cage, :2] - q[:, scene.outers[0], :2]
    dt = float(np.median(np.diff(t)))
    f, raw = hann_spectrum(housing[:, 0, 0], dt)
    spectrum = (f, 2.0 * raw / np.hanning(t.size).sum())    # a sine's amplitude, N
    peaks = _peaks(*spectrum, 8)
    freqs = defect_frequencies_Hz(scene)
    radius = {name: float(np.max(np.linalg.norm(o - o.mean(axis=0), axis=1))) for name, o in orbits.items()}
    summary = {
        "speed_rpm": scene.speed_rad_s * 30.0 / math.pi,
        "orbit_radius_um": {name: 1e6 * r for name, r in radius.items()},
        "damper_max_eccentricity": [float(x) for x in ecc.max(axis=0)],
        "housing_force_amplitude_N": [float(np.max(np.linalg.norm(housing[:, j], axis=1))) for j in range(2)],
        "inner_load_min_N": [float(x.min()) for x in inner], "inner_load_max_N": [float(x.max()) for x in inner],
        "inner_unloaded_share": [float(np.mean(x <= 0.0)) for x in inner],
        "cage_whirl_radius_um": 1e6 * float(np.max(np.linalg.norm(cage - cage.mean(axis=0), axis=1))),
        "defect_frequencies_Hz": freqs,
        "spectrum_resolution_Hz": float(f[1]) if f.size > 1 else math.nan,
        "spectrum_peaks_Hz": [float(x) for x in peaks],
        "timestep_s": float(rec.get("timestep_s", math.nan)),
        "power_losses": losses.summary(),
    }
    return RunFigures(t, orbits, ecc, film, housing, inner, outer, cage, spectrum, freqs, summary, losses)
