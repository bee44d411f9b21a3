"""The suite imports LightRocks as installed (``lightrocks.…``), never the repository's
folders as top-level packages: ``python -m pytest`` puts the working directory on
``sys.path``, where ``runtime`` or ``adapters`` would import by accident."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path[:] = [entry for entry in sys.path if Path(entry or ".").resolve() != ROOT]


@pytest.fixture(autouse=True)
def private_parse_cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch):
    """Keep the on-disk parse cache of tests (and of the servers they start) out of $HOME."""
    monkeypatch.setenv("LIGHTROCKS_CACHE", str(tmp_path_factory.getbasetemp() / "parse-cache"))
