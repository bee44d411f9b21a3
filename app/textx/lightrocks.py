"""Registration with textX's language registry, so that ``textx check`` knows ``.lr`` files
and runs the CoCos on them (see :mod:`app.textx.check`)."""

from functools import cache

from textx import language

from lightrocks.app.textx.check import with_cocos
from lightrocks.languages.lightrocks.syntax import FRAGMENTS, GRAMMAR, grammar_extensions
from lightrocks.metamodel.grammar import build_metamodel


@language("lightrocks", "*.lr")
@cache
def lightrocks_language():
    """LightRocks action components as UML/P statecharts."""
    return with_cocos(build_metamodel(GRAMMAR, FRAGMENTS, grammar_extensions()))
