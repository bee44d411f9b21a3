"""The studio's models: findings placed on their level and element, edits written to disk
atomically and checked again, a file changed on disk seen at the next request, and an edit
made on an older version of the file refused."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from lightrocks.app.studio import views
from lightrocks.app.studio.edits import EditError
from lightrocks.app.studio.history import Conflict
from lightrocks.app.studio.operations import operation
from lightrocks.app.studio.workspace import Studio

ROOT = Path(__file__).resolve().parents[2]
AHEAD = "din_rail_ahead.tasks.AssembleRailAhead"
PLUG = "din_rail_ahead.tasks.PlugTerminalAhead"


@pytest.fixture
def models(tmp_path: Path) -> Path:
    return shutil.copytree(ROOT / "examples", tmp_path / "examples")


def file_of(models: Path, chart: str) -> Path:
    return models.joinpath(*chart.split(".")).with_suffix(".lr")


def test_findings_are_placed_on_their_level_and_element(models: Path) -> None:
    plug = file_of(models, PLUG)
    plug.write_text(plug.read_text().replace("Unseen notFound;", "Unseen notFund;"))
    found = Studio([models]).state(PLUG)["findings"]
    where = {(f["code"], f["level"], f["element"]) for f in found}
    assert ("LR0111", f"{PLUG}/PressOn", "Camera/LookAhead->Camera/Unseen") in where
    assert ("LR0209", f"{PLUG}/PressOn", "Camera/LookAhead") in where


def test_an_edit_is_written_checked_and_drawn(models: Path) -> None:
    studio = Studio([models])
    state = studio.state(AHEAD)
    assert state["findings"] == [] and state["layer"] == "task"
    assert {"din_rail.skills.Retreat", PLUG} <= {p["name"] for p in state["palette"]}
    assert "din_rail.actions.Lift" not in {p["name"] for p in state["palette"]}
    request = {"op": "add-state", "name": "Away", "imports": "din_rail.skills.Retreat"}
    new = studio.edit(AHEAD, state["version"], AHEAD, operation(request))
    assert new != state["version"]
    text = file_of(models, AHEAD).read_text()
    assert '<<import="Retreat">> state Away;' in text
    assert not list(file_of(models, AHEAD).parent.glob(".*.tmp"))
    after = studio.state(AHEAD)
    assert after["version"] == new
    assert {f["element"] for f in after["findings"]} == {"Away"}  # unreachable, unhandled
    assert "<title>Away</title>" in studio.diagram(AHEAD)


def test_an_edit_in_a_region_of_an_orthogonal_state(models: Path) -> None:
    studio = Studio([models])
    version = studio.state(PLUG)["version"]
    request = {"op": "delete", "element": "Arm/Snap->Arm/Jammed"}
    studio.edit(PLUG, version, f"{PLUG}/PressOn", operation(request))
    assert "Snap -> Jammed jammed;" not in file_of(models, PLUG).read_text()
    assert studio.state(PLUG)["outcomes"][f"{PLUG}/PressOn"]["Arm/Snap"] == ["latched", "jammed"]


def test_a_file_changed_on_disk_is_seen_and_an_edit_on_the_old_version_refused(
    models: Path,
) -> None:
    studio = Studio([models])
    seen = studio.state(AHEAD)["version"]
    studio.diagram(AHEAD)
    ahead = file_of(models, AHEAD)
    changed = ahead.read_text().replace("PlugTerminal3 -> failed failed;\n", "")
    ahead.write_text(changed)
    assert studio.state(AHEAD)["version"] != seen
    assert "PlugTerminal3&#45;&gt;failed" not in studio.diagram(AHEAD)
    with pytest.raises(Conflict):
        studio.edit(
            AHEAD, seen, AHEAD, operation({"op": "move", "state": "PlugTerminal3", "steps": -1})
        )
    assert ahead.read_text() == changed


@pytest.mark.parametrize(
    ("level", "request_", "message"),
    [
        (AHEAD, {"op": "move", "state": "go", "steps": 1}, "not in a chain"),
        (AHEAD, {"op": "rename", "element": "PlugTerminal2", "to": "PlugTerminal3"}, "taken"),
        (AHEAD, {"op": "rename", "element": "go->PlugTerminal1", "to": "X"}, "no state"),
        (AHEAD, {"op": "rename", "element": "PlugTerminal1", "to": "two words"}, "not a name"),
        ("other.Chart", {"op": "delete", "element": "PlugTerminal1"}, "not one of"),
        (AHEAD, {"op": "add-transition", "source": "A/B", "target": "C"}, "one region"),
        (AHEAD, {"op": "add-state", "name": "A", "imports": "a; b"}, "qualified chart name"),
        (AHEAD, {"op": "set-parameters", "parameters": [["Length", "a b", ""]]}, "'a b' is not"),
    ],
)
def test_edits_that_do_not_fit_are_refused(models: Path, level, request_, message) -> None:
    studio = Studio([models])
    before = file_of(models, AHEAD).read_text()
    seen = studio.state(AHEAD)["version"]
    with pytest.raises(EditError, match=message):
        if request_["op"] == "rename":
            studio.rename(AHEAD, seen, level, request_["element"], request_["to"])
        else:
            studio.edit(AHEAD, seen, level, operation(request_))
    assert file_of(models, AHEAD).read_text() == before


def test_outcomes_of_the_boxes_of_each_level(models: Path) -> None:
    found = views.outcomes(Studio([models]).component(PLUG))
    assert found[PLUG]["PressOn"] == ["Latched", "Jammed"]
    assert found[f"{PLUG}/PressOn"]["Camera/LookAhead"] == ["located", "notFound"]


def test_undo_and_redo_and_an_undo_refused_after_a_change_on_disk(models: Path) -> None:
    studio = Studio([models])
    ahead = file_of(models, AHEAD)
    original = ahead.read_text()
    move = {"op": "move", "state": "PlugTerminal3", "steps": -1}
    studio.edit(AHEAD, studio.state(AHEAD)["version"], AHEAD, operation(move))
    moved = ahead.read_text()
    assert studio.history() == {"undo": "move PlugTerminal3", "redo": ""}
    assert studio.undo() == "move PlugTerminal3"
    assert ahead.read_text() == original
    assert studio.history() == {"undo": "", "redo": "move PlugTerminal3"}
    assert studio.redo() == "move PlugTerminal3"
    assert ahead.read_text() == moved
    outside = moved.replace("PlugTerminal3 -> failed failed;\n", "")
    ahead.write_text(outside)  # an editor changes the file: undo would lose that
    with pytest.raises(Conflict, match="changed on disk since; nothing was written"):
        studio.undo()
    assert ahead.read_text() == outside
    with pytest.raises(EditError, match="nothing to redo"):
        studio.redo()


def test_a_preview_checks_the_edit_with_the_language_s_check_and_writes_nothing(
    models: Path,
) -> None:
    studio = Studio([models])
    before = file_of(models, AHEAD).read_text()
    arguments = [["terminal", "terminal2"], ["slot", "0 N"], ["ahead", "terminal3"]]
    request = operation({"op": "set-arguments", "state": "PlugTerminal2", "arguments": arguments})
    found = studio.preview(AHEAD, studio.state(AHEAD)["version"], AHEAD, request)["findings"]
    assert [(f["code"], f["element"], f["new"]) for f in found] == [
        ("LR0304", "PlugTerminal2", True)
    ]
    assert "expected Length" in found[0]["message"]
    assert file_of(models, AHEAD).read_text() == before
    assert studio.history()["undo"] == ""


def test_a_rename_changes_every_file_that_names_it_and_undo_takes_it_back(models: Path) -> None:
    studio = Studio([models])
    plug = file_of(models, PLUG)
    texts = {f: f.read_text() for f in models.rglob("*.lr")}
    studio.rename(PLUG, studio.state(PLUG)["version"], PLUG, "", "PlugAhead")
    assert not plug.exists()
    moved = plug.with_name("PlugAhead.lr")
    assert "<<task>> statechart PlugAhead {" in moved.read_text()
    ahead = file_of(models, AHEAD).read_text()
    assert '<<import="PlugAhead">> state PlugTerminal1(terminal = terminal1,\n' in ahead
    assert "                                          slot = -70 mm," in ahead  # aligned again
    assert studio.state("din_rail_ahead.tasks.PlugAhead")["findings"] == []
    studio.undo()
    assert {f: f.read_text() for f in models.rglob("*.lr")} == texts


def test_a_state_renamed_on_a_level_below(models: Path) -> None:
    studio = Studio([models])
    studio.rename(PLUG, studio.state(PLUG)["version"], f"{PLUG}/PressOn", "Arm/Snap", "Click")
    text = file_of(models, PLUG).read_text()
    assert "Click -> Jammed jammed;" in text and "Snap" not in text.replace("SnapOn", "")
    assert studio.state(PLUG)["findings"] == []


def test_a_new_chart_is_created_empty_and_refused_when_it_is_there(models: Path) -> None:
    studio = Studio([models])
    catalogue = studio.catalogue()
    assert "din_rail.cell.RailCell" in catalogue["cells"]
    assert "din_rail.tasks" in catalogue["packages"]
    name = studio.create("din_rail.tasks", "Composed", "task", "din_rail.cell.RailCell")
    assert name == "din_rail.tasks.Composed"
    assert file_of(models, name).read_text().endswith("<<task>> statechart Composed { }\n")
    assert studio.state(name)["findings"] == []
    with pytest.raises(EditError, match="is there already"):
        studio.create("din_rail.tasks", "Composed", "task")
    studio.undo()
    assert not file_of(models, name).exists()


@pytest.mark.parametrize(
    "chart", [AHEAD, PLUG, "din_rail.actions.SnapOn", "screwing.tasks.ScrewTask"]
)
def test_the_diagram_is_what_the_dot_target_draws(models: Path, chart: str) -> None:
    from lightrocks.app.diagram import of_files
    from lightrocks.workbench.generators import GenerationRequest, load_generator, run_generator

    studio = Studio([models])
    snapshot = studio.snapshot()
    path = snapshot.components[chart].loaded.path
    request = GenerationRequest(snapshot.contexts[chart], [path], {"levels": "yes"})
    expected = of_files(run_generator(load_generator("dot"), request), chart).bundle()
    assert studio.diagram(chart) == expected


def test_after_a_change_only_the_files_it_affects_are_checked_and_drawn_again(
    models: Path,
) -> None:
    studio = Studio([models])
    studio.diagram(AHEAD)
    studio.diagram("screwing.tasks.ScrewTask")
    kept = studio.snapshot().bundles["screwing.tasks.ScrewTask"]
    plug = file_of(models, PLUG)
    plug.write_text(plug.read_text().replace("Unseen notFound;", "Unseen notFund;"))
    snapshot = studio.snapshot()
    assert snapshot.bundles == {"screwing.tasks.ScrewTask": kept}  # AHEAD imports PLUG
    assert {f.code for f in snapshot.findings} == {"LR0111", "LR0209"}
    assert "notFund" in studio.diagram(AHEAD)
    plug.write_text(plug.read_text().replace("Unseen notFund;", "Unseen notFound;"))
    assert studio.snapshot().findings == []
