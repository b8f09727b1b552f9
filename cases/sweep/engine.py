"""Run the points of a sweep as independent Dask tasks.

Each point is one :func:`run_point` task: an ordinary :func:`cases.run.run_case` into the
point's own folder, which it writes atomically (:func:`cases.outdir.atomic_folder`), so a point
is either complete or absent. A point that fails returns its error instead of raising, and the
sweep goes on.

Where the tasks run (:func:`open_client`):

- ``scheduler="local"``: a :class:`distributed.LocalCluster` on this machine, one worker process
  per core by default, one thread per worker (the points are the parallelism);
- ``scheduler="tcp://host:8786"``: an existing cluster (``dask scheduler`` and ``dask worker``
  on the machines, SSH, Kubernetes, or HPC queues through dask-jobqueue). Its workers need the
  package installed and the results folder (and, to share reductions, ``FLEXBEARING_CACHE``)
  on a file system they all see.

Inside every task BLAS and numba run on one thread (:func:`one_thread`), whatever the cluster's
environment says. The heavy inputs are built before the points start (:func:`prepare_inputs`):
the numba kernels compile once into their disk cache, and the FE meshes and reductions the
points need are built once into the model cache, from which every worker loads them.
"""

from __future__ import annotations

import contextlib
import importlib.util
import logging
import os
import socket
import time
import traceback
from dataclasses import dataclass

from ..config import CaseError, to_mapping

__all__ = ["PointTask", "run_point", "open_client", "compute", "prepare_inputs", "default_workers", "SchedulerError"]

log = logging.getLogger(__name__)


class SchedulerError(CaseError):
    """The Dask scheduler given with ``--scheduler`` cannot be reached."""


@dataclass(frozen=True)
class PointTask:
    """What a worker needs to run one point: the resolved case (validated already), the absolute
    folder, what the case comes from, its content hash and the point's values."""

    name: str
    case: object
    folder: str
    source: str
    case_hash: str
    values: tuple[tuple[str, str], ...]
    resume: bool = False
    pin_threads: bool = True


@contextlib.contextmanager
def one_thread():
    """BLAS (through threadpoolctl) and numba limited to one thread for the block."""
    from threadpoolctl import threadpool_limits

    previous = None
    try:
        import numba

        previous = numba.get_num_threads()
        numba.set_num_threads(1)
    except (ImportError, ValueError, RuntimeError):
        pass
    try:
        with threadpool_limits(limits=1):
            yield
    finally:
        if previous is not None:
            import numba

            numba.set_num_threads(previous)


def _where() -> str:
    return f"{socket.gethostname()}:{os.getpid()}"


def run_point(task: PointTask) -> dict:
    """Run one point (a Dask task); returns its record: ``status`` "computed" or "failed",
    ``error`` (one line), ``wall_time_s``, ``worker`` (host:pid) and ``peak_rss_mb`` of the worker."""
    from ..cli_input import USER_FAILURES
    from ..run import _peak_rss_mb, run_case
    from .variants import as_variant

    t0 = time.perf_counter()
    record = {"name": task.name, "worker": _where()}
    extra = {"sweep_point": {"name": task.name, "values": {k: v for k, v in task.values}, "case_hash": task.case_hash}}
    try:
        with (one_thread() if task.pin_threads else contextlib.nullcontext()), \
                (as_variant() if task.source == "variant" else contextlib.nullcontext()):
            run_case(task.case, task.folder, resume=task.resume, source=task.source, summary_extra=extra)
        record["status"] = "computed"
    except USER_FAILURES as exc:
        record.update(status="failed", error=" ".join(str(exc).split()) or type(exc).__name__)
    except Exception as exc:  # noqa: BLE001 — an internal error: recorded with its traceback's last line
        record.update(status="failed", error=f"internal error: {type(exc).__name__}: {' '.join(str(exc).split())}",
                      traceback=traceback.format_exc(limit=8))
    record.update(wall_time_s=time.perf_counter() - t0, peak_rss_mb=_peak_rss_mb())
    return record


def default_workers() -> int:
    """One worker per core this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


@contextlib.contextmanager
def open_client(scheduler: str, workers: int | None, n_points: int):
    """A connected :class:`distributed.Client` and a description of where it runs.

    ``scheduler``: "local" starts a LocalCluster of ``workers`` processes (default one per core,
    never more than ``n_points``); otherwise the address of a running scheduler.
    """
    from distributed import Client, LocalCluster

    if not logging.getLogger().isEnabledFor(logging.INFO):  # the cluster's own log only with --verbose
        for name in ("distributed", "bokeh", "tornado"):
            logging.getLogger(name).setLevel(logging.ERROR)
    dashboard = importlib.util.find_spec("bokeh") is not None  # the dashboard needs bokeh
    if scheduler == "local":
        n = max(1, min(workers or default_workers(), n_points))
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, silence_logs=logging.ERROR,
                          dashboard_address=":0" if dashboard else None) as cluster, Client(cluster) as client:
            yield client, {"scheduler": "local", "workers": n, "address": cluster.scheduler_address,
                           "dashboard": client.dashboard_link if dashboard else None}
        return
    if workers is not None:
        raise CaseError("--workers sizes the local cluster; an existing cluster (--scheduler ADDRESS) has its own")
    try:
        client = Client(scheduler, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise SchedulerError(f"--scheduler {scheduler}: cannot reach the Dask scheduler ({' '.join(str(exc).split())[:200]})") from None
    with client:
        n = len(client.scheduler_info().get("workers", {}))
        if n == 0:
            log.warning("the scheduler at %s has no workers yet: the points wait for one", scheduler)
        yield client, {"scheduler": scheduler, "workers": n, "address": scheduler,
                       "dashboard": client.dashboard_link if dashboard else None}


def _prepare_key(case) -> str | None:
    """What a case's heavy inputs depend on: the family's ``PREPARE_TABLES`` of the case."""
    from ..run import studies_of

    studies = studies_of(case)
    tables = getattr(studies, "PREPARE_TABLES", None)
    if tables is None:
        return None
    data = to_mapping(case)
    return repr((type(case).__name__, [data.get(t) for t in tables]))


def prepare_inputs(cases) -> dict:
    """Build what the points share before they start: the numba kernels (once, into their disk
    cache) when a point runs dynamics, and each distinct set of reduced bodies (into the model
    cache, where the workers find it). Returns counts for ``sweep.json``."""
    from mbd_core.multibody import warmup

    from ..run import studies_of

    cases = list(cases)
    dynamic = any(studies_of(c).uses_dynamics(c) for c in cases)
    compiling = dynamic and warmup.start()  # compiles in a second process meanwhile
    seen, built = set(), 0
    for case in cases:
        studies = studies_of(case)
        key = _prepare_key(case)
        if key is None or key in seen or not hasattr(studies, "prepare"):
            continue
        seen.add(key)
        built += bool(studies.prepare(case))
    if compiling:
        warmup.wait()
    return {"kernels_compiled": bool(compiling), "model_sets_prepared": built}


def compute(tasks, scheduler: str, workers: int | None, info: dict, echo=None, prepare: bool = True):
    """Run ``tasks`` (:class:`PointTask`) on the cluster; yield each record as its point completes
    (with a progress bar over the points, :func:`foundation.progress.phase`).

    ``info`` receives where they run (scheduler, workers, dashboard) and, with ``prepare``, what
    :func:`prepare_inputs` built once the cluster is reached. A task whose worker died (memory, a
    signal) or was lost yields a ``failed`` record naming that.
    """
    from distributed import as_completed

    from foundation.progress import phase

    tasks = list(tasks)
    with open_client(scheduler, workers, len(tasks)) as (client, where):
        info.update(where)
        if prepare:
            info["prepared"] = prepare_inputs([t.case for t in tasks])
        if where.get("dashboard") and echo is not None:
            echo(f"Dask dashboard: {where['dashboard']}")
        futures = {client.submit(run_point, t, key=f"point-{t.name}-{t.case_hash[:12]}", pure=False): t.name
                   for t in tasks}
        with phase("points", len(tasks)) as bar:
            for fut in as_completed(futures):
                try:
                    rec = fut.result()
                except Exception as exc:  # noqa: BLE001 — the worker died or the task was lost
                    rec = {"name": futures[fut], "status": "failed", "error": "the worker running it failed: "
                           f"{type(exc).__name__}: {' '.join(str(exc).split())[:300]}"}
                bar.advance()
                yield rec
