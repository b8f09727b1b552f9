"""Cross-section profiles, gmsh meshes and scikit-fem solid models of bearing rings and cages.

The first stage of the data flow::

    Profile (r, z section of lines and arcs)       fem_rings.profile, .sections, .cages, .dxf_section
      └─ mesh_ring(profile, MeshSpec)               gmsh → meshio → scikit-fem (tet10 / hex27)
           └─ build_model(..., material) → FEModel  K, M (vectorised assembly), named sets, cached
                ├─ static_solve / modal_analysis    fem_rings.solve (CHOLMOD or SuperLU)
                ├─ nodal_stress_Pa / von_mises_Pa   fem_rings.stress
                └─ write_vtu / render_png           fem_rings.output

Example::

    from fem_rings import MeshSpec, build_model, modal_analysis
    from fem_rings.sections import slewing_bottom_race
    from foundation.materials import ElasticMaterial

    model = build_model(slewing_bottom_race(1.0), MeshSpec(0.03, "hex27"),
                        ElasticMaterial("steel", 200e9, 0.3, 7850.0))
    modes = modal_analysis(model, 12)          # free–free: 6 rigid + 6 elastic

Units are SI throughout; node arrays are (n_nodes, 3) in metres and vector DOFs are interleaved
(``3 * node + component``).
"""

from .dxf_section import profile_from_dxf
from .mesh import MeshSpec, RingMesh, mesh_ring
from .model import FEModel, build_model
from .profile import Arc, Line, Profile, ProfileError
from .solve import Modes, Support, modal_analysis, static_solve
from .step_solid import StepInfo, check_step_solid
from .stress import nodal_stress_Pa, von_mises_Pa

__all__ = [
    "Arc", "Line", "Profile", "ProfileError", "profile_from_dxf",
    "MeshSpec", "RingMesh", "mesh_ring", "StepInfo", "check_step_solid",
    "FEModel", "build_model",
    "Support", "static_solve", "Modes", "modal_analysis",
    "nodal_stress_Pa", "von_mises_Pa",
]
