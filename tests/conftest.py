"""Test-session settings: the suite never reads or writes the user's own model cache.

Every test session gets a fresh temporary ``FLEXBEARING_CACHE`` (shared by the tests of that
session, so a model built by one test is reused by the next), removed at the end. Set
``FLEXBEARING_TEST_CACHE=/some/folder`` to keep and reuse a test cache between sessions instead.
Tests that need an empty cache of their own still point ``FLEXBEARING_CACHE`` at ``tmp_path``.
"""

import os
import shutil
import tempfile

import pytest


@pytest.fixture(scope="session", autouse=True)
def _session_model_cache():
    kept = os.environ.get("FLEXBEARING_TEST_CACHE")
    folder = kept or tempfile.mkdtemp(prefix="flexbearing-test-cache-")
    before = os.environ.get("FLEXBEARING_CACHE")
    os.environ["FLEXBEARING_CACHE"] = folder
    try:
        yield folder
    finally:
        if before is None:
            os.environ.pop("FLEXBEARING_CACHE", None)
        else:
            os.environ["FLEXBEARING_CACHE"] = before
        if not kept:
            shutil.rmtree(folder, ignore_errors=True)
