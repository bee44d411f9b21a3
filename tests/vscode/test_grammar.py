"""Snapshot tests of the TextMate grammar with vscode-tmgrammar-test.

The node tooling is installed into vscode/node_modules by ``cd vscode && npm ci`` (or by
``make vsix`` or ``make judges``); where node or that tooling is absent the tests skip, or
fail in CI (see ``judges.missing``)."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest
from judges import missing

VSCODE = Path(__file__).resolve().parents[2] / "vscode"
SNAP = VSCODE / "node_modules" / ".bin" / "vscode-tmgrammar-snap"
CASES = ["tests/*.lr", "tests/*.lrd"]


@pytest.fixture(autouse=True)
def tooling() -> None:
    if shutil.which("node") is None:
        missing("node", "apt-get install nodejs npm, then `make judges`")
    if not SNAP.exists():
        missing("vscode-tmgrammar-snap", "`make judges` (or `npm ci` in vscode/)")


def snapshot(folder: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(SNAP), *CASES], cwd=folder, capture_output=True, text=True, timeout=120
    )


def test_the_grammar_matches_its_snapshots() -> None:
    result = snapshot(VSCODE)
    assert result.returncode == 0, result.stdout + result.stderr


def test_a_changed_grammar_fails_the_snapshots(tmp_path: Path) -> None:
    copy = tmp_path / "vscode"
    shutil.copytree(VSCODE, copy, ignore=shutil.ignore_patterns("node_modules", "*.vsix"))
    (copy / "node_modules").symlink_to(VSCODE / "node_modules")
    grammar = copy / "syntaxes" / "lightrocks.tmLanguage.json"
    rules = json.loads(grammar.read_text(encoding="utf-8"))
    rules["patterns"] = [p for p in rules["patterns"] if p["include"] != "#stereotypes"]
    grammar.write_text(json.dumps(rules), encoding="utf-8")
    result = snapshot(copy)
    assert result.returncode != 0
    assert "stereotype" in result.stdout
