"""Every example model and library file round-trips through the formatter.

The parameters are collected from the folders, so new examples are covered automatically.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.languages.domain.printer import format_domain_text
from lightrocks.languages.domain.syntax import parse_domain
from lightrocks.languages.lightrocks.printer import format_statechart_text
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel.comments import Comments

ROOT = Path(__file__).parents[2]
FILES = sorted(
    [
        *ROOT.glob("examples/**/*.lr"),
        *ROOT.glob("examples/**/*.lrd"),
        *ROOT.glob("languages/domain/library/**/*.lrd"),
    ]
)
LANGUAGES = {
    ".lr": (parse_statechart, format_statechart_text),
    ".lrd": (parse_domain, format_domain_text),
}


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_formatting_keeps_model_and_comments_and_is_stable(path: Path) -> None:
    parse, format_text = LANGUAGES[path.suffix]
    text = path.read_text(encoding="utf-8")
    printed = format_text(text, path.name)
    assert parse(printed, path.name) == parse(text, path.name)
    assert [c.text for c in Comments(printed).comments] == [c.text for c in Comments(text).comments]
    assert format_text(printed, path.name) == printed
