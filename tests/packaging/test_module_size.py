"""No module of the project grows past 700 lines: a larger one holds several jobs, and the
next engineer should find each job in a module of its own."""

from __future__ import annotations

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LIMIT = 700
OUTSIDE = {".git", ".venv", "build", "node_modules", "__pycache__"}


def sources() -> list[Path]:
    """The project's Python files, without the virtualenv, build output and hidden folders."""
    found = []
    for folder, subfolders, files in os.walk(ROOT):
        subfolders[:] = [s for s in subfolders if s not in OUTSIDE and not s.startswith(".")]
        found += [Path(folder, name) for name in files if name.endswith(".py")]
    return found


def test_no_module_is_longer_than_the_limit() -> None:
    found = sources()
    assert len(found) > 300  # the project's own modules are searched, not an empty folder
    lengths = {path: len(path.read_text(encoding="utf-8").splitlines()) for path in found}
    over = sorted(f"{p.relative_to(ROOT)}: {n}" for p, n in lengths.items() if n > LIMIT)
    assert not over, f"modules over {LIMIT} lines: {over}"
