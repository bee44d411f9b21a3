"""A judge that is missing skips its tests locally and fails them in CI, naming the command
that provides it: CI can never turn green by losing MatIEC."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent
TEST = f"{HERE / 'test_matiec.py'}::test_the_reserved_names_cover_matiecs_library"


@pytest.mark.parametrize(("ci", "outcome"), [("true", "1 error"), ("", "1 skipped")])
def test_without_matiec(tmp_path: Path, ci: str, outcome: str) -> None:
    env = {**os.environ, "MATIEC": str(tmp_path), "CI": ci}
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-rfs", "-p", "no:cacheprovider", TEST],
        cwd=HERE.parents[1], env=env, capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert outcome in done.stdout, done.stdout
    assert "MatIEC not found" in done.stdout
    assert "../shared/tools/matiec/build.sh" in done.stdout
