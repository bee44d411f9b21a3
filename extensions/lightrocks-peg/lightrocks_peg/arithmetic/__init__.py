"""The ``arithmetic`` extension of LightRocks: a ``count`` statement and a ``clamp``
expression, added through the statement and expression grammar hooks."""

from pathlib import Path

from lightrocks.workbench.extensions import LanguageExtension
from lightrocks_peg.arithmetic.cocos import COCOS
from lightrocks_peg.arithmetic.syntax import GRAMMAR, build_clamp, build_count

EXTENSION = LanguageExtension(
    name="arithmetic",
    extends="lightrocks",
    grammar=GRAMMAR,
    build={"Count": build_count, "Clamp": build_clamp},
    printers={},
    cocos=COCOS,
    templates=Path(__file__).parents[1] / "templates",
    description="count statements and clamp expressions",
)
