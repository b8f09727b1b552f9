"""Cross-section profiles, gmsh meshes and scikit-fem solid models of bearing rings and cages.

The package is the first stage of the data flow (DESIGN §1, §3): profile → 3-D mesh → FE model
(K, M, node sets). It has no public functions yet; the quasi-static load distribution of
:mod:`mbd_core.quasistatic` works with rigid rings until the ring models exist.
"""

__all__: list[str] = []
