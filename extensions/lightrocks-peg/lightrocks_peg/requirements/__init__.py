"""The ``requirements`` extension of LightRocks: ``requirement`` elements in statecharts."""

from pathlib import Path

from lightrocks.workbench.extensions import LanguageExtension
from lightrocks_peg.requirements.cocos import COCOS
from lightrocks_peg.requirements.syntax import GRAMMAR, Requirement, build, print_requirement

EXTENSION = LanguageExtension(
    name="requirements",
    extends="lightrocks",
    grammar=GRAMMAR,
    build={"Requirement": build},
    printers={Requirement: print_requirement},
    cocos=COCOS,
    templates=Path(__file__).parents[1] / "templates",
    description="requirement elements traced to the outcomes that verify them",
    symbols={Requirement: "requirement"},
)
