"""The repository's model files and the worked PEG extension's grammars, which the tests of
parse trees and of their compiled form both read."""

from __future__ import annotations

import importlib
import subprocess
from pathlib import Path

import pytest

from lightrocks.metamodel.grammar import GrammarExtension

ROOT = Path(__file__).parents[2]


def model_files() -> list[Path]:
    listed = subprocess.run(
        ["git", "ls-files", "*.lr", "*.lrd"], cwd=ROOT, capture_output=True, text=True
    ).stdout.split()
    return [ROOT / name for name in listed if "broken" not in name]


PEG = ROOT / "extensions" / "lightrocks-peg"


def peg_grammars(monkeypatch: pytest.MonkeyPatch) -> tuple[GrammarExtension, ...]:
    """The syntax of the example extension, read from its source folder."""
    monkeypatch.syspath_prepend(str(PEG))
    requirements = importlib.import_module("lightrocks_peg.requirements.syntax")
    arithmetic = importlib.import_module("lightrocks_peg.arithmetic.syntax")
    return (requirements.GRAMMAR, arithmetic.GRAMMAR)
