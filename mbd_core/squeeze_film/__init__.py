"""Squeeze-film dampers: the film force on a journal (a bearing's outer race) in its housing.

``reynolds_grid`` solves Reynolds' equation with side leakage on a grid; ``limits`` holds the short-
and long-damper limits (the cheap rungs, and the closed forms the grid is checked against).
"""

from .limits import LIMITS, limit_force_N, long_circular_orbit_force_N, short_circular_orbit_force_N
from .reynolds_grid import CAVITATION_MODELS, FilmGrid, SqueezeFilmDamper, film_force_N, film_pressure_fields

__all__ = ["SqueezeFilmDamper", "FilmGrid", "film_force_N", "film_pressure_fields", "limit_force_N", "LIMITS",
           "CAVITATION_MODELS", "short_circular_orbit_force_N", "long_circular_orbit_force_N"]
