"""What one level shows: its own states, regions and pseudostates in UML/P notation, children
as boxes that open their level, an action's command and its end conditions as exits."""

from __future__ import annotations

import pytest

from diagram.models import EXAMPLES, ROOT, components
from lightrocks.generators.graphviz.levels import Level, all_levels

PLANT = ROOT / "tests" / "generators" / "models"


@pytest.fixture(scope="module")
def examples() -> dict[str, Level]:
    found: dict[str, Level] = {}
    for component in components(EXAMPLES):
        found.update(all_levels(component))
    return found


@pytest.fixture(scope="module")
def plant() -> dict[str, Level]:
    found: dict[str, Level] = {}
    for component in components(PLANT):
        found.update(all_levels(component))
    return found


def nodes(level: Level, kind: str) -> list[str]:
    return [n.id for n in level.nodes if n.kind == kind]


def test_a_task_shows_its_children_as_boxes_that_open_their_level(examples) -> None:
    task = examples["din_rail_ahead.tasks.AssembleRailAhead"]
    assert nodes(task, "state") == ["PlugTerminal1", "PlugTerminal2", "PlugTerminal3"]
    assert set(task.drills.values()) == {"din_rail_ahead.tasks.PlugTerminalAhead"}
    assert nodes(task, "start") == ["go"] and nodes(task, "end") == ["assembled", "failed"]
    assert not task.regions
    plug = examples["din_rail_ahead.tasks.PlugTerminalAhead"]
    assert plug.drills["PressOn"] == "din_rail_ahead.tasks.PlugTerminalAhead/PressOn"


def test_an_orthogonal_state_is_a_level_of_dashed_regions(examples) -> None:
    press = examples["din_rail_ahead.tasks.PlugTerminalAhead/PressOn"]
    assert press.regions == ["Arm", "Camera"]
    assert press.drills == {
        "Arm/Snap": "din_rail.skills.SnapOnRail",
        "Camera/LookAhead": "din_rail.skills.LocalizeTerminal",
    }
    arm = {n.id: n for n in press.nodes if n.region == "Arm"}
    assert {"Arm/Snap", "Arm/Snap#initial", "Arm/Latched", "Arm/Latched#final"} <= set(arm)
    assert arm["Arm/Latched#final"].kind == "final"
    edges = {(e.source, e.target): e.label for e in press.edges}
    assert edges[("Camera/LookAhead", "Camera/Seen")] == "located / ahead.located = true;"


def test_a_loop_two_levels_down_is_its_own_level(examples) -> None:
    """SnapOnRail's retries (Free -> Down) are drawn on SnapOnRail's level only."""
    snap = examples["din_rail.skills.SnapOnRail"]
    assert ("Free", "Down") in {(e.source, e.target) for e in snap.edges}
    for key in ("din_rail_ahead.tasks.AssembleRailAhead", "din_rail_ahead.tasks.PlugTerminalAhead"):
        assert "Free" not in {n.id for n in examples[key].nodes}


def test_parallel_transitions_share_one_arrow_with_a_label_each(examples) -> None:
    snap = examples["din_rail.skills.SnapOnRail"]
    arrows = [(e.source, e.target) for e in snap.edges]
    assert len(arrows) == len(set(arrows))
    label = next(e.label for e in snap.edges if (e.source, e.target) == ("GiveUp", "jammed"))
    assert label == "lifted, timeout"


def test_an_action_shows_its_command_and_its_end_conditions_as_exits(examples) -> None:
    touch = examples["din_rail.actions.Touch"]
    do = next(n for n in touch.nodes if n.kind == "do")
    assert do.lines[0].startswith("do / robot.moveCartesian(goal = ")
    assert any("stiffness = stiffness" in line for line in do.lines)
    exits = {e.target: e.label for e in touch.edges if e.kind == "exit"}
    assert exits["touched"] == "touched\n[robot.wrench.force.z >\ntouchForce]"  # 32 a line
    assert exits["#timeout"] == "timeout: after(10 s)"
    ends = [n for n in touch.nodes if n.kind == "end"]
    assert ends and all(not n.xlabel and not n.lines for n in ends)


def test_history_choice_and_time_events(plant) -> None:
    player = plant["plant.Player"]
    assert nodes(player, "choice") == ["Resume"]
    assert player.drills == {"Playing": "plant.Player/Playing"}
    heads = {(e.source, e.target): e.head for e in player.edges}
    assert heads[("Resume", "Playing")] == "H"  # two arrows into Playing's histories, merged
    playing = plant["plant.Player/Playing"]
    histories = {n.id: n.lines for n in playing.nodes if n.kind == "history"}
    assert histories == {"Back": ["H"], "Exact": ["H*"]}
    assert ("Intro", "Song", "after(500 ms)") in {
        (e.source, e.target, e.label) for e in playing.edges
    }
    song = next(n for n in playing.nodes if n.id == "Song")
    assert not song.drill and "next / tracks = tracks + 1;" in song.lines


def test_regions_of_a_plain_chart(plant) -> None:
    working = plant["plant.Crossing/Working"]
    assert working.regions == ["Traffic", "Walker"]
    assert working.notes == ["entry / calls = 0;"]
    assert "Walker/Wait" in {n.id for n in working.nodes}
