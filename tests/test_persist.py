"""Saving and loading reduced bodies: bit-identical round trip, refusal of bad files, the cache."""

import hashlib
import json
import logging

import numpy as np
import pytest

from cms_reduction import persist
from cms_reduction.body import ReducedBody
from cms_reduction.persist import FORMAT_VERSION, body_paths, cached_body, load_body, save_body


def _body(seed=0, n_nodes=20, n_modes=4):
    rng = np.random.default_rng(seed)
    nodes = rng.standard_normal((n_nodes, 3))
    return ReducedBody(
        name="outer ring",
        nodes_m=nodes,
        shapes=rng.standard_normal((3 * n_nodes, n_modes)),
        frequencies_Hz=np.sort(rng.uniform(10.0, 500.0, n_modes)),
        damping_ratio=np.full(n_modes, 0.02),
        floating=True,
        mesh_kind="tet10",
        mesh_doflocs=nodes.T.copy(),
        mesh_t=rng.integers(0, n_nodes, size=(10, 3)),
        metadata={"inputs": {"profile": "rect", "size_m": 0.05, "n_theta": [24, 48]}, "hash": "abc123"},
        extras={"inv:mass_kg": np.array(12.5), "raceway:theta_rad": rng.uniform(0, 6.28, 7),
                "stress:modes": rng.standard_normal((n_nodes, 6, n_modes)).astype(np.float32)},
    )


_ARRAYS = ("nodes_m", "shapes", "frequencies_Hz", "damping_ratio", "mesh_doflocs", "mesh_t")


def _assert_same_arrays(a, b):
    assert a.dtype == b.dtype and a.shape == b.shape
    assert a.tobytes() == b.tobytes()


def test_round_trip_is_bit_identical(tmp_path):
    body = _body()
    npz = save_body(body, tmp_path / "sub" / "ring")
    assert npz == tmp_path / "sub" / "ring.npz" and npz.with_suffix(".json").exists()
    assert not list((tmp_path / "sub").glob("*.part"))
    for where in (npz, npz.with_suffix(".json"), tmp_path / "sub" / "ring"):
        back = load_body(where)
        for name in _ARRAYS:
            _assert_same_arrays(getattr(back, name), getattr(body, name))
        assert back.extras.keys() == body.extras.keys()
        for name, a in body.extras.items():
            _assert_same_arrays(back.extras[name], a)
        assert (back.name, back.floating, back.mesh_kind) == (body.name, body.floating, body.mesh_kind)
        assert back.metadata == body.metadata
    header = json.loads(npz.with_suffix(".json").read_text())
    assert header["format_version"] == FORMAT_VERSION == 2
    assert (header["n_modes"], header["n_nodes"]) == (4, 20)
    assert header["frequencies_Hz"] == body.frequencies_Hz.tolist()
    assert header["units"]["shapes"] == "m/sqrt(kg)" and header["units"]["nodes_m"] == "m"


def test_body_paths_keep_dotted_stems(tmp_path):
    assert body_paths(tmp_path / "ring.v2") == (tmp_path / "ring.v2.npz", tmp_path / "ring.v2.json")
    assert body_paths(tmp_path / "ring.v2.json") == (tmp_path / "ring.v2.npz", tmp_path / "ring.v2.json")


def test_truncated_or_altered_npz_is_refused(tmp_path):
    npz = save_body(_body(), tmp_path / "ring")
    data = npz.read_bytes()
    npz.write_bytes(data[: len(data) // 2])
    with pytest.raises(ValueError, match="corrupt or modified"):
        load_body(npz)
    save_body(_body(), tmp_path / "ring")
    altered = bytearray(npz.read_bytes())
    altered[len(altered) // 2] ^= 0x01
    npz.write_bytes(bytes(altered))
    with pytest.raises(ValueError, match="corrupt or modified"):
        load_body(npz)


def test_other_format_version_is_refused_naming_both(tmp_path):
    npz = save_body(_body(), tmp_path / "ring")
    js = npz.with_suffix(".json")
    header = json.loads(js.read_text())
    header["format_version"] = 0
    js.write_text(json.dumps(header))
    with pytest.raises(ValueError, match=r"format_version 0.*format_version 2; rebuild"):
        load_body(npz)


def test_missing_json_or_array_is_named(tmp_path):
    npz = save_body(_body(), tmp_path / "ring")
    npz.with_suffix(".json").unlink()
    with pytest.raises(FileNotFoundError, match=r"ring\.json: metadata file .* missing"):
        load_body(npz)
    # An npz without `shapes` but with a consistent hash: the array is named.
    body = _body()
    arrays = {k: getattr(body, k) for k in _ARRAYS if k != "shapes"}
    npz = save_body(body, tmp_path / "other")
    np.savez(npz, **arrays)
    js = npz.with_suffix(".json")
    header = json.loads(js.read_text())
    header["npz_sha256"] = hashlib.sha256(npz.read_bytes()).hexdigest()
    header["header_sha256"] = persist._header_sha256(header)
    js.write_text(json.dumps(header))
    with pytest.raises(ValueError, match="required array 'shapes' missing"):
        load_body(npz)


def test_unserialisable_metadata_fails_before_writing(tmp_path):
    body = _body()
    body.metadata["bad"] = object()
    with pytest.raises(TypeError, match="metadata is not JSON-serialisable"):
        save_body(body, tmp_path / "ring")
    assert not list(tmp_path.iterdir())


def test_cached_body_builds_once_then_loads(tmp_path, monkeypatch, caplog):
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path))
    calls = []

    def build():
        calls.append(1)
        return _body(seed=3)

    with caplog.at_level(logging.INFO, logger="cms_reduction.persist"):
        first = cached_body("ring-abc", build)
        second = cached_body("ring-abc", build)
    assert len(calls) == 1
    assert all((tmp_path / "reduced" / f"ring-abc.{ext}").exists() for ext in ("npz", "json"))
    assert "building" in caplog.text and "loaded" in caplog.text
    _assert_same_arrays(second.shapes, first.shapes)
    # A corrupted entry is rebuilt, not returned.
    npz = tmp_path / "reduced" / "ring-abc.npz"
    npz.write_bytes(npz.read_bytes()[:100])
    third = cached_body("ring-abc", build)
    assert len(calls) == 2
    _assert_same_arrays(third.shapes, first.shapes)
    assert load_body(npz).n_modes == first.n_modes
    with pytest.raises(ValueError, match="plain file name"):
        cached_body("../escape", build)
