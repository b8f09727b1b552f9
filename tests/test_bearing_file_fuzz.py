"""Fuzz of bearing description files: every bad file is a one-line error naming a key or the file.

A seeded generator mutates the shipped description files and one with every row type: keys of
every table set to random values (numbers of every kind, strings, lists, tables), removed or made
up, row types swapped, spectrum and time history CSVs garbled, and files cut, garbled or not UTF-8. Each goes
through :func:`cases.bearing_file.read_bearing_file` only (no solve). The property checked: no
exception other than :class:`cases.config.CaseError` escapes, and its message is one line that
starts with the file or a dotted key (``rows[2].count: …``).
"""

from __future__ import annotations

import copy
import dataclasses
import math
import random
import re
import time

import tomli_w
import tomllib

from cases.bearing_file import BUILTIN_DIR, TOP_LEVEL, BearingKeys, LoadKeys, MaterialKeys, loads_bearing, read_bearing_file
from cases.bearing_rings import BoltKeys, RingKeys
from cases.bearing_rows import ROW_TYPES
from cases.config import CaseError
from cases.row_keys import SeparatorKeys

from tests.fuzz_values import random_value
from tests.test_bearing_file import EVERY_TYPE

SEED = 20261126
N_FILES = 400

ROW_KEYS = sorted({f.name for t in ROW_TYPES.values() for f in dataclasses.fields(t.keys)} | {"type"})
TABLE_KEYS = {"bearing": [f.name for f in dataclasses.fields(BearingKeys)],
              "load": [f.name for f in dataclasses.fields(LoadKeys)],
              "materials": [f.name for f in dataclasses.fields(MaterialKeys)]}
NUMBERS = [0, -1, 1, 3, 2**63 - 1, -(2**63), 10**6, math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, 0.5,
           0.49, 0.525, 45.0, 90.0, 91.0, -0.01, 1e-3, 1e-9, -1e-9]
WORDS = ["", "x", "inner", "outer", "+z", "-z", "z", "straight", "crowned", "logarithmic", "back_to_back", "tandem",
         "bearing_steel", "spectrum.csv", "nothere.csv", "/", "Ünïcødé", "two\nlines", "a" * 300, *ROW_TYPES,
         "alternate", "+-", "++--", "-", "+-x"]  # crossed roller patterns
CSVS = ["Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n0,0,-1e5,0,0\n", "Fx_N,Fy_N\n1,2\n", "Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n1,2\n",
        "Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,time_share\n0,0,1,0,0,-1\n", "", "\xff\xfe", "a\n\"b", "Fz_N\ninf\n",
        "Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,Fz_N\n0,0,0,0,0,0\n",
        # load time histories (time_history_csv)
        "time_s,Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n0,0,0,-1e5,0,0\n1,0,0,-2e5,0,0\n",
        "time_s,Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n1,0,0,-1e5,0,0\n0,0,0,-2e5,0,0\n",
        "time_s,Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n0,0,0,-1e5,0,0\n", "time_s\n-inf\n",
        "time_s,Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm\n-1e308,0,0,0,0,0\n1e308,0,0,0,0,0\n5e-324,0,0,0,0,0\n"]


def _value(rng: random.Random):
    return random_value(rng, NUMBERS, WORDS, ["a", "name", "count"], max_depth=2, max_items=3, exponent=9)


SEPARATOR_KEYS = [f.name for f in dataclasses.fields(SeparatorKeys)]


def _separator(rng: random.Random) -> dict:
    """A ``[rows.separator]`` table: a kind (or a bad one) and some of the keys, valued at random."""
    table = {"kind": rng.choice(["cage", "spacer_balls", "full_complement", "basket", 1])}
    for key in rng.sample(SEPARATOR_KEYS + ["bogus"], rng.randint(0, 3)):
        table[key] = rng.choice(NUMBERS + [0.012, 0.0119, 0.05]) if rng.random() < 0.8 else _value(rng)
    return table


def _mutate(rng: random.Random, data: dict) -> dict:
    data = copy.deepcopy(data)
    for _ in range(rng.randint(1, 4)):
        r = rng.random()
        rows = data.get("rows") if isinstance(data.get("rows"), list) else []
        if r < 0.55 and rows:
            row = rng.choice(rows)
            if isinstance(row, dict):
                own = ROW_TYPES.get(row.get("type")) if isinstance(row.get("type"), str) else None
                keys = [f.name for f in dataclasses.fields(own.keys)] if own and rng.random() < 0.8 else ROW_KEYS
                key = rng.choice(keys + ["bogus"])
                if key == "separator" and rng.random() < 0.7:
                    row[key] = _separator(rng)
                elif rng.random() < 0.8:
                    row[key] = _value(rng) if key != "type" or rng.random() < 0.3 else rng.choice(list(ROW_TYPES))
                else:
                    row.pop(key, None)
        elif r < 0.8:
            table = rng.choice(list(TABLE_KEYS))
            node = data.setdefault(table, {})
            if table == "materials" and isinstance(node, dict):
                node = node.setdefault(rng.choice(["bronze"] * 8 + ["steel", "bearing_steel"]), {})
            if isinstance(node, dict):
                node[rng.choice(TABLE_KEYS[table] + ["bogus"])] = _value(rng)
        elif r < 0.9:
            data[rng.choice(list(TOP_LEVEL) + ["extra"])] = _value(rng)
        elif rows and rng.random() < 0.3:
            rows.pop(rng.randrange(len(rows)))
    return data


def _broken(rng: random.Random, text: str) -> bytes:
    r = rng.random()
    if r < 0.3:
        return text[: rng.randint(0, len(text))].encode()
    if r < 0.6:
        i = rng.randint(0, len(text))
        return (text[:i] + rng.choice(["[", "]]", "=", '"', "\n[[rows]]\n", "{", "\x00"]) + text[i:]).encode()
    if r < 0.8:
        raw = bytearray(text.encode())
        raw.insert(rng.randint(0, len(raw)), 0xFF)
        return bytes(raw)
    return rng.choice([b"", b"# comment\n", bytes(rng.randrange(256) for _ in range(50))])


def _assert_names_a_key(message: str, path: str) -> None:
    assert "\n" not in message and "Traceback" not in message, message
    if message.startswith(path + ": "):
        return
    segment = r"(?:'[^']*'|[\w\-]+)(?:\[\d+\])?"
    lead = re.match(rf"{segment}(?:\.{segment})*: ", message)
    assert lead, message
    top = re.sub(r"\[\d+\]", "", lead.group(0).split(".")[0].rstrip(": ")).strip("'")
    assert top in (*TOP_LEVEL, "extra"), message


def test_fuzz_bearing_files(tmp_path):
    rng = random.Random(SEED)
    bases = [tomllib.loads(p.read_text()) for p in sorted(BUILTIN_DIR.glob("*.toml"))] + [tomllib.loads(EVERY_TYPE)]
    refused, start = 0, time.perf_counter()
    for i in range(N_FILES):
        data = _mutate(rng, rng.choice(bases))
        if rng.random() < 0.2:
            data.setdefault("load", {})
            if isinstance(data["load"], dict):
                data["load"] = {rng.choice(["spectrum_csv", "time_history_csv"]): "spectrum.csv"}
        path = tmp_path / f"b{i}.toml"
        (tmp_path / "spectrum.csv").write_bytes(rng.choice(CSVS).encode("latin-1"))
        text = tomli_w.dumps(data)
        path.write_bytes(_broken(rng, text) if rng.random() < 0.15 else text.encode())
        try:
            read_bearing_file(path)
        except CaseError as exc:
            _assert_names_a_key(str(exc), str(path))
            refused += 1
    assert refused > N_FILES // 2  # the generator mostly makes bad files
    assert time.perf_counter() - start < 20.0


RING_KEYS = [f.name for f in dataclasses.fields(RingKeys)]
BOLT_KEYS = [f.name for f in dataclasses.fields(BoltKeys)]
#: the files a mutated ring table may name (written by the test: a STEP ring that fits, other STEP
#: files that do not, a DXF that is not one)
RING_FILES = ["outer.step", "junk.step", "disk.step", "nothere.step", "outer.dxf", "/", ""]
N_RING_FILES = 150


def _mutate_rings(rng: random.Random, data: dict) -> dict:
    data = copy.deepcopy(data)
    for _ in range(rng.randint(1, 3)):
        rings = data.setdefault("rings", {})
        if not isinstance(rings, dict):
            break
        name = rng.choice(["inner", "outer", "outer", "middle"])
        table = rings.setdefault(name, {})
        if not isinstance(table, dict):
            continue
        r = rng.random()
        if r < 0.35:
            table["step_file"] = rng.choice(RING_FILES)
            if rng.random() < 0.3:
                table["step_unit"] = rng.choice(["mm", "m", "file", "inch", 3])
        elif r < 0.75:
            table[rng.choice(RING_KEYS + ["bogus"])] = _value(rng) if rng.random() < 0.6 else rng.choice(RING_FILES)
        elif r < 0.9:
            bolts = table.setdefault("bolts", {})
            if isinstance(bolts, dict):
                bolts[rng.choice(BOLT_KEYS + ["bogus"])] = _value(rng)
        else:
            table.pop(rng.choice(RING_KEYS), None)
    return data


def test_fuzz_ring_tables(tmp_path):
    """Mutated ``[rings.X]`` tables (sections, supports, STEP and DXF files) are refused in one line
    naming ``rings.X.key`` (or the file); a STEP ring is checked without meshing."""
    from tests.test_bearing_rings import SMALL
    from tests.test_step_ring import TET, write_ring_step

    from fem_rings.mesh import gmsh_session

    bases = [tomllib.loads(TET), tomllib.loads(SMALL)]  # tet10 outer ring; hex27 rings
    write_ring_step(loads_bearing(TET).rings["outer"].profile, tmp_path / "outer.step")
    (tmp_path / "junk.step").write_text("ISO-10303-21;\nnot really\n")
    (tmp_path / "outer.dxf").write_text("0\nSECTION\n0\nEOF\n")
    with gmsh_session("writer") as gmsh:
        gmsh.model.occ.addDisk(0, 0, 0, 300, 300)
        gmsh.model.occ.synchronize()
        gmsh.write(str(tmp_path / "disk.step"))
    rng = random.Random(SEED)
    refused, start = 0, time.perf_counter()
    for i in range(N_RING_FILES):
        data = _mutate_rings(rng, bases[0] if rng.random() < 0.8 else bases[1])
        path = tmp_path / f"r{i}.toml"
        path.write_text(tomli_w.dumps(data))
        try:
            read_bearing_file(path)
        except CaseError as exc:
            _assert_names_a_key(str(exc), str(path))
            refused += 1
    assert refused > N_RING_FILES // 2
    assert time.perf_counter() - start < 60.0
