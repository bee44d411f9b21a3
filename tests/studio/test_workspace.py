"""The studio's models: findings placed on their level and element, edits written to disk
atomically and checked again, a file changed on disk seen at the next request, and an edit
made on an older version of the file refused."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from lightrocks.app.studio import workspace
from lightrocks.app.studio.edits import EditError
from lightrocks.app.studio.workspace import Conflict, Studio

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
    new = studio.edit(AHEAD, state["version"], AHEAD, request)
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
    studio.edit(PLUG, version, f"{PLUG}/PressOn", request)
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
        studio.edit(AHEAD, seen, AHEAD, {"op": "move", "state": "PlugTerminal3", "steps": -1})
    assert ahead.read_text() == changed


@pytest.mark.parametrize(
    ("level", "request_", "message"),
    [
        (AHEAD, {"op": "move", "state": "go", "steps": 1}, "not in a chain"),
        (AHEAD, {"op": "rename"}, "no edit 'rename'"),
        ("other.Chart", {"op": "delete", "element": "PlugTerminal1"}, "not one of"),
        (AHEAD, {"op": "add-transition", "source": "A/B", "target": "C"}, "one region"),
    ],
)
def test_edits_that_do_not_fit_are_refused(models: Path, level, request_, message) -> None:
    studio = Studio([models])
    before = file_of(models, AHEAD).read_text()
    with pytest.raises(EditError, match=message):
        studio.edit(AHEAD, studio.state(AHEAD)["version"], level, request_)
    assert file_of(models, AHEAD).read_text() == before


def test_outcomes_of_the_boxes_of_each_level(models: Path) -> None:
    found = workspace.outcomes(Studio([models]).component(PLUG))
    assert found[PLUG]["PressOn"] == ["Latched", "Jammed"]
    assert found[f"{PLUG}/PressOn"]["Camera/LookAhead"] == ["located", "notFound"]
