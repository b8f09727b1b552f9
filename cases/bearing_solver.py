"""The load distribution of a described bearing, with rigid rings or with the rings its file makes modal.

:func:`bearing_solver` is the one place that decides: a description without ``[rings.X]`` tables
(or ``rigid=True``) is solved with rigid rings (:func:`mbd_core.quasistatic.solve_load_distribution`);
otherwise the rings given a table are reduced (or loaded from the cache) and every load case is a
flexible-ring equilibrium (:func:`mbd_core.quasistatic.flexible_solve.solve_flexible_load_distribution`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from foundation.progress import phase
from mbd_core.quasistatic import Bearing, RingLoad, solve_load_distribution
from mbd_core.quasistatic.flexible import build_flexible_model
from mbd_core.quasistatic.flexible_solve import solve_flexible_load_distribution

from .bearing_ring_reduction import flexible_rings

__all__ = ["BearingSolver", "bearing_solver"]


@dataclass(frozen=True)
class BearingSolver:
    """Solves load cases of one bearing: rigid rings (``model`` None) or a flexible-ring model."""

    bearing: Bearing
    model: Any = None
    rings: tuple = ()

    @property
    def flexible(self) -> bool:
        return self.model is not None

    @property
    def label(self) -> str:
        """"rigid rings", or e.g. "modal rings: inner (38 modes), outer (38 modes)"."""
        if not self.flexible:
            return "rigid rings"
        return "modal rings: " + ", ".join(f"{r.name} ({r.body.n_modes} modes)" for r in self.rings)

    def solve(self, load: RingLoad):
        """The load distribution under ``load`` (LoadDistributionError if none)."""
        if self.model is None:
            return solve_load_distribution(self.bearing, load)
        return solve_flexible_load_distribution(self.model, load)

    def summary(self) -> dict:
        """What the rings were: for summary.json."""
        out = {"rings": "modal" if self.flexible else "rigid"}
        if self.flexible:
            out["modal_rings"] = {r.name: {"side": r.ring, "n_modes": r.body.n_modes,
                                           "fe_dofs": int(r.body.shapes.shape[0]),
                                           "element": r.body.metadata.get("element"),
                                           "element_size_m": r.body.metadata.get("element_size_m"),
                                           "lowest_frequency_Hz": float(min(r.body.frequencies_Hz))}
                                  for r in self.rings}
        return out


def bearing_solver(desc, rigid: bool = False) -> BearingSolver:
    """The solver of a :class:`cases.bearing_file.BearingDescription` (its rings reduced here)."""
    if rigid or not desc.rings:
        return BearingSolver(desc.bearing)
    with phase(f"modal rings of {desc.name}"):
        rings = flexible_rings(desc.rings, desc.bearing)
    return BearingSolver(desc.bearing, build_flexible_model(desc.bearing, rings), rings)
