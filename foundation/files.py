"""Files that appear complete or not at all."""

from __future__ import annotations

import os
import uuid
from contextlib import contextmanager
from pathlib import Path

__all__ = ["atomic_path"]


@contextmanager
def atomic_path(path: Path, suffix: str = ""):
    """Yield a temporary file name next to ``path``; rename it to ``path`` on success.

    The file appears under its final name only when complete (``os.replace`` within one folder
    is atomic on POSIX and Windows); on error the temporary file is removed.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    # a unique name that the writer creates itself, so the file gets the usual permissions
    # (tempfile.mkstemp would leave it readable by the owner only)
    tmp = path.with_name(f".{path.name}.{os.getpid()}-{uuid.uuid4().hex[:12]}.part{suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
