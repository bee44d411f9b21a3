"""``lightrocks lsp``: a language server over stdio built on the incremental check.

Every open, change and save re-checks the edited file and the files that depend on it, and
publishes the findings of every file whose findings changed, so fixing an imported chart
clears the findings of its importers. The features answer from an index of the checked
files (:mod:`.index`); this module only wires requests to them. Parse results stay in the
server's memory: on disk, every state of a file being typed would be an entry.
"""

from __future__ import annotations

from pathlib import Path

from lsprotocol import types as lsp
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from lightrocks.app.lsp import completion as completing
from lightrocks.app.lsp import diagnostics, navigation
from lightrocks.app.lsp.hover import expression_hover, quantity_hover
from lightrocks.app.lsp.hover import hover as describe
from lightrocks.app.lsp.index import Index
from lightrocks.app.lsp.stdio import serve
from lightrocks.app.lsp.text import Text
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench import parsecache
from lightrocks.workbench.diagnostics import Diagnostic
from lightrocks.workbench.incremental import IncrementalCheck
from lightrocks.workbench.languages import language_for


class LightRocksServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("lightrocks", "1")
        self.checker: IncrementalCheck | None = None
        self.index = Index()
        self.published: dict[Path, list[Diagnostic]] = {}

    def text(self, path: Path) -> Text:
        """An open document's buffer, else the file on disk, in the position encoding
        negotiated with the client."""
        document = self.workspace.get_text_document(from_fs_path(str(path)))
        try:
            source = document.source
        except (OSError, UnicodeDecodeError):
            source = ""
        return Text(source, document.position_codec)

    def recheck(self, path: Path, text: str | None) -> None:
        """Re-check after an edit and publish the findings of every file that changed."""
        path = path.resolve()
        if self.checker is None:
            root = self.workspace.root_path
            self.checker = IncrementalCheck([Path(root) if root else path.parent])
            if text is not None:
                self.checker.texts[path] = text
            findings = self.checker.full()
        else:
            if not any(path.is_relative_to(root.resolve()) for root in self.checker.paths):
                self.checker.paths.append(path)  # a model opened from outside the workspace
            findings = self.checker.update({path: text})
        if self.checker.context is not None:
            context = self.checker.context
            inferred = analysis(context).typing.inferred
            self.index.update(context.workspace, self.text, inferred)
        by_file: dict[Path, list[Diagnostic]] = {}
        for finding in findings:
            by_file.setdefault(Path(finding.file).resolve(), []).append(finding)
        for file in {path} | set(self.published) | set(by_file):
            current = by_file.get(file, [])
            if file == path or current != self.published.get(file, []):
                text_of_file = self.text(file)
                items = [diagnostics.diagnostic(f, text_of_file) for f in current]
                self.text_document_publish_diagnostics(
                    lsp.PublishDiagnosticsParams(uri=from_fs_path(str(file)), diagnostics=items)
                )
        self.published = by_file


server = LightRocksServer()


def _path(uri: str) -> Path:
    return Path(to_fs_path(uri)).resolve()


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


@server.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
def did_close(ls: LightRocksServer, params: lsp.DidCloseTextDocumentParams) -> None:
    ls.recheck(_path(params.text_document.uri), None)  # back to the file on disk


@server.feature(lsp.TEXT_DOCUMENT_FORMATTING)
def formatting(ls: LightRocksServer, params: lsp.DocumentFormattingParams) -> list[lsp.TextEdit]:
    """The whole document printed canonically; nothing when it does not parse."""
    path = _path(params.text_document.uri)
    language = language_for(path.suffix)
    text = ls.text(path)
    if language is None:
        return []
    try:
        printed = language.format(text.source, str(path))
    except SyntaxProblem:
        return []
    if printed == text.source:
        return []
    return [lsp.TextEdit(lsp.Range(lsp.Position(0, 0), text.end()), printed)]


@server.feature(lsp.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
def document_symbols(
    ls: LightRocksServer, params: lsp.DocumentSymbolParams
) -> list[lsp.DocumentSymbol]:
    file = ls.index.files.get(_path(params.text_document.uri))
    return navigation.document_symbols(file) if file else []


@server.feature(lsp.TEXT_DOCUMENT_DEFINITION)
def definition(ls: LightRocksServer, params: lsp.DefinitionParams) -> lsp.Location | None:
    return navigation.definition(ls.index, _path(params.text_document.uri), params.position)


@server.feature(lsp.TEXT_DOCUMENT_REFERENCES)
def references(ls: LightRocksServer, params: lsp.ReferenceParams) -> list[lsp.Location]:
    path, include = _path(params.text_document.uri), params.context.include_declaration
    return navigation.references(ls.index, path, params.position, include)


@server.feature(lsp.TEXT_DOCUMENT_PREPARE_RENAME)
def prepare_rename(ls: LightRocksServer, params: lsp.PrepareRenameParams) -> lsp.Range | None:
    return navigation.prepare_rename(ls.index, _path(params.text_document.uri), params.position)


@server.feature(lsp.TEXT_DOCUMENT_RENAME)
def rename(ls: LightRocksServer, params: lsp.RenameParams) -> lsp.WorkspaceEdit | None:
    path = _path(params.text_document.uri)
    return navigation.rename(ls.index, path, params.position, params.new_name)


@server.feature(lsp.TEXT_DOCUMENT_COMPLETION, lsp.CompletionOptions(trigger_characters=[".", " "]))
def completion(ls: LightRocksServer, params: lsp.CompletionParams) -> list[lsp.CompletionItem]:
    path = _path(params.text_document.uri)
    prefix = ls.text(path).prefix(params.position)
    return completing.completions(ls.index.files.get(path), prefix, params.position)


@server.feature(lsp.TEXT_DOCUMENT_HOVER)
def hover(ls: LightRocksServer, params: lsp.HoverParams) -> lsp.Hover | None:
    path = _path(params.text_document.uri)
    found = ls.index.at(path, params.position)
    if found is None:
        return quantity_hover(ls.text(path), params.position) or expression_hover(
            ls.index.files.get(path), params.position
        )
    if ls.checker is None or ls.checker.context is None:
        return None
    return describe(ls.index, found, ls.checker.context.workspace)


@server.feature(
    lsp.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL,
    lsp.SemanticTokensLegend(token_types=navigation.TOKEN_TYPES, token_modifiers=[]),
)
def semantic_tokens(ls: LightRocksServer, params: lsp.SemanticTokensParams) -> lsp.SemanticTokens:
    path = _path(params.text_document.uri)
    return navigation.semantic_tokens(ls.index.files.get(path), ls.text(path))


@server.feature(
    lsp.TEXT_DOCUMENT_CODE_ACTION,
    lsp.CodeActionOptions(code_action_kinds=[lsp.CodeActionKind.QuickFix]),
)
def code_actions(ls: LightRocksServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction]:
    uri = params.text_document.uri
    path = _path(uri)
    return diagnostics.quick_fixes(uri, params.context.diagnostics, ls.text(path), _unit(ls, path))


def _unit(ls: LightRocksServer, path: Path) -> ast.StatechartUnit | None:
    """The document's statechart as it reads now (memory cache), or None where it does
    not parse or is no statechart."""
    language = language_for(path.suffix)
    if language is None:
        return None
    try:
        unit = parsecache.parse(language, ls.text(path).source, str(path))
    except SyntaxProblem:
        return None
    return unit if isinstance(unit, ast.StatechartUnit) else None


def main() -> int:
    parsecache.use_store(None)  # memory only, whatever the command line installed
    serve(server)
    return 0
