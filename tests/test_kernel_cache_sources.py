"""numba's disk cache and kernels that call kernels of other files (mbd_core.kernels.disk_cache).

numba keys a cached kernel on its own file's stamp only, so a caller whose callee's file changed would
load stale machine code. The reference is plain arithmetic: after the callee's constant changes, the
caller must return the new value in a fresh process; without the invalidation numba returns the old one
(the first half of the test shows that it does, so the test cannot pass for want of a cache).
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from mbd_core.kernels.disk_cache import invalidate_on_source_change, sources_hash

ROOT = Path(__file__).resolve().parents[1]


def _package(tmp_path: Path, value: int) -> Path:
    pkg = tmp_path / "kpkg"
    pkg.mkdir(exist_ok=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "callee.py").write_text(textwrap.dedent(f"""
        from numba import njit

        @njit(cache=True)
        def g():
            return {value}
    """))
    (pkg / "caller.py").write_text(textwrap.dedent("""
        from numba import njit
        from .callee import g

        @njit(cache=True)
        def f():
            return g() + 1000
    """))
    return pkg


def _run(tmp_path: Path, invalidate: bool) -> int:
    code = ("import sys; from pathlib import Path\n"
            "from mbd_core.kernels.disk_cache import invalidate_on_source_change\n"
            f"if {invalidate}: invalidate_on_source_change('kpkg', Path({str(tmp_path / 'kpkg')!r}))\n"
            "from kpkg.caller import f; print(f())\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), str(ROOT)]), "NUMBA_DISABLE_JIT": "0"}
    env.pop("NUMBA_CACHE_DIR", None)
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return int(out.stdout.split()[-1])


def _touch_later(path: Path) -> None:
    st = path.stat()
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 2_000_000_000))  # a later stamp, as an edit gives


@pytest.mark.parametrize("invalidate", [False, True])
def test_a_changed_callee_file_is_not_served_from_the_callers_cache(tmp_path, invalidate):
    _package(tmp_path, 1)
    assert _run(tmp_path, invalidate) == 1001                       # compiled and cached
    _package(tmp_path, 2)                                           # the callee's file changes
    _touch_later(tmp_path / "kpkg" / "callee.py")
    got = _run(tmp_path, invalidate)
    if invalidate:
        assert got == 1002
    else:
        assert got == 1001  # numba's own keying: the stale value (what the invalidation exists for)


def test_sources_hash_follows_contents_and_a_second_call_keeps_the_cache(tmp_path):
    pkg = _package(tmp_path, 1)
    h1 = sources_hash(pkg)
    (pkg / "callee.py").write_text((pkg / "callee.py").read_text().replace("return 1", "return 3"))
    assert sources_hash(pkg) != h1
    sys.path.insert(0, str(tmp_path))
    try:
        assert invalidate_on_source_change("kpkg", pkg) is True     # no stamp yet
        assert invalidate_on_source_change("kpkg", pkg) is False    # stamp current
    finally:
        sys.path.remove(str(tmp_path))
        for name in [n for n in sys.modules if n == "kpkg" or n.startswith("kpkg.")]:
            del sys.modules[name]
