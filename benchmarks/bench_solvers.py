"""Sparse Cholesky backends compared on the 150k-DOF ring: factor, 30 modes, Craig–Bampton.

Ring: the slewing-ring bottom race at Ø2 m (steel E = 200 GPa, ν = 0.3, ρ = 7850 kg/m³), swept
27-node hexahedra of 36 mm in the section and 170 round the circumference: 152k DOF. Every
backend of :mod:`fem_rings.linalg` that imports here — ``cholmod`` (scikit-sparse, supernodal),
``cvxopt`` (optional CHOLMOD wheel, supernodal, OpenBLAS), ``cholespy`` (the default install's
CHOLMOD wheel, simplicial), ``superlu`` (SciPy) — runs in a process of its own
(``FLEXBEARING_SPARSE_SOLVER=<backend>``, one BLAS thread as in the library), so that its memory
is its own:

factor
    ``factorize_spd(K − σM)``, σ = −(2π·1 Hz)², and the rise of peak resident memory it causes.
30 modes
    ``modal_analysis(model, 30)``: ``eigsh`` in shift-invert mode, its factorisation included.
Craig–Bampton
    ``reduce_model``: 16 bolt patches (±30 mm of arc on the bolt face) condensed to 6-DOF master
    nodes that stay free (96 constraint modes, one block solve) and 20 fixed-interface modes. No
    raceway load shapes: their cost is locating the groove points in the mesh, not solving.

Times are CPU seconds of the process (``time.process_time``) and wall seconds; the machine may be
shared, so compare CPU times. Ratios are CPU time over cholespy's. SuperLU needed > 900 s for the
factor of a 150k-DOF hex27 ring with SciPy's default ordering (the library uses a
minimum-degree ordering of A + Aᵀ instead): in the full run its process is stopped after
``--superlu-cap-s`` wall seconds (default 300; the table then shows the CPU seconds it had used,
its start-up included). ``--tet10`` runs all backends a second time on the same ring in 10-node
tetrahedra of 30 mm (about 156k DOF, much less fill). ``--quick`` (CI): hex27 of 0.15 m, 10
modes, a 6-mode reduction with 8 bolt patches of ±0.18 m (a patch must span more than one row of
nodes), one ring.

The models are meshed once into a temporary cache. Run::

    python benchmarks/bench_solvers.py [--quick] [--superlu-cap-s S] [--tet10]

Ends with one line of ``name=value`` figures (``dofs=… factor_cpu_s_cholespy=…
modes_cpu_s_cholespy=… cb_cpu_s_cholespy=… peak_rss_mb_cholespy=…`` per backend and model).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass

STEPS = ("factor", "modes", "cb")
SIGMA_HZ = 1.0


@dataclass(frozen=True)
class Ring:
    """One benchmark model: a label, the mesh and how much to compute on it."""

    label: str
    element: str
    size_m: float
    n_theta: int | None
    n_modes: int
    cb_modes: int
    bolts: int
    bolt_half_width_m: float

    def args(self) -> list[str]:
        return [self.label, self.element, str(self.size_m), str(self.n_theta or 0), str(self.n_modes),
                str(self.cb_modes), str(self.bolts), str(self.bolt_half_width_m)]

    @classmethod
    def from_args(cls, a: list[str]) -> "Ring":
        return cls(a[0], a[1], float(a[2]), int(a[3]) or None, int(a[4]), int(a[5]), int(a[6]), float(a[7]))


FULL = (Ring("hex27", "hex27", 0.036, 170, 30, 20, 16, 0.03), Ring("tet10", "tet10", 0.03, None, 30, 20, 16, 0.03))
QUICK = (Ring("hex27", "hex27", 0.15, None, 10, 6, 8, 0.18),)


# --- child process: one backend (or the model build) on one ring ---------------------------------

def _model(ring: Ring):
    from fem_rings import MeshSpec, build_model
    from fem_rings.sections import slewing_bottom_race
    from foundation.materials import ElasticMaterial

    steel = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
    return build_model(slewing_bottom_race(2.0), MeshSpec(ring.size_m, ring.element, n_theta=ring.n_theta), steel)


def _rss_mb() -> float:
    """Current resident memory of this process, MB (Linux /proc)."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _emit(step: str, **figures) -> None:
    print(json.dumps({"step": step, **figures}), flush=True)


def _timed(fn):
    c0, w0 = time.process_time(), time.perf_counter()
    out = fn()
    return out, round(time.process_time() - c0, 2), round(time.perf_counter() - w0, 2)


def _bolt_interfaces(model, ring: Ring) -> list:
    from cms_reduction.craig_bampton import Interface
    from fem_rings.nodesets import patch_nodes

    return [Interface(f"bolt@{a:g}", patch_nodes(model.ring, "bolt_face", a, ring.bolt_half_width_m), grounded=False)
            for a in (360.0 * (k + 0.5) / ring.bolts for k in range(ring.bolts))]


def child_build(ring: Ring) -> None:
    """Mesh and assemble into the cache; report size and times."""
    (model, cpu, wall) = _timed(lambda: _model(ring))
    _emit("build", dofs=model.n_dofs, nnz_K=model.K.nnz, cpu_s=cpu, wall_s=wall,
          mesh_s=round(model.timings_s.get("mesh", 0.0), 1), assemble_s=round(model.timings_s.get("assemble", 0.0), 1))


def child_backend(ring: Ring) -> None:
    """factor, modes and Craig–Bampton with the backend named by $FLEXBEARING_SPARSE_SOLVER."""
    import math

    from cms_reduction.craig_bampton import reduce_model
    from fem_rings.linalg import factorize_spd
    from fem_rings.solve import modal_analysis, solver_threads

    model = _model(ring)
    sigma = -(2.0 * math.pi * SIGMA_HZ) ** 2
    A = (model.K - sigma * model.M).tocsc()
    rss0 = _rss_mb()
    with solver_threads():
        factor, cpu, wall = _timed(lambda: factorize_spd(A))
    _emit("factor", backend=factor.backend, cpu_s=cpu, wall_s=wall, mem_mb=round(_peak_mb() - rss0))
    del factor, A
    modes, cpu, wall = _timed(lambda: modal_analysis(model, ring.n_modes))
    f = modes.elastic_frequencies_Hz
    _emit("modes", backend=modes.backend, cpu_s=cpu, wall_s=wall, f_first_Hz=float(f[0]), f_last_Hz=float(f[-1]))
    interfaces = _bolt_interfaces(model, ring)
    body, cpu, wall = _timed(lambda: reduce_model(model, ring.cb_modes, interfaces))
    _emit("cb", cpu_s=cpu, wall_s=wall, n_modes=int(body.n_modes), f_first_Hz=float(body.frequencies_Hz[0]),
          peak_mb=round(_peak_mb()))


# --- parent: one child per backend, a table, ratios, the name=value line ------------------------

def _children_cpu_s() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run_child(ring: Ring, what: str, env: dict, cap_s: float | None) -> tuple[dict, bool]:
    """Run a child; return its records by step and whether it was stopped at the cap.

    A stopped child's records get a "capped" entry with the CPU seconds it had used.
    """
    cmd = [sys.executable, __file__, "--child", what, *ring.args()]
    cpu0 = _children_cpu_s()
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=cap_s, check=True).stdout
        capped = False
    except subprocess.TimeoutExpired as err:
        out = err.stdout.decode() if isinstance(err.stdout, bytes) else (err.stdout or "")
        capped = True
    except subprocess.CalledProcessError as err:
        sys.exit(f"{what} on {ring.label} failed:\n{err.stderr[-2000:]}")
    records = {r["step"]: r for r in (json.loads(line) for line in out.splitlines() if line.startswith("{"))}
    if capped:
        done = sum(r.get("cpu_s", 0.0) for r in records.values())
        records["capped"] = {"cpu_s": round(_children_cpu_s() - cpu0 - done, 1), "wall_s": cap_s}
    return records, capped


def _cell(rec: dict | None, stopped: dict | None) -> str:
    """CPU s (wall s) of a step; for the step a cap stopped, the CPU it had used."""
    if rec is None:
        return f"> {stopped['cpu_s']:.0f} (cap {stopped['wall_s']:g})" if stopped else "–"
    return f"{rec['cpu_s']:>8.1f} ({rec['wall_s']:.1f})"


def _ratio(rec: dict | None, ref: dict | None, stopped: dict | None) -> str:
    if ref is None:
        return "–"
    if rec is None:
        return f"> {stopped['cpu_s'] / ref['cpu_s']:.1f}" if stopped else "–"
    return f"{rec['cpu_s'] / ref['cpu_s']:.2f}"


def _stopped_at(rec: dict, step: str) -> dict | None:
    """The "capped" record if the cap stopped the child during ``step`` (the first missing step)."""
    missing = [s for s in STEPS if s not in rec]
    return rec.get("capped") if missing and missing[0] == step else None


def bench_ring(ring: Ring, backends: tuple, cap_s: float | None, env: dict) -> dict:
    """All backends on one ring: printed table; returns the name=value figures."""
    build, _ = _run_child(ring, "build", env, None)
    b = build["build"]
    spacing = f", {ring.n_theta} round" if ring.n_theta else ""
    print(f"\n{ring.label}: bottom race Ø2 m, {ring.element} {ring.size_m * 1e3:g} mm{spacing}: {b['dofs']} DOF, "
          f"{b['nnz_K']} nonzeros in K; mesh {b['mesh_s']} s, assembly {b['assemble_s']} s (built once, cached)")
    results = {}
    for name in backends:
        cap = cap_s if name == "superlu" else None
        results[name] = _run_child(ring, name, {**env, "FLEXBEARING_SPARSE_SOLVER": name}, cap)
    print(f"  {'backend':<9} {'factor CPU s (wall)':>21} {'factor MB':>9} {f'{ring.n_modes} modes CPU s (wall)':>22} "
          f"{'CB CPU s (wall)':>19} {'peak MB':>8} {'f_first Hz':>10}")
    figures = {f"dofs_{ring.label}": b["dofs"]}
    for name, (rec, capped) in results.items():
        f, m, c = (rec.get(s) for s in STEPS)
        cells = [_cell(rec.get(s), _stopped_at(rec, s)) for s in STEPS]
        print(f"  {name:<9} {cells[0]:>21} {f['mem_mb'] if f else '–':>9} {cells[1]:>22} {cells[2]:>19} "
              f"{c['peak_mb'] if c else '–':>8} {m['f_first_Hz'] if m else float('nan'):>10.4f}")
        for step in STEPS:
            if rec.get(step):
                figures[f"{step}_cpu_s_{name}_{ring.label}"] = rec[step]["cpu_s"]
        if f:
            figures[f"factor_mb_{name}_{ring.label}"] = f["mem_mb"]
        if c:
            figures[f"peak_rss_mb_{name}_{ring.label}"] = c["peak_mb"]
    ref = results.get("cholespy", ({}, False))[0]
    if ref:
        print("  CPU time / cholespy's:  " + "; ".join(
            f"{name} " + " ".join(f"{s} {_ratio(rec.get(s), ref.get(s), _stopped_at(rec, s))}" for s in STEPS)
            for name, (rec, _) in results.items() if name != "cholespy"))
    freqs = [rec["modes"]["f_first_Hz"] for rec, _ in results.values() if rec.get("modes")]
    if len(freqs) > 1:
        spread = (max(freqs) - min(freqs)) / min(freqs)
        print(f"  first elastic frequency, spread between backends: {spread:.1e} (relative)")
        figures[f"f_spread_{ring.label}"] = float(f"{spread:.2g}")
    return figures


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="one small ring, 10 modes, small reduction (CI)")
    ap.add_argument("--superlu-cap-s", type=float, default=300.0, help="wall-time cap of each SuperLU process, s")
    ap.add_argument("--tet10", action="store_true", help="also the tet10 ring of the same size (full run only)")
    ap.add_argument("--child", nargs="+", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        what, ring = args.child[0], Ring.from_args(args.child[1:])
        child_build(ring) if what == "build" else child_backend(ring)
        return
    from fem_rings.linalg import available_backends

    backends = available_backends()
    print(f"backends here: {', '.join(backends)} (cholmod: scikit-sparse, supernodal; cvxopt: supernodal CHOLMOD "
          "wheel; cholespy: simplicial CHOLMOD wheel; superlu: SciPy)")
    rings = QUICK if args.quick else (FULL if args.tet10 else FULL[:1])
    cap = None if args.quick else args.superlu_cap_s
    if cap:
        print(f"SuperLU processes are stopped after {cap:g} s wall (> 900 s for a hex27 factor of this size with "
              "SciPy's default ordering); a stopped step shows the CPU seconds it had used")
    figures = {}
    with tempfile.TemporaryDirectory(prefix="bench-solvers-") as cache:
        env = {**os.environ, "FLEXBEARING_CACHE": cache}
        for ring in rings:
            figures.update(bench_ring(ring, backends, cap, env))
    print(" ".join(f"{k}={v}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
