"""Quasi-static load distribution of bearings with rigid rings (Newton, analytic Jacobian)."""

from .rows import BallRow, Bearing, RollerRow
from .solver import LoadDistribution, LoadDistributionError, RingLoad, solve_load_distribution

__all__ = [
    "BallRow",
    "RollerRow",
    "Bearing",
    "RingLoad",
    "LoadDistribution",
    "LoadDistributionError",
    "solve_load_distribution",
]
