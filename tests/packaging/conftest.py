"""What the packaging tests build from: a copy of the sources, so that no ``build/`` folder
or egg-info lands in the project."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
IGNORED = (".git", ".venv", "build", "*.egg-info", "__pycache__", ".*_cache", "out", "node_modules")


@pytest.fixture(scope="session")
def source(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The project's files, without its environment, caches and build outputs."""
    copy = tmp_path_factory.mktemp("source") / "lightrocks"
    shutil.copytree(ROOT, copy, ignore=shutil.ignore_patterns(*IGNORED))
    return copy
