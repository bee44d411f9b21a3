"""The language registry: languages are found through the ``lightrocks.languages`` entry points.

A language says which file extensions it reads, how to parse and print them, which
declarations a parsed unit contributes to the symbol table, and which context conditions
(CoCos) and passes check it. A separate package adds a language by declaring an entry point.
A language may also bring a library (a folder of models on every model path) and name the
packages whose declarations every file sees without an import: the kernel asks for both.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from functools import cache
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

from lightrocks.workbench.cocos import CoCo
from lightrocks.workbench.passes import Pass


@dataclass(frozen=True)
class Language:
    name: str
    extensions: tuple[str, ...]
    parse: Callable[[str, str], Any]
    format: Callable[[str, str], str]
    declarations: Callable[[Any], Iterable[tuple[str, Any]]]
    cocos: Sequence[CoCo] = field(default_factory=tuple)
    description: str = ""
    library: Path | None = None
    """A folder of models on every model path, after the user's folders."""
    implicit_packages: tuple[str, ...] = ()
    """Packages whose declarations every file sees without importing them."""
    passes: Sequence[type[Pass]] = ()
    """Passes whose findings are reported under the codes they declare."""


@cache
def languages() -> tuple[Language, ...]:
    """Every registered language, in entry-point name order."""
    found = sorted(entry_points(group="lightrocks.languages"), key=lambda e: e.name)
    return tuple(entry.load() for entry in found)


def language_for(extension: str) -> Language | None:
    return next((lang for lang in languages() if extension in lang.extensions), None)


def extensions() -> tuple[str, ...]:
    return tuple(ext for lang in languages() for ext in lang.extensions)


@cache
def libraries() -> tuple[Path, ...]:
    """The library folders of the registered languages, resolved, in registry order."""
    return tuple(lang.library.resolve() for lang in languages() if lang.library is not None)


@cache
def implicit_packages() -> tuple[str, ...]:
    """The packages every file sees without an import, of every registered language."""
    return tuple(package for lang in languages() for package in lang.implicit_packages)
