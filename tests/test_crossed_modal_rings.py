"""Modal rings on a crossed roller row: V-groove sections and the flexible load distribution.

References: the V-groove geometry in closed form (each flank half a roller diameter from the roller
axis along its diagonal's normal n± = (cos α0, ±sin α0), so the apex lies (D/2)/cos α0 from the
axis, radially); the rigid-ring load distribution (:func:`mbd_core.quasistatic.solve_load_distribution`)
as the limit of very stiff rings; a central finite difference of the flexible displacement–load
relation for the condensed stiffness matrix.
"""

import math

import numpy as np
import pytest

from cases.bearing_file import loads_bearing
from cases.bearing_solver import bearing_solver
from cases.config import CaseError
from cms_reduction.body import with_stiffness_scaled
from fem_rings.profile import Line
from mbd_core.quasistatic import solve_load_distribution
from mbd_core.quasistatic.flexible import FlexibleRing, build_flexible_model
from mbd_core.quasistatic.flexible_solve import solve_flexible_load_distribution
from tests.test_bearing_rings import check_equilibrium_and_condensed_stiffness

D, L, DM, ALPHA = 0.02, 0.018, 0.5, 45.0

CROSSED = f"""
[bearing]
name = "crossed roller test bearing"
moving_ring = "inner"

[[rows]]
type = "crossed_roller"
name = "rollers"
count = 60
roller_diameter_m = {D}
roller_length_m = {L}
pitch_diameter_m = {DM}
contact_angle_deg = {ALPHA}
diametral_clearance_m = -5.0e-6
n_slices = 6

[rings.inner]
inner_diameter_m = 0.44
z_min_m = -0.025
z_max_m = 0.025
n_modes = 12
raceway_harmonics = 4
element_size_m = 0.025
[rings.inner.bolts]
count = 12
pitch_diameter_m = 0.46
face = "top"

[rings.outer]
outer_diameter_m = 0.56
z_min_m = -0.025
z_max_m = 0.025
n_modes = 12
raceway_harmonics = 4
element_size_m = 0.025
clamped_face = "bottom"

[load]
Fx_N = 8.0e3
Fz_N = -2.0e4
My_Nm = 1.5e3
"""


@pytest.fixture(scope="module")
def desc():
    return loads_bearing(CROSSED)


@pytest.fixture(scope="module")
def solver(desc):
    return bearing_solver(desc)


@pytest.mark.parametrize("ring, side", [("inner", -1.0), ("outer", 1.0)])
def test_v_groove_of_the_row(desc, ring, side):
    m = desc.rings[ring]
    flanks = [s for s in m.profile.segments if s.name == "raceway rollers"]
    assert len(flanks) == 2 and all(isinstance(s, Line) for s in flanks)
    a = math.radians(ALPHA)
    apex = np.array([0.5 * DM + side * 0.5 * D / math.cos(a), 0.0])
    assert np.asarray(m.places["rollers"].point_rz_m) == pytest.approx(apex, abs=1e-12)
    for s in flanks:
        p, q = np.asarray(s.start), np.asarray(s.end)
        far = q if np.linalg.norm(p - apex) < 1e-12 else p
        assert min(np.linalg.norm(p - apex), np.linalg.norm(q - apex)) < 1e-12  # both flanks meet at the apex
        t = (far - apex) / np.linalg.norm(far - apex)
        # each flank at α0 to the axis direction, i.e. along ±(sin α0, ∓cos α0) seen from the apex …
        assert abs(t[0]) == pytest.approx(math.sin(a), rel=1e-12) and abs(t[1]) == pytest.approx(math.cos(a), rel=1e-12)
        assert -side * t[0] > 0.0  # … running from the apex back towards the rollers
        # … and long enough for the roller's contact line: its middle at (D/2)·tan α0, its end L/2 beyond
        assert np.linalg.norm(far - apex) == pytest.approx(0.5 * D * math.tan(a) + 0.5 * L, rel=1e-12)
        # half a roller diameter from the roller axis (at r = d_m/2, z = 0) along the flank's normal
        n = np.array([-t[1], t[0]])
        assert abs(float(n @ (apex - np.array([0.5 * DM, 0.0])))) == pytest.approx(0.5 * D, rel=1e-12)


def test_crossed_rows_equilibrium_and_condensed_stiffness(desc, solver):
    assert solver.flexible and {r.name for r in solver.rings} == {"inner", "outer"}
    check_equilibrium_and_condensed_stiffness(desc, solver)


def test_very_stiff_rings_give_the_rigid_ring_roller_loads(desc, solver):
    """E × 10⁶: the ring bending vanishes (∝ 1/E), so the roller loads approach the rigid-ring ones;
    soft rings (E / 100) change them (the coupling of both diagonals' rollers does something)."""
    load = desc.default_load
    rigid = solve_load_distribution(desc.bearing, load).rows[0].load_N
    stiff = tuple(FlexibleRing(r.name, with_stiffness_scaled(r.body, 1e6), r.ring, dict(r.raceways)) for r in solver.rings)
    q_stiff = solve_flexible_load_distribution(build_flexible_model(desc.bearing, stiff), load).rows[0].load_N
    assert np.max(np.abs(q_stiff - rigid)) <= 1e-4 * rigid.max()
    soft = tuple(FlexibleRing(r.name, with_stiffness_scaled(r.body, 1e-2), r.ring, dict(r.raceways)) for r in solver.rings)
    q_soft = solve_flexible_load_distribution(build_flexible_model(desc.bearing, soft), load).rows[0].load_N
    assert np.max(np.abs(q_soft - rigid)) >= 1e-2 * rigid.max()
    # both diagonals carry load under the moment and the radial force
    sign = np.sign(desc.bearing.rows[0].contact_angles_rad)
    assert rigid[sign > 0].max() > 0.0 and rigid[sign < 0].max() > 0.0


def test_crossed_rows_refuse_element_load_shapes():
    text = CROSSED.replace("raceway_harmonics = 4\nelement_size_m = 0.025\nclamped_face",
                           "raceway_harmonics = 4\nelement_size_m = 0.025\nelement_load_shapes = true\nclamped_face")
    desc = loads_bearing(text)
    with pytest.raises(CaseError, match=r"^rings\.outer\.element_load_shapes: not for the crossed roller row 'rollers'"):
        bearing_solver(desc)
