"""A dynamic run of the slewing ring against the quasi-static solution at the same positions.

At ``analysis.reference_samples`` recorded samples after the start-up window, the load balls'
normal loads on the top race are compared with the quasi-static equilibrium
(:func:`.quasistatic.equilibrium`: rigid or flexible rings, undulation and thermal offsets as in the
run) solved at the run's top rotation and with every ball at its azimuth in the run at that sample
(the phase, the circular mean of the balls' angles from their nominal positions, plus each ball's
angle from it). The balls of the run and of the quasi-static row are the same balls in the same
order. What the quasi-static model leaves out shows as the difference: inertia, damping, friction,
the spacer balls' forces and the balls' weight. ``max_ball_offset_deg`` reports the largest angle of
a ball from the even spacing: where the races change steeply along the circumference (undulation
flanks, the thermal sectors' 5° edges) a ball 1° off its place carries another load, and a
reference at even spacing would count that as an error of the run. ``even_spacing_deviation*``
give that comparison as well (the quasi-static row evenly spaced at the phase), to show how much
of a difference is the balls' spacing.
"""

from __future__ import annotations

import math

import numpy as np

from .case import SlewingCase
from .quasistatic import equilibrium
from .scene import Bodies

__all__ = ["LOADED_SHARE", "compare_with_quasistatic", "sample_position"]

#: the deviation that the comparison reports separately counts balls above this share of the
#: largest quasi-static load (at lighter balls a fixed error is a larger share of their load)
LOADED_SHARE = 0.25


def sample_position(q: np.ndarray, top: int, balls) -> tuple[float, float, np.ndarray]:
    """(top rotation about z, ball phase, (Z,) each ball's angle from phase + 2πj/Z) of one recorded
    pose array (n_b, 7), rad."""
    top_rad = 2.0 * math.atan2(q[top, 6], q[top, 3])
    balls = list(balls)
    psi = np.arctan2(q[balls, 1], q[balls, 0]) - 2.0 * math.pi * np.arange(len(balls)) / len(balls)
    phase = math.atan2(float(np.sin(psi).mean()), float(np.cos(psi).mean()))
    return top_rad, phase, np.angle(np.exp(1j * (psi - phase)))


def _deviations(got: np.ndarray, want: np.ndarray) -> tuple[float, float]:
    """Largest |run − reference| over all balls relative to the largest reference load, and over the
    balls above :data:`LOADED_SHARE` of it relative to their own reference load."""
    largest = float(want.max())
    loaded = want >= LOADED_SHARE * largest
    return float(np.abs(got - want).max() / largest), float((np.abs(got - want)[loaded] / want[loaded]).max())


def compare_with_quasistatic(case: SlewingCase, bodies: Bodies, run: dict, top: int, balls, pairs,
                             settled: np.ndarray, n_samples: int, progress=None) -> dict | None:
    """The ball loads of ``run`` (``pairs``: each ball's top-race contact) at ``n_samples`` samples,
    evenly spaced over the ``settled`` ones, against the quasi-static equilibrium there.

    Returns None for ``n_samples`` = 0, else the samples' times, top rotations (deg), the run's and
    the reference's loads (samples × balls), and the largest deviations relative to the largest
    reference load: over all balls and over the balls above :data:`LOADED_SHARE` of it (relative to
    their own reference load); the same against the evenly spaced row (``even_spacing_*``). A
    sample where a ball has moved half a spacing or more from its place (possible without spacers)
    is compared with the evenly spaced row (counted in ``samples_at_even_spacing``).
    """
    if n_samples <= 0:
        return None
    index = np.flatnonzero(settled)
    picks = index[np.unique(np.linspace(0, index.size - 1, n_samples).round().astype(int))]
    pairs = list(pairs)
    times, angles, got, want, even, offset, at_even = [], [], [], [], [], 0.0, 0
    for k in (progress(picks, "quasi-static references") if progress else picks):
        top_rad, phase, off = sample_position(run["q"][k], top, balls)
        offset = max(offset, float(np.abs(off).max()))
        res = equilibrium(case, bodies, top_rotation_rad=top_rad, ball_phase_rad=phase)
        even.append(res.rows[0].load_N)
        if np.abs(off).max() < math.pi / off.size:
            want.append(equilibrium(case, bodies, top_rotation_rad=top_rad, ball_phase_rad=phase,
                                    initial_displacement=res.displacement, ball_offsets_rad=off).rows[0].load_N)
        else:  # a ball half a spacing off (no spacers): the row has no order to keep; evenly spaced
            want.append(res.rows[0].load_N)
            at_even += 1
        got.append(run["fn"][k, pairs])
        times.append(float(run["t"][k]))
        angles.append(math.degrees(top_rad))
    got, want, even = np.array(got), np.array(want), np.array(even)
    dev, dev_loaded = _deviations(got, want)
    even_dev, even_loaded = _deviations(got, even)
    return {"time_s": times, "top_rotation_deg": angles, "run_load_N": got, "quasistatic_load_N": want,
            "max_deviation": dev, "max_deviation_loaded": dev_loaded, "loaded_share": LOADED_SHARE,
            "max_ball_offset_deg": math.degrees(offset), "even_spacing_deviation": even_dev,
            "even_spacing_deviation_loaded": even_loaded, "samples_at_even_spacing": at_even}


def plot_comparison(cmp: dict, case: SlewingCase):
    """Per compared sample, every ball's load in the run (line) and in the quasi-static solution at
    that position (markers), over the ball number."""
    from ..results import newtons, plt

    fig, ax = plt().subplots(figsize=(9, 4.2), constrained_layout=True)
    n = cmp["run_load_N"].shape[1]
    ball = np.arange(1, n + 1)
    for k, (t, got, want) in enumerate(zip(cmp["time_s"], cmp["run_load_N"], cmp["quasistatic_load_N"])):
        line, = ax.plot(ball, got, lw=1.0, label=f"t = {t:.3g} s, top at {cmp['top_rotation_deg'][k]:.1f}°")
        ax.plot(ball, want, "o", ms=3.5, mfc="none", color=line.get_color())
    ax.plot([], [], "ko", ms=3.5, mfc="none", label="quasi-static at the same position")
    ax.set_xlabel("ball")
    ax.set_ylabel("normal ball load (N)")
    ax.set_xlim(0.5, n + 0.5)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"{case.geometry.variant} ring: run (lines) against quasi-static (circles); largest deviation "
                 f"{newtons(cmp['max_deviation'] * float(cmp['quasistatic_load_N'].max()))} "
                 f"({100 * cmp['max_deviation']:.2f} % of the largest load)", fontsize=9)
    return fig
