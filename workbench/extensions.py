"""The registry of language extensions, found through the ``lightrocks.language_extensions``
entry points.

An extension adds syntax to a language without forking it: grammar rules that fill the
hooks its grammar leaves open, the AST node each new rule becomes, how the printer writes
it back, the CoCos that check it and the template folder through which generators render
it. The extended language composes them when it builds its parser.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

from lightrocks.metamodel.grammar import GrammarExtension
from lightrocks.workbench.cocos import CoCo
from lightrocks.workbench.passes import Pass

Build = Callable[[Any, Any], Any]
"""``(converter, textx node) -> AST node``; the converter offers ``position``, ``convert``…"""
Print = Callable[[Any, Any], None]
"""``(writer, AST node)``: print the node with :class:`metamodel.printer.Writer`."""


@dataclass(frozen=True)
class LanguageExtension:
    """Syntax added to the language ``extends``; ``printers`` names its AST node types."""

    name: str
    extends: str
    grammar: GrammarExtension
    build: Mapping[str, Build]
    printers: Mapping[type, Print]
    cocos: Sequence[CoCo] = ()
    templates: Path | None = None
    """Folder of generator templates: ``<target>/<node type>.jinja`` renders that node."""
    description: str = ""
    symbols: Mapping[type, str] = field(default_factory=dict)
    """Element types that declare a name, with the kind editors show (``{Requirement:
    "requirement"}``): outline, navigation, rename and completion then know the names."""
    passes: Sequence[type[Pass]] = ()
    """Passes whose findings are reported under the codes they declare."""


@cache
def language_extensions() -> tuple[LanguageExtension, ...]:
    """Every registered extension, in entry-point name order."""
    found = sorted(entry_points(group="lightrocks.language_extensions"), key=lambda e: e.name)
    return tuple(entry.load() for entry in found)


def extensions_of(language: str) -> tuple[LanguageExtension, ...]:
    return tuple(e for e in language_extensions() if e.extends == language)


def extension_of(node: Any) -> LanguageExtension | None:
    """The extension whose AST node ``node`` is, or None for a node of the base language."""
    return next((e for e in language_extensions() if type(node) in e.printers), None)


def symbol_kind(node: Any) -> str | None:
    """The kind of symbol an extension element declares, or None when it declares none."""
    return next(
        (e.symbols[type(node)] for e in language_extensions() if type(node) in e.symbols), None
    )


def template_name(target: str, node: Any) -> str:
    """The template through which generator ``target`` renders an extension node."""
    return f"{target}/{type(node).__name__}.jinja"
