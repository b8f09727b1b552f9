"""Checks of STEP solids (fem_rings.step_solid) on files written here with gmsh's OpenCASCADE kernel."""

import math

import pytest

from fem_rings.mesh import gmsh_session
from fem_rings.step_solid import check_step_solid

# ring in millimetres (OpenCASCADE's unit; gmsh labels the file SI_UNIT(.MILLI.,.METRE.))
R_OUT, R_IN, Z0, H = 450.0, 400.0, 10.0, 60.0


def write_step(path, build):
    with gmsh_session("writer") as gmsh:
        build(gmsh.model.occ)
        gmsh.model.occ.synchronize()
        gmsh.write(str(path))
    return path


def ring(occ, x0=0.0):
    outer = occ.addCylinder(x0, 0, Z0, 0, 0, H, R_OUT)
    inner = occ.addCylinder(x0, 0, Z0, 0, 0, H, R_IN)
    occ.cut([(3, outer)], [(3, inner)])


def test_ring_bbox_volume_and_axis(tmp_path):
    info = check_step_solid(write_step(tmp_path / "ring.step", ring))
    assert (info.n_volumes, info.is_ring_about_z, info.not_ring_reason) == (1, True, "")
    # reference: the drawn dimensions; OpenCASCADE enlarges bounding boxes by its
    # confusion tolerance 1e-7 mm = 1e-10 m, hence 1e-9 m
    assert info.bbox_min_m == pytest.approx((-R_OUT * 1e-3, -R_OUT * 1e-3, Z0 * 1e-3), abs=1e-9)
    assert info.bbox_max_m == pytest.approx((R_OUT * 1e-3, R_OUT * 1e-3, (Z0 + H) * 1e-3), abs=1e-9)
    # reference: hollow cylinder V = π (R² − r²) h; OpenCASCADE integrates the volume numerically
    # over the exact cylindrical faces (GProp), 1e-9 relative
    assert info.volume_m3 == pytest.approx(math.pi * (R_OUT**2 - R_IN**2) * H * 1e-9, rel=1e-9)
    assert check_step_solid(tmp_path / "ring.step", unit="mm").bbox_max_m == info.bbox_max_m


def test_not_rings_say_why(tmp_path):
    full = check_step_solid(write_step(tmp_path / "full.step",
                                       lambda occ: occ.addCylinder(0, 0, Z0, 0, 0, H, R_OUT)))
    assert not full.is_ring_about_z and "lies inside volume" in full.not_ring_reason
    off = check_step_solid(write_step(tmp_path / "off.step", lambda occ: ring(occ, x0=5.0)))
    # reference: the ring moved 5 mm along x has its centre of mass 5 mm = 0.005 m off the axis
    assert not off.is_ring_about_z and "centre of mass lies 0.005 m off the z axis" in off.not_ring_reason


def test_errors_name_the_file(tmp_path):
    disk = write_step(tmp_path / "disk.step", lambda occ: occ.addDisk(0, 0, 0, R_OUT, R_OUT))
    with pytest.raises(ValueError, match=r"disk\.step is not a solid: 1 surfaces, 0 volumes$"):
        check_step_solid(disk)
    junk = tmp_path / "junk.step"
    junk.write_text("hello\nthis is not STEP\n")
    with pytest.raises(ValueError, match=r"junk\.step: not a readable STEP file$"):
        check_step_solid(junk)
    with pytest.raises(ValueError, match=r"missing\.step: no such file"):
        check_step_solid(tmp_path / "missing.step")
    ring_file = write_step(tmp_path / "ring.step", ring)
    with pytest.raises(ValueError, match=r"ring\.step: unit='m' disagrees with the file, which declares mm"):
        check_step_solid(ring_file, unit="m")
    with pytest.raises(ValueError, match="unit must be"):
        check_step_solid(ring_file, unit="inch")
