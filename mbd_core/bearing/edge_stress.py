"""Edge stresses of a loaded roller: its raceway pressures along the roller with the slices coupled
through the elastic half-space (:mod:`mbd_core.contact.line_halfspace`), beside the uncoupled
ISO/TS 16281 slices of the load distribution.

The load distribution (ISO/TS 16281 slices, each loaded by its own approach) gives each roller's
slice loads q_k. For a loaded slice its interference is e_k = (q_k / k_s)^(9/10), k_s = c_L/n_s;
the interference plus the profile drop is linear along the roller, e_k + g_k = a + θ·x_k, since the
rings move as rigid bodies over one roller. The least-squares line through the loaded slices gives
the raceways' relative tilt θ in the roller's plane (exact for rigid rings; the best linear fit
where a flexible ring bends under the roller). Each raceway contact then carries the roller load
Q = Σ q_k with the roller profile and half of that tilt (the roller, free to tilt, shares it between
its two contacts — exactly so for two equal contacts), gap_k = g_k − (θ/2)·x_k, solved by
:func:`~mbd_core.contact.line_halfspace.coupled_slices_under_load` with that raceway's curvature.

The ISO pressures beside them are the Hertz line-contact peaks p0 of each slice load on a slice
length L/n_s (as the load distribution's contact sets report them).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..contact.line import LINE_EXPONENT, line_contact
from ..contact.line_halfspace import coupled_slices_under_load
from ..quasistatic.rows import RollerRow

__all__ = ["RollerEdgeStress", "roller_edge_stress", "raceway_tilt_rad"]


@dataclass(frozen=True)
class RollerEdgeStress:
    """Pressure along one roller on one raceway, coupled (half-space) and uncoupled (ISO) slices."""

    row: str
    roller: int
    raceway: str
    x_m: np.ndarray
    pressure_Pa: np.ndarray
    iso_pressure_Pa: np.ndarray
    load_N: float
    tilt_rad: float

    @property
    def peak_pressure_Pa(self) -> float:
        return float(np.max(self.pressure_Pa))

    @property
    def iso_peak_pressure_Pa(self) -> float:
        return float(np.max(self.iso_pressure_Pa))

    @property
    def warning(self) -> str | None:
        """Set when the peak lies on an end slice: there a sharp roller end makes the half-space pressure
        singular (r^(−1/2), Johnson §5.2), so the value is the mean over that slice and grows as the
        slices are refined."""
        k = int(np.argmax(self.pressure_Pa))
        if k not in (0, self.x_m.size - 1):
            return None
        return (f"{self.row}, roller {self.roller + 1}, {self.raceway} raceway: the peak pressure is on an end "
                f"slice, where the edge pressure of a sharp roller end is singular; it is the mean over the end "
                f"slice ({self.x_m.size} slices) and grows with the slice count")

    def to_dict(self) -> dict:
        """Scalars of the summary (SI): the peaks, their ratio, the roller's load and tilt."""
        return {"row": self.row, "roller": self.roller + 1, "raceway": self.raceway, "load_N": self.load_N,
                "raceway_tilt_rad": self.tilt_rad, "peak_pressure_Pa": self.peak_pressure_Pa,
                "iso_peak_pressure_Pa": self.iso_peak_pressure_Pa,
                "peak_over_iso": self.peak_pressure_Pa / self.iso_peak_pressure_Pa,
                "peak_at_m": float(self.x_m[int(np.argmax(self.pressure_Pa))]), "warning": self.warning}


def _slice_centres_m(row: RollerRow) -> np.ndarray:
    L, n = row.roller_length_m, row.n_slices
    return -0.5 * L + (np.arange(n) + 0.5) * L / n


def raceway_tilt_rad(row: RollerRow, slice_load_N: np.ndarray) -> float:
    """Relative tilt θ of the raceways along one roller from its ISO slice loads (module docstring);
    0 when fewer than two slices carry load (a line through one point has no slope)."""
    q = np.asarray(slice_load_N, dtype=float)
    loaded = q > 0.0
    if np.count_nonzero(loaded) < 2:
        return 0.0
    x = _slice_centres_m(row)
    e = (q[loaded] / (row.contact_stiffness() / row.n_slices)) ** (1.0 / LINE_EXPONENT)
    slope, _ = np.polyfit(x[loaded], e + row.drop_m(x[loaded]), 1)
    return float(slope)


def roller_edge_stress(row: RollerRow, slice_load_N: np.ndarray, roller: int) -> list[RollerEdgeStress]:
    """The inner and the outer raceway's pressures along roller ``roller`` of ``row`` from its ISO
    slice loads ``slice_load_N`` (n_s,) N; an empty list for an unloaded roller."""
    q = np.asarray(slice_load_N, dtype=float)
    if q.shape != (row.n_slices,):
        raise ValueError(f"roller row {row.name!r}: slice_load_N must hold {row.n_slices} slice loads, got {q.shape}")
    load = float(q.sum())
    if not load > 0.0:
        return []
    x = _slice_centres_m(row)
    tilt = raceway_tilt_rad(row, q)
    gap = row.drop_m(x) - 0.5 * tilt * x
    width = row.roller_length_m / row.n_slices
    out = []
    for raceway, diameter_m, concave in row.raceway_diameters_m():
        whole = line_contact(row.roller_diameter_m, diameter_m, row.roller_length_m, row.roller_material,
                             row.race_material, concave=concave)
        coupled, _ = coupled_slices_under_load(load, gap, row.roller_length_m, whole.effective_radius_m,
                                               whole.E_eff_Pa)
        per_slice = line_contact(row.roller_diameter_m, diameter_m, width, row.roller_material,
                                 row.race_material, concave=concave)
        out.append(RollerEdgeStress(row.name, roller, raceway, x, coupled.peak_pressure_Pa,
                                    np.asarray(per_slice.max_pressure_Pa(q), dtype=float), load, tilt))
    return out
