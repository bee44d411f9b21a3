"""Typing an example from an empty buffer: every partial document must leave the server
answering. Prefixes are sampled (every fourth character, and every line end) to keep the
run short while still passing through unterminated strings, blocks and transitions."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsp_session import change, document, open_file
from lsprotocol import types as lsp
from pytest_lsp import LanguageClient

from lightrocks.app.lsp.text import Text

RETREAT = Path("screwing") / "skills" / "Retreat.lr"


def prefixes(text: str) -> list[str]:
    ends = {i + 1 for i, char in enumerate(text) if char == "\n"}
    cuts = sorted(set(range(0, len(text), 4)) | ends | {len(text)})
    return [text[:cut] for cut in cuts]


@pytest.mark.asyncio
async def test_every_keystroke_state_leaves_the_server_answering(
    client: LanguageClient, examples: Path
) -> None:
    path = examples / RETREAT
    text = path.read_text(encoding="utf-8")
    uri = await open_file(client, path, "")
    assert [d.code for d in client.diagnostics[uri]] == ["LR0003"]
    for version, typed in enumerate(prefixes(text), start=2):
        await change(client, uri, version, typed)
        end = Text(typed).end()
        items = await client.text_document_completion_async(
            lsp.CompletionParams(document(uri), end)
        )
        assert items is not None
        await client.text_document_hover_async(lsp.HoverParams(document(uri), end))
        await client.text_document_semantic_tokens_full_async(
            lsp.SemanticTokensParams(document(uri))
        )
        assert [m.message for m in client.messages if m.type == lsp.MessageType.Error] == []
    assert client.diagnostics[uri] == ()
    [chart] = await client.text_document_document_symbol_async(
        lsp.DocumentSymbolParams(document(uri))
    )
    assert chart.name == "Retreat"
