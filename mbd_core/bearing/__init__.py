"""Bearing-level relations: rolling kinematics, defect frequencies, ISO 281 rating and life,
case-depth life factor; from a load distribution: static safety (ISO 76), rating life per row
(ISO/TS 16281) with its case-depth factor, and the static limiting load curve."""

from .kinematics import RollingKinematics, rad_s_to_rpm, rolling_kinematics, rpm_to_rad_s
from .case_depth import case_depth_life_factor, required_case_depth_m
from .distribution_life import BearingLife, RowLife, rating_life, spectrum_rating_life
from .distribution_case_depth import CaseDepth, RowCaseDepth, row_case_depth_factors
from .limiting_load import LimitingLoadCurve, limiting_load_curve
from .static_safety import RowStaticSafety, static_safety
from .rating import (
    basic_rating_life_Mrev,
    radial_ball_rating_N,
    radial_roller_rating_N,
    thrust_ball_rating_N,
    thrust_roller_rating_N,
)

__all__ = [
    "RollingKinematics",
    "rolling_kinematics",
    "rpm_to_rad_s",
    "rad_s_to_rpm",
    "radial_ball_rating_N",
    "thrust_ball_rating_N",
    "radial_roller_rating_N",
    "thrust_roller_rating_N",
    "basic_rating_life_Mrev",
    "case_depth_life_factor",
    "required_case_depth_m",
    "RowStaticSafety",
    "static_safety",
    "RowLife",
    "BearingLife",
    "rating_life",
    "spectrum_rating_life",
    "CaseDepth",
    "RowCaseDepth",
    "row_case_depth_factors",
    "LimitingLoadCurve",
    "limiting_load_curve",
]
