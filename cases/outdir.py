"""Results folders: written aside, swapped in whole, never replacing what the project did not write.

A run writes into a temporary folder beside the target and, when it completes, swaps it in:

1. the finished folder gets the marker file :data:`MARKER` (JSON: format, case name and, for a
   case run, ``source``: the named case or the case file it came from, :func:`marker_source`);
2. an existing target is exchanged with the new folder in one atomic step (Linux ``renameat2``
   ``RENAME_EXCHANGE``) and the old result, now in the temporary folder, is deleted; where the
   system cannot exchange, the target is renamed aside (``.NAME.fb-old-<pid>-<hex>``), the new
   folder renamed to the target, then the aside copy deleted.

Both renames stay within one folder, so each is atomic (POSIX ``rename``); the signals that
stop a run (SIGINT, SIGTERM, SIGHUP, see :mod:`cases.signals`) are held back between them. A run
killed outright (SIGKILL, power loss) leaves at most an aside copy and a temporary folder; the
next run writing beside them (:func:`recover`) moves the aside copy back when the target is
missing and deletes the leftovers of runs whose process is gone. The target therefore always
holds either the complete old or the complete new result.

An existing target is replaced only when it is an empty folder or carries the marker
(:func:`check_output_target`); the working folder, the home folder, the file-system root, any
folder holding one of them, a file and a symbolic link are refused before any work starts.
"""

from __future__ import annotations

import ctypes
import json
import logging
import os
import re
import shutil
import time
import uuid
from contextlib import contextmanager
from pathlib import Path

from fem_rings.cache import process_alive

from .config import CaseError
from .signals import at_stop, held

__all__ = ["MARKER", "OutputTargetError", "atomic_folder", "check_output_target", "is_results_folder", "marker_entry",
           "marker_source", "open_collection", "recover"]

log = logging.getLogger(__name__)

#: marker file in every results folder the project writes
MARKER = ".flexbearing-results.json"
MARKER_FORMAT = "flexbearing-results/1"
#: leftovers older than this are stale even when their process id is in use again, s
STALE_AGE_S = 7 * 24 * 3600.0

_TMP, _OLD = "fb-tmp", "fb-old"
#: temporary folders not yet swapped in or removed, with the process that made them (a forked child
#: inherits the parent's entries and must leave them alone; :func:`_remove_unfinished`)
_UNFINISHED: dict[Path, int] = {}
_LEFTOVER = re.compile(r"^\.(?P<name>.+)\.(?P<kind>fb-tmp|fb-old)-(?P<pid>\d+)-[0-9a-f]{8}$")


class OutputTargetError(CaseError):
    """The output folder cannot be (re)placed: the message names the path and why."""


def _marker(path: Path) -> dict | None:
    """The project marker of folder ``path``, or None when it has no readable one."""
    try:
        data = json.loads((Path(path) / MARKER).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError):
        return None
    return data if isinstance(data, dict) and data.get("format") == MARKER_FORMAT else None


def is_results_folder(path: Path) -> bool:
    """True when ``path`` is a folder carrying a readable project marker."""
    return _marker(path) is not None


def marker_source(path: Path) -> tuple[str | None, str | None]:
    """(case name, source) recorded in the marker of results folder ``path``; None for what it
    does not record (folders written before ``source`` existed)."""
    data = _marker(path) or {}
    return data.get("name"), data.get("source")


def _protected(path: Path) -> str | None:
    """Why ``path`` must never be replaced (it is or holds the working, home or root folder)."""
    here = Path.cwd().resolve()
    for what, p in (("the working folder", here), ("the home folder", Path.home().resolve()),
                    ("the file-system root", Path(here.anchor))):
        if path == p:
            return f"it is {what}"
        if path in p.parents:
            return f"it holds {what}"
    return None


def check_output_target(out_dir) -> Path:
    """Refuse an output folder the project may not replace; returns the resolved path.

    Raises
    ------
    OutputTargetError
        ``out_dir`` is or holds the working, home or root folder; is a file or a symbolic link;
        or is a non-empty folder without the project's marker (written by something else).
    """
    raw = Path(out_dir)
    if str(out_dir).strip() == "" or raw.name in ("", ".", ".."):
        raise OutputTargetError(f"output folder {str(out_dir)!r}: give a folder name (not '.', '..' or empty)")
    if raw.is_symlink():
        raise OutputTargetError(f"output folder {str(out_dir)!r} is a symbolic link; give the folder itself")
    path = raw.resolve()
    why = _protected(path)
    if why:
        raise OutputTargetError(f"output folder {str(out_dir)!r} refused: {why}")
    if path.exists() or path.is_symlink():
        if not path.is_dir():
            raise OutputTargetError(f"output folder {str(out_dir)!r} is a file, not a folder")
        if any(path.iterdir()) and not is_results_folder(path):
            raise OutputTargetError(f"output folder {str(out_dir)!r} holds files that flexbearing did not write "
                                    f"(no {MARKER} marker); choose another folder or empty it")
    for parent in path.parents:
        if parent.exists() and not parent.is_dir():
            raise OutputTargetError(f"output folder {str(out_dir)!r}: {str(parent)!r} is a file")
    return path


def _leftover_name(out: Path, kind: str) -> Path:
    return out.with_name(f".{out.name}.{kind}-{os.getpid()}-{uuid.uuid4().hex[:8]}")


def _is_stale(path: Path, pid: int) -> bool:
    try:
        age = time.time() - path.lstat().st_mtime
    except FileNotFoundError:
        return False
    return age > STALE_AGE_S or not process_alive(pid)


def recover(parent) -> None:
    """Finish or undo the swaps of killed runs in ``parent`` and delete their temporary folders.

    Only leftovers whose process is gone (or older than :data:`STALE_AGE_S`) are touched: an
    aside copy goes back to its target when the target is missing and is deleted otherwise; a
    temporary folder is deleted. Runs still going on are left alone.
    """
    parent = Path(parent)
    try:
        entries = sorted(parent.iterdir())
    except OSError:
        return
    for p in entries:
        m = _LEFTOVER.match(p.name)
        if not m or p.is_symlink() or not p.is_dir() or not _is_stale(p, int(m["pid"])):
            continue
        target = parent / m["name"]
        if m["kind"] == _OLD and not (target.exists() or target.is_symlink()):
            os.rename(p, target)
            log.warning("restored the previous results %s (the run replacing them was killed)", target)
        else:
            shutil.rmtree(p, ignore_errors=True)
            log.info("removed %s left by a killed run", p)


#: ``renameat2`` arguments: the current folder as base, and "exchange the two paths"
_AT_FDCWD = -100
_RENAME_EXCHANGE = 2

def _make_folder(path: Path) -> Path:
    """``mkdir`` with the usual permissions (0777 less the umask, unlike ``tempfile.mkdtemp``)."""
    os.mkdir(path)
    return path


def _write_marker(folder: Path, name: str, source: str | None = None, **extra) -> None:
    data = {"format": MARKER_FORMAT, "name": name, **({"source": source} if source is not None else {}), **extra}
    (folder / MARKER).write_text(json.dumps(data) + "\n", encoding="utf-8")


def marker_entry(path: Path, key: str):
    """Entry ``key`` of the marker of results folder ``path`` (None when absent)."""
    return (_marker(path) or {}).get(key)


def open_collection(out_dir, name: str, source: str, kind: str) -> Path:
    """Create (or reopen) a folder that collects results folders, e.g. the points of a sweep.

    Unlike a run's folder it is not swapped in whole: its sub-folders are. It carries the marker
    with ``kind``; an existing folder is reopened only when its marker has the same ``kind``
    (an ordinary run's results are not mixed with it). Returns the resolved path.
    """
    out = check_output_target(out_dir)
    if is_results_folder(out) and marker_entry(out, "kind") != kind:
        raise OutputTargetError(f"output folder {str(out_dir)!r} holds the results of a run, not of a {kind}; "
                                "choose another folder with --out")
    out.mkdir(parents=True, exist_ok=True)
    recover(out)
    _write_marker(out, name, source, kind=kind)
    return out


def _exchange(a: Path, b: Path) -> bool:
    """Swap two existing paths in one atomic step (Linux ``renameat2`` with ``RENAME_EXCHANGE``,
    glibc ≥ 2.28); False where the system or file system cannot, and nothing has changed then."""
    try:
        fn = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return False
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    return fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0


def _swap_in(tmp: Path, out: Path) -> None:
    check_output_target(out)  # the target may have changed during the run
    with held():
        if out.exists() and _exchange(tmp, out):
            # the target is never missing, not even to SIGKILL; the old result now sits in the
            # temporary folder, which the next run deletes if this one is killed before it does
            shutil.rmtree(tmp, ignore_errors=True)
            return
        aside = None
        if out.exists():
            aside = _leftover_name(out, _OLD)
            os.rename(out, aside)
        try:
            os.rename(tmp, out)
        except BaseException:
            if aside is not None:
                os.rename(aside, out)
            raise
        if aside is not None:
            shutil.rmtree(aside, ignore_errors=True)


@contextmanager
def atomic_folder(out_dir, name: str = "", source: str | None = None):
    """Yield a new temporary folder that replaces ``out_dir`` whole when the block completes.

    Parameters
    ----------
    out_dir : path
        The results folder; checked first (:func:`check_output_target`).
    name : str
        Written into the marker (the case or part name).
    source : str or None
        Written into the marker: what the results come from (a case run's named case or case file).

    On an error or interruption the temporary folder is deleted and ``out_dir`` stays as it was.
    """
    out = check_output_target(out_dir)
    out.parent.mkdir(parents=True, exist_ok=True)
    recover(out.parent)
    tmp = _leftover_name(out, _TMP)
    _UNFINISHED[tmp] = os.getpid()  # before it exists: a stop right after mkdir is still cleaned up
    try:
        _make_folder(tmp)
        yield tmp
        _write_marker(tmp, name or out.name, source)
        _swap_in(tmp, out)
    except BaseException:
        with held():
            shutil.rmtree(tmp, ignore_errors=True)
        raise
    finally:
        _UNFINISHED.pop(tmp, None)


def _remove_unfinished() -> None:
    """Delete the temporary folders of this process that no block finished: a stop signal that came
    between their creation and the ``with`` block that owns them (:func:`cases.signals.at_stop`)."""
    for tmp, pid in list(_UNFINISHED.items()):
        if pid == os.getpid():
            shutil.rmtree(tmp, ignore_errors=True)
            _UNFINISHED.pop(tmp, None)


at_stop(_remove_unfinished)
