"""``--robot``: a registered robot takes the cell's robot slot when its device type offers the
slot's interface; the model is then checked against that robot's safe ranges and generated
for it, without the re-binding reaching a later run without ``--robot``. Exit codes: 1 for
the model's findings and a robot that does not fit the cell, 2 for wrong use.

The robots come from a fake registry and the adapter is a dry run that simulates a chosen
robot (it offers the robot slot as the robot's device type, as the simulated cells do): no
physics is needed to decide any of this.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace
from typing import Any, ClassVar

import pytest

from lightrocks.adapters import scene_registry
from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app import adapter_factory, pipeline, robots
from lightrocks.app.cli import main
from lightrocks.app.errors import ModelError, RunError
from lightrocks.app.robots import choose
from lightrocks.runtime.contract import AdapterOption
from lightrocks.workbench.check import check

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"

CELL = """package lab;

import lightrocks.robots.*;

<<scene="none">> cell Lab {
  robot : LWR;
  gripper : ParallelGripper;
  camera : Camera;
}

device Tripod {
  command moveCartesian(Frame goal, Frame tool);
  sensor Boolean goalReached;
}
"""

PRESS = """package lab;

import lab.Lab;

<<action>> statechart Press {
  parameters {
    Stiffness6 stiffness = [{x}, 2000 N/m, 1000 N/m, 100 Nm/rad, 100 Nm/rad, 100 Nm/rad];
  }

  do / robot.moveCartesian(goal = robot.tcp, stiffness = stiffness);

  end condition done [robot.goalReached];
}
"""

FAKE_ROBOTS = {
    "lwr": SimpleNamespace(name="lwr", device_type="LWR", description="the light-weight robot"),
    "panda": SimpleNamespace(name="panda", device_type="Panda", description="Franka's arm"),
    "tripod": SimpleNamespace(name="tripod", device_type="Tripod", description="three legs"),
    "ghost": SimpleNamespace(name="ghost", device_type="Ghost", description="not declared"),
}


class RobotDryRun(DryRunAdapter):
    """A dry run with a choice of robot: like the simulated cells, it offers the robot slot
    as the chosen robot's device type, whatever the cell asks for."""

    made: ClassVar[list[RobotDryRun]] = []
    OPTIONS = (*DryRunAdapter.OPTIONS, AdapterOption("robot", str, "the robot in the slot"))

    def __init__(self, scene: str | None = None, *, robot: str = "lwr", **options: Any) -> None:
        super().__init__(scene, **options)
        self.robot = robot
        self.asked: dict[str, str] = {}
        RobotDryRun.made.append(self)

    def emulate(self, devices: Any) -> None:
        super().emulate(devices)
        self.asked = {name: protocol.DEVICE_TYPE for name, protocol in devices.items()}

    def devices(self) -> dict[str, str]:
        offered = dict(super().devices())
        offered["robot"] = scene_registry.robot(self.robot).device_type
        return offered


@pytest.fixture(autouse=True)
def fake_robots(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(scene_registry, "robots", lambda: FAKE_ROBOTS)
    real = adapter_factory.adapter_factory
    monkeypatch.setattr(
        adapter_factory,
        "adapter_factory",
        lambda name: RobotDryRun if name == "robotdry" else real(name),
    )
    RobotDryRun.made.clear()


def models(root: Path, x: str = "2000 N/m") -> Path:
    """The folder of the lab cell and its Press action; ``x`` its first stiffness."""
    (root / "lab").mkdir(exist_ok=True)
    (root / "lab" / "Lab.lrd").write_text(CELL, encoding="utf-8")
    (root / "lab" / "Press.lr").write_text(PRESS.replace("{x}", x), encoding="utf-8")
    return root / "lab" / "Press.lr"


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    status = main(["run", *argv])
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    return status, out, err


def test_list_robots_names_each_with_its_device_type(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["list", "robots"]) == 0
    assert capsys.readouterr().out.splitlines() == [
        "ghost  Ghost  not declared",
        "lwr  LWR  the light-weight robot",
        "panda  Panda  Franka's arm",
        "tripod  Tripod  three legs",
    ]


def test_the_robot_is_parsed_once_and_runs_in_the_cell(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    press = models(tmp_path)
    chosen: list[str] = []

    def counted(name: str) -> robots.RobotChoice:
        chosen.append(name)
        return choose(name)

    monkeypatch.setattr(robots, "choose", counted)
    trace = tmp_path / "run.jsonl"
    status, out, _ = run(
        capsys, str(press), "--path", str(tmp_path), "--adapter", "robotdry",
        "--robot", "panda", "--trace", str(trace),
    )  # fmt: skip
    assert status == 0, out
    assert chosen == ["panda"]
    [adapter] = RobotDryRun.made
    assert adapter.robot == "panda"
    assert adapter.asked["robot"] == "Panda"  # the class was generated for the Panda
    assert json.loads(trace.read_text().splitlines()[0])["robot"] == "panda"


def test_without_robot_the_cell_runs_as_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    press = models(tmp_path)
    trace = tmp_path / "run.jsonl"
    status, out, _ = run(
        capsys, str(press), "--path", str(tmp_path), "--adapter", "robotdry", "--trace", str(trace)
    )
    assert status == 0, out
    [adapter] = RobotDryRun.made
    assert (adapter.robot, adapter.asked["robot"]) == ("lwr", "LWR")
    assert "robot" not in json.loads(trace.read_text().splitlines()[0])


def test_a_value_only_the_lwr_takes_is_a_finding_at_its_place_for_the_panda(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    press = models(tmp_path, x="4000 N/m")
    lines = press.read_text().splitlines()
    line = next(i for i, text in enumerate(lines, 1) if "[4000 N/m" in text)
    column = lines[line - 1].index("[4000 N/m") + 1
    common = [str(press), "--path", str(tmp_path), "--adapter", "robotdry"]
    status, out, _ = run(capsys, *common, "--robot", "panda")
    assert status == 1
    assert "checked with robot 'panda': lightrocks.robots.Panda in the slot 'robot : LWR'" in out
    assert f"Press.lr:{line}:{column}: error LR0505: " in out
    assert "robot.moveCartesian(stiffness[0]) = 4000 N/m is outside its safe range" in out
    assert "0 N/m .. 3000 N/m" in out
    assert RobotDryRun.made == []  # refused before any adapter
    status, out, _ = run(capsys, *common)
    assert status == 0, out


def test_the_rebinding_does_not_reach_a_later_run_without_robot(tmp_path: Path) -> None:
    press = models(tmp_path, x="4000 N/m")
    with pytest.raises(ModelError, match="4000 N/m is outside"):
        pipeline.load(press, [tmp_path], choose("panda"))
    lwr = pipeline.load(press, [tmp_path])
    assert lwr.CELL.DEVICES["robot"].DEVICE_TYPE == "LWR"
    context = check([press], [tmp_path])
    assert not context.diagnostics.has_errors
    cell = context.workspace.lookup("lab.Lab").node
    assert {d.name: d.type for d in cell.devices}["robot"] == "LWR"
    with pytest.raises(ModelError, match="4000 N/m is outside"):  # nor the other way round
        pipeline.load(press, [tmp_path], choose("panda"))

    press = models(tmp_path)
    panda = pipeline.load(press, [tmp_path], choose("panda"))
    assert panda.CELL.DEVICES["robot"].DEVICE_TYPE == "Panda"
    assert panda.RANGES["stiffness"].bounds[0].high == 3000.0
    lwr = pipeline.load(press, [tmp_path])
    assert lwr.CELL.DEVICES["robot"].DEVICE_TYPE == "LWR"
    assert lwr.RANGES["stiffness"].bounds[0].high == 5000.0
    assert pipeline.load(press, [tmp_path], choose("lwr")) is lwr  # the slot's own robot


SOLO = """package solo;

cell Solo {
  robot : Tripod;
}

device Tripod {
  command moveCartesian(Frame goal, Frame tool);
  sensor Boolean goalReached;
}
"""

WAVE = """package solo;

import solo.Solo;

<<action>> statechart Wave {
  do / robot.moveCartesian(goal = transl(0 mm, 0 mm, 1 mm), tool = transl(0 mm, 0 mm, 0 mm));

  end condition done [robot.goalReached];
}
"""


def test_looking_for_the_robots_type_changes_nothing_a_run_without_robot_sees(
    tmp_path: Path,
) -> None:
    """A cell of a robot type of its own: the Panda is looked up in the device library, which
    the cell does not use, in a workspace of its own, so the checked model of a run without
    ``--robot`` stays as it was (and so does the generated code it is keyed by)."""
    (tmp_path / "solo").mkdir()
    (tmp_path / "solo" / "Solo.lrd").write_text(SOLO, encoding="utf-8")
    wave = tmp_path / "solo" / "Wave.lr"
    wave.write_text(WAVE, encoding="utf-8")
    own = pipeline.load(wave, [tmp_path])
    loaded = {u.path.name for u in check([wave], [tmp_path]).workspace.loaded_units()}
    assert loaded == {"Solo.lrd", "Wave.lr", "types.lrd"}
    with pytest.raises(ModelError, match="Panda has a sensor 'tcp' that Tripod does not have"):
        pipeline.load(wave, [tmp_path], choose("panda"))
    assert {u.path.name for u in check([wave], [tmp_path]).workspace.loaded_units()} == loaded
    assert pipeline.load(wave, [tmp_path]) is own


def test_a_run_parameter_is_held_to_the_chosen_robots_range(tmp_path: Path) -> None:
    press = models(tmp_path)
    value = "stiffness=[4000 N/m, 1 N/m, 1 N/m, 1 Nm/rad, 1 Nm/rad, 1 Nm/rad]"
    with pytest.raises(RunError, match="3000 N/m"):
        pipeline.spec_for(press, [tmp_path], [value], "robotdry", robot="panda")
    assert pipeline.spec_for(press, [tmp_path], [value], "robotdry").robot is None


def test_an_unknown_robot_is_named_with_the_known_ones(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    press = models(tmp_path)
    trace = tmp_path / "run.jsonl"
    status, _, err = run(
        capsys, str(press), "--path", str(tmp_path), "--adapter", "robotdry",
        "--robot", "atlas", "--trace", str(trace),
    )  # fmt: skip
    assert status == 2
    assert "unknown robot 'atlas'; known robots: ghost, lwr, panda, tripod" in err
    assert not trace.exists()


def test_a_robot_that_does_not_offer_the_slots_interface_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    press = models(tmp_path)
    status, out, _ = run(
        capsys, str(press), "--path", str(tmp_path), "--adapter", "robotdry", "--robot", "tripod"
    )
    assert status == 1
    assert (
        "robot 'tripod' (lab.Tripod) cannot take the slot 'robot : LWR' of cell lab.Lab: "
        "its interface differs from LWR's:" in out
    )
    assert "Tripod has no command 'moveJoint'" in out
    assert "Tripod has no sensor 'wrench'" in out
    assert "command 'moveCartesian' is moveCartesian(Frame goal, Frame task = …," in out
    assert RobotDryRun.made == []


def test_a_robot_whose_device_type_is_not_on_the_model_path_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    press = models(tmp_path)
    status, _, err = run(
        capsys, str(press), "--path", str(tmp_path), "--adapter", "robotdry", "--robot", "ghost"
    )
    assert status == 2
    assert "robot 'ghost' is a Ghost, but no device type Ghost is on the model path" in err


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (["--adapter", "dryrun"], "adapter 'dryrun' has no choice of robot; --robot needs one"),
        ([], "--robot chooses the robot an adapter simulates: give --adapter"),
    ],
)
def test_robot_needs_an_adapter_with_a_choice_of_robot(
    options: list[str], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    press = models(tmp_path)
    status, _, err = run(capsys, str(press), "--path", str(tmp_path), *options, "--robot", "panda")
    assert status == 2
    assert message in err


def test_the_adapter_still_refuses_a_robot_the_cell_was_not_generated_for(
    tmp_path: Path,
) -> None:
    """The binding rule is unchanged: the device type the adapter offers must be the one the
    generated cell declares."""
    press = models(tmp_path)
    spec = pipeline.spec_for(press, [tmp_path], adapter="robotdry")
    spec = replace(spec, adapter_options={**spec.adapter_options, "robot": "panda"})
    with pytest.raises(ModelError, match="device 'robot' is a Panda, expected LWR"):
        pipeline.run(spec)


def test_the_screwing_task_loads_unchanged_for_the_panda() -> None:
    panda = pipeline.load(SCREW_TASK, [], choose("panda"))
    assert panda.CELL.DEVICES["robot"].DEVICE_TYPE == "Panda"
    assert pipeline.load(SCREW_TASK, []).CELL.DEVICES["robot"].DEVICE_TYPE == "LWR"


def test_sweep_takes_the_robot_too(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("distributed")
    press = models(tmp_path)
    argv = ["sweep", str(press), "--path", str(tmp_path), "--adapter", "robotdry", "--seeds", "1"]
    status = main([*argv, "--robot", "atlas", "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert status == 2
    assert "unknown robot 'atlas'" in err
    assert not (tmp_path / "out").exists()
