"""Inertia invariants of a modal body in a floating frame of reference (FFRF), from the FE mass matrix.

A material point of the body sits at p = r + R u with u = x̄ + Φ η: x̄ its undeformed position in
the body frame, Φ the mode shapes and η the modal coordinates. The kinetic energy is
a quadratic form whose coefficients are volume integrals of the fields 1, x̄ and Φ; computed once
they are the invariants I1…I9 (A. A. Shabana, *Dynamics of Multibody Systems*, 3rd ed., Cambridge
University Press 2005, ch. 5, "inertia shape integrals"; numbered as the nine inertia invariants of
the Adams/Flex theory of flexible bodies, which are also the terms of O. Wallrapp's standard input
data, "Standardization of flexible body modeling in multibody system codes, Part I", Mech. Struct.
Mach. 22(3), 1994). With ã the skew matrix of a (ã b = a × b) and φ_k column k of Φ:

====  =========================  ============  ===========  =====================================
      integral                   shape         unit         meaning
====  =========================  ============  ===========  =====================================
I1    ∫ρ dV                      ()            kg           mass m
I2    ∫ρ x̄ dV                    (3,)          kg·m         first moment (m × centre of mass)
I3    ∫ρ Φ dV                    (3, m)        √kg·m        translational coupling
I4    ∫ρ x̄̃ Φ dV                  (3, m)        √kg·m²       rotational coupling, I4[a] = R_aᵀ M Φ
I5    ∫ρ φ̃_k Φ dV                (3, m, m)     m²           I5[:, k, l] = ∫ρ φ_k × φ_l dV
I6    ∫ρ Φᵀ Φ dV                 (m, m)        1            modal mass (1 if normalised)
I7    ∫ρ x̄̃ᵀ x̄̃ dV                (3, 3)        kg·m²        inertia tensor about the frame origin
I8    ∫ρ x̄̃ᵀ φ̃_k dV               (3, 3, m)     √kg·m²       first-order change of the inertia
I9    ∫ρ φ̃_kᵀ φ̃_l dV             (3, 3, m, m)  m²           second-order change of the inertia
====  =========================  ============  ===========  =====================================

(m in the shape column is the number of modes; R_a = e_a × x̄ is the rigid rotation field about
axis a; η is in √kg for mass-normalised Φ in m/√kg.) Signs: I8 and I9 are defined with the
transposed skew factor, so that the inertia tensor of the deformed body about the frame origin is

    J(η) = ∫ρ ũᵀ ũ dV = I7 + Σ_k (I8_k + I8_kᵀ) η_k + Σ_kl I9_kl η_k η_l.

Tables that store ∫ρ x̄̃ φ̃_k and ∫ρ φ̃_k φ̃_l instead (the Adams/Flex MNF layout) hold the
negatives of I8 and I9 and write the same J with minus signs. The ordering I5[a, k, l],
I8[i, j, k], I9[i, j, k, l] keeps the Cartesian indices first.

Equations of motion these feed (body-frame Newton–Euler for the reference frame, Lagrange for η,
as in R. Schwertassek & O. Wallrapp, *Dynamik flexibler Mehrkörpersysteme*, Vieweg 1999; Shabana
ch. 5 writes the same with ṙ in the global frame, which puts R in front of the translational row
and Rᵀ after the translational column). Velocities: v = Rᵀ ṙ and ω, both in the body frame, and η̇.
With m the mass, S = I2 + I3 η (first moment of the deformed body), J = J(η),
I4(η) = I4 + Σ_k η_k I5[:, k, :] and G_k = I8_k + Σ_l I9_lk η_l (so ∂J/∂η_k = G_k + G_kᵀ):

    [ m 1    S̃ᵀ       I3    ] [ v̇ ]   [ h_v ]   [ F              ]
    [ S̃      J        I4(η) ] [ ω̇ ] + [ h_ω ] = [ N              ]
    [ I3ᵀ    I4(η)ᵀ   I6    ] [ η̈ ]   [ h_η ]   [ Q − Kη − Dη̇    ]

    h_v = m ω̃ v + ω̃ ω̃ S + 2 ω̃ I3 η̇
    h_ω = S̃ ω̃ v + ω̃ J ω + 2 Σ_k η̇_k G_k ω
    h_η,k = I3[:, k]·(ω̃ v) − ωᵀ G_k ω + 2 Σ_l η̇_l ωᵀ I5[:, l, k]

F and N are the resultant force and moment about the frame origin in body axes, Q the modal
forces, K = diag(ω_k²) and D = diag(2 ζ_k ω_k) (mass-normalised modes). ``tests/test_invariants.py``
checks these expressions against the same integrals evaluated on the FE fields.

Every invariant is a block of one Gram matrix: with the nodal fields F = [1, x̄, Φ] split by
component, C_ij(F, G) = F_iᵀ M_s G_j, where M_s is the scalar mass matrix (M = M_s ⊗ I₃ for the
consistent mass of :func:`fem_rings.assembly.mass_matrix`), so ∫ρ f_i g_j dV = F_iᵀ M_s G_j holds
exactly for FE-interpolated fields. One sparse product and one dense product give them all.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
import scipy.sparse as sp

__all__ = ["Invariants", "compute_invariants", "inertia_tensor_kg_m2", "center_of_mass_m", "PREFIX"]

#: Key prefix of the invariants among a body's extras arrays.
PREFIX = "inv:"

# Levi-Civita symbol ε_abc: (x × y)_a = ε_abc x_b y_c.
_EPS = np.zeros((3, 3, 3))
_EPS[0, 1, 2] = _EPS[1, 2, 0] = _EPS[2, 0, 1] = 1.0
_EPS[0, 2, 1] = _EPS[2, 1, 0] = _EPS[1, 0, 2] = -1.0


@dataclass(frozen=True, eq=False)
class Invariants:
    """Inertia invariants I1…I9 of a modal body (module docstring for definitions and signs).

    Attributes
    ----------
    mass_kg : float
        I1, total mass.
    first_moment_kg_m : (3,) float64, kg·m
        I2 = ∫ρ x̄ dV.
    I3_translational_sqrtkg_m : (3, m) float64, √kg·m
        I3 = ∫ρ Φ dV.
    I4_rotational_sqrtkg_m2 : (3, m) float64, √kg·m²
        I4 = ∫ρ x̄ × Φ dV.
    I5_modal_cross_m2 : (3, m, m) float64, m²
        I5[:, k, l] = ∫ρ φ_k × φ_l dV (antisymmetric in k, l).
    I6_modal_mass : (m, m) float64
        I6 = ∫ρ Φᵀ Φ dV (the identity for mass-normalised modes).
    inertia_kg_m2 : (3, 3) float64, kg·m²
        I7, inertia tensor of the undeformed body about the frame origin.
    I8_inertia_linear_sqrtkg_m2 : (3, 3, m) float64, √kg·m²
        I8[:, :, k] = ∫ρ x̄̃ᵀ φ̃_k dV.
    I9_inertia_quadratic_m2 : (3, 3, m, m) float64, m²
        I9[:, :, k, l] = ∫ρ φ̃_kᵀ φ̃_l dV.
    """

    mass_kg: float
    first_moment_kg_m: np.ndarray
    I3_translational_sqrtkg_m: np.ndarray
    I4_rotational_sqrtkg_m2: np.ndarray
    I5_modal_cross_m2: np.ndarray
    I6_modal_mass: np.ndarray
    inertia_kg_m2: np.ndarray
    I8_inertia_linear_sqrtkg_m2: np.ndarray
    I9_inertia_quadratic_m2: np.ndarray

    def __post_init__(self) -> None:
        i3 = self.I3_translational_sqrtkg_m
        m = np.shape(i3)[-1] if np.ndim(i3) == 2 else -1
        expected = {
            "first_moment_kg_m": (3,), "I3_translational_sqrtkg_m": (3, m), "I4_rotational_sqrtkg_m2": (3, m),
            "I5_modal_cross_m2": (3, m, m), "I6_modal_mass": (m, m), "inertia_kg_m2": (3, 3),
            "I8_inertia_linear_sqrtkg_m2": (3, 3, m), "I9_inertia_quadratic_m2": (3, 3, m, m),
        }
        for name, shape in expected.items():
            value = np.asarray(getattr(self, name), dtype=float)
            if value.shape != shape:
                raise ValueError(f"invariants: {name} must have shape {shape}, got {value.shape}")
            value.flags.writeable = False
            object.__setattr__(self, name, value)
        if not (np.isfinite(self.mass_kg) and self.mass_kg > 0.0):
            raise ValueError(f"invariants: mass_kg must be positive and finite, got {self.mass_kg}")
        object.__setattr__(self, "mass_kg", float(self.mass_kg))

    @property
    def n_modes(self) -> int:
        return self.I6_modal_mass.shape[0]

    # Short aliases for formulas written as in the literature.
    I1 = property(lambda self: self.mass_kg)
    I2 = property(lambda self: self.first_moment_kg_m)
    I3 = property(lambda self: self.I3_translational_sqrtkg_m)
    I4 = property(lambda self: self.I4_rotational_sqrtkg_m2)
    I5 = property(lambda self: self.I5_modal_cross_m2)
    I6 = property(lambda self: self.I6_modal_mass)
    I7 = property(lambda self: self.inertia_kg_m2)
    I8 = property(lambda self: self.I8_inertia_linear_sqrtkg_m2)
    I9 = property(lambda self: self.I9_inertia_quadratic_m2)

    def to_arrays(self) -> dict:
        """Flat dict ``{"inv:<field>": array}`` for a body's extras or an ``.npz`` file."""
        return {PREFIX + f.name: np.array(getattr(self, f.name), dtype=float) for f in fields(self)}

    @classmethod
    def from_arrays(cls, arrays: dict) -> "Invariants":
        """Inverse of :meth:`to_arrays`; keys without the ``inv:`` prefix are ignored.

        Raises
        ------
        KeyError
            Naming the first missing invariant.
        """
        values = {}
        for f in fields(cls):
            key = PREFIX + f.name
            if key not in arrays:
                have = sorted(k for k in arrays if str(k).startswith(PREFIX))
                raise KeyError(f"invariants: array {key!r} missing (have {have})")
            values[f.name] = np.array(arrays[key], dtype=float)
        values["mass_kg"] = float(values["mass_kg"])
        return cls(**values)


def _scalar_mass(M, n_nodes: int) -> sp.csr_matrix:
    """M_s of a consistent mass M = M_s ⊗ I₃ (interleaved DOFs), or M itself when already scalar."""
    if M.shape == (n_nodes, n_nodes):
        return sp.csr_matrix(M)
    if M.shape != (3 * n_nodes, 3 * n_nodes):
        raise ValueError(f"mass matrix has shape {M.shape}; expected ({3 * n_nodes}, {3 * n_nodes}) "
                         f"for {n_nodes} nodes (or the scalar ({n_nodes}, {n_nodes}))")
    M = sp.csr_matrix(M)
    Ms = M[0::3, 0::3].tocsr()
    # One product with a random field detects any coupling between components or unequal blocks.
    w = np.random.default_rng(0).standard_normal((n_nodes, 3))
    full, blocks = M @ w.ravel(), (Ms @ w).ravel()
    if np.linalg.norm(full - blocks) > 1e-12 * max(np.linalg.norm(full), np.finfo(float).tiny):
        raise ValueError("mass matrix is not of the form M_s ⊗ I₃ (interleaved, equal diagonal blocks): "
                         "the invariants need the consistent mass of fem_rings")
    return Ms


def compute_invariants(M, nodes_m: np.ndarray, shapes: np.ndarray) -> Invariants:
    """Invariants I1…I9 from the consistent mass matrix, exact for the FE fields.

    Parameters
    ----------
    M : (3N, 3N) sparse, kg
        Consistent mass, interleaved DOFs ``3 * node + component`` (or the scalar (N, N) M_s).
    nodes_m : (N, 3) float64, m
        Undeformed node positions x̄ in the body frame (the origin of the frame matters for I2,
        I4, I7, I8).
    shapes : (3N, m) float64, m/√kg
        Mode shapes Φ, interleaved.

    Returns
    -------
    Invariants

    Notes
    -----
    The fields G = [1, x̄_x, x̄_y, x̄_z, Φ_x, Φ_y, Φ_z] (N × (4 + 3m)) give the Gram matrix
    C = Gᵀ M_s G, symmetrised; every invariant is a linear combination of its blocks
    (module docstring). Cost: one sparse-times-dense product and one (4 + 3m)² dense product
    of length N.
    """
    x = np.asarray(nodes_m, dtype=float)
    if x.ndim != 2 or x.shape[1] != 3:
        raise ValueError(f"nodes_m must have shape (N, 3), got {x.shape}")
    n = len(x)
    phi = np.asarray(shapes, dtype=float)
    if phi.ndim != 2 or phi.shape[0] != 3 * n:
        raise ValueError(f"shapes must have shape ({3 * n}, m) for {n} nodes, got {phi.shape}")
    m = phi.shape[1]
    Ms = _scalar_mass(M, n)

    G = np.empty((n, 4 + 3 * m))
    G[:, 0] = 1.0
    G[:, 1:4] = x
    # columns 4 + c*m + k: component c of mode k
    G[:, 4:] = phi.reshape(n, 3 * m)
    C = G.T @ (Ms @ G)
    C = 0.5 * (C + C.T)

    Cxx = C[1:4, 1:4]
    A = C[1:4, 4:].reshape(3, 3, m)                              # A[b, c, k] = ∫ρ x̄_b φ_ck
    B = C[4:, 4:].reshape(3, m, 3, m).transpose(0, 2, 1, 3)     # B[b, c, k, l] = ∫ρ φ_bk φ_cl
    I6 = np.einsum("cckl->kl", B)
    eye = np.eye(3)
    return Invariants(
        mass_kg=C[0, 0],
        first_moment_kg_m=C[0, 1:4].copy(),
        I3_translational_sqrtkg_m=C[0, 4:].reshape(3, m).copy(),
        I4_rotational_sqrtkg_m2=np.einsum("abc,bck->ak", _EPS, A),
        I5_modal_cross_m2=np.einsum("abc,bckl->akl", _EPS, B),
        I6_modal_mass=I6,
        # x̃ᵀỹ = (x·y) 1 − y xᵀ
        inertia_kg_m2=np.trace(Cxx) * eye - Cxx,
        I8_inertia_linear_sqrtkg_m2=eye[:, :, None] * np.einsum("cck->k", A) - A.transpose(1, 0, 2),
        I9_inertia_quadratic_m2=eye[:, :, None, None] * I6 - B.transpose(1, 0, 2, 3),
    )


def _eta(inv: Invariants, eta) -> np.ndarray:
    eta = np.asarray(eta, dtype=float)
    if eta.shape != (inv.n_modes,):
        raise ValueError(f"eta must have shape ({inv.n_modes},), got {eta.shape}")
    return eta


def inertia_tensor_kg_m2(inv: Invariants, eta) -> np.ndarray:
    """Inertia tensor of the deformed body about the frame origin, (3, 3) kg·m², body axes.

    J(η) = I7 + Σ_k (I8_k + I8_kᵀ) η_k + Σ_kl I9_kl η_k η_l — exact for the FE fields, since
    the dependence on η is quadratic.

    Parameters
    ----------
    inv : Invariants
    eta : (m,) float64, √kg
        Modal coordinates.
    """
    eta = _eta(inv, eta)
    first = np.tensordot(inv.I8, eta, axes=(2, 0))
    return inv.I7 + first + first.T + np.einsum("ijkl,k,l->ij", inv.I9, eta, eta)


def center_of_mass_m(inv: Invariants, eta) -> np.ndarray:
    """Centre of mass of the deformed body, (3,) m in the body frame: (I2 + I3 η) / m."""
    eta = _eta(inv, eta)
    return (inv.I2 + inv.I3 @ eta) / inv.I1
