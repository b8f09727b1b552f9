"""Size of a ring's finite-element model before it is meshed: degrees of freedom and memory.

A mesh too fine for the machine, or more modes than a mesh has degrees of freedom, should be
refused in a second with the estimate, not after minutes of meshing or gigabytes of memory. The
estimate follows the hex27 sweep of :func:`fem_rings.mesh.mesh_ring`: the section is meshed with
about ``A/h²`` quadrilaterals and at least two edges per boundary segment, and revolved in
``max(8, r_out·θ/h)`` element layers. A quadrilateral mesh with ``Q`` cells and ``N_b`` boundary
edges has ``4Q + N_b + 1`` quadratic (9-node) nodes (Euler's formula ``V − E + F = 1`` with
``4Q = 2E − N_b``), and each layer of 27-node hexahedra adds two node layers. Measured against
meshes of the built-in parts at their default and twice their default element size, the estimate
lies between 0.19 and 0.76 of the true count (hex27 and tet10): a lower estimate, so that a mesh
is never refused for a size it does not reach.
"""

from __future__ import annotations

import math
import os
from functools import lru_cache

from fem_rings.profile import Arc, Profile

__all__ = ["BYTES_PER_DOF", "cached_profile", "estimate_dofs", "estimate_memory_bytes", "machine_memory_bytes",
           "check_model_size"]

#: peak memory per degree of freedom of meshing, assembly, factorisation and the eigen solve,
#: measured with ``flexbearing modes slewing-bottom-race-1m --modes 16 --no-cache`` at 60, 40 and
#: 30 mm (23 424, 60 480 and 115 968 DOF; 412, 862 and 1596 MB peak): 12.1–13.2 kB per DOF
#: above the 130 MB the program needs before meshing
BYTES_PER_DOF = 12e3


@lru_cache(maxsize=32)
def cached_profile(make, *args) -> Profile:
    """``make(*args)``, kept: building a section takes milliseconds, and cases are validated often."""
    return make(*args)


@lru_cache(maxsize=64)
def _section_numbers(profile: Profile) -> tuple[float, float, tuple[tuple[float, int], ...]]:
    """Area m², outer radius m and (length m, gmsh curves) of each segment (arcs over 90° are two)."""
    pieces = tuple((s.length_m, 2 if isinstance(s, Arc) and s.sweep_rad > 0.5 * math.pi + 1e-12 else 1)
                   for s in profile.segments)
    return profile.area_m2, profile.bounds_m[1], pieces


def estimate_dofs(profile: Profile, size_m: float, sector_rad: float = 2.0 * math.pi) -> float:
    """Lower estimate of the degrees of freedom of a quadratic mesh of the revolved section.

    Parameters
    ----------
    profile : Profile
        The section in the (r, z) plane, m.
    size_m : float
        Element size, m.
    sector_rad : float
        Revolve angle, rad.

    Returns
    -------
    float
        Three times the node count of the module docstring's estimate (may be ``inf``).
    """
    area_m2, r_out_m, pieces = _section_numbers(profile)
    boundary_edges = sum(n * max(2.0, length / n / size_m) for length, n in pieces)
    section_nodes = 4.0 * area_m2 / size_m / size_m + boundary_edges + 1.0
    layers = max(8.0, r_out_m * sector_rad / size_m)
    return 3.0 * 2.0 * layers * section_nodes


def estimate_memory_bytes(n_dofs: float, n_vectors: int) -> float:
    """Peak memory of a model of ``n_dofs`` with ``n_vectors`` eigenvectors: the measured
    :data:`BYTES_PER_DOF` plus the Lanczos basis of 2·n_vectors + 1 vectors (ARPACK's default)."""
    return n_dofs * (BYTES_PER_DOF + 8.0 * (2 * n_vectors + 1))


def machine_memory_bytes() -> float | None:
    """Total physical memory of this machine, bytes (None where the system does not say)."""
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):
        return None


def check_model_size(profile: Profile, size_m: float, n_modes: int, size_key: str, modes_key: str,
                     size_text: str | None = None, n_rigid: int = 6) -> None:
    """Refuse a model that cannot give ``n_modes`` modes or would not fit in memory.

    Parameters
    ----------
    profile : Profile
        The section to be revolved.
    size_m : float
        Element size, m.
    n_modes : int
        Modes asked for (``n_rigid`` more are solved for a free body).
    size_key, modes_key : str
        How the user named the element size and the mode count (``top.element_size_m``, ``--modes``).
    size_text : str, optional
        The element size as the user gave it; default ``size_m``.

    Raises
    ------
    ValueError
        Starting with the key, giving the estimate.
    """
    n = estimate_dofs(profile, size_m)
    given = size_text or f"{size_m:g}"
    if n_modes + n_rigid >= n:
        raise ValueError(f"{modes_key} = {n_modes} is more than the mesh can give: {size_key} = {given} gives "
                         f"~{n:.0f} DOF for the {profile.name}")
    need = estimate_memory_bytes(n, n_modes + n_rigid)
    have = machine_memory_bytes()
    if have is not None and not need <= have:
        lanczos = need > 2.0 * estimate_memory_bytes(n, 0)  # the eigenvectors, not the mesh, take most
        cause = (f"{modes_key} = {n_modes} with ~{n:.1e} DOF ({size_key} = {given}) would need" if lanczos else
                 f"{size_key} = {given} would give ~{n:.1e} DOF")
        raise ValueError(f"{cause} for the {profile.name} (~{need / 1e9:.3g} GB), more than this machine's "
                         f"{have / 1e9:.3g} GB")
