"""Positions in the encoding agreed at initialization: UTF-16 code units unless the client
offers UTF-8 or UTF-32; a finding's range spans the element it is reported at."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import pytest_lsp
from lsp_session import document, fixes, open_file
from lsprotocol import types as lsp
from pytest_lsp import ClientServerConfig, LanguageClient

LIFT = Path("screwing") / "actions" / "Lift.lr"
WRONG = "distance > 3 N"
"""A comparison of a length with a force (LR0304), after an emoji in a comment."""
UNITS = {"utf-16": 2, "utf-8": 4, "utf-32": 1}
"""Code units of the emoji in each encoding."""


def broken(examples: Path) -> str:
    text = (examples / LIFT).read_text(encoding="utf-8")
    return text.replace("[robot.goalReached]", f"[robot.goalReached && /* 🤖 */ {WRONG}]")


def expected(text: str, encoding: str) -> lsp.Range:
    """The range of ``WRONG`` in code units of ``encoding`` (the emoji is the line's only
    character outside ASCII)."""
    row = next(i for i, line in enumerate(text.split("\n")) if WRONG in line)
    start = text.split("\n")[row].index(WRONG) - 1 + UNITS[encoding]
    return lsp.Range(lsp.Position(row, start), lsp.Position(row, start + len(WRONG)))


async def finding(client: LanguageClient, uri: str, code: str) -> lsp.Diagnostic:
    [found] = [d for d in client.diagnostics[uri] if d.code == code]
    return found


@pytest.mark.asyncio
async def test_columns_count_utf16_code_units_by_default(
    client: LanguageClient, examples: Path
) -> None:
    text = broken(examples)
    uri = await open_file(client, examples / LIFT, text)
    assert (await finding(client, uri, "LR0304")).range == expected(text, "utf-16")
    after = expected(text, "utf-16").start  # a cursor on 'distance', in UTF-16 units
    found = await client.text_document_hover_async(lsp.HoverParams(document(uri), after))
    assert "Length distance" in found.contents.value


@pytest.mark.asyncio
async def test_a_range_spans_the_offending_element_and_stops_at_its_first_line(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / LIFT).read_text(encoding="utf-8")
    wrong = text.replace("Length distance", "Lenght distance")
    uri = await open_file(client, examples / LIFT, wrong)
    row = next(i for i, line in enumerate(wrong.split("\n")) if "Lenght" in line)
    line = wrong.split("\n")[row]
    start, end = line.index("Lenght"), line.index(";") + 1  # the whole parameter
    unknown = await finding(client, uri, "LR0105")
    assert unknown.range == lsp.Range(lsp.Position(row, start), lsp.Position(row, end))
    [fix] = await fixes(client, uri, unknown)
    [edit] = fix.edit.changes[uri]
    assert edit.new_text == "Length"  # the written name is replaced, not the declaration
    assert edit.range == lsp.Range(lsp.Position(row, start), lsp.Position(row, start + 6))


@pytest_lsp.fixture(
    config=ClientServerConfig(server_command=[sys.executable, "-m", "lightrocks.app.cli", "lsp"]),
    params=["utf-8", "utf-32"],
)
async def negotiated(lsp_client: LanguageClient, request: pytest.FixtureRequest, examples: Path):
    offered = lsp.GeneralClientCapabilities(position_encodings=[request.param, "utf-16"])
    result = await lsp_client.initialize_session(
        lsp.InitializeParams(
            capabilities=lsp.ClientCapabilities(general=offered), root_uri=examples.as_uri()
        )
    )
    assert result.capabilities.position_encoding == request.param
    yield
    await lsp_client.shutdown_session()


@pytest.mark.asyncio
async def test_a_client_offering_utf8_or_utf32_gets_its_units(
    negotiated: LanguageClient, examples: Path, request: pytest.FixtureRequest
) -> None:
    encoding = request.node.callspec.params["negotiated"]
    text = broken(examples)
    uri = await open_file(negotiated, examples / LIFT, text)
    assert (await finding(negotiated, uri, "LR0304")).range == expected(text, encoding)
