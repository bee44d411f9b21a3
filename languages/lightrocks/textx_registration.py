"""Registration with textX's language registry, so that ``textx check`` knows ``.lr`` files."""

from textx import language

from lightrocks.languages.lightrocks.syntax import metamodel


@language("lightrocks", "*.lr")
def lightrocks_language():
    """LightRocks action components as UML/P statecharts."""
    return metamodel()
