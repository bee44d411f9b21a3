"""``lightrocks run`` on a broken scene and the scene's judgement of the goal.

A scene whose MJCF does not load is its author's mistake, not a wrong use of the command:
one line naming the scene and its file, exit 1, no traceback, nothing written. A scene hook
that raises (``measurements()``, ``goal_met``, ``step``) is reported as the scene's, with
exit 1, after the outcome and skill table of the run, which finished. A scene that states a
goal has it judged on the ground truth beside the outcome; other runs show no goal.
"""

from __future__ import annotations

import csv
import json
import logging
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import mujoco
import pytest

from lightrocks.adapters import scene_registry
from lightrocks.adapters.robots.common import MODELS_DIR
from lightrocks.adapters.scene import Scene
from lightrocks.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
EMPTY = MODELS_DIR / "empty.xml"

CELL = """package bench;

import lightrocks.robots.*;

<<scene="part">> cell Bench {
  robot : LWR;
  gripper : ParallelGripper;
  camera : Camera;

  object block;
}
"""

OPEN = """package bench;

import bench.Bench;

<<action>> statechart Open {
  do / gripper.open();

  end condition done [gripper.done];
}
"""

GRIP = """package bench;

import bench.Bench;

<<skill>> statechart Grip {
  start condition go;
  end condition opened;

  <<import="Open">> state Release;

  go -> Release;
  Release -> opened done;
}
"""

JOB = """package bench;

import bench.Bench;

<<task>> statechart Job {
  start condition go;
  end condition finished;

  <<import="Grip">> state Work;

  go -> Work;
  Work -> finished opened;
}
"""


class Judged(Scene):
    """The block's height as ground truth; the goal: it is still on the table."""

    def measurements(self, model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, Any]:
        return {"block_height": float(data.body("block").xpos[2])}

    def goal_met(self, values: Mapping[str, Any]) -> bool:
        return values["block_height"] > 0.1


class Unmeasurable(Judged):
    def measurements(self, model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, Any]:
        return {"block_height": data.body("block").xpos[2], "tilt": {}["block_tilt"]}


class Unjudged(Judged):
    def goal_met(self, values: Mapping[str, Any]) -> bool:
        return values["block_placed"]


class Stepping(Judged):
    def step(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        if data.time > 0.31:  # after the cell settled (0.3 s), while the gripper opens
            raise KeyError("thread")


@pytest.fixture
def models(tmp_path: Path) -> Path:
    folder = tmp_path / "bench"
    folder.mkdir()
    for name, text in (("Bench.lrd", CELL), ("Open.lr", OPEN), ("Grip.lr", GRIP), ("Job.lr", JOB)):
        (folder / name).write_text(text)
    return tmp_path


@pytest.fixture
def part(monkeypatch: pytest.MonkeyPatch):
    """``part(scene)``: the installed scenes and ``scene`` as the cell's scene ``part``."""

    def register(scene: Scene) -> None:
        known = {**scene_registry.scenes(), "part": scene}
        monkeypatch.setattr(scene_registry, "scenes", lambda: known)

    return register


def run(models: Path, capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str, Path]:
    trace = models / "run.jsonl"
    job = models / "bench" / "Job.lr"
    status = main(["run", str(job), "--adapter", "mujoco", "--trace", str(trace)])
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    return status, out, err, trace


def records(trace: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in trace.read_text().splitlines()]


def test_an_include_that_is_not_robot_xml_is_the_scene_s_error(
    models: Path, part, capsys: pytest.CaptureFixture[str]
) -> None:
    mjcf = models / "part.xml"
    mjcf.write_text(EMPTY.read_text().replace('"robot.xml"', '"lwr_robot.xml"'))
    part(Scene(mjcf))
    status, out, err, trace = run(models, capsys)
    assert status == 1
    assert out == ""
    [line] = err.splitlines()
    assert line.startswith(f"lightrocks: error: scene 'part': {mjcf} does not load: ")
    assert "Error opening file 'lwr_robot.xml'" in line
    assert '<include file="robot.xml"/>' in line
    assert "\\n" not in line and "adapter" not in line
    assert not trace.exists()


def test_malformed_mjcf_is_the_scene_s_error_with_its_file(
    models: Path, part, capsys: pytest.CaptureFixture[str]
) -> None:
    mjcf = models / "part.xml"
    mjcf.write_text(EMPTY.read_text().replace("</body>", "</bodyx>", 1))
    part(Scene(mjcf))
    status, out, err, trace = run(models, capsys)
    assert status == 1
    assert out == ""
    [line] = err.splitlines()
    assert line.startswith(f"lightrocks: error: scene 'part': {mjcf} does not load: XML parse")
    assert "XML_ERROR_MISMATCHED_ELEMENT" in line and "Line number=" in line
    assert not trace.exists()


def test_an_unknown_scene_stays_a_usage_error(
    models: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    status, _, err, trace = run(models, capsys)
    assert status == 2
    assert "unknown scene 'part'" in err
    assert not trace.exists()


@pytest.mark.parametrize(
    ("scene", "message", "measured"),
    [
        (Unmeasurable, "measurements() raised KeyError: 'block_tilt'", False),
        (Unjudged, "goal_met() raised KeyError: 'block_placed'", True),
    ],
)
def test_a_hook_that_raises_after_the_run_is_reported_after_the_run(
    models: Path,
    part,
    capsys: pytest.CaptureFixture[str],
    scene: type[Scene],
    message: str,
    measured: bool,
) -> None:
    part(scene(EMPTY))
    status, out, err, trace = run(models, capsys)
    assert status == 1
    assert err == ""
    assert "Job/Work" in out  # the skill table
    assert ("block height" in out) is measured
    assert "goal:" not in out
    lines = out.splitlines()
    assert lines[-2].startswith("outcome: finished after")
    assert lines[-1] == f"error: scene 'part': {message}"
    last = records(trace)[-1]  # the trace is whole: the run finished before the hook ran
    assert (last["kind"], last["outcome"]) == ("finished", "finished")


def test_a_step_hook_that_raises_ends_the_run_with_an_error_named_for_the_scene(
    models: Path, part, capsys: pytest.CaptureFixture[str]
) -> None:
    part(Stepping(EMPTY))
    status, out, err, trace = run(models, capsys)
    assert status == 1
    assert err == ""
    assert "outcome: error after" in out
    assert "scene 'part': step() raised KeyError: 'thread'" in out
    assert records(trace)[-1]["outcome"] == "error"


class Unreached(Judged):
    def goal_met(self, values: Mapping[str, Any]) -> bool:
        return values["block_height"] > 0.2


@pytest.mark.parametrize(("scene", "goal"), [(Judged, "met"), (Unreached, "not met")])
def test_the_scene_s_goal_is_shown_beside_the_outcome_which_alone_decides_the_exit(
    models: Path, part, capsys: pytest.CaptureFixture[str], scene: type[Scene], goal: str
) -> None:
    part(scene(EMPTY))
    status, out, _, _ = run(models, capsys)
    assert status == 0
    *_, judged, outcome = out.splitlines()
    assert judged == f"goal: {goal} (the scene's ground truth)"
    assert outcome.startswith("outcome: finished after")


def test_a_scene_without_a_goal_and_a_run_without_adapter_show_none(
    models: Path, part, capsys: pytest.CaptureFixture[str]
) -> None:
    part(Scene(EMPTY))
    status, out, _, _ = run(models, capsys)
    assert status == 0
    assert "goal" not in out
    turnstile = ROOT / "examples" / "plain" / "Turnstile.lr"
    main(["run", str(turnstile), "--events", "coin,push"])
    assert "goal" not in capsys.readouterr().out


@pytest.fixture
def scheduler():
    """A cluster whose worker is a thread of this process: it sees the scenes registered
    here."""
    from distributed import LocalCluster

    with LocalCluster(
        n_workers=1, processes=False, dashboard_address=":0", silence_logs=logging.ERROR
    ) as cluster:
        yield cluster.scheduler_address


def sweep(models: Path, scheduler: str, capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    job = models / "bench" / "Job.lr"
    output = models / "out"
    status = main(["sweep", str(job), "--adapter", "mujoco", "--seeds", "1", "--output",
                   str(output), "--scheduler", scheduler])  # fmt: skip
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    return status, err


def test_a_sweep_on_a_scene_that_does_not_load_writes_nothing(
    models: Path, part, scheduler: str, capsys: pytest.CaptureFixture[str]
) -> None:
    mjcf = models / "part.xml"
    mjcf.write_text(EMPTY.read_text().replace('"robot.xml"', '"lwr_robot.xml"'))
    part(Scene(mjcf))
    status, err = sweep(models, scheduler, capsys)
    assert status == 1
    assert f"lightrocks: error: scene 'part': {mjcf} does not load: " in err
    assert not (models / "out").exists()


@pytest.mark.parametrize(
    ("scene", "goal", "error"),
    [(Judged, "True", ""), (Unmeasurable, "", "measurements() raised KeyError: 'block_tilt'")],
)
def test_a_sweep_keeps_the_goal_per_run_and_names_a_hook_that_raised(
    models: Path,
    part,
    scheduler: str,
    capsys: pytest.CaptureFixture[str],
    scene: type[Scene],
    goal: str,
    error: str,
) -> None:
    part(scene(EMPTY))
    status, err = sweep(models, scheduler, capsys)
    assert status == (1 if error else 0)
    assert [line for line in err.splitlines() if "error" in line] == (
        [f"lightrocks: error: scene 'part': {error}"] if error else []
    )
    with (models / "out" / "runs.csv").open() as stream:
        [row] = csv.DictReader(stream)
    assert (row["success"], row["goal_met"]) == ("True", goal)
