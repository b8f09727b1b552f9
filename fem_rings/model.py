"""The finite-element model of one ring or cage: mesh, named sets, K and M — built or loaded from cache.

``build_model(profile, spec, material)`` = ``mesh_ring`` → scalar basis → ``stiffness_matrix`` /
``mass_matrix``. The product is stored on disk keyed by a hash of all inputs
(:mod:`fem_rings.cache`), so a case run that needs the same ring again loads it in a fraction of a
second.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
import skfem

from foundation.materials import ElasticMaterial
from foundation.progress import phase

from . import cache
from .assembly import DEFAULT_INTORDER, mass_matrix, scalar_basis, stiffness_matrix
from .mesh import MESH_VERSION, MeshSpec, RingMesh, facet_nodes, mesh_ring
from .profile import Profile

if TYPE_CHECKING:
    from .cages import CagePockets

__all__ = ["FEModel", "build_model", "vector_dofs"]

log = logging.getLogger(__name__)

_MESH_TYPES = {"tet10": skfem.MeshTet2, "hex27": skfem.MeshHex2}


def vector_dofs(nodes: np.ndarray, components=(0, 1, 2)) -> np.ndarray:
    """Interleaved vector DOFs ``3 * node + component`` of the given nodes, sorted by node."""
    nodes = np.asarray(nodes, dtype=np.int64)
    return (3 * nodes[:, None] + np.asarray(components)[None, :]).ravel()


@dataclass(frozen=True, eq=False)
class FEModel:
    """Linear-elastic solid model of a ring.

    Attributes
    ----------
    ring : RingMesh
        Mesh and named node/facet sets.
    material : ElasticMaterial
    K : (3N, 3N) scipy.sparse.csr_matrix, N/m
        Stiffness, free–free (no supports applied).
    M : (3N, 3N) scipy.sparse.csr_matrix, kg
        Consistent mass.
    intorder : (int, int)
        Quadrature orders used for K and M.
    timings_s : dict
        Wall time of the build stages (mesh, assemble) or of the cache load.
    """

    ring: RingMesh
    material: ElasticMaterial
    K: sp.csr_matrix
    M: sp.csr_matrix
    intorder: tuple
    timings_s: dict = field(default_factory=dict)

    @property
    def mesh(self) -> skfem.Mesh:
        return self.ring.mesh

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]

    @property
    def nodes_m(self) -> np.ndarray:
        """(n_nodes, 3) float64, m."""
        return self.ring.nodes_m

    def basis(self, intorder: int | None = None) -> skfem.CellBasis:
        """Scalar basis on the mesh (default: the stiffness quadrature order)."""
        return scalar_basis(self.mesh, self.intorder[0] if intorder is None else intorder)

    def node_set(self, name: str) -> np.ndarray:
        if name not in self.ring.node_sets:
            raise KeyError(f"model {self.ring.profile.name!r} has no node set {name!r}; "
                           f"it has {sorted(self.ring.node_sets)}")
        return self.ring.node_sets[name]


def build_model(
    profile: Profile,
    spec: MeshSpec,
    material: ElasticMaterial,
    pockets: "CagePockets | None" = None,
    *,
    intorder: tuple | None = None,
    use_cache: bool = True,
) -> FEModel:
    """Mesh and assemble a ring (or load it from the cache).

    Parameters
    ----------
    profile, spec, pockets
        Passed to :func:`fem_rings.mesh.mesh_ring`.
    material : ElasticMaterial
        E_Pa, nu, density_kg_m3.
    intorder : (int, int), optional
        Quadrature orders for (K, M); default per element family.
    use_cache : bool
        Read and write the on-disk cache.
    """
    mesh_type = _MESH_TYPES[spec.element]
    intorder = tuple(intorder or DEFAULT_INTORDER[mesh_type])
    key = cache.input_hash("fe-model", MESH_VERSION, profile, spec, material, pockets, intorder)
    if use_cache:
        stored = cache.load_arrays("fe-model", key)
        if stored is not None:
            t0 = time.perf_counter()
            model = _from_arrays(stored, profile, spec, material, intorder)
            log.info("loaded %s from cache %s", model.ring.summary(), key)
            return FEModel(model.ring, material, model.K, model.M, intorder,
                           {"cache_load": time.perf_counter() - t0})
    t0 = time.perf_counter()
    with phase(f"meshing {profile.name}"):
        ring = mesh_ring(profile, spec, pockets)
    t1 = time.perf_counter()
    with phase(f"assembling K and M ({ring.n_dofs} DOF)"):
        K = stiffness_matrix(scalar_basis(ring.mesh, intorder[0]), material)
        M = mass_matrix(scalar_basis(ring.mesh, intorder[1]), material.density_kg_m3)
    t2 = time.perf_counter()
    model = FEModel(ring, material, K, M, intorder, {"mesh": t1 - t0, "assemble": t2 - t1})
    if use_cache:
        cache.save_arrays("fe-model", key, _to_arrays(model))
    return model


def _to_arrays(model: FEModel) -> dict:
    out = {"doflocs": model.mesh.doflocs, "t": model.mesh.t}
    for name, mat in (("K", model.K), ("M", model.M)):
        out[f"{name}_data"], out[f"{name}_indices"], out[f"{name}_indptr"] = mat.data, mat.indices, mat.indptr
    for name, f in model.ring.facet_sets.items():
        out[f"facets:{name}"] = f
    return out


def _from_arrays(a: dict, profile, spec, material, intorder) -> FEModel:
    mesh = _MESH_TYPES[spec.element](a["doflocs"], a["t"])
    n = 3 * mesh.doflocs.shape[1]
    K, M = (sp.csr_matrix((a[f"{k}_data"], a[f"{k}_indices"], a[f"{k}_indptr"]), shape=(n, n)) for k in "KM")
    facets = {k.split(":", 1)[1]: v for k, v in a.items() if k.startswith("facets:")}
    nodes = {k: facet_nodes(mesh, f) for k, f in facets.items()}
    return FEModel(RingMesh(mesh, profile, spec, facets, nodes), material, K, M, intorder)
