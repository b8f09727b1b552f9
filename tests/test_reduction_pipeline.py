"""The cached reduction pipeline: one call from a section to a reduced body with its extras."""

import numpy as np
import pytest

from cms_reduction.invariants import Invariants
from cms_reduction.pipeline import InterfaceSpec, RacewaySpec, ReductionSpec, reduced_body
from cms_reduction.sampling import samples_from_arrays
from fem_rings import MeshSpec
from fem_rings.sections import SlewingSection, slewing_bottom_race
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)


def test_bolted_race_reduced_cached_and_reloaded_identically(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path))
    contact = tuple(SlewingSection().groove("bottom", 1.0).contact_point_m)
    spec = ReductionSpec(
        n_modes=8,
        interfaces=(InterfaceSpec("bolt_face", tuple(np.arange(8) * 45.0), 0.03),),
        raceways=(RacewaySpec("groove", 64, contact, ("normal",), 4),),
        damping_ratio=0.02,
    )
    profile, mesh = slewing_bottom_race(1.0), MeshSpec(0.06, "hex27")
    a = reduced_body(profile, mesh, STEEL, spec)
    b = reduced_body(profile, mesh, STEEL, spec)            # from the cache
    assert not a.floating and a.n_modes == 8 + 9           # 8 normal + cos/sin n = 0…4 load shapes
    assert np.array_equal(a.shapes, b.shapes) and np.array_equal(a.frequencies_Hz, b.frequencies_Hz)
    assert set(a.extras) == set(b.extras)
    assert all(np.array_equal(a.extras[k], b.extras[k]) for k in a.extras)
    assert b.metadata["input_hash"] == a.metadata["input_hash"]
    assert np.all(b.damping_ratio == 0.02)
    # extras: invariants of the grounded body (mass of the race) and the groove samples
    inv = Invariants.from_arrays(b.extras)
    assert inv.mass_kg == pytest.approx(profile.revolved_properties(7850.0)["mass_kg"], rel=1e-3)
    assert np.allclose(inv.I6_modal_mass, np.eye(b.n_modes), atol=1e-10)
    groove = samples_from_arrays(b.extras)["groove"]
    assert groove.displacement.shape == (64, 3, b.n_modes) and groove.periodic
    # another spec is another entry
    c = reduced_body(profile, mesh, STEEL, ReductionSpec(n_modes=6))
    assert c.floating and c.n_modes == 6


def test_cage_pockets_and_roller_track_grid_are_stored():
    from cms_reduction.sampling import samples_from_arrays
    from fem_rings.cages import CagePockets
    from fem_rings.profile import rectangle

    # pockets centred at 15° + k·30°, ±2.9° wide: clear of the 10° sampling grid on the outer face
    pockets = CagePockets(12, "box", "radial", 0.5, 0.0, width_m=0.05, height_m=0.03, angle_offset_deg=15.0)
    cage = reduced_body(rectangle("cage", 0.48, 0.52, -0.03, 0.03), MeshSpec(0.015, "tet10"), STEEL,
                        ReductionSpec(n_modes=4, raceways=(RacewaySpec("outer", 36, None, ("radial",), -1, 3),)),
                        pockets, use_cache=False)
    samples = samples_from_arrays(cage.extras)
    assert set(samples) == {"pockets", "outer@s0", "outer@s1", "outer@s2"}
    assert samples["pockets"].displacement.shape == (24, 3, cage.n_modes)
    # the grid circles sit at the Gauss points across the 60 mm high outer face
    z = sorted(float(samples[f"outer@s{k}"].points_m[0, 2]) for k in range(3))
    assert z == pytest.approx([-0.03 * np.sqrt(0.6), 0.0, 0.03 * np.sqrt(0.6)], abs=1e-12)
