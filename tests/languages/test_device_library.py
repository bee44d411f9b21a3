"""The device library's robots: the Panda offers the LWR's interface (so that a run puts it
in a cell's LWR slot) with ranges and defaults of its own; what two device types differ in
is named."""

from __future__ import annotations

from pathlib import Path

from lightrocks.languages.domain import LIBRARY
from lightrocks.languages.domain.interface import Interface, differences, interface
from lightrocks.languages.domain.ranges import command_ranges
from lightrocks.languages.domain.types import Types
from lightrocks.metamodel.constants import fold
from lightrocks.workbench.check import CheckContext, check

ROBOTS = LIBRARY / "lightrocks" / "robots"


def interfaces(context: CheckContext, *names: str) -> list[Interface]:
    workspace = context.workspace
    types = Types(workspace)
    found = [workspace.lookup(name) for name in names]
    return [interface(types, symbol.loaded, symbol.node) for symbol in found]


def test_the_panda_offers_the_interface_of_the_lwr() -> None:
    context = check([ROBOTS])
    assert context.diagnostics.items == []
    lwr, panda = interfaces(context, "lightrocks.robots.LWR", "lightrocks.robots.Panda")
    assert differences(lwr, panda) == []
    assert lwr.commands == panda.commands
    assert lwr.sensors == panda.sensors
    assert list(lwr.commands) == ["moveCartesian", "moveJoint"]


def test_the_panda_has_ranges_and_defaults_of_its_own() -> None:
    context = check([ROBOTS])
    panda = context.workspace.lookup("lightrocks.robots.Panda").node
    lwr = context.workspace.lookup("lightrocks.robots.LWR").node
    stiffness = command_ranges("robot", panda.commands[0])["stiffness"].safe_range()
    assert [b.high for b in stiffness.bounds] == [3000.0] * 3 + [300.0] * 3
    assert stiffness.breach([4000.0, 1.0, 1.0, 1.0, 1.0, 1.0]) is not None
    lwr_stiffness = command_ranges("robot", lwr.commands[0])["stiffness"].safe_range()
    assert lwr_stiffness.breach([4000.0, 1.0, 1.0, 1.0, 1.0, 1.0]) is None
    joints = panda.commands[1]
    assert fold(joints.parameters[1].default) == (600.0, 600.0, 600.0, 600.0, 250.0, 150.0, 50.0)
    q = command_ranges("robot", joints)["q"].safe_range()
    assert q.breach([0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0]) is None
    assert "q[3]" in q.breach([0.0, 0.0, 0.0, 0.0, 0.0, 1.5, 0.0])  # the elbow bends one way


DEVICES = """package lab;

device Arm {
  command move(Frame goal, Velocity speed = 0.1 m/s);
  command stop();
  sensor Boolean done;
  sensor Force load;
}

device Other {
  command move(Frame target, Velocity speed);
  command wave();
  sensor Boolean done;
  sensor Torque load;
}
"""


def test_what_two_device_types_differ_in_is_named(tmp_path: Path) -> None:
    (tmp_path / "lab").mkdir()
    (tmp_path / "lab" / "Devices.lrd").write_text(DEVICES, encoding="utf-8")
    context = check([tmp_path / "lab"], [tmp_path])
    assert not context.diagnostics.has_errors
    arm, other = interfaces(context, "lab.Arm", "lab.Other")
    assert differences(arm, other) == [
        "command 'move' is move(Frame goal, Velocity speed = …) in Arm, "
        "move(Frame target, Velocity speed) in Other",
        "Other has no command 'stop'",
        "Other has a command 'wave' that Arm does not have",
        "sensor 'load' is Force load in Arm, Torque load in Other",
    ]
    assert differences(arm, arm) == []


PANDA_CELL = """package lab;

import lightrocks.robots.*;

cell Lab {
  robot : Panda;
}
"""

PUSH = """package lab;

import lab.Lab;

<<action>> statechart Push {
  do / robot.moveCartesian(goal = robot.tcp, speed = {speed});

  end condition done [robot.goalReached];
}
"""


def test_check_holds_a_cell_of_the_panda_to_its_ranges(tmp_path: Path) -> None:
    (tmp_path / "lab").mkdir()
    (tmp_path / "lab" / "Lab.lrd").write_text(PANDA_CELL, encoding="utf-8")
    push = tmp_path / "lab" / "Push.lr"
    push.write_text(PUSH.replace("{speed}", "0.8 m/s"), encoding="utf-8")
    assert check([push], [tmp_path]).diagnostics.items == []  # beyond the LWR's 0.5 m/s
    text = PUSH.replace("{speed}", "1.2 m/s")
    push.write_text(text, encoding="utf-8")
    [finding] = check([push], [tmp_path]).diagnostics.items
    column = text.splitlines()[5].index("1.2 m/s") + 1
    assert (finding.code, finding.line, finding.column) == ("LR0305", 6, column)
    assert finding.message == (
        "robot.moveCartesian(speed) = 1200 mm/s is outside its safe range 1 mm/s .. 1000 mm/s"
    )
