"""The language server knows every robot of the device library: a cell that names the Panda
is checked against it, and its type leads to its declaration."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsp_session import cursor, document, open_file, path_of, settle
from lsprotocol import types as lsp
from pytest_lsp import LanguageClient

CELL = Path("screwing") / "cell" / "ScrewingCell.lrd"


@pytest.mark.asyncio
async def test_a_cell_names_the_panda_of_the_library(
    client: LanguageClient, examples: Path
) -> None:
    cell = examples / CELL
    text = cell.read_text(encoding="utf-8").replace("robot : LWR;", "robot : Panda;")
    cell.write_text(text, encoding="utf-8")
    uri = await open_file(client, cell)
    await settle(client, uri)
    assert list(client.diagnostics[uri]) == []  # published, and empty
    location = await client.text_document_definition_async(
        lsp.DefinitionParams(document(uri), cursor(text, "robot : Panda", "Panda"))
    )
    library = path_of(location.uri)
    assert library.parts[-4:] == ("library", "lightrocks", "robots", "panda.lrd")
    declared = library.read_text(encoding="utf-8").splitlines()
    assert "device Panda" in declared[location.range.start.line]
