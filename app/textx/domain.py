"""Registration with textX's language registry, so that ``textx check`` knows ``.lrd`` files
and runs the CoCos on them (see :mod:`app.textx.check`)."""

from functools import cache

from textx import language

from lightrocks.app.textx.check import with_cocos
from lightrocks.languages.domain.syntax import FRAGMENTS, GRAMMAR
from lightrocks.metamodel.grammar import build_metamodel


@language("lightrocks-domain", "*.lrd")
@cache
def domain_language():
    """LightRocks domain interfaces: value types, devices and cells."""
    return with_cocos(build_metamodel(GRAMMAR, FRAGMENTS))
