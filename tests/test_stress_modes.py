"""Stress modes combine linearly to the stress of the combined displacement."""

import numpy as np

from cms_reduction import reduce_model
from cms_reduction.stress_modes import add_stress_modes, modal_stress_Pa, render_modal_state
from fem_rings import MeshSpec, build_model
from fem_rings.profile import rectangle
from fem_rings.stress import nodal_stress_Pa
from foundation.materials import ElasticMaterial


def test_stress_modes_superpose_and_render(tmp_path):
    # Reference: stress recovered directly from the displacement Φη of the full field (linear
    # elasticity: the two must agree to round-off).
    steel = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
    model = build_model(rectangle("ring", 0.95, 1.05, -0.05, 0.05), MeshSpec(0.05, "hex27", n_theta=24),
                        steel, use_cache=False)
    body = add_stress_modes(reduce_model(model, 6), model)
    eta = np.random.default_rng(3).normal(size=body.n_modes) * 1e-3
    direct = nodal_stress_Pa(model, body.displacement_m(eta))
    combined = modal_stress_Pa(body, eta)
    assert np.abs(combined - direct).max() <= 1e-10 * np.abs(direct).max()
    png = render_modal_state(body, eta, tmp_path / "state.png")
    from matplotlib.image import imread
    img = imread(png)
    assert img.shape[:2] == (800, 1200) and img[..., :3].std() > 0.05
