"""``lightrocks run`` and ``sweep`` on a broken scene.

A scene whose MJCF does not load is its author's mistake, not a wrong use of the command:
one line naming the scene and its file, exit 1, no traceback, nothing written.
"""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

from lightrocks.adapters import scene_registry
from lightrocks.adapters.robot_model import MODELS_DIR
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
