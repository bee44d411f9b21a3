"""Faults are reported where they are written, and the trace tells what a stop condition saw:
a choice none of whose branches holds is located at the choice (not ``?``), a division by
zero in an exit, entry or transition action at that action (not the chart's first line),
and a ``stop`` record holds the sensors as they were when the condition held (not as the
adapter shows them once it holds the arm)."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.cli import main

from .fault_runs import trace_records, within, write_models

PICK = """package t;

statechart Pick {
  parameters {
    Real x = 1;
  }
  initial state A;
  choice C;
  final state B;
  final state D;
  A -> C go;
  C -> B [x > 5];
  C -> D [x < 0];
}
"""

DIVIDES = {
    "exit": ("  initial state A {\n    exit / { x = x / z; }\n  }\n  A -> B go;", "9:5"),
    "entry": ("  initial state A {\n    entry / { x = x / z; }\n  }\n  A -> B go;", "9:5"),
    "transition": ("  initial state A;\n  A -> B go / { x = x / z; };", "9:3"),
}


def divides(body: str) -> str:
    return (
        "package t;\n\nstatechart Divides {\n  parameters {\n    Real x = 1;\n    Real z = 0;\n"
        f"  }}\n{body}\n  final state B;\n}}\n"
    )


def test_a_choice_without_a_branch_that_holds_is_located_at_the_choice(build, capsys):
    chart = build({"Pick": PICK}, "Pick")()
    within(lambda: (chart.start(), chart.send("go")))
    assert chart.outcome == "error"
    assert chart.fault.location.endswith("t/Pick.lr:8:3")
    assert "no branch of choice 'C' holds" in chart.fault.message


def test_the_command_line_shows_where_the_choice_is(tmp_path: Path, capsys) -> None:
    write_models(tmp_path, {"Pick": PICK})
    assert main(["run", str(tmp_path / "t" / "Pick.lr"), "--events", "go"]) == 1
    out = capsys.readouterr().out
    assert "holds at " in out and "t/Pick.lr:8:3 via Pick" in out and " at ? " not in out


@pytest.mark.parametrize("where", sorted(DIVIDES))
def test_a_fault_of_an_action_is_located_at_the_action(build, where: str) -> None:
    body, place = DIVIDES[where]
    chart = build({"Divides": divides(body)}, "Divides")()
    within(lambda: (chart.start(), chart.send("go")))
    assert chart.outcome == "error"
    assert chart.fault.message.startswith("ZeroDivisionError in model code")
    assert chart.fault.location.endswith(f"t/Divides.lr:{place}")


MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  do / arm.move(x = 1 mm);
  end condition reached [arm.goalReached];
}
"""


class HoldsAfterwards(DryRunAdapter):
    """A dry run whose arm, like the simulated cell's, holds after every command: a fresh
    hold has not reached its goal yet, so ``goalReached`` reads false once it returns."""

    def execute(self, commands, on_tick=None):
        results = super().execute(commands, on_tick)
        self._state["arm"]["goalReached"] = False
        return results


def test_a_stop_record_holds_the_sensors_its_condition_saw(build) -> None:
    chart = build({"Move": MOVE}, "Move")()
    within(lambda: chart.start(HoldsAfterwards()))
    [stop] = [r for r in chart.trace if r["kind"] == "stop"]
    assert stop["outcome"] == "reached"
    assert stop["sensors"] == {"arm.goalReached": True}


@pytest.mark.slow
def test_the_simulated_cell_records_reached_goals_as_reached(tmp_path: Path) -> None:
    pytest.importorskip("mujoco", reason="the simulated cell needs MuJoCo")
    model = Path(__file__).resolve().parents[2] / "examples" / "din_rail" / "tasks"
    trace = tmp_path / "run.jsonl"
    run = ["run", str(model / "AssembleRail.lr"), "--adapter", "mujoco", "--trace", str(trace)]
    assert within(lambda: main(run), 600.0) == 0
    stops = [r for r in trace_records(trace) if r["kind"] == "stop" and r["outcome"] == "reached"]
    assert stops and all(r["sensors"]["robot.goalReached"] is True for r in stops)
