"""The domain language: value types, devices and cells (``.lrd``)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from lightrocks.workbench.cocos import Deferred, cocos_in
from lightrocks.workbench.languages import Language

if TYPE_CHECKING:
    from lightrocks.metamodel import ast


def _declarations(unit: ast.DomainUnit) -> list[tuple[str, Any]]:
    return [(declaration.name, declaration) for declaration in unit.declarations]


def _parse(text: str, file: str) -> ast.DomainUnit:
    """Parsed on first use, as the LightRocks language does (see its ``_parse``)."""
    from lightrocks.languages.domain.syntax import parse_domain

    return parse_domain(text, file)


def _format(text: str, file: str) -> str:
    from lightrocks.languages.domain.printer import format_domain_text

    return format_domain_text(text, file)


def _cocos() -> tuple:
    from lightrocks.languages.domain import cocos

    return cocos_in(cocos)


LIBRARY = Path(__file__).resolve().parent / "library"
"""The device library and the quantity types: package ``lightrocks``, seen by every file."""

LANGUAGE = Language(
    name="domain",
    extensions=(".lrd",),
    parse=_parse,
    format=_format,
    declarations=_declarations,
    cocos=Deferred(_cocos),
    description="robot domain interfaces: value types, devices, cells",
    library=LIBRARY,
    implicit_packages=("lightrocks",),
)
