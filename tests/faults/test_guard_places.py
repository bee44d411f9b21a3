"""A guard, a time event's delay, a start or end condition, a postcondition, an invariant or
an internal transition's action that raises at run time is reported where it is written:
at the transition (condition, invariant) with its file:line:col, not at the state that was
active when it was evaluated. Each case divides by a parameter that is zero."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.cli import main

from .fault_runs import within, write_models

BAD = "x / z > 0"  # ZeroDivisionError once evaluated

# name -> (body of a plain statechart, what to send, line:col of the faulty element)
PLAIN = {
    "event guard": (f"  initial state A;\n  final state B;\n  A -> B [{BAD}] go;", "go", "10:3"),
    "completion guard": (
        "  initial state A {\n    initial state A1;\n    final state Fin;\n    A1 -> Fin go;\n"
        f"  }}\n  final state B;\n  A -> B [{BAD}] Fin;",
        "go",
        "14:3",
    ),
    "choice branch": (
        f"  initial state A;\n  choice C;\n  final state B;\n  A -> C go;\n  C -> B [{BAD}];",
        "go",
        "12:3",
    ),
    "postcondition": (
        f"  initial state A;\n  final state B;\n  A -> B go / {{ x = 2; }} [{BAD}];",
        "go",
        "10:3",
    ),
    "invariant": (
        f"  initial state A;\n  state B [{BAD}];\n  A -> B go;",
        "go",
        "9:3",
    ),
    "internal action": (
        "  initial state A {\n    internal go / { x = x / z; };\n  }",
        "go",
        "9:5",
    ),
    "start condition": (
        f"  start condition s [{BAD}];\n  end condition done;\n  s -> done;",
        "",
        "8:3",
    ),
    "start transition guard": (
        f"  start condition s;\n  end condition done;\n  s -> done [{BAD}];",
        "",
        "10:3",
    ),
}

TIMED = {
    "time event guard": (
        f"  initial state A;\n  final state B;\n  A -> B [{BAD}] after(1 s);",
        "10:3",
    ),
    "time event delay": (
        "  initial state A;\n  final state B;\n  A -> B after(x / z * 1 s);",
        "10:3",
    ),
}


def chart(body: str) -> str:
    """A plain statechart, a skill when it has start and end conditions."""
    layer = "<<skill>> " if "condition" in body else ""
    return (
        f"package t;\n\n{layer}statechart Divides {{\n  parameters {{\n    Real x = 1;\n"
        "    Real z = 0;\n"
        f"  }}\n{body}\n}}\n"
    )


def assert_at(fault, place: str) -> None:
    assert fault is not None
    assert fault.message.startswith("ZeroDivisionError in model code"), fault.message
    assert fault.location.endswith(f"t/Divides.lr:{place}"), fault.location


@pytest.mark.parametrize("case", sorted(PLAIN))
def test_a_fault_is_located_where_it_is_written(build, case: str) -> None:
    body, event, place = PLAIN[case]
    run = build({"Divides": chart(body)}, "Divides")()

    def go() -> None:
        run.start()
        if event:
            run.send(event)

    within(go)
    assert run.outcome == "error"
    assert_at(run.fault, place)


@pytest.mark.parametrize("case", sorted(TIMED))
def test_a_fault_of_a_time_event_is_located_at_its_transition(build, case: str) -> None:
    body, place = TIMED[case]
    run = build({"Divides": chart(body)}, "Divides")()
    within(lambda: (run.start(), run.advance(2.0)))
    assert run.outcome == "error"
    assert_at(run.fault, place)


GUARDED = """package t;

import t.Cell;

<<skill>> statechart Guarded {
  start condition go;
  end condition done;
  end condition halt [arm.z / arm.z > 1];

  <<import="Move">> state M;

  go -> M;
  M -> done reached;
}
"""

MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  do / arm.move(x = 1 mm);
  end condition reached [arm.goalReached && arm.z / arm.z > 1];
}
"""


def test_an_end_condition_that_raises_is_located_at_the_condition(build) -> None:
    run = build({"Move": MOVE.replace(" && arm.z / arm.z > 1", ""), "Guarded": GUARDED},
                "Guarded")()  # fmt: skip
    within(lambda: run.start(DryRunAdapter()))
    assert run.outcome == "error"
    assert run.fault.location.endswith("t/Guarded.lr:8:3"), run.fault
    assert "ZeroDivisionError" in run.fault.message
    action = build({"Move": MOVE}, "Move")()
    within(lambda: action.start(DryRunAdapter()))
    assert action.outcome == "error"
    assert action.fault.location.endswith("t/Move.lr:7:3"), action.fault


def test_the_command_line_shows_the_transition(tmp_path: Path, capsys) -> None:
    write_models(tmp_path, {"Divides": chart(PLAIN["event guard"][0])})
    assert main(["run", str(tmp_path / "t" / "Divides.lr"), "--events", "go"]) == 1
    out = " ".join(capsys.readouterr().out.split())
    assert "division by zero at " in out and "t/Divides.lr:10:3 via Divides/A" in out
