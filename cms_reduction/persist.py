"""Reduced bodies on disk: one ``.npz`` of arrays plus a ``.json`` sidecar of metadata.

Layout of a pair ``<stem>.npz`` / ``<stem>.json``:

* npz: ``nodes_m``, ``shapes``, ``frequencies_Hz``, ``damping_ratio``, ``mesh_doflocs``, ``mesh_t``
  and every extras array as ``extra:<name>`` (e.g. ``extra:inv:mass_kg``); read without pickle;
* json: ``format_version``, name, floating, mesh_kind, n_modes, n_nodes, frequencies_Hz, units,
  the body's ``metadata`` (inputs, hash), the array names, ``npz_sha256``, the SHA-256 of the
  npz bytes, and ``header_sha256``, the SHA-256 of all other entries (canonical JSON: sorted keys),
  so an edited sidecar is caught like an edited npz.

Both files are written atomically (temporary name in the same folder, then ``os.replace``), the
npz first and the json last, and an existing json is removed before its npz is replaced: a json
is only ever present next to the npz it describes, and the hash catches any later change.
:func:`load_body` refuses a pair that is incomplete, of another format version, or whose npz or
json does not match its hash; :func:`cached_body` then rebuilds (with a warning naming the file) and
goes on without storing when the cache cannot be written.
"""

from __future__ import annotations

import hashlib
import json
import logging
from pathlib import Path
from typing import Callable

import numpy as np

from fem_rings.cache import atomic_path, cache_dir, clean_stale_parts
from foundation.npzfile import NPZ_ERRORS, read_npz

from .body import ReducedBody

__all__ = ["FORMAT_VERSION", "UNITS", "save_body", "load_body", "cached_body", "body_paths"]

log = logging.getLogger(__name__)

#: Version of the stored layout; a file of another version is refused (rebuild the body).
#: 2: the json carries ``header_sha256``.
FORMAT_VERSION = 2

#: Units of the stored arrays (extras carry theirs in their names).
UNITS = {
    "nodes_m": "m",
    "shapes": "m/sqrt(kg)",
    "frequencies_Hz": "Hz",
    "damping_ratio": "1",
    "mesh_doflocs": "m",
    "mesh_t": "node index",
    "modal_coordinates": "sqrt(kg)",
}

_REQUIRED = ("nodes_m", "shapes", "frequencies_Hz", "damping_ratio", "mesh_doflocs", "mesh_t")
_EXTRA = "extra:"
_CHUNK_BYTES = 1 << 20


def body_paths(path) -> tuple[Path, Path]:
    """(npz, json) paths of a body file given either file or their common stem."""
    p = Path(path)
    if p.suffix in (".npz", ".json"):
        p = p.with_suffix("")
    return p.with_name(p.name + ".npz"), p.with_name(p.name + ".json")


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(_CHUNK_BYTES), b""):
            h.update(block)
    return h.hexdigest()


def _header_sha256(header: dict) -> str:
    """SHA-256 of the sidecar's entries other than ``header_sha256`` (canonical JSON)."""
    rest = {k: v for k, v in header.items() if k != "header_sha256"}
    text = json.dumps(json.loads(json.dumps(rest, allow_nan=False)), sort_keys=True, ensure_ascii=False,
                      separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _arrays(body: ReducedBody) -> dict:
    arrays = {name: np.asarray(getattr(body, name)) for name in _REQUIRED}
    for name, value in body.extras.items():
        a = np.asarray(value)
        if a.dtype == object:
            raise TypeError(f"body {body.name!r}: extras[{name!r}] is not a numeric array (dtype object)")
        arrays[_EXTRA + str(name)] = a
    return arrays


def save_body(body: ReducedBody, path) -> Path:
    """Write a reduced body as ``<stem>.npz`` + ``<stem>.json``.

    Parameters
    ----------
    body : ReducedBody
        ``metadata`` must be JSON-serialisable (tuples come back as lists).
    path : str or Path
        The stem, or either file of the pair; folders are created.

    Returns
    -------
    Path
        The npz file.
    """
    npz_path, json_path = body_paths(path)
    arrays = _arrays(body)
    header = {
        "format_version": FORMAT_VERSION,
        "name": body.name,
        "floating": bool(body.floating),
        "mesh_kind": body.mesh_kind,
        "n_modes": int(body.n_modes),
        "n_nodes": int(len(body.nodes_m)),
        "frequencies_Hz": [float(f) for f in body.frequencies_Hz],
        "units": UNITS,
        "metadata": body.metadata,
        "arrays": {k: {"shape": list(a.shape), "dtype": str(a.dtype)} for k, a in arrays.items()},
    }
    try:  # fail before touching the files
        json.dumps(header, allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"body {body.name!r}: metadata is not JSON-serialisable: {exc}") from exc
    npz_path.parent.mkdir(parents=True, exist_ok=True)
    json_path.unlink(missing_ok=True)
    with atomic_path(npz_path, ".npz") as tmp:
        np.savez(tmp, **arrays)
    header["npz_sha256"] = _sha256(npz_path)
    header["header_sha256"] = _header_sha256(header)
    text = json.dumps(header, indent=1, ensure_ascii=False, allow_nan=False) + "\n"
    with atomic_path(json_path, ".json") as tmp:
        tmp.write_text(text, encoding="utf-8")
    log.info("saved reduced body %r (%d nodes, %d modes) to %s", body.name, header["n_nodes"],
             header["n_modes"], npz_path)
    return npz_path


def _read_header(json_path: Path, npz_path: Path) -> dict:
    if not json_path.exists():
        raise FileNotFoundError(f"{json_path}: metadata file of the reduced body missing "
                                f"(incomplete save?); rebuild the body or save it again")
    if not npz_path.exists():
        raise FileNotFoundError(f"{npz_path}: array file of the reduced body missing")
    try:
        header = json.loads(json_path.read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ValueError(f"{json_path}: not a valid JSON metadata file ({exc})") from exc
    if not isinstance(header, dict):
        raise ValueError(f"{json_path}: metadata must be a JSON object")
    version = header.get("format_version")
    if version != FORMAT_VERSION:
        raise ValueError(f"{json_path}: reduced body has format_version {version!r}, this version of "
                         f"flexbearing reads format_version {FORMAT_VERSION}; rebuild the body")
    for key in ("name", "floating", "mesh_kind", "n_modes", "n_nodes", "npz_sha256", "header_sha256"):
        if key not in header:
            raise ValueError(f"{json_path}: metadata entry {key!r} missing")
    if _header_sha256(header) != header["header_sha256"]:
        raise ValueError(f"{json_path}: metadata file is corrupt or modified (its entries do not match "
                         f"header_sha256); rebuild the body")
    return header


def load_body(path) -> ReducedBody:
    """Read a body written by :func:`save_body`.

    Parameters
    ----------
    path : str or Path
        The stem or either file of the pair.

    Raises
    ------
    FileNotFoundError
        Either file of the pair is missing.
    ValueError
        Other format version, npz not matching its recorded hash ("corrupt or modified"),
        a required array missing, or sizes disagreeing with the metadata.
    """
    npz_path, json_path = body_paths(path)
    header = _read_header(json_path, npz_path)
    digest = _sha256(npz_path)
    if digest != header["npz_sha256"]:
        raise ValueError(f"{npz_path}: array file is corrupt or modified (SHA-256 {digest[:16]}…, "
                         f"metadata records {str(header['npz_sha256'])[:16]}…); rebuild the body")
    try:
        arrays = read_npz(npz_path)
    except NPZ_ERRORS as exc:
        raise ValueError(f"{npz_path}: unreadable array file ({type(exc).__name__}: {exc})") from None
    for name in _REQUIRED:
        if name not in arrays:
            raise ValueError(f"{npz_path}: required array {name!r} missing")
    body = ReducedBody(
        name=header["name"],
        nodes_m=arrays["nodes_m"],
        shapes=arrays["shapes"],
        frequencies_Hz=arrays["frequencies_Hz"],
        damping_ratio=arrays["damping_ratio"],
        floating=bool(header["floating"]),
        mesh_kind=header["mesh_kind"],
        mesh_doflocs=arrays["mesh_doflocs"],
        mesh_t=arrays["mesh_t"],
        metadata=header.get("metadata", {}),
        extras={k[len(_EXTRA):]: a for k, a in arrays.items() if k.startswith(_EXTRA)},
    )
    if (body.n_modes, len(body.nodes_m)) != (header["n_modes"], header["n_nodes"]):
        raise ValueError(f"{npz_path}: arrays hold {len(body.nodes_m)} nodes and {body.n_modes} modes, "
                         f"metadata says {header['n_nodes']} and {header['n_modes']}")
    return body


def cached_body(key: str, build: Callable[[], ReducedBody]) -> ReducedBody:
    """The body stored under ``key`` in the cache, or ``build()`` stored there.

    Parameters
    ----------
    key : str
        File stem in ``cache_dir()/"reduced"`` (e.g. :func:`fem_rings.cache.input_hash` of the
        reduction inputs).
    build : callable () -> ReducedBody
        Called only when no valid entry exists (absent, incomplete, other version, corrupt).
    """
    key = str(key)
    if not key or Path(key).name != key or key in (".", ".."):
        raise ValueError(f"cache key must be a plain file name, got {key!r}")
    npz_path = cache_dir() / "reduced" / f"{key}.npz"
    clean_stale_parts(npz_path.parent)
    if npz_path.exists() or npz_path.with_suffix(".json").exists():
        try:
            body = load_body(npz_path)
        except (OSError, ValueError) as exc:
            log.warning("rebuilding reduced body %s: cached entry unusable (%s)", key, exc)
        else:
            log.info("loaded reduced body %r from cache %s", body.name, npz_path)
            return body
    else:
        log.info("building reduced body %s (not in cache)", key)
    body = build()
    if not isinstance(body, ReducedBody):
        raise TypeError(f"build() must return a ReducedBody, got {type(body).__name__}")
    try:
        save_body(body, npz_path)
    except OSError as exc:
        log.warning("could not store reduced body %s in the cache (%s): going on without it", npz_path, exc)
    return body
