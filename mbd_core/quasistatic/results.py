"""Results of the quasi-static load distribution: the ring load, per-row element loads, the equilibrium."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["DOF_NAMES", "LOAD_NAMES", "STIFFNESS_UNITS", "stiffness_to_dict", "RingLoad", "RowLoads", "LoadDistribution", "LoadDistributionError"]

#: Names of the unknowns and of the matching load components.
DOF_NAMES = ("x", "y", "z", "rot_x", "rot_y")
LOAD_NAMES = ("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm")


#: Units of the entries K[i, j] = dF_i/dq_j of a bearing's stiffness matrix.
STIFFNESS_UNITS = tuple(tuple(f"{f}/{d}" for d in ("m", "m", "m", "rad", "rad")) for f in ("N", "N", "N", "N·m", "N·m"))


def stiffness_to_dict(K: np.ndarray) -> dict:
    """A (5, 5) stiffness matrix with the names of its rows (loads), columns (displacements) and units."""
    return {"rows": list(LOAD_NAMES), "columns": list(DOF_NAMES),
            "units": [list(u) for u in STIFFNESS_UNITS], "values": np.asarray(K).tolist()}


class LoadDistributionError(RuntimeError):
    """No equilibrium: the rows cannot carry the load, or the solver did not converge."""


@dataclass(frozen=True)
class RingLoad:
    """External load on the moving ring at its reference point (the bearing centre).

    Forces in N, moments in N·m, in the bearing frame (z along the axis).
    """

    Fx_N: float = 0.0
    Fy_N: float = 0.0
    Fz_N: float = 0.0
    Mx_Nm: float = 0.0
    My_Nm: float = 0.0

    def __post_init__(self) -> None:
        for name in LOAD_NAMES:
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v)):
                raise ValueError(f"load: {name} must be a finite number, got {v!r}")

    def as_array(self) -> np.ndarray:
        return np.array([getattr(self, n) for n in LOAD_NAMES], dtype=float)


@dataclass(frozen=True)
class RowLoads:
    """Loads of one row at equilibrium.

    Attributes (Z = elements in the row)
    ----------
    name, kind : str
        Row name and "ball" or "roller".
    azimuth_rad : (Z,) element azimuth ψ, rad
    load_N : (Z,) normal load of a ball, or total load of a roller, N
    approach_m : (Z,) ball approach δ, or the largest slice approach of a roller, m
    contact_angle_rad : (Z,) loaded contact angle (balls); nominal 0 / π/2 (radial / thrust rollers),
        ±α0 of crossed rollers (the sign the roller's diagonal)
    unloaded : (Z,) True where the element carries no load
    slice_load_N : (Z, n_s) slice loads of rollers, or None for balls

    Four-point rows (:mod:`.rows_four_point`) also give per ball and diagonal (+α, −α), else None:

    contact_load_N : (Z, 2) normal load of each diagonal, N
    contact_angles_rad : (Z, 2) loaded contact angle of each diagonal, rad
    contact_approach_m : (Z, 2) approach of each diagonal, m
    n_contact_points : (Z,) int, 0, 2 or 4 (two per loaded diagonal)

    and ``load_N``, ``approach_m``, ``contact_angle_rad`` are those of each ball's more loaded
    diagonal (of the one with the larger approach where both are unloaded).
    """

    name: str
    kind: str
    azimuth_rad: np.ndarray
    load_N: np.ndarray
    approach_m: np.ndarray
    contact_angle_rad: np.ndarray
    unloaded: np.ndarray
    slice_load_N: np.ndarray | None = None
    contact_load_N: np.ndarray | None = None
    contact_angles_rad: np.ndarray | None = None
    contact_approach_m: np.ndarray | None = None
    n_contact_points: np.ndarray | None = None

    def diagonal(self, j: int) -> RowLoads:
        """The loads of diagonal ``j`` (0: +α, 1: −α) of a four-point row, as a one-contact row."""
        if self.contact_load_N is None:
            raise ValueError(f"row {self.name!r} has one contact per element, no diagonals")
        Q = self.contact_load_N[:, j]
        return RowLoads(self.name, self.kind, self.azimuth_rad, Q, self.contact_approach_m[:, j],
                        self.contact_angles_rad[:, j], Q <= 0.0)

    @property
    def max_load_N(self) -> float:
        return float(self.load_N.max())

    @property
    def n_unloaded(self) -> int:
        return int(self.unloaded.sum())

    def to_dict(self) -> dict:
        d = {
            "name": self.name,
            "kind": self.kind,
            "azimuth_deg": np.degrees(self.azimuth_rad).tolist(),
            "load_N": self.load_N.tolist(),
            "approach_m": self.approach_m.tolist(),
            "contact_angle_deg": np.degrees(self.contact_angle_rad).tolist(),
            "unloaded": self.unloaded.tolist(),
            "max_load_N": self.max_load_N,
            "n_unloaded": self.n_unloaded,
        }
        if self.slice_load_N is not None:
            d["slice_load_N"] = self.slice_load_N.tolist()
        if self.contact_load_N is not None:
            d["contact_load_N"] = self.contact_load_N.tolist()
            d["contact_angles_deg"] = np.degrees(self.contact_angles_rad).tolist()
            d["contact_approach_m"] = self.contact_approach_m.tolist()
            d["n_contact_points"] = self.n_contact_points.tolist()
        return d


@dataclass(frozen=True)
class LoadDistribution:
    """Equilibrium of the moving ring and the loads of every element.

    Attributes
    ----------
    bearing_name : str
    load : (5,) applied (Fx, Fy, Fz, Mx, My), N and N·m
    displacement : (5,) moving-ring (x, y, z, θx, θy), m and rad
    reaction : (5,) resultant of the element forces on the moving ring, N and N·m
    rows : tuple of RowLoads
    iterations : int
    equilibrium_error : float
        |load + reaction| / max(|load|, Σ element loads), moments over the largest pitch radius.
    held_dofs : tuple of str
        Degrees of freedom held at zero (no stiffness and no load).
    warnings : tuple of str
        Where the result lies outside the model's validity (see :mod:`.validity`): contact
        pressure above the ISO 76 static limit, contact ellipse beyond the groove edge, contact
        angle at its limit, ring displacement too large for the small-displacement model.
    stiffness : (5, 5) or None
        Tangent stiffness K = dF/dq of the bearing at the equilibrium (rigid rings): the change of
        the load (Fx, Fy, Fz, Mx, My) that holds the moving ring at q = (x, y, z, θx, θy) per
        change of q; units N/m, N/rad, N·m/m, N·m/rad (:data:`STIFFNESS_UNITS`). See
        :func:`.solver.stiffness_matrix`.
    """

    bearing_name: str
    load: np.ndarray
    displacement: np.ndarray
    reaction: np.ndarray
    rows: tuple[RowLoads, ...]
    iterations: int
    equilibrium_error: float
    held_dofs: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    stiffness: np.ndarray | None = None

    def row(self, name: str) -> RowLoads:
        for r in self.rows:
            if r.name == name:
                return r
        raise KeyError(f"no row named {name!r}; rows: {[r.name for r in self.rows]}")

    def to_dict(self) -> dict:
        return {
            "bearing": self.bearing_name,
            "load": dict(zip(LOAD_NAMES, self.load.tolist())),
            "displacement": dict(zip(("x_m", "y_m", "z_m", "rot_x_rad", "rot_y_rad"), self.displacement.tolist())),
            "reaction": dict(zip(LOAD_NAMES, self.reaction.tolist())),
            "iterations": self.iterations,
            "equilibrium_error": self.equilibrium_error,
            "held_dofs": list(self.held_dofs),
            "warnings": list(self.warnings),
            "rows": [r.to_dict() for r in self.rows],
            **({} if self.stiffness is None else {"stiffness_matrix": stiffness_to_dict(self.stiffness)}),
        }
