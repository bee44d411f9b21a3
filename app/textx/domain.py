"""Registration with textX's language registry, so that ``textx check`` knows ``.lrd`` files
and runs the CoCos on them (see :mod:`workbench.textx_check`)."""

from functools import cache

from textx import language

from lightrocks.languages.domain.syntax import FRAGMENTS, GRAMMAR
from lightrocks.metamodel.grammar import build_metamodel
from lightrocks.workbench.textx_check import with_cocos


@language("lightrocks-domain", "*.lrd")
@cache
def domain_language():
    """LightRocks domain interfaces: value types, devices and cells."""
    return with_cocos(build_metamodel(GRAMMAR, FRAGMENTS))
