"""Case definitions to TOML and back: exact round trips and the exact user-facing messages.

The schema below is a stand-in; the machinery in :mod:`cases.config` knows no schema.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Literal

import pytest

from cases.config import (
    CaseError,
    dumps_case,
    from_mapping,
    loads_case,
    read_case,
    to_mapping,
    with_overrides,
    write_case,
)


@dataclass(frozen=True)
class Mesh:
    n_modes: int = 20
    size_m: float = 0.01
    element: Literal["tet4", "tet10"] = "tet10"
    refine: bool = False
    offsets_m: tuple[float, ...] = (0.0,)

    def __post_init__(self):
        if self.n_modes < 1:
            raise ValueError(f"n_modes must be ≥ 1, got {self.n_modes}")
        if len(self.offsets_m) > 3:
            raise ValueError(f"at most 3 offsets, got {len(self.offsets_m)}")


@dataclass(frozen=True)
class Case:
    name: str
    speed_rpm: float = 10.0
    damping: float | None = None
    mesh: Mesh = field(default_factory=Mesh)
    profile_m: tuple[tuple[float, float], ...] = ((0.0, 0.0), (1.0, 0.5))


MESH_KEYS = "element, n_modes, offsets_m, refine, size_m"
CASE_KEYS = "damping, mesh, name, profile_m, speed_rpm"
FULL = Case("slewing ring", 0.1 + 0.2, 1e-300, Mesh(7, 2.5e-3, "tet4", True, (3e-4, -4e-4)),
            ((0.0, 1 / 3), (2.0, -0.125)))


def test_round_trip_through_text_is_exact():
    text = dumps_case(FULL)
    assert loads_case(Case, text) == FULL
    assert text.index("speed_rpm =") < text.index("[mesh]")  # scalars before tables
    assert loads_case(Case, dumps_case(Case("x"))) == Case("x")


def test_round_trip_through_file(tmp_path):
    path = tmp_path / "case.toml"
    write_case(FULL, path)
    assert read_case(Case, path) == FULL


def test_to_mapping_omits_none_and_lists_tuples():
    assert to_mapping(Case("x")) == {
        "name": "x", "speed_rpm": 10.0, "profile_m": [[0.0, 0.0], [1.0, 0.5]],
        "mesh": {"n_modes": 20, "size_m": 0.01, "element": "tet10", "refine": False, "offsets_m": [0.0]},
    }


def test_defaults_and_int_to_float():
    case = from_mapping(Case, {"name": "x", "speed_rpm": 3, "mesh": {"n_modes": 4}})
    assert case == Case("x", 3.0, mesh=Mesh(n_modes=4))
    assert type(case.speed_rpm) is float


@pytest.mark.parametrize("data, message", [
    ({"name": "x", "sped_rpm": 1.0}, f"sped_rpm: unknown key (known: {CASE_KEYS})"),
    ({"name": "x", "mesh": {"nmodes": 3}}, f"mesh.nmodes: unknown key (known: {MESH_KEYS})"),
    ({}, "name: missing key"),
    ({"name": "x", "speed_rpm": True}, "speed_rpm: expected a number, got true"),
    ({"name": "x", "speed_rpm": "fast"}, "speed_rpm: expected a number, got 'fast'"),
    ({"name": "x", "mesh": {"n_modes": 2.5}}, "mesh.n_modes: expected an integer, got 2.5"),
    ({"name": "x", "mesh": {"refine": 1}}, "mesh.refine: expected true or false, got 1"),
    ({"name": 3}, "name: expected a string, got 3"),
    ({"name": "x", "mesh": {"element": "hex8"}}, "mesh.element: must be one of 'tet4', 'tet10', got 'hex8'"),
    ({"name": "x", "mesh": {"offsets_m": [1.0, "a"]}}, "mesh.offsets_m[1]: expected a number, got 'a'"),
    ({"name": "x", "profile_m": [[0.0, 1.0, 2.0]]}, "profile_m[0]: expected a list of 2 items, got 3"),
    ({"name": "x", "mesh": 5}, "mesh: expected a table, got 5"),
    ({"name": "x", "mesh": {"n_modes": 0}}, "mesh.n_modes must be ≥ 1, got 0"),
    ({"name": "x", "mesh": {"offsets_m": [0, 1, 2, 3]}}, "mesh: at most 3 offsets, got 4"),
])
def test_bad_input_names_the_key(data, message):
    with pytest.raises(CaseError, match=f"^{re.escape(message)}$"):
        from_mapping(Case, data)


@pytest.mark.parametrize("assignment, expected", [
    ("mesh.size_m=5e-3", Case("x", mesh=Mesh(size_m=5e-3))),
    ("mesh.n_modes = 30", Case("x", mesh=Mesh(n_modes=30))),
    ('mesh.element="tet4"', Case("x", mesh=Mesh(element="tet4"))),
    ("mesh.element=tet4", Case("x", mesh=Mesh(element="tet4"))),
    ("mesh.offsets_m=[3e-4, 4e-4]", Case("x", mesh=Mesh(offsets_m=(3e-4, 4e-4)))),
    ("damping=0.02", Case("x", damping=0.02)),
    ("name=two words", Case("two words")),
])
def test_override(assignment, expected):
    assert with_overrides(Case("x"), [assignment]) == expected


def test_overrides_apply_in_order_and_keep_the_rest():
    case = with_overrides(FULL, ["speed_rpm=5", "speed_rpm=6", "mesh.refine=false"])
    assert case == Case(FULL.name, 6.0, FULL.damping, Mesh(7, 2.5e-3, "tet4", False, (3e-4, -4e-4)),
                        FULL.profile_m)


@pytest.mark.parametrize("assignment, message", [
    ("mesh.nmodes=3", f"mesh.nmodes: unknown key (known: {MESH_KEYS})"),
    ("grid.n=3", f"grid: unknown key (known: {CASE_KEYS})"),
    ("speed_rpm.x=1", "speed_rpm: not a table, cannot set speed_rpm.x"),
    ("mesh.n_modes", "mesh.n_modes: expected key=value"),
    ("mesh.n_modes=0", "mesh.n_modes must be ≥ 1, got 0"),
    ("mesh.element=hex8", "mesh.element: must be one of 'tet4', 'tet10', got 'hex8'"),
])
def test_bad_override_names_the_key(assignment, message):
    with pytest.raises(CaseError, match=f"^{re.escape(message)}$"):
        with_overrides(Case("x"), [assignment])


def test_toml_syntax_error_names_file_and_line(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('name = "x"\nspeed_rpm 12\n', encoding="utf-8")
    with pytest.raises(CaseError, match=f"^{re.escape(str(path))}: invalid TOML: .*line 2"):
        read_case(Case, path)
