"""The extension package's models, whose requirements and arithmetic only parse with the
extension installed, are drawn at every level by ``generate --option levels=yes``."""

from __future__ import annotations

import json
import os
import sysconfig
from pathlib import Path

import pytest
from extensions.peg_package import EXAMPLES, MODELS, Environment, installed  # noqa: F401


def test_every_level_of_the_extension_models_is_drawn(
    installed: Environment,  # noqa: F811
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    scripts = sysconfig.get_path("scripts")  # where the project's graphviz-pure is
    monkeypatch.setenv("PATH", os.pathsep.join([scripts, os.environ.get("PATH", "")]))
    result = installed.lightrocks(
        "generate", str(MODELS), "--path", str(EXAMPLES), "--target", "dot",
        "--option", "levels=yes", "-o", str(tmp_path),
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    indexes = sorted(tmp_path.glob("*/levels.json"))
    assert len(indexes) == len(list(MODELS.rglob("*.lr")))
    for index in indexes:
        for level in json.loads(index.read_text())["levels"]:
            assert level["layout"].startswith("graphviz"), (index, level)
            assert (index.parent / level["file"]).read_bytes().startswith(b"<?xml")
