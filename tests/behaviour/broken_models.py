"""The corpus of broken models: the examples with one model replaced by a case's broken copy,
and what verifying it must find."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
CORPUS = Path(__file__).with_name("corpus")


def broken(case: str, tmp_path: Path) -> tuple[Path, Path, dict]:
    """The examples with one model replaced by the corpus case's broken copy."""
    root = tmp_path / "examples"
    shutil.copytree(EXAMPLES, root)
    expect = json.loads((CORPUS / case / "expect.json").read_text(encoding="utf-8"))
    shutil.copyfile(CORPUS / case / expect["file"], root / expect["file"])
    return root, root / expect["file"], expect
