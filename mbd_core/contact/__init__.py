"""Contact mechanics that the contact laws need: Hertz point and line contact, subsurface stress."""

from .hertz import HertzPointContact, ball_on_groove, point_contact, series_stiffness, sphere_on_sphere
from .line import HertzLineContact, iso16281_stiffness, line_contact, palmgren_stiffness, slice_stiffness
from .subsurface import max_shear_profile_Pa, subsurface_shear

__all__ = [
    "HertzPointContact",
    "point_contact",
    "ball_on_groove",
    "sphere_on_sphere",
    "series_stiffness",
    "HertzLineContact",
    "line_contact",
    "palmgren_stiffness",
    "iso16281_stiffness",
    "slice_stiffness",
    "max_shear_profile_Pa",
    "subsurface_shear",
]
