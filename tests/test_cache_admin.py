"""``flexbearing cache info|clean``: sizes and ages of the cache's entries, and removing only them.

References: the files' sizes from ``os.stat`` and their times set here with ``os.utime``; files
the cache did not write (other names, other folders' contents) must survive every clean.
"""

import json
import os
import time

import numpy as np
import pytest

from cases.cli import main
from fem_rings.cache import input_hash, save_arrays

DAY_S = 86400.0


@pytest.fixture
def cache(tmp_path, monkeypatch):
    root = tmp_path / "cache"
    monkeypatch.setenv("FLEXBEARING_CACHE", str(root))
    now = time.time()
    old_key, new_key = input_hash("x", 1), input_hash("x", 2)
    old = save_arrays("fe-model", old_key, {"K": np.ones(1000)})
    new = save_arrays("fe-model", new_key, {"K": np.ones(10)})
    body = save_arrays("reduced", old_key, {"Phi": np.ones(500)})
    sidecar = body.with_suffix(".json")
    sidecar.write_text("{}")
    for p, age_days in ((old, 30), (new, 1), (body, 40), (sidecar, 20)):
        os.utime(p, (now - age_days * DAY_S, now - age_days * DAY_S))
    foreign = [root / "notes.txt", root / "fe-model" / "keep.npz", root / "fe-model" / f"{old_key}.txt"]
    for p in foreign:
        p.write_text("mine")
    return {"old": old, "new": new, "body": (body, sidecar), "foreign": foreign}


def _json(capsys, argv):
    assert main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_info_counts_entries_and_bytes_per_kind(cache, capsys):
    info = _json(capsys, ["cache", "info"])
    sizes = {p: os.stat(p).st_size for p in (cache["old"], cache["new"], *cache["body"])}
    assert info["kinds"]["fe-model"] == {"entries": 2, "size_bytes": sizes[cache["old"]] + sizes[cache["new"]]}
    assert info["kinds"]["reduced"] == {"entries": 1, "size_bytes": sum(sizes[p] for p in cache["body"])}
    assert info["entries"] == 3 and info["size_bytes"] == sum(sizes.values())
    # the reduced body's last use is its newest file (sidecar, 20 days), the oldest entry's 30 days
    assert info["least_recently_used_days"] == pytest.approx(30.0, abs=0.01)


def test_clean_removes_entries_by_last_use_and_nothing_else(cache, capsys):
    done = _json(capsys, ["cache", "clean", "--older-than-days", "10"])
    assert done["removed"]["entries"] == 2            # 30 days (fe-model) and 20 days (reduced body)
    assert not cache["old"].exists() and not any(p.exists() for p in cache["body"])
    assert cache["new"].exists()
    assert all(p.read_text() == "mine" for p in cache["foreign"])
    done = _json(capsys, ["cache", "clean"])
    assert done["removed"]["entries"] == 1 and done["left"]["entries"] == 0
    assert all(p.read_text() == "mine" for p in cache["foreign"])


@pytest.mark.parametrize("days", ["-1", "nan"])
def test_clean_refuses_a_bad_age_in_one_line(cache, capsys, days):
    assert main(["cache", "clean", "--older-than-days", days]) == 2
    err = capsys.readouterr().err.strip()
    assert "--older-than-days" in err and "\n" not in err
    assert cache["old"].exists()


def test_help_names_the_cache_folder_and_size(cache, capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    out = "".join(capsys.readouterr().out.split())    # argparse wraps long paths
    assert str(cache["old"].parent.parent) in out and "3entries" in out
