"""Stress recovery: nodal stress tensors and von Mises from a displacement field.

The displacement gradient is evaluated at each element's own nodes (the shape functions'
gradients at the reference node positions), turned into stress with Hooke's law
σ = λ tr(ε) I + 2μ ε, and averaged over the elements sharing a node (nodal averaging; exact for
any field the element reproduces, e.g. uniform or linearly varying stress).

Voigt order of the 6 components: xx, yy, zz, yz, xz, xy (Pa).
"""

from __future__ import annotations

import numpy as np
import skfem

from .assembly import lame_Pa
from .model import FEModel

__all__ = ["nodal_stress_Pa", "von_mises_Pa", "cylindrical_stress_Pa", "VOIGT"]

VOIGT = ("xx", "yy", "zz", "yz", "xz", "xy")


def _nodal_basis(mesh: skfem.Mesh) -> skfem.CellBasis:
    elem = mesh.elem()
    X = np.ascontiguousarray(elem.doflocs.T)  # (3, n_local) reference node positions
    return skfem.CellBasis(mesh, elem, quadrature=(X, np.ones(X.shape[1])))


def nodal_stress_Pa(model: FEModel, displacement_m: np.ndarray) -> np.ndarray:
    """Nodal stress tensors (n_nodes, 6) Pa (Voigt: xx, yy, zz, yz, xz, xy), averaged.

    Parameters
    ----------
    displacement_m : (n_nodes, 3) or (3N,) float64, m
        One displacement field; for several fields (e.g. mode shapes) call once per field.
    """
    u = np.asarray(displacement_m, dtype=float).reshape(-1, 3)
    if u.shape[0] != model.ring.n_nodes:
        raise ValueError(f"displacement_m has {u.shape[0]} nodes, the model {model.ring.n_nodes}")
    basis = _nodal_basis(model.mesh)
    dofs = basis.element_dofs                                         # (nloc, nel)
    grads = np.stack([basis.basis[a][0].grad for a in range(basis.Nbfun)])  # (nloc, 3, nel, nq)
    ue = u[dofs]                                                      # (nloc, nel, 3)
    # H[c, i, e, q] = ∂u_c/∂x_i at local node q of element e
    H = np.einsum("aec,aieq->cieq", ue, grads)
    eps = 0.5 * (H + H.transpose(1, 0, 2, 3))
    lam, mu = lame_Pa(model.material)
    tr = eps[0, 0] + eps[1, 1] + eps[2, 2]
    sig = 2.0 * mu * eps
    for i in range(3):
        sig[i, i] += lam * tr
    voigt = np.stack([sig[0, 0], sig[1, 1], sig[2, 2], sig[1, 2], sig[0, 2], sig[0, 1]], axis=-1)  # (nel, nq, 6)
    n = model.ring.n_nodes
    acc = np.zeros((n, 6))
    cnt = np.zeros(n)
    node_of = dofs.T                                                  # (nel, nq) — q-th point is local node q
    np.add.at(acc, node_of.ravel(), voigt.reshape(-1, 6))
    np.add.at(cnt, node_of.ravel(), 1.0)
    return acc / cnt[:, None]


def von_mises_Pa(stress_Pa: np.ndarray) -> np.ndarray:
    """Von Mises equivalent stress (n,) Pa of Voigt stress tensors (n, 6)."""
    s = np.asarray(stress_Pa)
    xx, yy, zz, yz, xz, xy = (s[..., k] for k in range(6))
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3.0 * (xy**2 + yz**2 + xz**2))


def cylindrical_stress_Pa(nodes_m: np.ndarray, stress_Pa: np.ndarray) -> dict:
    """Radial, hoop and axial normal stresses and the r–z shear, each (n,) Pa, at the nodes."""
    x, y = nodes_m[:, 0], nodes_m[:, 1]
    th = np.arctan2(y, x)
    c, s = np.cos(th), np.sin(th)
    sxx, syy, szz, syz, sxz, sxy = (stress_Pa[:, k] for k in range(6))
    return {
        "rr": c * c * sxx + s * s * syy + 2 * c * s * sxy,
        "tt": s * s * sxx + c * c * syy - 2 * c * s * sxy,
        "zz": szz,
        "rz": c * sxz + s * syz,
    }
