"""FE operators of a solid spinning about its z axis: centrifugal prestress, its geometric (stress)
stiffness, and the mass-weighted circumferential derivative that tells a mode's nodal diameters.

A body spinning at Ω about z carries the centrifugal load Ω² ρ (x, y, 0); its static stress σ₀
adds to the stiffness of small motions about that state the geometric stiffness

    K_σ[3a+i, 3b+i] = ∫ σ₀_jk ∂_j N_a ∂_k N_b dV     (same for each component i)

(K.-J. Bathe, *Finite Element Procedures*, 2nd ed. 2014, §6.3.2, the initial-stress term of the
updated Lagrangian stiffness). Both scale with Ω², so :func:`centrifugal_geometric_stiffness`
returns K_σ for Ω = 1 rad/s. In the spinning frame it balances the spin softening −Ω² P of the
linear equations: without it a rigid rotation of the spinning body about z or a tilt of a disc would
soften, which a body of revolution does not (an error of a few per cent in a disc's gyroscopic
whirl at 1 000 rad/s; see ``tests/test_rotordynamics.py``).

Angular order. Turning a vector field u by α about z gives R_α u(R_−α x); its rate at α = 0 is
𝓛u = ẑ × u − ∂_θ u with ∂_θ = x ∂_y − y ∂_x. On a body of revolution 𝓛 is skew in the mass inner
product and a field with n nodal diameters, u ∝ e^{i n θ} in cylindrical components, has
𝓛u = −i n u. :func:`circumferential_derivative` returns D = ∫ρ N_a ∂_θ N_b dV ⊗ I₃, from which
the mass-weighted 𝓛 of mode shapes follows (the ẑ× part is an inertia invariant).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .assembly import _chunks, _gradients, _to_csr, lame_Pa, scalar_basis
from .linalg import factorize_spd
from .model import FEModel

__all__ = ["centrifugal_load_N", "centrifugal_geometric_stiffness", "circumferential_derivative",
           "statically_determinate_holds"]


def centrifugal_load_N(model: FEModel) -> np.ndarray:
    """Consistent centrifugal load at Ω = 1 rad/s about z, (3N,) N: M (x, y, 0) interleaved."""
    r = model.nodes_m.copy()
    r[:, 2] = 0.0
    return np.asarray(model.M @ r.ravel())


def centrifugal_geometric_stiffness(model: FEModel, held: np.ndarray) -> tuple[sp.csr_matrix, np.ndarray]:
    """Geometric stiffness of the centrifugal prestress at Ω = 1 rad/s about z.

    Parameters
    ----------
    model : FEModel
    held : (h,) int
        DOFs held at zero (the supports); they must leave no rigid motion free.

    Returns
    -------
    K_sigma : (3N, 3N) sparse, N/m per (rad/s)²
    u0_m : (3N,) float64
        The static centrifugal displacement at Ω = 1 rad/s, m.
    """
    n = model.n_dofs
    free = np.setdiff1d(np.arange(n), np.asarray(held, dtype=np.int64))
    f = centrifugal_load_N(model)
    u0 = np.zeros(n)
    u0[free] = factorize_spd(model.K.tocsr()[free][:, free]).solve(f[free])
    basis = scalar_basis(model.mesh, model.intorder[0])
    lam, mu = lame_Pa(model.material)
    dofs = basis.element_dofs.T                          # (ne, nloc) node indices
    U = u0.reshape(-1, 3)
    nloc, nel = basis.Nbfun, basis.nelems
    blocks = np.empty((nel, nloc, nloc))
    for el in _chunks(nel):
        g = _gradients(basis, el)                        # (ne, 3 deriv, nloc, nq)
        grad_u = np.einsum("eac,ejaq->ecjq", U[dofs[el]], g)   # ∂_j u_c
        eps = 0.5 * (grad_u + grad_u.transpose(0, 2, 1, 3))
        tr = np.einsum("eccq->eq", eps)
        sig = 2.0 * mu * eps + lam * tr[:, None, None, :] * np.eye(3)[None, :, :, None]
        blocks[el] = np.einsum("ejkq,ejaq,ekbq,eq->eab", sig, g, g, basis.dx[el])
    Ks = _to_csr(basis, blocks)
    return sp.kron(0.5 * (Ks + Ks.T), sp.identity(3, format="csr"), format="csr"), u0


def circumferential_derivative(model: FEModel, density_kg_m3=None) -> sp.csr_matrix:
    """D[3a+i, 3b+i] = ∫ρ N_a (x ∂_y − y ∂_x) N_b dV, (3N, 3N) sparse, kg (module docstring).

    ``density_kg_m3``: per element (n_elements,), for a model whose mass was assembled with
    several densities; default the model's material."""
    rho = np.broadcast_to(np.asarray(model.material.density_kg_m3 if density_kg_m3 is None else density_kg_m3,
                                     dtype=float), (model.mesh.t.shape[1],))
    basis = scalar_basis(model.mesh, model.intorder[0])
    xq = basis.mapping.F(basis.X)                       # (3, ne, nq) quadrature points, m
    nloc, nel = basis.Nbfun, basis.nelems
    blocks = np.empty((nel, nloc, nloc))
    for el in _chunks(nel):
        g = _gradients(basis, el)                        # (ne, 3, nloc, nq)
        phi = np.stack([np.asarray(basis.basis[a][0])[el] for a in range(nloc)], axis=1)  # (ne, nloc, nq)
        dtheta = xq[0, el][:, None, :] * g[:, 1] - xq[1, el][:, None, :] * g[:, 0]
        blocks[el] = np.einsum("eaq,ebq,eq->eab", phi, dtheta, basis.dx[el] * rho[el][:, None])
    D = _to_csr(basis, blocks)
    return sp.kron(D, sp.identity(3, format="csr"), format="csr")


def statically_determinate_holds(model: FEModel) -> np.ndarray:
    """Six DOFs that hold a free body's rigid motions and nothing more (3-2-1): the reactions of a
    self-equilibrated load there are zero, so they carry a free rotor's centrifugal prestress."""
    x = model.nodes_m
    a = int(np.argmin(np.linalg.norm(x - x.mean(axis=0), axis=1)))
    b = int(np.argmax(np.linalg.norm(x - x[a], axis=1)))
    ab = (x[b] - x[a]) / np.linalg.norm(x[b] - x[a])
    off = np.linalg.norm(np.cross(x - x[a], ab), axis=1)
    c = int(np.argmax(off))
    n = np.cross(ab, x[c] - x[a])
    n /= np.linalg.norm(n)
    # a: all three; b: the two components with the least of ab; c: the one most along the normal n
    b_comps = np.argsort(np.abs(ab))[:2]
    c_comp = int(np.argmax(np.abs(n)))
    return np.array([3 * a, 3 * a + 1, 3 * a + 2, *(3 * b + b_comps), 3 * c + c_comp], dtype=np.int64)
