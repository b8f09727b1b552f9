"""Compile the explicit-dynamics kernels in a second process while the first one does other work.

On a cold numba cache the first dynamic run of a process spends minutes compiling its kernels
(``@njit(cache=True)``, :mod:`mbd_core.kernels`). A case that meshes and reduces rings first can
have that compilation done meanwhile on another core: :func:`start` launches
``python -m mbd_core.multibody.warmup``, which builds a small model (:func:`small_model`) and runs
every kernel entry point that a dynamic run calls from Python (builder helpers, static
equilibrium, stable step, explicit integration) for a few steps, so that numba writes exactly
those specialisations into its disk cache. The kernels take the model as one namedtuple of flat
arrays whose types do not depend on the model's contents, so the small model's specialisations
are the ones any model needs.

:func:`wait` is called by :meth:`ModelBuilder.finalize`: a model exists only after it, and every
kernel call of a process needs a model, so no kernel is compiled twice and no two processes write
the same cache files at once. A failed or stalled warm-up costs time only: the waiting process
then compiles for itself. Nothing starts when the cache already holds the kernels or when
``FLEXBEARING_KERNEL_WARMUP=0``.
"""

from __future__ import annotations

import logging
import math
import os
import subprocess
import sys
import time

import numpy as np

from foundation.progress import phase

from ..kernels.compile_progress import COMPILING_LABEL

__all__ = ["start", "started", "stop", "wait", "compile_kernels", "small_model", "kernels_cached", "WARMUP_ENV"]

log = logging.getLogger(__name__)

#: environment variable: "0" switches the background compilation off
WARMUP_ENV = "FLEXBEARING_KERNEL_WARMUP"
#: longest wait for the warm-up before compiling in this process, s (compilation takes ~3 min of CPU)
WAIT_LIMIT_S = 1800.0
#: simulated steps of the small model's run
N_STEPS = 4

_process: subprocess.Popen | None = None
_started_s = 0.0


def kernels_cached() -> bool:
    """True when numba's disk cache holds a current compilation of the explicit step loop."""
    from ..kernels.disk_cache import has_cached_overloads
    from ..kernels.explicit import run_explicit

    return has_cached_overloads(run_explicit)


def start() -> bool:
    """Launch the background compilation unless it runs already, is switched off or not needed.

    Returns True when a warm-up process runs after the call.
    """
    global _process, _started_s
    if _process is not None:
        return True
    if os.environ.get(WARMUP_ENV, "1") == "0" or os.environ.get("NUMBA_DISABLE_JIT", "0") == "1":
        return False
    if kernels_cached():
        log.debug("kernel warm-up: the numba cache is current")
        return False
    try:
        _process = subprocess.Popen([sys.executable, "-m", __name__], stdin=subprocess.DEVNULL,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    except OSError as exc:
        log.info("kernel warm-up not started (%s): the kernels compile when first called", exc)
        return False
    _started_s = time.perf_counter()
    log.info("compiling the dynamics kernels in the background (process %d)", _process.pid)
    return True


def wait() -> None:
    """Wait for a running warm-up to finish (no-op when none was started)."""
    global _process
    proc, _process = _process, None
    if proc is None:
        return
    try:
        if proc.poll() is None:
            log.info("waiting for the background compilation of the dynamics kernels")
            with phase(f"{COMPILING_LABEL}, in the background since {time.perf_counter() - _started_s:.0f} s",
                       once=True):  # one-off: out of the time-left estimates around it
                _, err = proc.communicate(timeout=max(WAIT_LIMIT_S - (time.perf_counter() - _started_s), 1.0))
        else:
            _, err = proc.communicate()
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        log.warning("the background compilation of the kernels took over %.0f s and was stopped; "
                    "compiling here", WAIT_LIMIT_S)
        return
    if proc.returncode != 0:
        last = (err or b"").decode(errors="replace").strip().splitlines()[-1:] or ["no message"]
        log.warning("the background compilation of the kernels failed (exit status %d: %s); compiling here",
                    proc.returncode, last[0])
        return
    log.info("dynamics kernels compiled in the background in %.0f s", time.perf_counter() - _started_s)


def started() -> bool:
    """True when this process launched a warm-up that was not stopped since (it may have finished)."""
    return _process is not None


def stop() -> None:
    """Stop a running warm-up (for a process that ends before it needs the kernels)."""
    global _process
    proc, _process = _process, None
    if proc is not None and proc.poll() is None:
        proc.kill()
        proc.communicate()


def small_model():
    """A small model that reaches every kernel entry point of a dynamic run: a modal ring with a
    sampled groove driven inside a fixed rigid ring, two balls between them with friction, touching
    each other and a rigid cage pocket, a load history. Returns (model, state, ball indices)."""
    from cms_reduction.body import ReducedBody
    from cms_reduction.invariants import compute_invariants
    from cms_reduction.sampling import RacewaySample
    import scipy.sparse as sp

    from ..contact.friction import Coulomb
    from .builder import ContactLaw, Driven, Fixed, ModelBuilder

    n_pts, n_modes, r_c, z_c, f_d, r_ball = 24, 2, 0.05, 0.0, 4.2e-3, 4e-3
    th = 2.0 * math.pi * np.arange(n_pts) / n_pts
    nodes = np.column_stack((r_c * np.cos(th), r_c * np.sin(th), np.zeros(n_pts)))
    phi = np.zeros((3 * n_pts, n_modes))
    phi[2::3, 0] = np.cos(2.0 * th)     # out-of-plane ovalisation
    phi[0::3, 1] = np.sin(2.0 * th)
    w = np.full(n_pts, 0.3 / n_pts)
    phi /= np.sqrt(np.diag(phi.T @ (np.repeat(w, 3)[:, None] * phi)))
    ring = ReducedBody("ring", nodes, phi, np.array([2e3, 3e3]), np.full(n_modes, 0.02), False, "hex27",
                       np.zeros((3, n_pts)), np.zeros((27, 0), dtype=np.int64),
                       extras=compute_invariants(sp.diags(w), nodes, phi).to_arrays())
    towards = np.column_stack((-np.cos(th), -np.sin(th), np.zeros(n_pts)))
    sample = RacewaySample("groove", th, nodes + f_d * towards, 1e-3 * np.ones((n_pts, 3, n_modes)),
                           np.zeros((n_pts, 3, n_modes)), True)
    law = ContactLaw(1e10, 1.5, 300.0, 1e-6, "impact", Coulomb(0.1, 0.08, 1e-3, 2e-3))
    mb = ModelBuilder(gravity_m_s2=(0.0, 0.0, -9.81), implicit_friction=True)
    inner = mb.add_modal_body("inner", ring, motion=Driven(10.0))
    g_in = mb.add_groove(inner, r_c, z_c, f_d, raceway=sample, undulation_m=np.full(5, 1e-6))
    clear = f_d - r_ball                    # curvature centre to ball centre at first touch
    r_ball_c = r_c - clear - 1e-6           # ball centres 1 µm into the ring's groove
    mb.add_body("outer", 1.0, (1e-3, 1e-3, 2e-3), motion=Fixed())
    g_out = mb.add_groove("outer", r_ball_c - clear - 1e-6, z_c, f_d)
    cage = mb.add_body("cage", 0.01, (1e-5, 1e-5, 2e-5))
    balls = []
    for k, a_rad in enumerate((0.0, 2.0 * math.asin((r_ball - 1e-7) / r_ball_c))):
        ball = mb.add_body(f"ball{k}", 2e-3, (1.2e-8,) * 3,
                           position_m=(r_ball_c * math.cos(a_rad), r_ball_c * math.sin(a_rad), z_c))
        mb.add_ball_groove(ball, inner, g_in, r_ball, law)
        mb.add_ball_groove(ball, "outer", g_out, r_ball, law)
        pocket = mb.add_pocket(cage, "cylinder", a_rad, r_ball_c, z_c, 1e-5)
        mb.add_element_pocket(ball, cage, pocket, r_ball, law)
        balls.append(ball)
    mb.add_ball_ball(balls[0], balls[1], r_ball, r_ball, law)
    mb.add_load_history(cage, [0.0, 1e-3, 2e-3, 3e-3], np.zeros((4, 6)))
    model, state = mb.finalize()
    return model, state, balls


def compile_kernels() -> None:
    """Call every kernel entry point of a dynamic run once on :func:`small_model` (compiles them)."""
    from .bearings import set_rolling_velocities
    from .explicit import simulate, stable_timestep
    from .statics import static_equilibrium

    model, state, balls = small_model()
    set_rolling_velocities(model, state, balls, model.body_names.index("inner"), model.body_names.index("outer"))
    try:
        static_equilibrium(model, state, max_evaluations=3)
    except Exception as exc:  # only the compilation matters here, not the equilibrium
        log.debug("small model's equilibrium: %s", exc)
    h = stable_timestep(model, state).timestep_s
    simulate(model, state, state.t + N_STEPS * h, timestep_s=h, record_every=1)


if __name__ == "__main__":
    compile_kernels()
