"""Load shapes that augment a ring's modal basis: static responses to raceway loads (harmonic line
loads, forces at the rolling elements' places) and to the centrifugal body force.

Each kind gives its consistent nodal load vectors (``load_vectors(model, full_circle)``);
:func:`cms_reduction.craig_bampton.reduce_model` solves for their static shapes (with inertia relief
on a floating body) and adds them to the basis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_rings.model import FEModel
from fem_rings.nodesets import RacewayCurve
from fem_rings.probe import vector_probe_matrix
from fem_rings.solve import line_load_operator

__all__ = ["Augmentation", "ElementAugmentation", "CentrifugalAugmentation"]


@dataclass(frozen=True)
class Augmentation:
    """Static load shapes of unit raceway line loads q(θ) = cos nθ, sin nθ (N/m), n = 0…n_max.

    Parameters
    ----------
    curve : RacewayCurve
        Raceway points (from :func:`fem_rings.nodesets.raceway_curve`).
    directions : tuple of str
        Load directions in the section: ``"normal"`` (into the raceway surface, i.e. along the
        contact line for a groove at its contact point), ``"axial"``, ``"radial"``.
    n_max : int
        Highest circumferential harmonic.
    patch : tuple of (RacewayCurve, float)
        Empty: each load acts on ``curve`` itself. Else (from
        :func:`fem_rings.nodesets.raceway_patch`) each load is spread over the patch circles, circle
        k carrying w_k of its force per radian (per unit length: w_k q r₀ / r_k, r₀ the radius of
        ``curve``), in the direction it has on ``curve``: the transpose of the patch-averaged
        sampling (:func:`cms_reduction.sampling.sample_raceway`), so the generalized force of a
        load shape stays work-consistent with the sampled mode shapes.
    """

    curve: RacewayCurve
    directions: tuple = ("normal",)
    n_max: int = 8
    patch: tuple = ()

    def __post_init__(self) -> None:
        bad = set(self.directions) - {"normal", "axial", "radial"}
        if bad:
            raise ValueError(f"augmentation directions must be 'normal', 'axial' or 'radial', got {sorted(bad)}")
        if int(self.n_max) < 0:
            raise ValueError(f"augmentation n_max must be ≥ 0, got {self.n_max}")

    def load_vectors(self, model: FEModel, full_circle: bool) -> np.ndarray:
        """Consistent nodal force vectors (3N, k) of all harmonics and directions."""
        c = self.curve
        th = c.theta_rad
        radial = np.column_stack((np.cos(th), np.sin(th), np.zeros_like(th)))
        axial = np.tile([0.0, 0.0, 1.0], (len(th), 1))
        dirs = {"radial": radial, "axial": axial,
                "normal": -(c.normal_rz[0] * radial + c.normal_rz[1] * axial)}
        load = (line_load_operator(model, c.points_m, closed=full_circle) if not self.patch
                else _patch_load_operator(model, c, self.patch, full_circle))
        out = []
        for name in self.directions:
            d = dirs[name]
            for n in range(int(self.n_max) + 1):
                for trig in ((np.cos,) if n == 0 else (np.cos, np.sin)):
                    out.append(load(trig(n * th)[:, None] * d))
        return np.column_stack(out)


def _patch_load_operator(model: FEModel, curve: RacewayCurve, patch, full_circle: bool):
    """q ↦ Σ_k (w_k r₀ / r_k) F_k(q): a line load on ``curve`` spread over the patch circles with
    the same force per radian times their weights (F_k the consistent loads on circle k)."""
    r0 = float(curve.rz_m[0])
    parts = [(wk * r0 / float(ck.rz_m[0]), line_load_operator(model, ck.points_m, closed=full_circle))
             for ck, wk in patch]

    def apply(force_per_length_N_m) -> np.ndarray:
        return sum(a * op(force_per_length_N_m) for a, op in parts)

    return apply


#: Gauss points along the circumference of a ball-position load shape's patch
N_ARC = 4


@dataclass(frozen=True)
class ElementAugmentation:
    """Static load shapes of unit radial and axial forces at given angles of a raceway — one per
    rolling element of a scene — each spread over the raceway patch across the section
    (:func:`fem_rings.nodesets.raceway_patch`) and over ±``half_arc_m`` along the circumference.

    With these shapes in the basis, the static response of the ring to the element forces at those
    angles lies in the reduced space, so a quasi-static equilibrium with the elements there is the
    finite-element solution of the ring under those (patch-spread) forces: the Galerkin (Ritz)
    solution is exact when the exact one lies in the trial space. Circumferential harmonics reach
    the same response only slowly, since each element's load is local.

    Parameters
    ----------
    curve : RacewayCurve
    angles_rad : tuple of float
        Element angles in the ring's own frame, rad.
    patch : tuple of (RacewayCurve, float)
        The patch circles and weights (must not be empty: a point force has an unbounded response).
    half_arc_m : float
        Half-length of the patch along the circumference at the radius of ``curve``, m.
    directions : tuple of str
        ``"radial"`` and/or ``"axial"``.
    """

    curve: RacewayCurve
    angles_rad: tuple
    patch: tuple
    half_arc_m: float
    directions: tuple = ("radial", "axial")

    def __post_init__(self) -> None:
        if not self.patch or not self.half_arc_m > 0.0:
            raise ValueError("element load shapes need a raceway patch (spread_m > 0): a force at a point "
                             "of a solid has an unbounded displacement there")
        bad = set(self.directions) - {"axial", "radial"}
        if bad:
            raise ValueError(f"element load shape directions must be 'axial' or 'radial', got {sorted(bad)}")

    def load_vectors(self, model: FEModel, full_circle: bool) -> np.ndarray:
        x, w = np.polynomial.legendre.leggauss(N_ARC)
        r0 = float(self.curve.rz_m[0])
        rz = np.array([c.rz_m for c, _ in self.patch])                    # (k, 2)
        wk = np.array([wt for _, wt in self.patch])                       # (k,)
        th = (np.asarray(self.angles_rad, float)[:, None] + self.half_arc_m * x[None, :] / r0)   # (Z, g)
        weight = (0.5 * w[None, None, :] * wk[None, :, None]) * np.ones((th.shape[0], 1, 1))     # (Z, k, g)
        T = np.broadcast_to(th[:, None, :], weight.shape)
        R = np.broadcast_to(rz[None, :, 0, None], weight.shape)
        Zc = np.broadcast_to(rz[None, :, 1, None], weight.shape)
        pts = np.stack((R * np.cos(T), R * np.sin(T), Zc), axis=-1).reshape(-1, 3)
        P = vector_probe_matrix(model.basis(2), pts).T.tocsr()            # (3N, 3 n_points)
        per_element = weight[0].size
        cols = []
        for i in range(th.shape[0]):
            sl = slice(i * per_element, (i + 1) * per_element)
            t = T.reshape(-1)[sl]
            wt = weight.reshape(-1)[sl]
            for name in self.directions:
                f = np.zeros((len(pts), 3))
                f[sl] = wt[:, None] * (np.column_stack((np.cos(t), np.sin(t), np.zeros_like(t))) if name == "radial"
                                       else np.array([0.0, 0.0, 1.0]))
                cols.append(P @ f.ravel())
        return np.column_stack(cols)


@dataclass(frozen=True)
class CentrifugalAugmentation:
    """Static load shape of the centrifugal body force of a spin about the body's z axis.

    The load per unit Ω² is ρ (x, y, 0) per unit volume; its consistent nodal vector is M (x, y, 0)
    (M the FE mass matrix, nodal positions interleaved). Its static response is the stretch of a ring
    spinning about its axis, which raceway load shapes reproduce only roughly.
    """

    def load_vectors(self, model: FEModel, full_circle: bool) -> np.ndarray:
        field = model.nodes_m.copy()
        field[:, 2] = 0.0
        return np.asarray(model.M @ field.reshape(-1))[:, None]
