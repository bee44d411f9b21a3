"""Every example model parses; packages match folders and statechart names match files.

The code blocks of ``docs/language.md`` tagged ``lr`` or ``lrd`` are complete units too and
must parse, so that the language reference cannot drift from the grammar.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from lightrocks.languages.domain.syntax import parse_domain
from lightrocks.languages.lightrocks.syntax import parse_statechart

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
REFERENCE = ROOT / "docs" / "language.md"

STATECHARTS = sorted(EXAMPLES.rglob("*.lr"))
DOMAINS = sorted(EXAMPLES.rglob("*.lrd"))


def _package_of(path: Path) -> str:
    return ".".join(path.relative_to(EXAMPLES).parent.parts)


def _id(path: Path) -> str:
    return path.relative_to(EXAMPLES).as_posix()


def test_examples_exist() -> None:
    assert len(STATECHARTS) >= 20
    assert len(DOMAINS) >= 2  # the cells; the device types are the library's


@pytest.mark.parametrize("path", STATECHARTS, ids=_id)
def test_statechart_parses(path: Path) -> None:
    unit = parse_statechart(path.read_text(encoding="utf-8"), str(path))
    assert unit.package == _package_of(path)
    assert unit.statechart.name == path.stem


@pytest.mark.parametrize("path", DOMAINS, ids=_id)
def test_domain_parses(path: Path) -> None:
    unit = parse_domain(path.read_text(encoding="utf-8"), str(path))
    assert unit.package == _package_of(path)
    assert unit.declarations


def _reference_blocks() -> list[tuple[str, int, str]]:
    if not REFERENCE.exists():
        return []
    text = REFERENCE.read_text(encoding="utf-8")
    blocks = []
    for match in re.finditer(r"^```(lrd?)\n(.*?)^```", text, flags=re.M | re.S):
        line = text.count("\n", 0, match.start()) + 1
        blocks.append((match.group(1), line, match.group(2)))
    return blocks


REFERENCE_BLOCKS = _reference_blocks()


@pytest.mark.parametrize(
    ("kind", "line", "code"), REFERENCE_BLOCKS, ids=[f"line{b[1]}" for b in REFERENCE_BLOCKS]
)
def test_reference_block_parses(kind: str, line: int, code: str) -> None:
    where = f"{REFERENCE}:{line}"
    if kind == "lr":
        parse_statechart(code, where)
    else:
        parse_domain(code, where)
