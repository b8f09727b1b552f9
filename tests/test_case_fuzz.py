"""Fuzz of case files and ``--set`` values: every bad input is a one-line error naming a key or the file.

A seeded generator mutates the TOML of the named cases (both families) and writes ``--set``
assignments with existing and made-up keys and with wrong types, NaN, ±inf, huge, negative and zero
numbers, strings, lists and tables; it also writes files that are not TOML, not UTF-8, nested too
deeply, empty or without their family. Each input goes through the resolve/validate path only
(:func:`cases.run.resolve_case`, and the command line with the run itself replaced), never
meshing or simulating. The property checked: no exception other than :class:`cases.config.CaseError`
escapes, and its message is one line that starts with the file or a dotted key of the case (or
the ``--quick`` or ``--set`` option that carried it).
"""

from __future__ import annotations

import dataclasses
import json
import math
import random
import re
from types import SimpleNamespace
from typing import get_type_hints

import pytest
import tomli_w

from tests.fuzz_values import random_value

import cases.run
from cases.cli import main
from cases.config import FAMILY_KEY, CaseError, to_mapping
from cases.run import _FAMILIES, PRESETS, resolve_case

SEED = 20261125
N_FILES = 3000
N_SETS = 3000
N_CLI = 200


def _key_paths(cls: type, prefix: str = "") -> list[str]:
    """Every dotted key of a case class, tables included."""
    out = []
    hints = get_type_hints(cls)
    for f in dataclasses.fields(cls):
        path = f"{prefix}{f.name}"
        out.append(path)
        hint = hints[f.name]
        if dataclasses.is_dataclass(hint):
            out += _key_paths(hint, path + ".")
    return out


KEYS = {cls: _key_paths(cls) for cls in _FAMILIES}  # every family's keys
TOP_LEVEL = {f.name for cls in KEYS for f in dataclasses.fields(cls)} | {FAMILY_KEY}

NUMBERS = [0, -1, 1, 3, 7, 2**63 - 1, -(2**63), 10**6, math.nan, math.inf, -math.inf, 1e308, -1e308, 1e-308,
           5e-324, 0.0, -0.0, 0.5, 0.525, 2.5, 1e-3, 1e9, -1e-9]
WORDS = ["", "x", "rigid", "modal", "hertz", "thesis", "adams", "csv", "constant", "full", "1m", "2m", "static",
         "single", "life", "quasi_static", "dynamic_explicit", "Ünïcødé ✓", "two\nlines", "a" * 500, "nan", "inf"]


def _value(rng: random.Random):
    """A random TOML value: numbers of every kind, strings, booleans, lists and tables."""
    return random_value(rng, NUMBERS, WORDS, ["a", "kind", "n_modes", "x y", "scale"], max_depth=3, max_items=5,
                        exponent=12)


def _toml_text(value) -> str:
    """``value`` spelled as a TOML value (inline tables for tables)."""
    return tomli_w.dumps({"v": value}).partition("=")[2].strip() if not isinstance(value, dict) else \
        "{" + ", ".join(f'"{k}" = {_toml_text(v)}' for k, v in value.items()) + "}"


def _key(rng: random.Random, cls: type) -> str:
    """An existing key, or one made up from existing ones (typos, extra or missing levels)."""
    key = rng.choice(KEYS[cls])
    r = rng.random()
    if r < 0.65:
        return key
    if r < 0.75:
        return key + "x"
    if r < 0.85:
        return key + "." + rng.choice(["a", "n_modes", "0"])
    if r < 0.9:
        return "." + key if rng.random() < 0.5 else key + "."
    if r < 0.95:
        return rng.choice(["", " ", "bogus", "family", "top..kind", "Top.Kind"])
    return key.split(".")[-1]


def _set(node: dict, path: list[str], value) -> None:
    for name in path[:-1]:
        nxt = node.get(name)
        if not isinstance(nxt, dict):
            nxt = node[name] = {}
        node = nxt
    node[path[-1]] = value


def _mutated_mapping(rng: random.Random, cls: type, case, used: set[str]) -> dict:
    """The case's table with keys set to random values, removed or made up (their parts go to ``used``)."""
    data = {FAMILY_KEY: cls.FAMILY, **to_mapping(case)} if rng.random() < 0.8 else to_mapping(case)
    for _ in range(rng.randint(1, 4)):
        key = [p for p in _key(rng, cls).split(".") if p] or ["name"]
        used.update(key)
        r = rng.random()
        if r < 0.75:
            _set(data, key, _value(rng))
        elif r < 0.9:
            node = data
            for name in key[:-1]:
                node = node.get(name) if isinstance(node.get(name), dict) else {}
            node.pop(key[-1], None)
        else:
            data[FAMILY_KEY] = rng.choice(["slewing", "wind", "Wind", "", 3, ["wind"]])
    return data


def _broken_file(rng: random.Random, text: str) -> bytes:
    """Bytes that are not a valid case file: cut, garbled, non-UTF-8, nested, empty."""
    r = rng.random()
    if r < 0.2:
        return text[: rng.randint(0, len(text))].encode()
    if r < 0.4:
        i = rng.randint(0, len(text))
        return (text[:i] + rng.choice(["[", "]", "=", '"', "\n[[x]]\n", "{", "\\", "\x00", "key"]) + text[i:]).encode()
    if r < 0.55:
        raw = bytearray(text.encode())
        raw.insert(rng.randint(0, len(raw)), rng.choice([0xFF, 0xC3, 0x80, 0xFE]))
        return bytes(raw)
    if r < 0.65:
        n = rng.choice([50, 1000, 100_000])
        return ("a = " + "[" * n + "]" * n + "\n").encode()
    if r < 0.75:
        return ("x = " + "{a = " * 2000 + "1" + "}" * 2000).encode()
    if r < 0.9:
        return rng.choice([b"", b"\n\n", b"# only a comment\n", b"   \t\n# a\n#b\n", "\ufeff".encode()])
    return bytes(rng.randrange(256) for _ in range(rng.randint(1, 200)))


#: what a message about the file as a whole (rather than one key) says after the file's name
FILE_LEVEL = ("invalid TOML", "not UTF-8 text", "no case entries", "family: ")


def _assert_names_a_key(message: str, source: str, used: set[str]) -> None:
    assert "\n" not in message and "Traceback" not in message, message
    if source and message.startswith(source + ": "):  # else an option applied after reading it
        message = message[len(source) + 2:]
        if message.startswith(FILE_LEVEL):
            return
    segment = r"(?:'[^']*'|\"[^\"]*\"|[\w\-\[\]]+)"  # a plain or a quoted key, with [i] indices
    match = re.match(rf"{segment}(?:\.{segment})*", message)
    lead = match.group(0) if match else ""
    top = re.sub(r"\[\d+\]", "", re.match(segment, lead).group(0) if lead else "").strip("'\"")
    named = top in TOP_LEVEL or top in used or lead in ("--quick", "--set")
    assert (lead and named) or any(message.startswith(f"{u}: ") for u in used), message


def _check(source: str, call, used: set[str]) -> bool:
    """Run ``call``; True when it was refused with a good message, False when accepted."""
    try:
        call()
    except CaseError as exc:
        _assert_names_a_key(str(exc), source, used)
        return True
    return False


def test_fuzz_case_files(tmp_path):
    rng = random.Random(SEED)
    names = sorted(PRESETS)
    refused = 0
    for i in range(N_FILES):
        case = PRESETS[rng.choice(names)]
        cls = type(case)
        used: set[str] = set()
        text = tomli_w.dumps(_mutated_mapping(rng, cls, case, used)) if rng.random() < 0.8 else None
        path = tmp_path / f"case{i}.toml"
        if text is None or rng.random() < 0.1:
            from cases.config import dumps_case

            raw = _broken_file(rng, text or dumps_case(case))
            path.write_bytes(raw)
            used |= set(re.findall(r"[\w\-]+", raw.decode("utf-8", "replace")))  # keys it may hold
        else:
            path.write_text(text, encoding="utf-8")
        refused += _check(str(path), lambda: resolve_case(str(path), rng.random() < 0.3), used)
    assert refused > N_FILES // 2  # the generator mostly makes bad files


def test_fuzz_set_values():
    rng = random.Random(SEED + 1)
    names = sorted(PRESETS)
    refused = 0
    for _ in range(N_SETS):
        name = rng.choice(names)
        cls = type(PRESETS[name])
        sets, used = [], set()
        for _ in range(rng.randint(1, 3)):
            key = _key(rng, cls)
            used |= {p.strip() for p in key.split(".")}
            r = rng.random()
            rhs = (_toml_text(_value(rng)) if r < 0.7 else
                   rng.choice(["[[[", "{", "1 2", "'open", "]", "1\nx = 2", "=", "[" * 5000 + "]" * 5000, "-inf",
                               "nan", "+inf", "1e999", "0x10", "1_000", "true", "True", "2026-11-25"]))
            sets.append(f"{key}={rhs}" if rng.random() < 0.95 else key)
            used.add(sets[-1])  # a --set without "=" is named as given
        refused += _check("", lambda: resolve_case(name, rng.random() < 0.3, sets), used)
    assert refused > N_SETS // 2


def test_fuzz_command_line(tmp_path, monkeypatch, capsys):
    """The same ``--set`` inputs through ``flexbearing run`` (the run itself replaced): exit status 2
    and one line on stderr for a bad input, 0 for a good one, never a traceback."""
    done = SimpleNamespace(report=[], folder=tmp_path, summary={"wall_time_s": 0.0, "peak_rss_mb": 0.0})
    monkeypatch.setattr(cases.run, "run_case", lambda case, out_dir, progress=None, resume=False, source=None: done)
    rng = random.Random(SEED + 2)
    names = sorted(PRESETS)
    for _ in range(N_CLI):
        name = rng.choice(names)
        cls = type(PRESETS[name])
        argv = ["run", name, "--out", str(tmp_path / "out")]
        for _ in range(rng.randint(1, 3)):
            argv += ["--set", f"{_key(rng, cls)}={_toml_text(_value(rng))}"]
        if rng.random() < 0.3:
            argv.append("--quick")
        status = main(argv)
        err = capsys.readouterr().err
        assert status in (0, 2), (argv, err)
        assert "Traceback" not in err
        if status == 2:
            assert err.startswith("flexbearing: error: ") and err.count("\n") == 1, err


@pytest.mark.parametrize("rhs", ["nan", "inf", "-inf", "1e999"])
def test_non_finite_numbers_are_refused_naming_the_key(rhs):
    # before the fix, NaN and ±inf passed every `x > 0` style check (comparisons with NaN are false)
    with pytest.raises(CaseError, match=r"^undulation\.profile_deg_mm\[1\]\[1\]: expected a finite number"):
        resolve_case("slewing-undulation",
                     overrides=[f"undulation.profile_deg_mm=[[0, 0], [90, {rhs}], [180, 0], [270, 0]]"])


HERTZ = {
    "ball": ["--ball-diameter-mm", "--conformity", "--pitch-diameter-mm", "--contact-angle-deg", "--load-N", "--E-GPa",
             "--nu"],
    "spheres": ["--diameter-1-mm", "--diameter-2-mm", "--load-N", "--E-GPa", "--nu"],
    "line": ["--roller-diameter-mm", "--raceway-diameter-mm", "--length-mm", "--load-N", "--E-GPa", "--nu"],
}
GOOD = {"--ball-diameter-mm": 95.25, "--conformity": 0.525, "--pitch-diameter-mm": 6690, "--contact-angle-deg": 60,
        "--load-N": 5e4, "--E-GPa": 207, "--nu": 0.29, "--diameter-1-mm": 95.25, "--diameter-2-mm": 85.25,
        "--roller-diameter-mm": 55, "--raceway-diameter-mm": 1908, "--length-mm": 55}


def test_fuzz_hertz_numbers(capsys):
    """``flexbearing hertz`` with one or two numbers replaced by NaN, ±inf, huge, tiny, negative or
    zero values: exit status 0 with strict JSON, or 2 with one line naming an option."""
    rng = random.Random(SEED + 3)
    for _ in range(300):
        geometry = rng.choice(sorted(HERTZ))
        values = {k: GOOD[k] for k in HERTZ[geometry]}
        for k in rng.sample(HERTZ[geometry], rng.randint(1, 2)):
            values[k] = rng.choice(NUMBERS)
        argv = ["hertz", geometry, *(f"{k}={v!r}" for k, v in values.items()), "--json"]
        status = main(argv)
        out, err = capsys.readouterr()
        assert status in (0, 2) and "Traceback" not in err, (argv, err)
        if status == 0:
            json.loads(out, parse_constant=lambda c: pytest.fail(f"{argv}: non-standard JSON constant {c}"))
        else:
            assert err.startswith("flexbearing: error: ") and err.count("\n") == 1, (argv, err)
            assert any(k in err for k in HERTZ[geometry]) or "roller" in err, (argv, err)
