"""docs/extending.md shows the worked extension package as it is: every code block that
names a file is a verbatim excerpt of that file (tests/extensions runs the package), and
every recipe has one."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
GUIDE = (ROOT / "docs" / "extending.md").read_text(encoding="utf-8")
BLOCK = re.compile(r"^```\w+ (\S+)\n(.*?)^```$", re.MULTILINE | re.DOTALL)
EXCERPTS = BLOCK.findall(GUIDE)
RECIPES = (
    "A language extension: new syntax",
    "A language extension: new statements and expressions",
    "A CoCo",
    "Generator template additions",
    "A generator",
    "A template override",
    "An adapter",
    "A scene",
)


@pytest.mark.parametrize(("path", "text"), EXCERPTS, ids=[p for p, _ in EXCERPTS])
def test_each_excerpt_is_in_its_file(path: str, text: str) -> None:
    assert text in (ROOT / path).read_text(encoding="utf-8"), f"{path} changed: update the guide"


@pytest.mark.parametrize("recipe", RECIPES)
def test_each_recipe_shows_a_file_of_the_worked_package(recipe: str) -> None:
    section = GUIDE.split(f"## {recipe}", 1)[1].split("\n## ", 1)[0]
    assert BLOCK.search(section), recipe
