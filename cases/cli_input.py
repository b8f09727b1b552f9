"""Checks of command-line numbers shared by the commands: one line naming the option on bad input."""

from __future__ import annotations

import argparse
import math

from mbd_core.multibody import SimulationError
from mbd_core.multibody.statics import StaticEquilibriumError
from mbd_core.quasistatic import LoadDistributionError

__all__ = ["UserError", "USER_FAILURES", "option_name", "require_positive", "require_finite"]


class UserError(Exception):
    """Bad input from the command line."""


#: failures that the input causes: their message names the cause (exit status 2; a sweep point
#: failing with one of them records the message, :mod:`cases.sweep.engine`)
USER_FAILURES = (UserError, ValueError, LoadDistributionError, SimulationError, StaticEquilibriumError)


def option_name(dest: str) -> str:
    """The command-line spelling of an argparse destination (``E_GPa`` → ``--E-GPa``)."""
    return "--" + dest.replace("_", "-")


#: (unit suffix, low, high): where the contact formulas stay finite in double precision, far
#: beyond any bearing — lengths 1 nm … 1000 km, loads 1e-30 … 1e30 N, moduli 1 kPa … 1e6 GPa
_RANGES = (("_mm", 1e-6, 1e9), ("_N", 1e-30, 1e30), ("_GPa", 1e-6, 1e6))


def require_positive(**values: float) -> None:
    for name, v in values.items():
        if not (math.isfinite(v) and v > 0.0):
            raise UserError(f"{option_name(name)} must be a positive number, got {v}")
        for suffix, low, high in _RANGES:
            if name.endswith(suffix) and not low <= v <= high:
                raise UserError(f"{option_name(name)} must lie in [{low:g}, {high:g}], got {v:g}")


#: options where an infinite value means something (a flat raceway)
_INFINITE_ALLOWED = {"raceway_diameter_mm"}


def require_finite(args: argparse.Namespace) -> None:
    """Every number given on the command line is finite (nan and inf are valid floats to argparse)."""
    for dest, v in vars(args).items():
        if isinstance(v, float) and not math.isfinite(v) and not (dest in _INFINITE_ALLOWED and v == math.inf):
            raise UserError(f"{option_name(dest)} must be a finite number, got {v}")
