"""Reproducible modes: fixed Lanczos start vector and a canonical basis for degenerate pairs."""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from fem_rings import MeshSpec, build_model, modal_analysis
from fem_rings.modal_basis import canonical_modes
from fem_rings.profile import rectangle
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
ROOT = Path(__file__).resolve().parents[1]

# Builds a small ring, optionally runs an unrelated eigensolve first (which moves ARPACK's own
# random generator on: the situation of a second body built in the same run), then reduces the
# ring with raceway load shapes and prints SHA-256 digests of the arrays.
SCRIPT = textwrap.dedent("""
    import hashlib, json, sys
    import numpy as np
    from cms_reduction import Augmentation, reduce_model
    from fem_rings import MeshSpec, build_model, modal_analysis
    from fem_rings.nodesets import raceway_curve
    from fem_rings.profile import rectangle
    from foundation.materials import ElasticMaterial

    steel = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
    model = build_model(rectangle("ring", 0.95, 1.05, -0.05, 0.05), MeshSpec(0.05, "hex27", n_theta=48),
                        steel, use_cache=False)
    if sys.argv[1] == "after-other-work":
        other = build_model(rectangle("other", 0.9, 1.1, -0.05, 0.05), MeshSpec(0.1, "hex27", n_theta=24),
                            steel, use_cache=False)
        modal_analysis(other, 9)
    body = reduce_model(model, 10, augmentation=[Augmentation(raceway_curve(model.ring, "top", 96), ("axial",), 4)])
    modes = modal_analysis(model, 12)
    digest = lambda a: hashlib.sha256(np.ascontiguousarray(a).tobytes()).hexdigest()
    print(json.dumps({"body_shapes": digest(body.shapes), "body_Hz": digest(body.frequencies_Hz),
                      "modes_shapes": digest(modes.shapes), "modes_Hz": digest(modes.frequencies_Hz)}))
""")


def _digests(mode: str) -> dict:
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    out = subprocess.run([sys.executable, "-c", SCRIPT, mode], capture_output=True, text=True, env=env,
                         cwd=ROOT, timeout=600, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_two_builds_in_separate_processes_are_bit_identical():
    # Reference: the first build. A second process that did other eigen-work first must give the
    # same bytes (SHA-256 of every array); ARPACK's internal random start made them differ.
    first, second = _digests("fresh"), _digests("after-other-work")
    assert first == second


@pytest.fixture(scope="module")
def ring_modes():
    model = build_model(rectangle("ring", 0.95, 1.05, -0.05, 0.05), MeshSpec(0.05, "hex27", n_theta=48),
                        STEEL, use_cache=False)
    return model, modal_analysis(model, 10)


def test_canonical_basis_does_not_depend_on_how_a_pair_was_returned(ring_modes):
    # Reference: the canonical basis of the pair as computed. Rotating the pair by any angle and
    # flipping signs (what another start vector gives) must lead back to the same shapes.
    model, modes = ring_modes
    pair = modes.shapes[:, 6:8]
    lam = (2 * np.pi * modes.frequencies_Hz[6:8]) ** 2
    assert abs(lam[1] / lam[0] - 1) < 1e-8                       # a degenerate pair
    for angle in (0.3, 1.9, -2.4):
        c, s = np.cos(angle), np.sin(angle)
        turned = pair @ np.array([[c, -s], [s, c]]) @ np.diag([1.0, -1.0])
        lam2, back = canonical_modes(lam[::-1], turned)
        assert np.abs(back - pair).max() < 1e-10 * np.abs(pair).max()
        assert np.all(lam2 == lam2[0])
    # a single mode: its sign is fixed
    shape = modes.shapes[:, 8:9]
    assert np.array_equal(canonical_modes(lam[:1], -shape)[1], canonical_modes(lam[:1], shape)[1])
