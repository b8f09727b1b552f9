"""Reading a ``.npz`` file whole, and the errors a damaged one raises (shared by every reader of
the project's npz files: FE-model cache, reduced bodies, run records, case checkpoints)."""

from __future__ import annotations

import zipfile
import zlib

import numpy as np

__all__ = ["NPZ_ERRORS", "read_npz"]

#: what reading a damaged .npz may raise: truncated or empty (BadZipFile, EOFError), bad CRC-32
#: (BadZipFile), damaged compression (zlib.error), missing member (KeyError), bad array header
#: (ValueError), unreadable file (OSError)
NPZ_ERRORS = (OSError, ValueError, EOFError, KeyError, zipfile.BadZipFile, zlib.error)


def read_npz(path) -> dict:
    """All arrays of an npz file (read without pickle); raises one of :data:`NPZ_ERRORS`."""
    with np.load(path, allow_pickle=False) as f:
        return {k: f[k] for k in f.files}
