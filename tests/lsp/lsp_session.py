"""What an editor sends: open, change, and a request that proves earlier notifications ran."""

from __future__ import annotations

from pathlib import Path

from lsprotocol import types as lsp
from pytest_lsp import LanguageClient


def document(uri: str) -> lsp.TextDocumentIdentifier:
    return lsp.TextDocumentIdentifier(uri)


async def settle(client: LanguageClient, uri: str) -> None:
    """Wait until the server answered a request sent after the last notification: it handles
    messages in order, so every diagnostic of the earlier edits has been published."""
    await client.text_document_document_symbol_async(lsp.DocumentSymbolParams(document(uri)))


async def open_file(client: LanguageClient, path: Path, text: str | None = None) -> str:
    uri = path.as_uri()
    source = path.read_text(encoding="utf-8") if text is None else text
    client.text_document_did_open(
        lsp.DidOpenTextDocumentParams(lsp.TextDocumentItem(uri, "lightrocks", 1, source))
    )
    await settle(client, uri)
    return uri


async def change(client: LanguageClient, uri: str, version: int, text: str) -> None:
    client.text_document_did_change(
        lsp.DidChangeTextDocumentParams(
            lsp.VersionedTextDocumentIdentifier(version=version, uri=uri),
            [lsp.TextDocumentContentChangeWholeDocument(text)],
        )
    )
    await settle(client, uri)


def cursor(text: str, line_text: str, word: str) -> lsp.Position:
    """The position of ``word`` inside the line containing ``line_text``."""
    lines = text.splitlines()
    row = next(i for i, line in enumerate(lines) if line_text in line)
    return lsp.Position(row, lines[row].index(line_text) + line_text.index(word))


def path_of(uri: str) -> Path:
    return Path(uri.removeprefix("file://")).resolve()


async def fixes(client: LanguageClient, uri: str, finding: lsp.Diagnostic) -> list[lsp.CodeAction]:
    """The code actions offered for one published finding."""
    context = lsp.CodeActionContext(diagnostics=[finding])
    params = lsp.CodeActionParams(document(uri), finding.range, context)
    return await client.text_document_code_action_async(params)
