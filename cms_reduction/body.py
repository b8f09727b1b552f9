"""The reduced (modal) flexible body: what the multibody core needs of a ring or cage.

A ``ReducedBody`` holds, for m kept modal coordinates η:

* ``shapes`` Φ, (3N, m): mass-normalised mode shapes on the FE nodes (Φᵀ M Φ = I), interleaved
  vector DOFs ``3 * node + component``; rigid-body content removed for a floating body;
* ``frequencies_Hz`` and ``damping_ratio`` per mode: the modal stiffness is diag(ω²) and the
  modal damping diag(2ζω) in the equations of motion;
* ``nodes_m`` (N, 3) and the mesh arrays, to evaluate fields and draw the deformed body;
* optional extras filled by later stages: inertia invariants, raceway samples, stress modes.

The body is a plain data object; building it is :func:`cms_reduction.craig_bampton.reduce_model`.
"""

from __future__ import annotations

import math

from dataclasses import dataclass, field, replace

import numpy as np

__all__ = ["ReducedBody", "with_stiffness_scaled"]


@dataclass(frozen=True, eq=False)
class ReducedBody:
    """Modal flexible body in a floating (or grounded) frame of reference.

    Attributes
    ----------
    name : str
        Label of the body.
    nodes_m : (N, 3) float64, m
        Undeformed FE node positions in the body frame.
    shapes : (3N, m) float64
        Mass-normalised mode shapes, m/√kg per unit η.
    frequencies_Hz : (m,) float64
        Natural frequency of each kept mode (ascending).
    damping_ratio : (m,) float64
        Modal damping ratio ζ of each mode (dimensionless).
    floating : bool
        True when the reference frame carries the rigid motion (rigid content removed from Φ);
        False for a body grounded at its interfaces.
    mesh_kind : {"tet10", "hex27"}
        Element family of the FE model (to rebuild the mesh for pictures and stresses).
    mesh_doflocs : (3, N) float64 and mesh_t : (k, n_elements) int
        Mesh arrays (``skfem.MeshTet2(doflocs, t)`` / ``skfem.MeshHex2``).
    metadata : dict
        Inputs, hash, units and provenance (JSON-serialisable).
    extras : dict
        Named arrays of later stages (invariants, samples, stress modes).
    """

    name: str
    nodes_m: np.ndarray
    shapes: np.ndarray
    frequencies_Hz: np.ndarray
    damping_ratio: np.ndarray
    floating: bool
    mesh_kind: str
    mesh_doflocs: np.ndarray
    mesh_t: np.ndarray
    metadata: dict = field(default_factory=dict)
    extras: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        if np.ndim(self.nodes_m) != 2 or np.shape(self.nodes_m)[1] != 3:
            raise ValueError(f"body {self.name!r}: nodes_m must have shape (N, 3), got {np.shape(self.nodes_m)}")
        if np.ndim(self.shapes) != 2:
            raise ValueError(f"body {self.name!r}: shapes must have shape (3N, m), got {np.shape(self.shapes)}")
        if self.mesh_kind not in ("tet10", "hex27"):
            raise ValueError(f"body {self.name!r}: mesh_kind must be 'tet10' or 'hex27', got {self.mesh_kind!r}")
        n, m = self.shapes.shape
        if n != 3 * len(self.nodes_m):
            raise ValueError(f"body {self.name!r}: shapes have {n} rows, expected 3 × {len(self.nodes_m)} nodes")
        for attr in ("frequencies_Hz", "damping_ratio"):
            if np.shape(getattr(self, attr)) != (m,):
                raise ValueError(f"body {self.name!r}: {attr} must have shape ({m},), got {np.shape(getattr(self, attr))}")
        if not np.all(np.asarray(self.damping_ratio) >= 0.0):
            raise ValueError(f"body {self.name!r}: damping_ratio must be finite and ≥ 0")
        f = np.asarray(self.frequencies_Hz)
        if not (np.all(np.isfinite(f)) and np.all(f >= 0.0)):
            raise ValueError(f"body {self.name!r}: frequencies_Hz must be finite and ≥ 0")

    @property
    def n_modes(self) -> int:
        return self.shapes.shape[1]

    @property
    def omega_rad_s(self) -> np.ndarray:
        return 2.0 * np.pi * np.asarray(self.frequencies_Hz)

    @property
    def modal_stiffness(self) -> np.ndarray:
        """diag(ω²), (m, m), 1/s² (mass-normalised coordinates)."""
        return np.diag(self.omega_rad_s**2)

    @property
    def modal_damping(self) -> np.ndarray:
        """diag(2ζω), (m, m), 1/s."""
        return np.diag(2.0 * np.asarray(self.damping_ratio) * self.omega_rad_s)

    def displacement_m(self, eta: np.ndarray) -> np.ndarray:
        """Nodal displacement (N, 3) m of modal coordinates η (m,)."""
        return (self.shapes @ np.asarray(eta, dtype=float)).reshape(-1, 3)

    def mesh(self):
        """The scikit-fem mesh of the body (for stresses and pictures)."""
        import skfem

        cls = {"tet10": skfem.MeshTet2, "hex27": skfem.MeshHex2}[self.mesh_kind]
        return cls(self.mesh_doflocs, self.mesh_t)


def with_stiffness_scaled(body: ReducedBody, factor: float) -> ReducedBody:
    """The body with every Young's modulus multiplied by ``factor`` (Poisson's ratio unchanged).

    K scales with E while M does not, so the mass-normalised shapes, the inertia invariants and
    the raceway samples stay as they are, ω scales with √factor and the stresses per unit η with
    ``factor`` — exactly what a new reduction of the scaled material would give, without the FE
    work (e.g. the thesis' reduced-stiffness ring, E·(2/6.69)⁴).
    """
    if not (isinstance(factor, (int, float)) and math.isfinite(factor) and factor > 0.0):
        raise ValueError(f"body {body.name!r}: stiffness factor must be a positive number, got {factor!r}")
    extras = dict(body.extras)
    if "stress_modes" in extras:
        extras["stress_modes"] = extras["stress_modes"] * factor
    metadata = {**body.metadata, "stiffness_factor": float(factor) * float(body.metadata.get("stiffness_factor", 1.0))}
    for key in ("residual_compliance_m_per_N", "probe_compliance_m_per_N"):  # a compliance scales with 1/E
        if key in metadata:
            metadata[key] = (np.asarray(metadata[key]) / factor).tolist()
    return replace(body, frequencies_Hz=np.asarray(body.frequencies_Hz) * math.sqrt(factor), extras=extras,
                   metadata=metadata)
