"""The language server seen from an editor: diagnostics, completion, definitions, outline."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsprotocol import types as lsp
from pytest_lsp import LanguageClient


async def open_file(client: LanguageClient, path: Path, text: str | None = None) -> str:
    uri = path.as_uri()
    client.text_document_did_open(
        lsp.DidOpenTextDocumentParams(
            lsp.TextDocumentItem(uri, "lightrocks", 1, text or path.read_text(encoding="utf-8"))
        )
    )
    await client.wait_for_notification(lsp.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    return uri


def change(client: LanguageClient, uri: str, version: int, text: str) -> None:
    client.text_document_did_change(
        lsp.DidChangeTextDocumentParams(
            lsp.VersionedTextDocumentIdentifier(uri, version),
            [lsp.TextDocumentContentChangeWholeDocument(text)],
        )
    )


async def settle(client: LanguageClient, uri: str) -> None:
    """Wait until the server answered a request sent after the last notification."""
    await client.text_document_document_symbol_async(
        lsp.DocumentSymbolParams(lsp.TextDocumentIdentifier(uri))
    )


@pytest.mark.asyncio
async def test_a_misspelled_outcome_is_reported_where_it_is_written(
    client: LanguageClient, examples: Path
) -> None:
    retreat = examples / "screwing" / "skills" / "Retreat.lr"
    text = retreat.read_text(encoding="utf-8")
    uri = await open_file(client, retreat)
    assert not [d for d in client.diagnostics.get(uri, []) if d.code == "LR0111"]
    change(client, uri, 2, text.replace("retreated lifted;", "retreated liftd;"))
    await client.wait_for_notification(lsp.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    [finding] = [d for d in client.diagnostics[uri] if d.code == "LR0111"]
    row = text.splitlines().index("  Up -> retreated lifted;")
    column = len("  Up -> retreated ")
    assert finding.range == lsp.Range(
        lsp.Position(row, column), lsp.Position(row, column + len("liftd"))
    )
    assert "did you mean 'lifted'" in finding.message


@pytest.mark.asyncio
async def test_breaking_an_imported_chart_reaches_its_importers_and_fixing_it_clears_them(
    client: LanguageClient, examples: Path
) -> None:
    lift = examples / "screwing" / "actions" / "Lift.lr"
    retreat_uri = (examples / "screwing" / "skills" / "Retreat.lr").as_uri()
    text = lift.read_text(encoding="utf-8")
    uri = await open_file(client, lift)
    assert not client.diagnostics.get(retreat_uri)
    change(client, uri, 2, text.replace("condition lifted", "condition raised"))
    await settle(client, uri)
    assert any(d.code == "LR0111" for d in client.diagnostics.get(retreat_uri, []))
    change(client, uri, 3, text)
    await settle(client, uri)
    assert not client.diagnostics.get(retreat_uri)


@pytest.mark.asyncio
async def test_completion_offers_the_outcomes_and_states(
    client: LanguageClient, examples: Path
) -> None:
    retreat = examples / "screwing" / "skills" / "Retreat.lr"
    uri = await open_file(client, retreat)
    row = retreat.read_text(encoding="utf-8").splitlines().index("  Up -> retreated lifted;")
    result = await client.text_document_completion_async(
        lsp.CompletionParams(lsp.TextDocumentIdentifier(uri), lsp.Position(row, 20))
    )
    labels = {item.label for item in result}
    assert {"lifted", "Up", "statechart"} <= labels


@pytest.mark.asyncio
async def test_definition_of_an_imported_chart_is_in_its_file(
    client: LanguageClient, examples: Path
) -> None:
    retreat = examples / "screwing" / "skills" / "Retreat.lr"
    uri = await open_file(client, retreat)
    lines = retreat.read_text(encoding="utf-8").splitlines()
    row = next(i for i, line in enumerate(lines) if '"Lift"' in line)
    column = lines[row].index("Lift") + 1
    location = await client.text_document_definition_async(
        lsp.DefinitionParams(lsp.TextDocumentIdentifier(uri), lsp.Position(row, column))
    )
    lift = examples / "screwing" / "actions" / "Lift.lr"
    assert Path(location.uri.removeprefix("file://")).resolve() == lift.resolve()
    declared = lift.read_text(encoding="utf-8").splitlines()[location.range.start.line]
    assert "statechart Lift" in declared


@pytest.mark.asyncio
async def test_outline_lists_the_chart_and_its_states(
    client: LanguageClient, examples: Path
) -> None:
    uri = await open_file(client, examples / "plain" / "Turnstile.lr")
    [chart] = await client.text_document_document_symbol_async(
        lsp.DocumentSymbolParams(lsp.TextDocumentIdentifier(uri))
    )
    assert chart.name == "Turnstile"
    assert {s.name for s in chart.children} == {"Operating", "Maintenance", "Off"}
    operating = next(s for s in chart.children if s.name == "Operating")
    assert {s.name for s in operating.children} == {"Locked", "Unlocked"}


@pytest.mark.asyncio
async def test_formatting_prints_the_canonical_form(client: LanguageClient, examples: Path) -> None:
    turnstile = examples / "plain" / "Turnstile.lr"
    text = turnstile.read_text(encoding="utf-8")
    uri = await open_file(
        client, turnstile, text.replace("  state Maintenance", "state   Maintenance")
    )
    [edit] = await client.text_document_formatting_async(
        lsp.DocumentFormattingParams(
            lsp.TextDocumentIdentifier(uri), lsp.FormattingOptions(2, True)
        )
    )
    assert edit.new_text == text
