"""The suite imports LightRocks as installed (``lightrocks.…``), never the repository's
folders as top-level packages: ``python -m pytest`` puts the working directory on
``sys.path``, where ``runtime`` or ``adapters`` would import by accident."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path[:] = [entry for entry in sys.path if Path(entry or ".").resolve() != ROOT]


@pytest.fixture(autouse=True, scope="session")
def _private_run_cache(tmp_path_factory: pytest.TempPathFactory):
    """Runs cache their generated code under a temporary folder, not the user's cache."""
    patch = pytest.MonkeyPatch()
    patch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.mktemp("user-cache")))
    yield
    patch.undo()
