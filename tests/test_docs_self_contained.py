"""The repository's documentation stands on its own: no file points at texts outside it.

Reference: the sources are cited by author, title, venue and year in README.md (Sources) and where
they are used; the modelling choices are stated where they are made. A pointer to the project's
private brief or to its local copies of the sources would leave a reader with nothing to open.
"""

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
#: the pointers that must not appear (spelt in pieces so that this file does not match itself)
FORBIDDEN = re.compile("|".join((re.escape("shared/" + "seeds"), re.escape("DESIGN" + " §"), "seed" + r" 0\d\d")))
SKIP_DIRS = {".git", "__pycache__", ".pytest_cache", "results", "build", "dist", ".venv", "node_modules"}
TEXT_SUFFIXES = {".py", ".md", ".toml", ".txt", ".cfg", ".ini", ".yml", ".yaml", ".json", ".csv", ".sh", ""}


def _text_files():
    for path in sorted(REPO.rglob("*")):
        rel = path.relative_to(REPO)
        if any(part in SKIP_DIRS or part.endswith(".egg-info") for part in rel.parts) or not path.is_file():
            continue
        if path.suffix in TEXT_SUFFIXES and path.stat().st_size < 2_000_000:
            yield rel, path


def test_no_file_points_at_texts_outside_the_repository():
    hits = []
    for rel, path in _text_files():
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        hits += [f"{rel}:{n}: {line.strip()[:100]}" for n, line in enumerate(text.splitlines(), 1)
                 if FORBIDDEN.search(line)]
    assert not hits, "\n".join(hits)


def test_the_check_finds_what_it_looks_for():
    # the pattern itself, on the kinds of line it replaced
    for line in ("the thesis in `../" + "shared/" + "seeds/003_*`", "(" + "DESIGN" + " §7.1)", "(" + "seed" + " 001, §3)"):
        assert FORBIDDEN.search(line), line
    assert not FORBIDDEN.search("Pang et al., Lubricants 12 (2024) 252; Harris & Kotzalas 2007, §7.2")
