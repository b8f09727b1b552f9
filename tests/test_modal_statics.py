"""Static equilibrium of a floating modal body: its weight is part of the load scale."""

import math

import numpy as np
import pytest

from cms_reduction.pipeline import ReductionSpec, reduced_body
from fem_rings import MeshSpec
from fem_rings.profile import rectangle
from foundation.materials import ElasticMaterial
from mbd_core.multibody import ModelBuilder
from mbd_core.multibody.builder import Fixed, Free
from mbd_core.multibody.statics import static_equilibrium

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
G = 9.81


def test_floating_modal_ring_on_a_bushing_weight_sets_the_load_scale():
    # A free–free modal ring (R = 0.5 m, 100 × 100 mm) hangs at its centre on a stiff bushing
    # (k = 1e9 N/m) under gravity. References: its mass ρ·2πR·A (Pappus), Hooke's law for the
    # drop m g / k, and zero modal response (the modes are M-orthogonal to the uniform weight
    # field). The residual's yardstick (force_scale_N) must be that weight: it was the largest
    # applied force of the *rigid* bodies (1 N here), which made the tolerance 1e4× too strict
    # and the search basis-dependent.
    ring = reduced_body(rectangle("ring", 0.45, 0.55, -0.05, 0.05), MeshSpec(0.05, "hex27"), STEEL,
                        ReductionSpec(n_modes=4), use_cache=False)
    mass_kg = STEEL.density_kg_m3 * 2 * math.pi * 0.5 * 0.1 * 0.1
    b = ModelBuilder(gravity_m_s2=(0.0, 0.0, -G))
    ground = b.add_body("ground", 1.0, (1.0, 1.0, 1.0), motion=Fixed())
    body = b.add_modal_body("ring", ring, motion=Free())
    k = 1e9
    b.add_bushing(ground, body, (0.0, 0.0, 0.0), (k, k, k, k, k, k))
    model, state = b.finalize()
    res = static_equilibrium(model, state)
    assert res.force_scale_N == pytest.approx(mass_kg * G, rel=1e-3)
    assert res.state.q[body, 2] - state.q[body, 2] == pytest.approx(-mass_kg * G / k, rel=1e-3)
    assert np.abs(res.state.eta).max() * np.abs(ring.shapes).max() < 1e-9 * mass_kg * G / k
