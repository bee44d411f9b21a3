"""Loading models from the model path and resolving names through one index.

Every declaration gets a qualified name in one dictionary, so resolving a reference is a
dictionary lookup: checking grows linearly with the model, unlike textX's default scoping
that searches the whole model for every reference.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields, is_dataclass
from pathlib import Path
from typing import Any

from lightrocks.metamodel.ast import Import, Position
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench import parsecache
from lightrocks.workbench.diagnostics import Diagnostics, did_you_mean
from lightrocks.workbench.languages import Language, extensions, language_for
from lightrocks.workbench.modelpath import ModelPath

IMPLICIT_PACKAGES = ("lightrocks",)


@dataclass
class Loaded:
    """One parsed file."""

    path: Path
    language: Language
    unit: Any

    @property
    def package(self) -> str:
        return self.unit.package


@dataclass(frozen=True)
class Symbol:
    qualified_name: str
    node: Any
    loaded: Loaded = field(compare=False)

    @property
    def name(self) -> str:
        return self.qualified_name.rpartition(".")[2]


class Workspace:
    def __init__(
        self,
        model_path: ModelPath,
        diagnostics: Diagnostics,
        texts: Mapping[Path, str] | None = None,
    ) -> None:
        self.model_path = model_path
        self.diagnostics = diagnostics
        self.texts = texts or {}  # unsaved editor contents that replace files on disk
        self.files: dict[Path, Loaded | None] = {}
        self.symbols: dict[str, Symbol] = {}
        self._packages: dict[str, dict[str, Symbol]] = {}
        self._loaded_packages: set[str] = set()
        self._scopes: dict[Path, dict[str, Symbol]] = {}

    # -- loading --------------------------------------------------------------------------

    def load(self, path: Path) -> Loaded | None:
        """Parse a file once; problems become diagnostics and the file yields ``None``."""
        path = path.resolve()
        if path in self.files:
            return self.files[path]
        self.files[path] = None
        language = language_for(path.suffix)
        shown = _shown(path)
        if language is None:
            self.diagnostics.error(Position(shown, 1, 1), "LR0004", "not a model file")
            return None
        text = self._read(path, shown)
        if text is None:
            return None
        try:
            unit = parsecache.parse(language, text, shown)
        except SyntaxProblem as problem:
            where = Position(shown, problem.line, problem.column)
            self.diagnostics.error(where, "LR0001", problem.message)
            return None
        except RecursionError:
            self.diagnostics.error(deepest(text, shown), "LR0001", TOO_DEEP)
            return None
        too_deep = deepest_node(unit)
        if too_deep is not None:
            self.diagnostics.error(too_deep, "LR0001", TOO_DEEP)
            return None
        loaded = Loaded(path, language, unit)
        self.files[path] = loaded
        for name, node in language.declarations(unit):
            self._declare(f"{unit.package}.{name}" if unit.package else name, node, loaded)
        return loaded

    def _read(self, path: Path, shown: str) -> str | None:
        where = Position(shown, 1, 1)
        if not path.is_file():  # a FIFO or device would block or never end
            self.diagnostics.error(where, "LR0004", "not a regular file")
            return None
        try:
            data = self._bytes(path)
        except OSError as error:
            self.diagnostics.error(where, "LR0004", f"cannot read file: {error.strerror}")
            return None
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as error:
            line = data[: error.start].count(b"\n") + 1
            self.diagnostics.error(
                Position(shown, line, 1), "LR0002", "not a text file: invalid UTF-8"
            )
            return None
        if "\x00" in text:
            line = text[: text.index("\x00")].count("\n") + 1
            self.diagnostics.error(
                Position(shown, line, 1), "LR0002", "not a text file: contains NUL bytes"
            )
            return None
        if not text.strip():
            self.diagnostics.error(where, "LR0003", "empty model file")
            return None
        return text

    def _bytes(self, path: Path) -> bytes:
        if path in self.texts:
            return self.texts[path].encode("utf-8", "surrogateescape")
        return path.read_bytes()

    def _declare(self, qualified_name: str, node: Any, loaded: Loaded) -> None:
        existing = self.symbols.get(qualified_name)
        if existing is not None:
            self.diagnostics.error(
                node.position,
                "LR0101",
                f"'{qualified_name}' is already declared at {existing.node.position}",
            )
            return
        symbol = Symbol(qualified_name, node, loaded)
        self.symbols[qualified_name] = symbol
        package, _, name = qualified_name.rpartition(".")
        self._packages.setdefault(package, {})[name] = symbol

    def load_package(self, package: str) -> dict[str, Symbol]:
        """Load every model file of a package (not its sub-packages) and return its symbols."""
        if package not in self._loaded_packages:
            self._loaded_packages.add(package)
            for folder in self.model_path.package_folders(package):
                for path in sorted(folder.iterdir()):
                    if path.suffix in extensions() and path.is_file():
                        self.load(path)
        return self._packages.get(package, {})

    # -- resolution -----------------------------------------------------------------------

    def lookup(self, qualified_name: str) -> Symbol | None:
        """A declaration by qualified name, loading its package on demand."""
        symbol = self.symbols.get(qualified_name)
        if symbol is None and "." in qualified_name:
            self.load_package(qualified_name.rpartition(".")[0])
            symbol = self.symbols.get(qualified_name)
        return symbol

    def scope(self, loaded: Loaded) -> dict[str, Symbol]:
        """Simple names visible in a file: implicit library, own package, then its imports."""
        scope = self._scopes.get(loaded.path)
        if scope is not None:
            return scope
        scope = {}
        for package in (*IMPLICIT_PACKAGES, loaded.package):
            scope.update(self.load_package(package))
        for imported in loaded.unit.imports:
            scope.update(self._import(imported))
        self._scopes[loaded.path] = scope
        return scope

    def _import(self, imported: Import) -> dict[str, Symbol]:
        if imported.wildcard:
            symbols = self.load_package(imported.name)
            if not symbols:
                parent = imported.name.rpartition(".")[0]
                siblings = {
                    f"{parent}.{child.name}" if parent else child.name
                    for folder in self.model_path.package_folders(parent)
                    for child in folder.iterdir()
                    if child.is_dir()
                }
                self.diagnostics.error(
                    imported.position,
                    "LR0102",
                    f"package '{imported.name}' not found",
                    did_you_mean(imported.name, siblings),
                )
            return symbols
        symbol = self.lookup(imported.name)
        if symbol is None:
            package, _, name = imported.name.rpartition(".")
            hint = did_you_mean(name, self._packages.get(package, {}))
            self.diagnostics.error(
                imported.position, "LR0102", f"cannot resolve import '{imported.name}'", hint
            )
            return {}
        return {symbol.name: symbol}

    def resolve(self, loaded: Loaded, name: str) -> Symbol | None:
        """A simple name through the file's scope, or a qualified name directly."""
        if "." in name:
            return self.lookup(name)
        return self.scope(loaded).get(name)

    def loaded_units(self) -> list[Loaded]:
        return [loaded for loaded in self.files.values() if loaded is not None]


def _shown(path: Path) -> str:
    """A path as users see it in findings: relative to the working folder when possible."""
    try:
        return str(path.relative_to(Path.cwd()))
    except ValueError:
        return str(path)


MAX_DEPTH = 100
"""Nesting of the syntax tree that later passes (typing, printing, generating) may walk
recursively without running out of stack."""

TOO_DEEP = (
    f"nested too deeply (more than {MAX_DEPTH} levels): "
    "split the expression with intermediate parameters"
)


def deepest_node(root: Any) -> Position | None:
    """The position of the first node nested deeper than ``MAX_DEPTH``, found without
    recursion; None when the tree is shallow enough."""
    pending: list[tuple[Any, int, Position | None]] = [(root, 0, None)]
    while pending:
        node, depth, where = pending.pop()
        if not is_dataclass(node):
            continue
        where = getattr(node, "position", where)
        if depth > MAX_DEPTH:
            return where
        for item in fields(node):
            value = getattr(node, item.name)
            children = value if isinstance(value, tuple) else (value,)
            pending.extend((child, depth + 1, where) for child in children)
    return None


def deepest(text: str, shown: str) -> Position:
    """Where the text nests deepest in brackets, else the start of its longest line: the
    best pointer to an expression too deep for the parser."""
    depth, best, where = 0, 0, None
    line, column = 1, 1
    for char in text:
        if char in "([{":
            depth += 1
            if depth > best:
                best, where = depth, (line, column)
        elif char in ")]}":
            depth -= 1
        line, column = (line + 1, 1) if char == "\n" else (line, column + 1)
    if where is None or best < 8:
        lines = text.splitlines() or [""]
        longest = max(range(len(lines)), key=lambda i: len(lines[i]))
        where = (longest + 1, len(lines[longest]) - len(lines[longest].lstrip()) + 1)
    return Position(shown, *where)
