"""Rotordynamics of a modal body spinning on its supports: the spinning-frame matrices (``spin``),
the Campbell diagram with forward and backward whirl (``campbell``), the steady response to an
unbalance (``unbalance``), modes of a body held at chosen DOFs (``supported``) and a rotor on
bearing springs at its seats (``seats``)."""

from .campbell import ORDER_TOL, CampbellDiagram, angular_order, campbell, spinning_modes
from .spin import SpinningBody, spinning_body, spinning_body_of_model, spinning_matrices
from .seats import BearingSpring, ball_row_spring, isotropic_bearing, on_bearings, seat_basis, seat_motion, statically_determinate_holds
from .supported import held_dofs, supported_modes
from .unbalance import UnbalanceResponse, unbalance_response

__all__ = ["SpinningBody", "spinning_body", "spinning_matrices", "CampbellDiagram", "campbell", "spinning_modes",
           "angular_order", "ORDER_TOL", "spinning_body_of_model", "held_dofs", "supported_modes", "UnbalanceResponse", "unbalance_response",
           "BearingSpring", "ball_row_spring", "isotropic_bearing", "on_bearings", "seat_basis", "seat_motion", "statically_determinate_holds"]
