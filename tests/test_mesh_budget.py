"""The model-size estimate made before meshing, against the meshes gmsh makes.

Reference: the DOF count of the actual mesh (:func:`fem_rings.mesh.mesh_ring`). The estimate is
meant as a lower one (a mesh is never refused for a size it does not reach) within a factor 6,
hex27 and tet10 alike (measured 0.19–0.76 on every built-in part at its default and twice its
default element size).
"""

from __future__ import annotations

import math

import pytest

from cases.mesh_budget import check_model_size, estimate_dofs, estimate_memory_bytes
from cases.parts import ring_part
from fem_rings import MeshSpec
from fem_rings.mesh import mesh_ring


@pytest.mark.parametrize("name, size_m", [
    ("slewing-bottom-race-1m", 0.04),
    ("slewing-bottom-race-1m", 0.08),
    ("slewing-tmr", 0.3),
    ("three-row-outer-ring", 0.12),
    ("three-row-rear-cage", 0.04),   # tet10, pockets cut out
])
def test_estimate_is_a_lower_bound_within_a_factor_six(name, size_m):
    part = ring_part(name)
    profile, pockets = part.make()
    n_mesh = mesh_ring(profile, MeshSpec(size_m, part.default_element), pockets).n_dofs
    ratio = estimate_dofs(profile, size_m) / n_mesh
    assert 1.0 / 6.0 < ratio <= 1.0, ratio


def test_refusals_name_the_keys_and_give_the_estimate(monkeypatch):
    profile, _ = ring_part("slewing-bottom-race-1m").make()
    n = math.ceil(estimate_dofs(profile, 0.04))
    with pytest.raises(ValueError, match=rf"^n_modes = {n} is more than the mesh can give: size_m = 0.04 gives"):
        check_model_size(profile, 0.04, n, "size_m", "n_modes", n_rigid=0)
    # memory: the estimate for the machine's memory, here pretended to be 1 GB
    monkeypatch.setattr("cases.mesh_budget.machine_memory_bytes", lambda: 1e9)
    need = estimate_memory_bytes(estimate_dofs(profile, 0.01), 16)
    assert need > 1e9
    with pytest.raises(ValueError, match=rf"^size_m = 0.01 would give ~.* \(~{need / 1e9:.3g} GB\), more than this "
                                         r"machine's 1 GB$"):
        check_model_size(profile, 0.01, 16, "size_m", "n_modes", n_rigid=0)
    check_model_size(profile, 0.08, 16, "size_m", "n_modes", n_rigid=0)  # 17 568 DOF: fits
