"""Parse results keyed by content: an unchanged file is never parsed twice.

Units are immutable dataclasses, so one parsed unit can serve every later check of the same
text. Results live in memory for the process (the language server re-checks on every
keystroke, and keeps its results there only) and, when a :class:`Store` is installed,
between processes (the command line installs the bounded on-disk store of
:mod:`lightrocks.app.parsestore`). The key covers the installed
version, a digest of the grammar and of the code that builds units, the language, the file
name shown in positions and the text, so no stale result is ever returned.
"""

from __future__ import annotations

import hashlib
import importlib
from functools import cache
from pathlib import Path
from typing import Any, Protocol

from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem, paused_gc
from lightrocks.workbench.cachestore import Memory, installed_version
from lightrocks.workbench.depth import deepest, deepest_node
from lightrocks.workbench.extensions import extensions_of
from lightrocks.workbench.languages import Language
from lightrocks.workbench.sources import sources_digest


class Store(Protocol):
    """Somewhere results outlive the process; a miss or an unreadable entry is ``None``."""

    def get(self, key: str) -> ast.Unit | SyntaxProblem | None: ...

    def put(self, key: str, result: ast.Unit | SyntaxProblem) -> None: ...


FORMAT = "3"  # what a stored result means: raised to retire every result stored before
MEMORY_ENTRIES = 10_000  # a large workspace plus the keystroke states of an editing session
_memory: Memory[Any] = Memory(MEMORY_ENTRIES)
_store: Store | None = None


def use_store(store: Store | None) -> None:
    """Keep results in ``store`` too (``None``: memory only)."""
    global _store
    _store = store


def parse(language: Language, text: str, shown: str, remember: bool = True) -> Any:
    """``language.parse(text, shown)``, answered from the cache when the content is known.

    Without ``remember`` the text is parsed afresh and its result kept nowhere: a text that
    stands in for a file for one check only (see :func:`lightrocks.workbench.check.check`)."""
    result = _remembered(language, text, shown) if remember else _parsed(language, text, shown)
    if isinstance(result, SyntaxProblem):
        raise result
    return result


def _remembered(language: Language, text: str, shown: str) -> Any:
    """The result of a text from memory, else from the store, else parsed and kept in both."""
    key = _key(language, text, shown)
    result = _memory.get(key)
    if result is None:
        result = _store.get(key) if _store is not None else None
        if result is None:
            result = _parsed(language, text, shown)
            if _store is not None:
                _store.put(key, result)
        _memory.put(key, result)
    return result


def _parsed(language: Language, text: str, shown: str) -> Any:
    """The unit of a text, or the problem that stops it: a syntax error, or nesting deeper
    than later passes can walk (checked once per content, as the result is cached)."""
    try:
        unit = language.parse(text, shown)
    except SyntaxProblem as problem:
        return problem
    except RecursionError:
        where, message = deepest(text, shown)
        return SyntaxProblem(message, where.line, where.column)
    with paused_gc():
        found = deepest_node(unit)
    if found is None:
        return unit
    where, message = found
    return SyntaxProblem(message, where.line, where.column)


def _key(language: Language, text: str, shown: str) -> str:
    digest = hashlib.blake2b(digest_size=20)
    grammar = grammar_digest(language.parse.__module__)
    extended = extensions_digest(language.name)
    for part in (FORMAT, installed_version(), grammar, extended, language.name, shown):
        digest.update(part.encode("utf-8", "surrogatepass") + b"\x00")
    digest.update(text.encode("utf-8", "surrogatepass"))
    return digest.hexdigest()


@cache
def grammar_digest(module: str) -> str:
    """A digest of the grammar fragments and of the code turning parse trees into units:
    an editable install changes them without changing the version."""
    folders = {Path(importlib.import_module(module).__file__).parent, Path(ast.__file__).parent}
    return sources_digest(folders, (".tx", ".py"))


@cache
def extensions_digest(language: str) -> str:
    """A digest of the syntax installed extensions add to a language: installing or removing
    one changes what a text means."""
    digest = hashlib.sha256()
    for extension in extensions_of(language):
        rules = "\x00".join(
            (extension.name, extension.grammar.rules, repr(extension.grammar.hooks))
        )
        digest.update(rules.encode("utf-8") + b"\x00")
    return digest.hexdigest()
