"""Quasi-static load distribution of bearings with rigid or flexible (modal) rings (Newton, analytic Jacobian)."""

from .high_speed import HighSpeedRow, solve_high_speed_row
from .flexible import FlexibleBearingModel, FlexibleRing, GrooveOffset, build_flexible_model
from .flexible_solve import FlexibleLoadDistribution, RacewayDeflection, solve_flexible_load_distribution
from .rows import BallRow, Bearing, FourPointRow, RollerRow
from .solver import LoadDistribution, LoadDistributionError, RingLoad, solve_load_distribution, stiffness_matrix

__all__ = [
    "BallRow",
    "FourPointRow",
    "RollerRow",
    "Bearing",
    "RingLoad",
    "LoadDistribution",
    "LoadDistributionError",
    "solve_load_distribution",
    "stiffness_matrix",
    "FlexibleRing",
    "GrooveOffset",
    "FlexibleBearingModel",
    "build_flexible_model",
    "RacewayDeflection",
    "FlexibleLoadDistribution",
    "solve_flexible_load_distribution",
    "HighSpeedRow",
    "solve_high_speed_row",
]
