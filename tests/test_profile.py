"""Validation and exact section properties of fem_rings.profile."""

import math

import pytest

from fem_rings.profile import Arc, Line, Profile, ProfileError, polygon, rectangle


def test_torus_section_properties_match_pappus():
    # Reference: torus of tube radius a about a circle of radius R (Pappus): V = 2π²Ra²,
    # J_zz = ρV(R² + 3a²/4), J_xx = ρV(R²/2 + 5a²/8) (e.g. Gieck, Engineering Formulas, K 9).
    R, a, rho = 0.5, 0.03, 7850.0
    torus = Profile("torus", (Arc((R + a, 0), (R - a, 0), (R, 0), True, "skin"),
                              Arc((R - a, 0), (R + a, 0), (R, 0), True, "skin")))
    props = torus.revolved_properties(rho)
    V = 2 * math.pi**2 * R * a * a
    assert props["mass_kg"] == pytest.approx(rho * V, rel=1e-12)
    assert props["J_zz_kg_m2"] == pytest.approx(rho * V * (R * R + 0.75 * a * a), rel=1e-12)
    assert props["J_xx_kg_m2"] == pytest.approx(rho * V * (R * R / 2 + 5 * a * a / 8), rel=1e-12)
    # a half revolution has half the mass and the same J_zz per unit mass
    half = torus.revolved_properties(rho, math.pi)
    assert half["mass_kg"] == pytest.approx(props["mass_kg"] / 2, rel=1e-12)


def test_orientation_is_normalised_counter_clockwise():
    cw = polygon("cw", [(1, 0), (1, 1), (2, 1), (2, 0)], ["inner", "top", "outer", "bottom"])
    assert cw.area_m2 == pytest.approx(1.0)
    assert rectangle("r", 1, 2, 0, 1).names == ("bottom", "outer", "top", "inner")


@pytest.mark.parametrize("points,match", [
    ([(0, 0), (1, 1), (1, 0), (0, 1)], "crosses itself"),
    ([(1, 0), (2, 0), (2, 1), (3, 1), (3, 2), (2, 2), (2, 1), (1, 1)], "touches itself"),   # figure eight
    ([(1, 0), (2, 0), (3, 1), (2, 0), (2, -1)], "touches itself"),                         # slit
    ([(0, 0), (1, 0), (1, 1), (-1, 1)], "crosses the axis"),
    ([(1, 0), (2, 0), (3, 0)], "no area"),
])
def test_invalid_regions_are_rejected_with_the_reason(points, match):
    with pytest.raises(ProfileError, match=match):
        polygon("bad", points, [f"s{i}" for i in range(len(points))])


def test_bad_segments_name_the_field():
    with pytest.raises(ProfileError, match="start and end coincide"):
        Arc((1, 0), (1, 0), (0, 0), name="loop")
    with pytest.raises(ProfileError, match="different distances"):
        Arc((1, 0), (0, 2), (0, 0), name="oval")
    with pytest.raises(ProfileError, match="180"):
        Arc((1, 0), (0, -1), (0, 0), True, "big")
    with pytest.raises(ProfileError, match=r"'edge' start must be an \(r, z\) pair"):
        Line((1, 0, 0), (2, 0), "edge")
    with pytest.raises(ProfileError, match="not closed"):
        Profile("open", (Line((1, 0), (2, 0)), Line((2, 0), (2, 1)), Line((2, 1), (1, 0.5))))
