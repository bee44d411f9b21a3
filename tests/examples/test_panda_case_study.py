"""The screwing case study on the Franka Emika Panda with nothing but ``--robot`` changed:
the unchanged task, skills and cell (``robot : LWR;``) checked, generated and run for the
registered robot ``panda``, judged by the scene's ground truth as on the LWR."""

from __future__ import annotations

from pathlib import Path

import pytest
from judges import missing

from lightrocks.adapters.robots.robot import RobotDataMissing
from lightrocks.adapters.scene_registry import robot, scene
from lightrocks.app.cli import main
from lightrocks.app.pipeline import run_model

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"


def test_list_robots_shows_the_lwr_and_the_panda(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["list", "robots"]) == 0
    rows = [line.split("  ")[:2] for line in capsys.readouterr().out.splitlines()]
    assert ["lwr", "LWR"] in rows
    assert ["panda", "Panda"] in rows


@pytest.mark.slow
@pytest.mark.parametrize("adapter", ["mujoco", "pinocchio"])
def test_the_screw_task_drives_the_screw_home_on_the_panda(adapter: str, tmp_path: Path) -> None:
    try:
        robot("panda").mjcf()
    except RobotDataMissing as error:
        missing("the model files of robot 'panda'", str(error))
    trace = tmp_path / "run.jsonl"
    result = run_model(SCREW_TASK, [], [], adapter, trace=trace, robot="panda")
    assert result.outcome == "screwed", result
    assert scene("screwing").goal_met(result.measurements), result.measurements
    assert '"robot": "panda"' in trace.read_text().splitlines()[0]
