"""Loading models from the model path and resolving names through one index.

Every declaration gets a qualified name in one dictionary, so resolving a reference is a
dictionary lookup: checking grows linearly with the model, unlike textX's default scoping
that searches the whole model for every reference.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.metamodel.ast import Import, Position
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench import parsecache
from lightrocks.workbench.diagnostics import Diagnostics, did_you_mean
from lightrocks.workbench.languages import Language, extensions, implicit_packages, language_for
from lightrocks.workbench.modelpath import ModelPath
from lightrocks.workbench.reads import Reads, TooLarge, listing, raw


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
        unchanged: Mapping[Path, Loaded] | None = None,
        substituted: Mapping[Path, Any] | None = None,
    ) -> None:
        self.model_path = model_path
        self.diagnostics = diagnostics
        self.texts = texts or {}  # unsaved editor contents that replace files on disk
        self.unchanged = unchanged or {}  # files known unchanged since an earlier load
        self.substituted = substituted or {}  # a text or a unit per file, never cached
        self.files: dict[Path, Loaded | None] = {}
        self.symbols: dict[str, Symbol] = {}
        self._packages: dict[str, dict[str, Symbol]] = {}
        self._loaded_packages: set[str] = set()
        self._scopes: dict[Path, dict[str, Symbol]] = {}
        self.targets: dict[Path, None] | None = None  # the files CoCos report on; None: all
        self.uses: dict[Path, set[Path]] = {}  # files whose declarations a file's names reached
        self.reads = Reads()  # what loading read from disk, for the findings cache

    # -- loading --------------------------------------------------------------------------

    def load(self, path: Path) -> Loaded | None:
        """Parse a file once; problems become diagnostics and the file yields ``None``."""
        given, path = path, path.resolve()
        if given != path:
            self.reads.links[str(given)] = str(path)
        if path in self.files:
            return self.files[path]
        self.files[path] = None
        if path in self.unchanged:
            self.reads.complete = False
            return self._add(self.unchanged[path])
        language = language_for(path.suffix)
        shown = shown_name(path)
        if language is None:
            self.diagnostics.error(Position(shown, 1, 1), "LR0004", "not a model file")
            return None
        substitute = self.substituted.get(path)
        if substitute is not None:
            self.reads.complete = False
            if not isinstance(substitute, str):
                return self._add(Loaded(path, language, substitute))
        text = self._read(path, shown) if substitute is None else self._text(substitute, shown)
        if text is None:
            return None
        try:
            unit = parsecache.parse(language, text, shown, remember=substitute is None)
        except SyntaxProblem as problem:
            where = Position(shown, problem.line, problem.column)
            self.diagnostics.error(where, "LR0001", problem.message)
            return None
        return self._add(Loaded(path, language, unit))

    def _add(self, loaded: Loaded) -> Loaded:
        self.files[loaded.path] = loaded
        unit = loaded.unit
        for name, node in loaded.language.declarations(unit):
            self._declare(f"{unit.package}.{name}" if unit.package else name, node, loaded)
        return loaded

    def _read(self, path: Path, shown: str) -> str | None:
        where = Position(shown, 1, 1)
        if not path.is_file():  # a FIFO or device would block or never end
            self.reads.file(path, None)
            self.diagnostics.error(where, "LR0004", "not a regular file")
            return None
        try:
            data = raw(path, self.texts)
        except TooLarge as error:
            self.reads.file(path, None)
            self.diagnostics.error(where, "LR0004", str(error))
            return None
        except OSError as error:
            self.reads.file(path, None)
            self.diagnostics.error(where, "LR0004", f"cannot read file: {error.strerror}")
            return None
        self.reads.file(path, data)
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as error:
            line = data[: error.start].count(b"\n") + 1
            self.diagnostics.error(
                Position(shown, line, 1), "LR0002", "not a text file: invalid UTF-8"
            )
            return None
        return self._text(text, shown)

    def _text(self, text: str, shown: str) -> str | None:
        """The text of a model file, or ``None`` with a finding when it is none."""
        where = Position(shown, 1, 1)
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
            for folder in self._package_folders(package):
                for name in self._listing(folder):
                    if not name.endswith("/"):
                        self.load(folder / name)
        return self._packages.get(package, {})

    def _package_folders(self, package: str) -> list[Path]:
        folders = list(self.model_path.package_folders(package))
        self.reads.packages[package] = [str(folder) for folder in folders]
        return [folder.resolve() for folder in folders]

    def _listing(self, folder: Path) -> list[str]:
        entries = listing(folder, extensions())
        self.reads.listings[str(folder)] = entries
        return entries

    # -- resolution -----------------------------------------------------------------------

    def lookup(self, qualified_name: str) -> Symbol | None:
        """A declaration by qualified name, loading its package on demand."""
        symbol = self.symbols.get(qualified_name)
        if symbol is None and "." in qualified_name:
            self.load_package(qualified_name.rpartition(".")[0])
            symbol = self.symbols.get(qualified_name)
        return symbol

    def scope(self, loaded: Loaded) -> dict[str, Symbol]:
        """Simple names visible in a file: the languages' implicit packages, its own package,
        then its imports."""
        scope = self._scopes.get(loaded.path)
        if scope is not None:
            return scope
        scope = {}
        for package in (*implicit_packages(), loaded.package):
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
                    f"{parent}.{name[:-1]}" if parent else name[:-1]
                    for folder in self._package_folders(parent)
                    for name in self._listing(folder)
                    if name.endswith("/")
                }
                if imported.name in siblings:  # its folder holds no declaration
                    message, hint = f"package '{imported.name}' has no models", ""
                else:
                    message = f"package '{imported.name}' not found"
                    hint = did_you_mean(imported.name, siblings)
                self.diagnostics.error(imported.position, "LR0102", message, hint)
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
        symbol = self.lookup(name) if "." in name else self.scope(loaded).get(name)
        if symbol is not None:
            self.use(loaded, symbol)
        return symbol

    def use(self, loaded: Loaded, symbol: Symbol) -> None:
        """Record that what ``loaded`` means depends on the declaration behind ``symbol``:
        an edit of that declaration's file must re-check this one."""
        if symbol.loaded.path != loaded.path:
            self.uses.setdefault(loaded.path, set()).add(symbol.loaded.path)

    def interface(self, loaded: Loaded) -> frozenset[tuple[str, str]]:
        """The names a file declares, with their kinds: what other files' scopes see of it."""
        return frozenset(
            (name, type(node).__name__) for name, node in loaded.language.declarations(loaded.unit)
        )

    def loaded_units(self) -> list[Loaded]:
        return [loaded for loaded in self.files.values() if loaded is not None]

    def checked_units(self) -> list[Loaded]:
        """The units CoCos report on: every loaded unit, or the targets of a partial check
        (the files they import are loaded for their declarations only)."""
        if self.targets is None:
            return self.loaded_units()
        return [loaded for path in self.targets if (loaded := self.files.get(path)) is not None]


def shown_name(path: Path) -> str:
    """A path as users see it in findings: relative to the working folder when possible."""
    try:
        return str(path.relative_to(Path.cwd()))
    except ValueError:
        return str(path)
