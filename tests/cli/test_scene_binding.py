"""Binding at start: the cell's objects are compared with the adapter's scene before the run
starts; a missing object is the model's mistake (exit 1), an unknown scene a wrong use
(exit 2); both are named, and nothing is written."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.cli import main

ROOT = Path(__file__).resolve().parents[2]

CELL = """package bench;

import lightrocks.robots.*;

<<scene="{scene}">> cell Bench {{
  robot : LWR;
  gripper : ParallelGripper;
  camera : Camera;

  object block;
  object peg;
  object hole;
}}
"""

LOOK = """package bench;

import bench.Bench;

<<action, timeout="5 s">> statechart Look {
  do / block.pose = camera.localize(target = block);

  end condition located [camera.done];
}
"""


@pytest.fixture
def models(tmp_path: Path) -> Path:
    (tmp_path / "bench").mkdir()
    (tmp_path / "bench" / "Look.lr").write_text(LOOK)
    return tmp_path


def run(capsys: pytest.CaptureFixture[str], models: Path, scene: str) -> tuple[int, str]:
    (models / "bench" / "Bench.lrd").write_text(CELL.format(scene=scene))
    trace = models / "run.jsonl"
    status = main(
        ["run", str(models / "bench" / "Look.lr"), "--adapter", "mujoco", "--trace", str(trace)]
    )
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    assert not trace.exists()
    return status, out + err


def test_objects_missing_from_the_scene_are_named(
    models: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    status, output = run(capsys, models, "empty")
    assert status == 1
    assert "scene 'empty' has no object 'peg'" in output
    assert "scene 'empty' has no object 'hole'" in output
    assert "'block'" not in output  # the empty scene has a block


def test_an_unknown_scene_is_named_with_the_known_ones(
    models: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    status, output = run(capsys, models, "atlantis")
    assert status == 2
    assert "unknown scene 'atlantis'" in output
    assert "din_rail, empty, screwing" in output
