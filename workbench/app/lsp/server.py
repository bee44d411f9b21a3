"""``lightrocks lsp``: a language server over stdio built on the incremental check.

Every open, change and save re-checks the edited file and the files that depend on it, and
publishes the findings of every file whose findings changed, so fixing an imported chart
clears the findings of its importers.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from lsprotocol import types as lsp
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from lightrocks.metamodel.ast import Condition, Position, State
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench.diagnostics import Diagnostic, Severity
from lightrocks.workbench.incremental import IncrementalCheck
from lightrocks.workbench.languages import language_for
from lightrocks.workbench.workspace import Loaded

KEYWORDS = (
    "package", "import", "statechart", "state", "initial", "final", "parameters", "entry",
    "exit", "do", "end", "condition", "true", "false",
)  # fmt: skip
WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_.]*")
SEVERITIES = {
    Severity.ERROR: lsp.DiagnosticSeverity.Error,
    Severity.WARNING: lsp.DiagnosticSeverity.Warning,
    Severity.INFO: lsp.DiagnosticSeverity.Information,
}


class LightRocksServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("lightrocks", "1")
        self.checker: IncrementalCheck | None = None
        self.published: set[Path] = set()

    def recheck(self, path: Path, text: str | None) -> None:
        """Re-check after an edit and publish findings of every file that may have changed."""
        if self.checker is None:
            root = self.workspace.root_path
            self.checker = IncrementalCheck([Path(root) if root else path.parent])
            self.checker.texts[path.resolve()] = text if text is not None else ""
            if text is None:
                self.checker.texts.pop(path.resolve())
            findings = self.checker.full()
        else:
            findings = self.checker.update({path: text})
        by_file: dict[Path, list[lsp.Diagnostic]] = {}
        for finding in findings:
            by_file.setdefault(Path(finding.file).resolve(), []).append(self.diagnostic(finding))
        for file in self.published | set(by_file):
            uri = from_fs_path(str(file))
            items = by_file.get(file, [])
            self.text_document_publish_diagnostics(
                lsp.PublishDiagnosticsParams(uri=uri, diagnostics=items)
            )
        self.published = set(by_file)

    def diagnostic(self, finding: Diagnostic) -> lsp.Diagnostic:
        path = Path(finding.file).resolve()
        return lsp.Diagnostic(
            range=self.word_range(path, finding.line, finding.column),
            message=finding.message + (f" ({finding.hint})" if finding.hint else ""),
            severity=SEVERITIES[finding.severity],
            code=finding.code,
            source="lightrocks",
            data={"hint": finding.hint} if finding.hint else None,
        )

    def text_of(self, path: Path) -> str:
        document = self.workspace.get_text_document(from_fs_path(str(path)))
        try:
            return document.source
        except OSError:
            return ""

    def word_range(self, path: Path, line: int, column: int) -> lsp.Range:
        """The identifier starting at a 1-based position, or an empty range there."""
        lines = self.text_of(path).splitlines()
        row, col = max(line - 1, 0), max(column - 1, 0)
        text = lines[row] if row < len(lines) else ""
        match = WORD.match(text, col)
        end = match.end() if match else col
        return lsp.Range(lsp.Position(row, col), lsp.Position(row, end))

    def loaded(self, uri: str) -> Loaded | None:
        if self.checker is None or self.checker.context is None:
            return None
        path = Path(to_fs_path(uri)).resolve()
        found = self.checker.context.workspace.files.get(path)
        if found is None:
            found = self.checker.context.workspace.load(path)
        return found


server = LightRocksServer()


def _path(uri: str) -> Path:
    return Path(to_fs_path(uri))


@server.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
def did_open(ls: LightRocksServer, params: lsp.DidOpenTextDocumentParams) -> None:
    ls.recheck(_path(params.text_document.uri), params.text_document.text)


@server.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
def did_change(ls: LightRocksServer, params: lsp.DidChangeTextDocumentParams) -> None:
    uri = params.text_document.uri
    ls.recheck(_path(uri), ls.workspace.get_text_document(uri).source)


@server.feature(lsp.TEXT_DOCUMENT_DID_SAVE)
def did_save(ls: LightRocksServer, params: lsp.DidSaveTextDocumentParams) -> None:
    uri = params.text_document.uri
    ls.recheck(_path(uri), ls.workspace.get_text_document(uri).source)


@server.feature(lsp.TEXT_DOCUMENT_FORMATTING)
def formatting(ls: LightRocksServer, params: lsp.DocumentFormattingParams) -> list[lsp.TextEdit]:
    """The whole document printed canonically; nothing when it does not parse."""
    path = _path(params.text_document.uri)
    language = language_for(path.suffix)
    text = ls.workspace.get_text_document(params.text_document.uri).source
    if language is None:
        return []
    try:
        printed = language.format(text, str(path))
    except SyntaxProblem:
        return []
    if printed == text:
        return []
    end = lsp.Position(len(text.splitlines()) + 1, 0)
    return [lsp.TextEdit(lsp.Range(lsp.Position(0, 0), end), printed)]


@server.feature(lsp.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
def document_symbols(
    ls: LightRocksServer, params: lsp.DocumentSymbolParams
) -> list[lsp.DocumentSymbol]:
    """The declarations of the file, with the states of a statechart nested below it."""
    loaded = ls.loaded(params.text_document.uri)
    if loaded is None:
        return []
    path = _path(params.text_document.uri)
    return [
        _symbol(ls, path, name.rpartition(".")[2], node)
        for name, node in loaded.language.declarations(loaded.unit)
    ]


def _symbol(ls: LightRocksServer, path: Path, name: str, node: Any) -> lsp.DocumentSymbol:
    where = node.position
    kind = lsp.SymbolKind.Class if not isinstance(node, State) else lsp.SymbolKind.EnumMember
    children = [
        _symbol(ls, path, child.name, child)
        for child in (getattr(node, "elements", None) or getattr(node, "body", None) or ())
        if isinstance(child, State)
    ]
    word = ls.word_range(path, where.line, where.column)
    return lsp.DocumentSymbol(
        name=name or "?", kind=kind, range=word, selection_range=word, children=children
    )


@server.feature(lsp.TEXT_DOCUMENT_DEFINITION)
def definition(ls: LightRocksServer, params: lsp.DefinitionParams) -> lsp.Location | None:
    """Where the name under the cursor is declared: a state of the file or an imported model."""
    loaded = ls.loaded(params.text_document.uri)
    word = _word_at(ls, params.text_document.uri, params.position)
    if loaded is None or not word or ls.checker is None or ls.checker.context is None:
        return None
    state = _states(loaded.unit).get(word)
    if state is not None:
        return _location(ls, loaded.path, state.position)
    symbol = ls.checker.context.workspace.resolve(loaded, word)
    if symbol is None:
        return None
    return _location(ls, symbol.loaded.path, symbol.node.position)


@server.feature(lsp.TEXT_DOCUMENT_COMPLETION, lsp.CompletionOptions(trigger_characters=["."]))
def completion(ls: LightRocksServer, params: lsp.CompletionParams) -> list[lsp.CompletionItem]:
    """Keywords, the file's states, outcomes of its imported charts, and the visible names."""
    items = [lsp.CompletionItem(k, kind=lsp.CompletionItemKind.Keyword) for k in KEYWORDS]
    loaded = ls.loaded(params.text_document.uri)
    if loaded is not None and ls.checker is not None and ls.checker.context is not None:
        workspace = ls.checker.context.workspace
        states = _states(loaded.unit)
        items += [lsp.CompletionItem(s, kind=lsp.CompletionItemKind.EnumMember) for s in states]
        outcomes = {
            element.name
            for state in states.values()
            for stereotype in state.stereotypes
            if stereotype.name == "import" and stereotype.value
            for symbol in [workspace.resolve(loaded, stereotype.value)]
            if symbol is not None
            for element in getattr(symbol.node, "elements", ())
            if isinstance(element, Condition) and element.kind == "end"
        }
        items += [lsp.CompletionItem(o, kind=lsp.CompletionItemKind.Event) for o in outcomes]
        scope = workspace.scope(loaded)
        items += [lsp.CompletionItem(n, kind=lsp.CompletionItemKind.Class) for n in scope]
    return items


def _states(unit: Any) -> dict[str, State]:
    found: dict[str, State] = {}
    pending = list(getattr(getattr(unit, "statechart", None), "elements", ()))
    while pending:
        element = pending.pop()
        if isinstance(element, State):
            found.setdefault(element.name, element)
            pending.extend(element.body or ())
    return found


def _word_at(ls: LightRocksServer, uri: str, position: lsp.Position) -> str:
    lines = ls.workspace.get_text_document(uri).source.splitlines()
    if position.line >= len(lines):
        return ""
    text = lines[position.line]
    for match in WORD.finditer(text):
        if match.start() <= position.character <= match.end():
            return match.group()
    return ""


def _location(ls: LightRocksServer, path: Path, where: Position) -> lsp.Location:
    return lsp.Location(from_fs_path(str(path)), ls.word_range(path, where.line, where.column))


def main() -> int:
    server.start_io()
    return 0
