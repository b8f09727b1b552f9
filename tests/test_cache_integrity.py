"""The FE-model and reduced-body caches: damaged entries are reported, rebuilt and replaced;
a cache that cannot be written costs a warning, not the run; killed writers' files are removed.

Reference for every rebuilt model: the same model assembled without the cache
(``use_cache=False``), compared exactly (same code path, so bit-identical).
"""

import json
import logging
import os
import subprocess
import sys

import numpy as np
import pytest

from cms_reduction.persist import cached_body, load_body, save_body
from fem_rings import cache
from fem_rings.mesh import MeshSpec
from fem_rings.model import build_model
from fem_rings.profile import rectangle
from foundation.materials import ElasticMaterial
from test_persist import _assert_same_arrays, _body

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
PROFILE = rectangle("ring", 0.95, 1.05, -0.1, 0.1)
SPEC = MeshSpec(0.06, "hex27", sector_deg=120.0)


@pytest.fixture(scope="module")
def reference():
    return build_model(PROFILE, SPEC, STEEL, use_cache=False)


def _entry(tmp_path):
    (entry,) = (tmp_path / "fe-model").glob("*.npz")
    return entry


def _truncate(p):
    p.write_bytes(p.read_bytes()[: p.stat().st_size // 2])


def _flip_byte(p):  # inside the stored K data: a bad CRC-32
    data = bytearray(p.read_bytes())
    data[len(data) // 3] ^= 0xFF
    p.write_bytes(bytes(data))


def _drop_member(p):  # a valid npz without K's values (KeyError on the original code)
    with np.load(p) as f:
        arrays = {k: f[k] for k in f.files if k != "K_data"}
    np.savez(p, **arrays)


def _alter_K(p):  # a valid npz, every member present, K doubled
    with np.load(p) as f:
        arrays = {k: f[k] for k in f.files}
    arrays["K_data"] = 2.0 * arrays["K_data"]
    np.savez(p, **arrays)


def _empty(p):
    p.write_bytes(b"")


@pytest.mark.parametrize("damage", [_truncate, _flip_byte, _drop_member, _alter_K, _empty])
def test_a_damaged_fe_entry_is_reported_rebuilt_and_replaced(tmp_path, monkeypatch, caplog, reference, damage):
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path))
    build_model(PROFILE, SPEC, STEEL)
    entry = _entry(tmp_path)
    damage(entry)
    with caplog.at_level(logging.WARNING, logger="fem_rings.cache"):
        model = build_model(PROFILE, SPEC, STEEL)
    assert "assemble" in model.timings_s  # rebuilt, not loaded
    assert str(entry) in caplog.text and "rebuilding" in caplog.text
    assert abs(model.K - reference.K).max() == 0.0 and abs(model.M - reference.M).max() == 0.0
    again = build_model(PROFILE, SPEC, STEEL)  # the entry was replaced by a good one
    assert "cache_load" in again.timings_s
    assert abs(again.K - reference.K).max() == 0.0


def test_an_unwritable_cache_warns_and_the_run_goes_on(tmp_path, monkeypatch, caplog, reference):
    blocker = tmp_path / "cache-is-a-file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("FLEXBEARING_CACHE", str(blocker))
    with caplog.at_level(logging.WARNING):
        model = build_model(PROFILE, SPEC, STEEL)
        body = cached_body("ring-abc", lambda: _body(seed=3))
    assert abs(model.K - reference.K).max() == 0.0
    _assert_same_arrays(body.shapes, _body(seed=3).shapes)
    assert "could not write cache entry" in caplog.text and "could not store reduced body" in caplog.text
    assert blocker.read_text() == "not a folder"


def test_a_full_disk_warns_and_the_run_goes_on(tmp_path, monkeypatch, caplog, reference):
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path))

    def savez(path, **arrays):
        with open(path, "wb") as fh:
            fh.write(b"PK")  # a few bytes, then the disk is full
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(cache.np, "savez", savez)
    with caplog.at_level(logging.WARNING):
        model = build_model(PROFILE, SPEC, STEEL)
    assert abs(model.K - reference.K).max() == 0.0
    assert "No space left on device" in caplog.text
    assert list((tmp_path / "fe-model").iterdir()) == []  # no partial file left


def test_a_read_only_cache_warns_and_the_run_goes_on(tmp_path, monkeypatch, caplog):
    if os.geteuid() == 0:
        pytest.skip("root ignores folder permissions")
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path))
    (tmp_path / "fe-model").mkdir(mode=0o555)
    with caplog.at_level(logging.WARNING):
        build_model(PROFILE, SPEC, STEEL)
    assert "could not write cache entry" in caplog.text


def _dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_killed_writers_part_files_are_removed_at_the_next_use(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path))
    folder = tmp_path / "fe-model"
    folder.mkdir()
    stale = folder / f".abc.npz.{_dead_pid()}-0123456789ab.part.npz"
    live = folder / f".abc.npz.{os.getppid()}-0123456789ab.part.npz"  # a process that is running
    other = folder / "notes.part.npz"  # not a name the cache writes
    for p in (stale, live, other):
        p.write_bytes(b"partial")
    build_model(PROFILE, SPEC, STEEL)
    assert not stale.exists() and live.exists() and other.exists()


def test_an_edited_reduced_body_sidecar_is_refused_and_rebuilt(tmp_path, monkeypatch, caplog):
    npz = save_body(_body(), tmp_path / "ring")
    js = npz.with_suffix(".json")
    header = json.loads(js.read_text())
    header["floating"] = False  # the npz is untouched: only the sidecar's hash can tell
    js.write_text(json.dumps(header))
    with pytest.raises(ValueError, match=r"ring\.json: metadata file is corrupt or modified"):
        load_body(npz)
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path))
    first = cached_body("ring-abc", lambda: _body(seed=3))
    js = tmp_path / "reduced" / "ring-abc.json"
    header = json.loads(js.read_text())
    header["frequencies_Hz"][0] *= 2.0
    js.write_text(json.dumps(header))
    with caplog.at_level(logging.WARNING, logger="cms_reduction.persist"):
        again = cached_body("ring-abc", lambda: _body(seed=3))
    assert "ring-abc.json" in caplog.text and "rebuilding" in caplog.text
    _assert_same_arrays(again.frequencies_Hz, first.frequencies_Hz)
    assert load_body(js).floating is True  # replaced by a good pair


def test_content_hash_tells_names_shapes_and_values_apart():
    a = {"x": np.arange(6.0)}
    assert cache.content_hash(a) == cache.content_hash({"x": np.arange(6.0)})
    for other in ({"y": np.arange(6.0)}, {"x": np.arange(6.0).reshape(2, 3)}, {"x": np.arange(6)},
                  {"x": np.arange(6.0) + 1e-300}):
        assert cache.content_hash(other) != cache.content_hash(a)
