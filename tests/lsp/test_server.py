"""The language server seen from an editor, over stdio, on a copy of the examples."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsp_session import change, cursor, document, fixes, open_file, path_of, settle
from lsprotocol import types as lsp
from pytest_lsp import LanguageClient

RETREAT = Path("screwing") / "skills" / "Retreat.lr"
SNAP = Path("din_rail") / "skills" / "SnapOnRail.lr"
LIFT = Path("screwing") / "actions" / "Lift.lr"


@pytest.mark.asyncio
async def test_a_misspelled_outcome_is_reported_where_it_is_written_with_a_fix(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / RETREAT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / RETREAT)
    assert client.diagnostics[uri] == ()
    await change(client, uri, 2, text.replace("retreated lifted;", "retreated liftd;"))
    [finding] = [d for d in client.diagnostics[uri] if d.code == "LR0111"]
    start = cursor(text, "Up -> retreated lifted", "lifted")
    end = lsp.Position(start.line, start.character + len("liftd"))
    assert finding.range == lsp.Range(start, end)
    [fix] = await fixes(client, uri, finding)
    assert list(fix.edit.changes[uri]) == [lsp.TextEdit(finding.range, "lifted")]


@pytest.mark.asyncio
async def test_an_unhandled_timeout_is_fixed_as_a_sibling_handles_it(
    client: LanguageClient, examples: Path
) -> None:
    shipped = (examples / SNAP).read_text(encoding="utf-8")
    text = shipped.replace("  Press -> GiveUp timeout;\n", "")
    uri = await open_file(client, examples / SNAP, text)
    [finding] = [d for d in client.diagnostics[uri] if d.code == "LR0209"]
    assert finding.range.start == cursor(text, '<<import="Seat">> state Press;', "<<")
    [fix] = await fixes(client, uri, finding)
    [edit] = fix.edit.changes[uri]
    assert edit.range.start == cursor(text, "Press -> Settle seated", "Press")
    lines = text.split("\n")
    row, column = edit.range.start.line, edit.range.start.character
    lines[row] = lines[row][:column] + edit.new_text + lines[row][column:]
    await change(client, uri, 2, "\n".join(lines))
    assert not [d for d in client.diagnostics[uri] if d.code == "LR0209"]
    assert "  Press -> GiveUp timeout;\n  Press -> Settle seated" in "\n".join(lines)


@pytest.mark.asyncio
async def test_a_syntax_error_is_reported_on_its_line(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / RETREAT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / RETREAT, text.replace("go -> Up;", "go -> ;"))
    [finding] = client.diagnostics[uri]
    assert finding.code == "LR0001"
    assert finding.range.start.line == cursor(text, "go -> Up;", "go").line


@pytest.mark.asyncio
async def test_breaking_an_imported_chart_reaches_its_importers_and_fixing_it_clears_them(
    client: LanguageClient, examples: Path
) -> None:
    retreat_uri = (examples / RETREAT).as_uri()
    text = (examples / LIFT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / LIFT)
    assert not client.diagnostics.get(retreat_uri)
    await change(client, uri, 2, text.replace("condition lifted", "condition raised"))
    assert any(d.code == "LR0111" for d in client.diagnostics.get(retreat_uri, []))
    await change(client, uri, 3, text)
    assert client.diagnostics[retreat_uri] == ()


@pytest.mark.asyncio
async def test_completion_after_a_child_state_offers_its_outcomes(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / RETREAT).read_text(encoding="utf-8")
    typing = text.replace("Up -> retreated lifted;", "Up -> retreated l")
    uri = await open_file(client, examples / RETREAT)
    await change(client, uri, 2, typing)
    position = cursor(typing, "Up -> retreated l", "l")
    items = await client.text_document_completion_async(
        lsp.CompletionParams(document(uri), lsp.Position(position.line, position.character + 1))
    )
    labels = [item.label for item in items]
    assert labels[0] == "lifted"
    assert "Up" not in labels
    anywhere = await client.text_document_completion_async(
        lsp.CompletionParams(document(uri), lsp.Position(position.line, 0))
    )
    assert {"Up", "distance", "go", "robot", "statechart"} <= {i.label for i in anywhere}


@pytest.mark.asyncio
async def test_completion_after_a_device_lists_its_sensors_and_commands(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / LIFT).read_text(encoding="utf-8")
    typing = text.replace("[robot.goalReached]", "[robot.")
    uri = await open_file(client, examples / LIFT)
    await change(client, uri, 2, typing)
    position = cursor(typing, "[robot.", ".")
    items = await client.text_document_completion_async(
        lsp.CompletionParams(document(uri), lsp.Position(position.line, position.character + 1))
    )
    kinds = {item.label: item.kind for item in items}
    assert kinds["goalReached"] == lsp.CompletionItemKind.Property
    assert kinds["moveCartesian"] == lsp.CompletionItemKind.Method


@pytest.mark.asyncio
async def test_definition_jumps_across_files(client: LanguageClient, examples: Path) -> None:
    text = (examples / RETREAT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / RETREAT)
    lift = (examples / LIFT).read_text(encoding="utf-8").splitlines()
    for line_text, word, declared in (
        ('<<import="Lift">>', "Lift", "statechart Lift"),
        ("Up -> retreated lifted", "lifted", "end condition lifted"),
    ):
        location = await client.text_document_definition_async(
            lsp.DefinitionParams(document(uri), cursor(text, line_text, word))
        )
        assert path_of(location.uri) == (examples / LIFT).resolve()
        assert declared in lift[location.range.start.line]
        start, end = location.range.start.character, location.range.end.character
        assert lift[location.range.start.line][start:end] == word


@pytest.mark.asyncio
async def test_definition_of_a_sensor_is_in_the_device_model(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / LIFT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / LIFT)
    location = await client.text_document_definition_async(
        lsp.DefinitionParams(document(uri), cursor(text, "robot.goalReached", "goalReached"))
    )
    library = path_of(location.uri)  # the device library, on every model path
    assert library.parts[-4:] == ("library", "lightrocks", "robots", "lwr.lrd")
    declared = library.read_text(encoding="utf-8").splitlines()
    assert "goalReached" in declared[location.range.start.line]


@pytest.mark.asyncio
async def test_references_of_a_parameter_include_its_uses(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / LIFT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / LIFT)
    found = await client.text_document_references_async(
        lsp.ReferenceParams(
            text_document=document(uri),
            position=cursor(text, "Length distance", "distance"),
            context=lsp.ReferenceContext(include_declaration=True),
        )
    )
    lines = text.splitlines()
    uses = {
        (path_of(r.uri).name, lines[r.range.start.line].strip())
        for r in found
        if path_of(r.uri) == (examples / LIFT).resolve()
    }
    assert len(uses) == 2
    assert any("Retreat.lr" in r.uri for r in found)  # Up(distance = …) names it


@pytest.mark.asyncio
async def test_renaming_a_state_edits_its_declaration_and_transitions(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / RETREAT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / RETREAT)
    edit = await client.text_document_rename_async(
        lsp.RenameParams(document(uri), cursor(text, "go -> Up", "Up"), "Rise")
    )
    [change_of_file] = edit.document_changes
    assert path_of(change_of_file.text_document.uri) == (examples / RETREAT).resolve()
    lines = text.splitlines()
    assert len(change_of_file.edits) == 3
    for item in change_of_file.edits:
        start, end = item.range.start, item.range.end
        assert lines[start.line][start.character : end.character] == "Up"
        assert item.new_text == "Rise"


@pytest.mark.asyncio
async def test_renaming_a_statechart_renames_its_file_and_importers(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / LIFT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / LIFT)
    edit = await client.text_document_rename_async(
        lsp.RenameParams(document(uri), cursor(text, "statechart Lift", "Lift"), "Raise")
    )
    *edits, moved = edit.document_changes
    assert path_of(moved.old_uri) == (examples / LIFT).resolve()
    assert path_of(moved.new_uri).name == "Raise.lr"
    assert (examples / RETREAT).resolve() in {path_of(e.text_document.uri) for e in edits}


@pytest.mark.asyncio
async def test_hover_shows_units_signatures_and_imported_outcomes(
    client: LanguageClient, examples: Path
) -> None:
    retreat = (examples / RETREAT).read_text(encoding="utf-8")
    lift = (examples / LIFT).read_text(encoding="utf-8")
    retreat_uri = await open_file(client, examples / RETREAT)
    lift_uri = await open_file(client, examples / LIFT)
    shown = {}
    for uri, text, line_text, word in (
        (retreat_uri, retreat, "state Up(", "Up"),
        (lift_uri, lift, "distance)", "distance"),
        (lift_uri, lift, "robot.moveCartesian", "moveCartesian"),
        (lift_uri, lift, "distance = 100 mm", "mm"),
    ):
        found = await client.text_document_hover_async(
            lsp.HoverParams(document(uri), cursor(text, line_text, word))
        )
        shown[word] = found.contents.value
    assert "statechart Lift(Length distance" in shown["Up"]
    assert "outcomes: lifted" in shown["Up"]
    assert "Length distance" in shown["distance"] and "[m]" in shown["distance"]
    assert shown["moveCartesian"].count("command moveCartesian(") == 1
    assert "100 mm = 0.1 [m]" in shown["mm"]


@pytest.mark.asyncio
async def test_hover_types_members_and_operators(client: LanguageClient, examples: Path) -> None:
    approach = examples / "screwing" / "actions" / "Approach.lr"
    text = approach.read_text(encoding="utf-8")
    uri = await open_file(client, approach)
    shown = {}
    for word in ("force", "z", ">"):
        where = cursor(text, "abs(robot.wrench.force.z) > maxForce", word)
        found = await client.text_document_hover_async(lsp.HoverParams(document(uri), where))
        shown[word] = found.contents.value
    assert shown["force"] == "`robot.wrench.force : Force3`"
    assert shown["z"].startswith("`robot.wrench.force.z : Force [")
    assert shown[">"] == "`abs(robot.wrench.force.z) > maxForce : Boolean`"


@pytest.mark.asyncio
async def test_outline_nests_states_below_their_chart_and_composite_states(
    client: LanguageClient, examples: Path
) -> None:
    uri = await open_file(client, examples / "plain" / "Turnstile.lr")
    [chart] = await client.text_document_document_symbol_async(
        lsp.DocumentSymbolParams(document(uri))
    )
    assert chart.name == "Turnstile"
    states = {s.name: s for s in chart.children if s.kind == lsp.SymbolKind.EnumMember}
    assert set(states) == {"Operating", "Maintenance", "Off"}
    assert {s.name for s in states["Operating"].children} == {"Locked", "Unlocked"}


@pytest.mark.asyncio
async def test_semantic_tokens_mark_states_and_keywords(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / RETREAT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / RETREAT)
    tokens = await client.text_document_semantic_tokens_full_async(
        lsp.SemanticTokensParams(document(uri))
    )
    decoded, line, start = {}, 0, 0
    for index in range(0, len(tokens.data), 5):
        delta_line, delta_start, length, kind, _ = tokens.data[index : index + 5]
        line, start = line + delta_line, (start + delta_start if delta_line == 0 else delta_start)
        decoded[text.splitlines()[line][start : start + length], line] = kind
    up = cursor(text, "go -> Up", "Up")
    statechart = cursor(text, "statechart Retreat", "statechart")
    assert decoded["Up", up.line] != decoded["statechart", statechart.line]


@pytest.mark.asyncio
async def test_formatting_prints_the_canonical_form(client: LanguageClient, examples: Path) -> None:
    turnstile = examples / "plain" / "Turnstile.lr"
    text = turnstile.read_text(encoding="utf-8")
    messy = text.replace("  state Maintenance", "state   Maintenance")
    uri = await open_file(client, turnstile, messy)
    [edit] = await client.text_document_formatting_async(
        lsp.DocumentFormattingParams(document(uri), lsp.FormattingOptions(2, True))
    )
    assert edit.new_text == text
    assert edit.range.end == lsp.Position(len(messy.split("\n")) - 1, len(messy.split("\n")[-1]))


@pytest.mark.asyncio
async def test_closing_an_edited_file_goes_back_to_the_file_on_disk(
    client: LanguageClient, examples: Path
) -> None:
    text = (examples / RETREAT).read_text(encoding="utf-8")
    uri = await open_file(client, examples / RETREAT, text.replace("go -> Up;", "go -> ;"))
    assert client.diagnostics[uri]
    client.text_document_did_close(lsp.DidCloseTextDocumentParams(document(uri)))
    await settle(client, (examples / LIFT).as_uri())
    assert client.diagnostics[uri] == ()


@pytest.mark.asyncio
async def test_a_model_outside_the_workspace_is_checked_too(
    client: LanguageClient, examples: Path, tmp_path: Path
) -> None:
    await open_file(client, examples / RETREAT)
    outside = tmp_path / "elsewhere" / "Door.lr"
    outside.parent.mkdir()
    text = (examples / "plain" / "Turnstile.lr").read_text(encoding="utf-8")
    door = text.replace("package plain", "package elsewhere").replace("Turnstile", "Door")
    outside.write_text(door, encoding="utf-8")
    uri = await open_file(client, outside, door.replace("Locked -> Unlocked", "Locked -> Opened"))
    [finding] = [d for d in client.diagnostics[uri] if d.code == "LR0110"]
    assert "'Opened'" in finding.message
