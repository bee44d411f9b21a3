"""``check --strict`` fails on warnings; a mistyped wildcard import names the close package."""

from __future__ import annotations

from pathlib import Path

import pytest
from cocos.cases import CASES
from cocos.models import BASE, PICK, materialize, replace

from lightrocks.app.cli import main

ROOT = Path(__file__).resolve().parents[2]


def test_strict_makes_warnings_fail(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    warning = next(c for c in CASES if c.code == "LR0111")
    materialize(tmp_path, {**warning.base, **warning.bad})
    assert main(["check", str(tmp_path)]) == 0
    assert main(["check", "--strict", str(tmp_path)]) == 1
    assert "warning LR0111" in capsys.readouterr().out


def test_strict_passes_on_the_examples(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", "--strict", str(ROOT / "examples")]) == 0
    assert "0 error(s), 0 warning(s)" in capsys.readouterr().out


def test_wildcard_import_of_a_mistyped_package_says_did_you_mean(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    materialize(tmp_path, {**BASE, "skills/Pick.lr": replace(PICK, "actions.*", "action.*")})
    assert main(["check", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert "package 'action' not found (did you mean 'actions'?)" in out


def test_a_nested_package_is_suggested_by_its_full_name(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    nested = {
        f"peg/{name}": text.replace("package actions;", "package peg.actions;")
        .replace("package skills;", "package peg.skills;")
        .replace("import actions.*;", "import peg.action.*;")
        for name, text in BASE.items()
        if name.startswith(("actions/", "skills/"))
    }
    others = {
        name: text for name, text in BASE.items() if not name.startswith(("actions/", "skills/"))
    }
    materialize(tmp_path, {**others, **nested})
    assert main(["check", str(tmp_path / "peg" / "skills")]) == 1
    out = capsys.readouterr().out
    assert "package 'peg.action' not found (did you mean 'peg.actions'?)" in out
