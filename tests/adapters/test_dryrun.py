"""The dry run as a test double: per-command sensors start from zero with every command, a
scripted outcome belongs to the next call of its command however that call ends, and a
script file walks a task's branches."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pinocchio as pin
import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.cli import main
from lightrocks.runtime.contract import AdapterError, Command, StopCondition, Vector3


class Robot:
    DEVICE_TYPE = "Robot"

    @property
    def tcp(self) -> pin.SE3: ...

    @property
    def travel(self) -> Vector3: ...

    @property
    def turned(self) -> float: ...

    @property
    def peakForce(self) -> float: ...

    @property
    def goalReached(self) -> bool: ...

    def moveCartesian(self, goal: pin.SE3) -> None: ...


def _adapter(**options: object) -> DryRunAdapter:
    adapter = DryRunAdapter(**options)
    adapter.emulate({"robot": Robot})
    return adapter


REACHED = StopCondition("reached", lambda s: s.robot.goalReached)


def move(adapter: DryRunAdapter, args: dict, stop: list[StopCondition]) -> str:
    """The outcome of one ``robot.moveCartesian`` with a budget of 1 s."""
    return adapter.execute([Command("robot", "moveCartesian", args, stop, 1.0)])[0].outcome


def test_a_move_reports_how_far_it_went_and_the_next_one_starts_from_zero() -> None:
    adapter = _adapter()
    goal = pin.SE3(pin.utils.rotate("z", 0.5), pin.utils.zero(3) + 0.01)
    assert move(adapter, {"goal": goal}, [REACHED]) == "reached"
    done = adapter.snapshot().robot
    assert done.travel.array() == pytest.approx([0.01, 0.01, 0.01])
    assert done.turned == pytest.approx(0.5)
    seen = []

    def first_tick(s: object) -> bool:
        seen.append((s.robot.travel, s.robot.turned, s.robot.goalReached))
        return True

    move(adapter, {"goal": goal}, [StopCondition("x", first_tick)])
    assert seen[0] == (Vector3(), 0.0, False)


def test_a_scripted_outcome_belongs_to_its_call_even_when_another_stop_ends_it() -> None:
    adapter = _adapter(outcomes={"robot.moveCartesian": ["reached", "blocked"]})
    goal = {"goal": pin.SE3.Identity()}
    preempted = StopCondition("preempted", lambda s: True)
    blocked = StopCondition("blocked", lambda s: False)
    assert move(adapter, goal, [REACHED, preempted]) == "preempted"  # used "reached"
    assert move(adapter, goal, [REACHED, blocked]) == "blocked"
    assert move(adapter, goal, [REACHED]) == "reached"


def test_a_scripted_outcome_the_call_cannot_end_in_is_a_fault_that_names_them() -> None:
    adapter = _adapter(outcomes={"robot.moveCartesian": ["blocked"]})
    with pytest.raises(AdapterError, match=r"'blocked', cannot end this call: it ends in "
                       r"reached, timeout, error"):  # fmt: skip
        move(adapter, {"goal": pin.SE3.Identity()}, [REACHED])


# -- run --script FILE ---------------------------------------------------------------------

CELL = """package t;

device Arm {
  command move(Length x);
  sensor Boolean done;
  sensor Force force;
}

<<scene="none">> cell Cell {
  arm : Arm;
}
"""

MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  parameters { Length x = 10 mm; }
  do / arm.move(x = x);
  end condition done [arm.done];
  end condition blocked [arm.force > 20 N];
}
"""

PICK = """package t;

import t.Cell;
import t.Move;

<<skill>> statechart Pick {
  start condition go;
  end condition picked;
  end condition failed;
  end condition broken;
  <<import="Move">> state Reach(x = 5 mm);
  <<import="Move">> state Retry(x = 6 mm);
  go -> Reach;
  Reach -> picked done;
  Reach -> Retry blocked;
  Reach -> broken error;
  Retry -> picked [arm.force < 1 N] done;
  Retry -> failed [arm.force >= 1 N] done;
  Retry -> failed blocked;
}
"""


@pytest.fixture(autouse=True)
def cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "xdg"))


@pytest.fixture
def pick(tmp_path: Path) -> Path:
    (tmp_path / "t").mkdir()
    for name, text in (("Cell.lrd", CELL), ("Move.lr", MOVE), ("Pick.lr", PICK)):
        (tmp_path / "t" / name).write_text(text, encoding="utf-8")
    return tmp_path / "t" / "Pick.lr"


def _run(pick: Path, script: object, *extra: str) -> list[str]:
    file = pick.parent.parent / "script.json"
    file.write_text(script if isinstance(script, str) else json.dumps(script), encoding="utf-8")
    path = str(pick.parent.parent)
    return ["run", str(pick), "--path", path, "--adapter", "dryrun", "--script", str(file), *extra]


@pytest.mark.parametrize(
    ("script", "outcome"),
    [
        ({}, "picked"),
        ({"outcomes": {"arm.move": ["done"]}}, "picked"),
        ({"outcomes": {"arm.move": ["blocked"]}}, "picked"),
        ({"outcomes": {"arm.move": ["blocked", "blocked"]}}, "failed"),
        ({"outcomes": {"arm.move": ["blocked"]}, "sensors": {"arm.force": 5.0}}, "failed"),
        ({"outcomes": {"arm.move": ["error"]}}, "broken"),
    ],
)
def test_every_branch_from_a_script_file(
    pick: Path, script: dict, outcome: str, capsys: pytest.CaptureFixture[str]
) -> None:
    main(_run(pick, script))
    assert f"outcome: {outcome}" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("script", "words"),
    [
        ("{", "script.json:1:2: not JSON"),
        ("[]", 'expected an object with "outcomes" and/or "sensors"'),
        ({"outcome": {}}, 'expected an object with "outcomes" and/or "sensors"'),
        ({"outcomes": {"arm.mov": ["done"]}}, "Pick never calls arm.mov; it calls: arm.move"),
        ({"outcomes": {"arm.move": "done"}}, "outcomes of arm.move are a list of names"),
        (
            {"outcomes": {"arm.move": ["dne"]}},
            "arm.move cannot end in 'dne'; it ends in: blocked, done, error, timeout",
        ),
        ({"sensors": {"arm.forc": 1}}, "Pick's cell has no sensor arm.forc"),
        ({"sensors": {"arm.force": [1, 2]}}, "arm.force = [1, 2]: script a number (SI)"),
    ],
)
def test_a_bad_script_file_is_a_usage_error(
    pick: Path, script: object, words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(_run(pick, script)) == 2
    err = capsys.readouterr().err
    assert words in " ".join(err.split()), err
    assert "Traceback" not in err and "internal error" not in err


def test_a_script_needs_the_dry_run(pick: Path, capsys: pytest.CaptureFixture[str]) -> None:
    command = _run(pick, {})
    command.remove("--adapter")
    command.remove("dryrun")
    assert main(command) == 2
    assert "script need an adapter" in capsys.readouterr().err


@pytest.mark.parametrize("kind", ["missing", "fifo", "folder"])
def test_a_script_that_is_no_file(
    pick: Path, kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "script"
    if kind == "fifo":
        os.mkfifo(target)
    elif kind == "folder":
        target.mkdir()
    command = _run(pick, {})
    command[-1] = str(target)
    assert main(command) == 2
    err = capsys.readouterr().err
    assert str(target) in err and "Traceback" not in err


def test_a_script_holds_for_every_seed(pick: Path, capsys: pytest.CaptureFixture[str]) -> None:
    main(_run(pick, {"outcomes": {"arm.move": ["blocked", "blocked"]}}, "--seeds", "2"))
    out = capsys.readouterr().out
    assert "success (picked): 0/2" in out


def test_a_call_that_ends_as_scripted_by_itself_uses_the_script_up() -> None:
    adapter = _adapter(outcomes={"robot.moveCartesian": ["clicked", "blocked"]})
    goal = {"goal": pin.SE3.Identity()}
    clicked = StopCondition("clicked", lambda s: True)
    blocked = StopCondition("blocked", lambda s: False)
    assert move(adapter, goal, [clicked]) == "clicked"
    assert move(adapter, goal, [REACHED, blocked]) == "blocked"


def test_the_rail_example_script_assembles(capsys: pytest.CaptureFixture[str]) -> None:
    """The example script walks AssembleRail's success path: three terminals touched, clicked
    on and seated."""
    examples = Path(__file__).resolve().parents[2] / "examples"
    task = examples / "din_rail" / "tasks" / "AssembleRail.lr"
    script = examples / "din_rail" / "assembled.dryrun.json"
    assert main(["run", str(task), "--adapter", "dryrun", "--script", str(script)]) == 0
    assert "outcome: assembled" in capsys.readouterr().out
