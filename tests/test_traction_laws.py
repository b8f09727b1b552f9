"""Film traction and mixed lubrication laws (``LimitingShear``, ``MixedFriction``, kernel law 5).

References:
- Newtonian film: at small slip a film of thickness h and viscosity η carries τ = η·u/h, so
  κ = τ/p̄ → η·u/(h·p̄) as u → 0 (the limit the limiting-shear law must reach); at large slip the
  limiting shear stress τ_L = κ_L·p̄ (Bair & Winer 1979).
- Zhou & Hoeprich (1991): asperity load share φ = exp(−B·Λ^C): φ(0) = 1 (boundary friction only),
  φ → 0 for thick films.
- The kernel law against its numpy twin (tests/reference/contact_laws.py) and its slope against a
  central difference.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mbd_core.contact.friction import LimitingShear, MixedFriction, asperity_load_share
from mbd_core.kernels.laws import FRICTION_LIMITING_SHEAR, friction_coefficient, friction_slope
from mbd_core.multibody import ContactLaw
from tests.reference import contact_laws as twin


def test_kernel_law_matches_twin_and_its_slope():
    p = np.array([0.06, 2e-3, 0.0, 0.0])
    for u in (0.0, 1e-7, 5e-4, 2e-3, 0.01, 3.0):
        mu = friction_coefficient(FRICTION_LIMITING_SHEAR, u, *p)
        # (the twin's 1 − exp loses digits at small u that the kernel's expm1 keeps)
        assert mu == pytest.approx(float(twin.friction_coefficient(5, u, p)), rel=1e-9, abs=1e-18)
        if u > 0.0:
            h = 1e-6 * u
            fd = (friction_coefficient(FRICTION_LIMITING_SHEAR, u + h, *p)
                  - friction_coefficient(FRICTION_LIMITING_SHEAR, u - h, *p)) / (2 * h)
            assert friction_slope(FRICTION_LIMITING_SHEAR, u, *p) == pytest.approx(fd, rel=1e-6)
    assert friction_coefficient(FRICTION_LIMITING_SHEAR, 1.0, *p) == pytest.approx(0.06, rel=1e-12)


def test_film_traction_reaches_newtonian_shear_and_the_limiting_stress():
    h, p_mean, eta = 2e-7, 6e8, 1.5e3            # m, Pa, Pa·s (the viscosity in the contact)
    law = LimitingShear.from_film(h, p_mean, eta, limiting_shear_coefficient=0.07)
    u = 1e-6 * law.u_c_m_s
    newtonian = eta * u / (h * p_mean)
    assert friction_coefficient(law.code, u, *law.params) == pytest.approx(newtonian, rel=1e-5)
    assert friction_coefficient(law.code, 100 * law.u_c_m_s, *law.params) == pytest.approx(0.07, rel=1e-12)
    with pytest.raises(ValueError, match="film_m"):
        LimitingShear.from_film(0.0, p_mean, eta)


def test_mixed_friction_blends_boundary_and_film_by_asperity_share():
    fluid = LimitingShear(0.03, 1e-3)
    assert asperity_load_share(0.0, 1.8, 1.2) == 1.0
    assert asperity_load_share(1.0, 1.8, 1.2) == pytest.approx(math.exp(-1.8), rel=1e-15)
    boundary = MixedFriction(0.12, fluid, 0.0, 1.8, 1.2)
    thick = MixedFriction(0.12, fluid, 10.0, 1.8, 1.2)
    mid = MixedFriction(0.12, fluid, 1.0, 1.8, 1.2)
    big = 1.0                                   # m/s ≫ u_c
    assert friction_coefficient(boundary.code, big, *boundary.params) == pytest.approx(0.12, rel=1e-12)
    assert friction_coefficient(thick.code, big, *thick.params) == pytest.approx(0.03, rel=1e-6)
    phi = math.exp(-1.8)
    assert friction_coefficient(mid.code, big, *mid.params) == pytest.approx(phi * 0.12 + (1 - phi) * 0.03, rel=1e-12)
    assert ContactLaw(1e9, friction=mid).friction is mid           # a law the multibody model takes
    with pytest.raises(ValueError, match="film_parameter"):
        MixedFriction(0.12, fluid, -1.0, 1.8, 1.2)
