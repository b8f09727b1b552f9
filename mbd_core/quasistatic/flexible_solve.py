"""Solution of the flexible-ring load distribution (model: :mod:`.flexible`) and its results.

The unknowns, residual and Jacobian are those of :class:`.flexible.FlexibleBearingModel`; this module
runs the two Newton stages (rigid rings with the offsets, then rings and modal coordinates) and
collects the element loads, modal coordinates and raceway deflections.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .flexible import FlexibleBearingModel
from .newton import safe_norm
from .results import LoadDistributionError
from .solver import (
    DOF_NAMES,
    LoadDistribution,
    RingLoad,
    _Problem,
    ball_forces,
    damped_newton,
    no_equilibrium_error,
    row_loads,
    slice_forces,
    supported_dofs,
)
from .validity import approach_limit_error, load_distribution_warnings

#: Load steps tried, one count after the other, when Newton from the rigid-ring solution fails.
CONTINUATION_STEPS = (4, 16)

__all__ = ["RacewayDeflection", "FlexibleLoadDistribution", "solve_flexible_load_distribution", "condensed_stiffness"]


@dataclass(frozen=True)
class RacewayDeflection:
    """Elastic deflection of a flexible ring's raceway at the elements of one row (Z balls or rollers;
    a four-point row has 2Z entries, one per ball and diagonal, interleaved ball by ball).

    Attributes
    ----------
    ring, row : str
    azimuth_rad : (Z,) element azimuths, rad
    points_m : (Z, 3) undeformed raceway points at the elements (interpolated samples), m
    displacement_m : (Z, 3) raceway displacement D_i η, m (without the rigid motion q of a moving ring)
    rotation_rad : (Z, 3) raceway small rotation Ω_i η, rad
    groove_centre_displacement_m : (Z, 3) T_i η, the groove curvature centre's displacement, m
        (ball rows; None for roller rows)
    """

    ring: str
    row: str
    azimuth_rad: np.ndarray
    points_m: np.ndarray
    displacement_m: np.ndarray
    rotation_rad: np.ndarray
    groove_centre_displacement_m: np.ndarray | None

    def to_dict(self) -> dict:
        return {"ring": self.ring, "row": self.row, "azimuth_deg": np.degrees(self.azimuth_rad).tolist(),
                "displacement_m": self.displacement_m.tolist(), "rotation_rad": self.rotation_rad.tolist()}


@dataclass(frozen=True)
class FlexibleLoadDistribution(LoadDistribution):
    """:class:`LoadDistribution` with the modal coordinates of the flexible rings.

    Extra attributes
    ----------------
    ring_names : tuple of str
    modal_coordinates : tuple of (m_k,) arrays, √kg, in the order of ``ring_names``
    deflections : tuple of RacewayDeflection, one per (ring, row)

    ``equilibrium_error`` covers the modal equations too (scaled residual of all unknowns);
    ``stiffness`` is the bearing's with the rings bending (:func:`condensed_stiffness`).
    """

    ring_names: tuple[str, ...] = ()
    modal_coordinates: tuple[np.ndarray, ...] = ()
    deflections: tuple[RacewayDeflection, ...] = ()

    def modal(self, ring: str) -> np.ndarray:
        """η of a flexible ring, (m,) √kg."""
        if ring not in self.ring_names:
            raise KeyError(f"no flexible ring named {ring!r}; rings: {list(self.ring_names)}")
        return self.modal_coordinates[self.ring_names.index(ring)]

    def raceway_deflection(self, ring: str, row: str) -> RacewayDeflection:
        """Deflection of ``ring``'s raceway at the elements of ``row``."""
        for d in self.deflections:
            if d.ring == ring and d.row == row:
                return d
        raise KeyError(f"no raceway of flexible ring {ring!r} at row {row!r}; "
                       f"have {[(d.ring, d.row) for d in self.deflections]}")

    def to_dict(self) -> dict:
        d = super().to_dict()
        d["modal_coordinates"] = {n: e.tolist() for n, e in zip(self.ring_names, self.modal_coordinates)}
        d["raceway_deflections"] = [x.to_dict() for x in self.deflections]
        return d


def solve_flexible_load_distribution(
    model: FlexibleBearingModel,
    load: RingLoad,
    *,
    tolerance: float = 1e-10,
    max_iterations: int = 100,
    initial_displacement: np.ndarray | None = None,
    load_steps: int | None = None,
) -> FlexibleLoadDistribution:
    """Equilibrium of the moving ring and of the flexible rings' modes under ``load``.

    Parameters
    ----------
    model : FlexibleBearingModel
        From :func:`build_flexible_model`.
    load : RingLoad
        External load on the moving ring, N and N·m.
    tolerance : float
        Convergence when |scaled residual| ≤ tolerance·max(|load|, Σ element loads) (moments
        over the largest pitch radius, modal forces over their mode's largest raceway displacement).
    max_iterations : int
        Newton iterations per stage before giving up.
    initial_displacement : (5,) array, optional
        Starting q (m, rad); default from a linear spring estimate.
    load_steps : int, optional
        Apply the load in this many equal steps, each solved from the last (stage 2). Default: at
        once, and where that Newton fails (rings deflecting far beyond the rigid-ring solution) in
        :data:`CONTINUATION_STEPS` steps.

    Raises
    ------
    LoadDistributionError
        Load on a degree of freedom without stiffness, or no converged equilibrium.
    """
    if not isinstance(model, FlexibleBearingModel):
        raise TypeError(f"model must be a FlexibleBearingModel (build_flexible_model), got {type(model).__name__}")
    if not isinstance(load, RingLoad):
        raise TypeError(f"load must be a RingLoad, got {type(load).__name__}")
    if load_steps is not None and (isinstance(load_steps, bool) or not isinstance(load_steps, int) or load_steps < 1):
        raise ValueError(f"load_steps must be an integer ≥ 1, got {load_steps!r}")
    bearing = model.bearing
    S = model.dof_scale
    f_ext = load.as_array()
    supported, K_lin = supported_dofs(_Problem(bearing), bearing.name, f_ext, S[:5])
    free_q = np.flatnonzero(supported)
    held = tuple(DOF_NAMES[i] for i in np.flatnonzero(~supported))
    N = model.n_unknowns
    fallback = np.zeros((N, N))
    fallback[:5, :5] = K_lin
    fallback[5:, 5:] = np.diag(model.stiffness_diag[5:] / S[5:] ** 2)

    y = np.zeros(N)
    if initial_displacement is None:
        y[free_q] = np.linalg.solve(K_lin[np.ix_(free_q, free_q)], f_ext[free_q] / S[free_q])
    else:
        y[:5] = np.asarray(initial_displacement, dtype=float).reshape(5) * S[:5]
        y[:5][~supported] = 0.0

    def residual_at(case: RingLoad):
        def residual(y_scaled, jac=True):
            R, J = model.residual(y_scaled / S, case, jac)
            return R / S, (None if J is None else J / S[:, None] / S[None, :])
        return residual

    residual = residual_at(load)

    # relative to the load at every load (no absolute floor), overflow-safe
    scale = safe_norm(f_ext / S[:5])
    if not math.isfinite(scale):
        raise LoadDistributionError(f"load on bearing {bearing.name!r} is not finite: {f_ext.tolist()}")
    # stage 1: rigid rings (η = 0) with the offsets; stage 2: all unknowns from there
    y, _, _, it1 = damped_newton(residual, y, free_q, tolerance * scale, max_iterations, fallback)
    Qb = ball_forces(model.balls, model.ball_dofs, y / S, jacobian=False)[0]
    Qs = slice_forces(model.slices, model.slice_dofs, y / S, jacobian=False)[0]
    element_sum = float(Qb.sum() + Qs.sum())
    scale = max(scale, element_sum if math.isfinite(element_sum) else 0.0)
    free = np.concatenate((free_q, np.arange(5, N)))
    y1, it2, norm = y, 0, math.inf
    if load_steps is None:
        y, R, norm, it2 = damped_newton(residual, y1, free, tolerance * scale, max_iterations, fallback)
    for n_steps in (CONTINUATION_STEPS if load_steps is None else (int(load_steps),)):
        if norm <= tolerance * scale:
            break
        # Newton from the rigid-ring solution can fail where the rings deflect far beyond it (large
        # loads on soft rings): the load applied in equal steps, each solved from the last
        y = np.zeros_like(y1)
        y[:5] = y1[:5] / n_steps
        for k in range(1, n_steps + 1):
            part = RingLoad(*(f_ext * (k / n_steps)))
            y, R, norm, it = damped_newton(residual_at(part), y, free, tolerance * scale * k / n_steps,
                                           max_iterations, fallback)
            it2 += it
            if not norm <= tolerance * scale * k / n_steps:
                break
    if not norm <= tolerance * scale:
        raise no_equilibrium_error(bearing.name, it1 + it2, R[:5], S[:5], f_ext)
    return _collect(model, load, y / S, it1 + it2, norm / scale if scale > 0.0 else 0.0, held)


def _collect(model: FlexibleBearingModel, load: RingLoad, x: np.ndarray, iterations: int, error: float,
             held: tuple[str, ...]) -> FlexibleLoadDistribution:
    Qb, db, s, rb, _ = ball_forces(model.balls, model.ball_dofs, x, jacobian=False)
    Qs, ds, rs, _ = slice_forces(model.slices, model.slice_dofs, x, jacobian=False)
    rows = row_loads(model.bearing, model.balls, model.slices, (Qb, db, s), (Qs, ds))
    etas = tuple(x[cols].copy() for cols in model.ring_dofs)
    names = tuple(r.name for r in model.rings)
    deflections = []
    for c in model.couplings:
        eta = etas[names.index(c.ring)]
        deflections.append(RacewayDeflection(c.ring, c.row, c.azimuth_rad, c.points_m, c.D @ eta, c.Omega @ eta,
                                             None if c.T is None else c.T @ eta))
    err = approach_limit_error(model.bearing, rows)
    if err:
        raise LoadDistributionError(f"no converged equilibrium within the model for bearing {model.bearing.name!r}: {err}")
    warnings = load_distribution_warnings(model.bearing, rows, x[:5])
    return FlexibleLoadDistribution(model.bearing.name, load.as_array(), x[:5].copy(), (rb + rs)[:5], rows,
                                    iterations, float(error), held, warnings, condensed_stiffness(model, x, load),
                                    ring_names=names, modal_coordinates=etas, deflections=tuple(deflections))


def condensed_stiffness(model: FlexibleBearingModel, x: np.ndarray, load: RingLoad) -> np.ndarray:
    """Tangent stiffness K = dF/dq (5, 5) of the bearing with its rings free to bend, at x.

    With S = −dR/dx (the element stiffness plus the rings' modal stiffness, symmetric) split into
    the ring displacement q and the modal coordinates η, the load F that holds the moving ring at q
    with the rings in equilibrium (R_η = 0) changes by dF = (S_qq − S_qη S_ηη⁻¹ S_ηq)·dq: the static
    condensation of η (Guyan, AIAA J. 3(2), 380, 1965). Units as :func:`.solver.stiffness_matrix`.
    """
    S = -model.residual(x, load, jacobian=True)[1]
    if S.shape[0] == 5:
        return S
    return S[:5, :5] - S[:5, 5:] @ np.linalg.solve(S[5:, 5:], S[5:, :5])
