"""numba kernels of the multibody core: plain functions on float64/int arrays, ``@njit(cache=True, _nrt=False)``.

``_nrt=False`` compiles them without numba's runtime (reference counting and allocation). They
allocate nothing (the model and its work arrays come in preallocated), and the runtime's reference
counting of the model's ~85 arrays at every inlined helper with branches cost more than the physics:
the rigid 32-ball step took 22 µs with it and 8.8 µs without, the same balls on a 20-mode ring 45 µs
and 18.5 µs (benchmarks/bench_modal.py). A kernel that needs a temporary array must take it from the
work arrays (``make_work``); numba refuses to compile an allocation here, so it cannot slip in
unnoticed. Call the kernels from Python or from functions compiled the same way: an ``@njit``
function *with* the runtime that calls them corrupted the heap in a trial (glibc's malloc
consistency check fired), so wrappers in tests and benchmarks take ``_nrt=False`` too.

Only this package imports numba. Each kernel has a plain-numpy twin under ``tests/reference``
and a test comparing the two on seeded random and corner inputs (STYLE.md). Kernels dispatch on
integer codes (``NORMAL_*``, ``FRICTION_*``) instead of taking callables, so whole step loops can
be compiled.

Modules: ``laws`` (normal force, friction), ``ball_groove`` (ball–groove geometry with race
deviations), ``roller_slices`` (slice penetrations of tilted, skewed, crowned rollers),
``element_contacts`` (ball–ball, roller end–rib, element–pocket geometry), ``splines`` (load
histories), ``forces`` (the force stage of a whole model) with its contact families ``ball_pairs``,
``roller_pairs``, ``pocket_pairs`` and their shared parts ``pair_types``, ``body_frames``, ``point_contact``,
``friction_damping``, ``flexible_surface`` (contacts on modal bodies), ``explicit`` (the compiled step loop),
``implicit`` (generalized-α pieces), ``rigid`` (quaternions, symplectic free rotation),
``raceway`` (flexible-raceway interpolation and its transpose, for modal rings), ``modal``
(generalized mass matrix and quadratic-velocity vector of a modal body from its invariants),
``strip_traction`` (traction and spin moment of an elliptical contact from strips along its major axis).
"""

from pathlib import Path

from . import compile_progress, disk_cache
from .laws import (
    FRICTION_COULOMB,
    FRICTION_DREB_CONSTANT,
    FRICTION_DREB_FALLING,
    FRICTION_DREB_LINEAR,
    FRICTION_KRAGELSKII,
    FRICTION_LIMITING_SHEAR,
    NORMAL_HUNT_CROSSLEY,
    NORMAL_IMPACT,
    friction_coefficient,
    friction_force,
    normal_force,
    step,
)
from .ball_groove import ball_groove_contacts
from .rigid import free_rotation_step, quat_rotate

compile_progress.install()      # a kernel about to compile (not load from the cache) shows as a phase
# cached code that embeds kernels of other files is dropped when any kernel source changed (disk_cache)
disk_cache.invalidate_on_source_change(__name__, Path(__file__).parent)

__all__ = [
    "NORMAL_IMPACT", "NORMAL_HUNT_CROSSLEY",
    "FRICTION_COULOMB", "FRICTION_DREB_LINEAR", "FRICTION_DREB_CONSTANT", "FRICTION_DREB_FALLING",
    "FRICTION_KRAGELSKII",
    "FRICTION_LIMITING_SHEAR",
    "step", "normal_force", "friction_coefficient", "friction_force", "ball_groove_contacts",
    "free_rotation_step", "quat_rotate",
]
