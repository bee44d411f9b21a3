"""The top-hat rail case study on the Franka Emika Panda with nothing but ``--robot``
changed: the shipped task, skills and cell (``robot : LWR;``) checked, generated and run for
the registered robot ``panda``, judged by the scene's ground truth as on the LWR."""

from __future__ import annotations

from pathlib import Path

import pytest
from judges import missing

from lightrocks.adapters.robots.robot import RobotDataMissing
from lightrocks.adapters.scene_registry import robot, scene
from lightrocks.app.pipeline import run_model

ROOT = Path(__file__).resolve().parents[2]
ASSEMBLE_RAIL = ROOT / "examples" / "din_rail" / "tasks" / "AssembleRail.lr"


@pytest.fixture(autouse=True)
def private_cache(tmp_path_factory, monkeypatch) -> None:
    """Generated code goes to a cache of this test session, not the working tree."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "cache"))


@pytest.mark.slow
@pytest.mark.parametrize("adapter", ["mujoco", "pinocchio"])
def test_the_panda_snaps_all_three_terminals_onto_the_rail(adapter: str) -> None:
    try:
        robot("panda").mjcf()
    except RobotDataMissing as error:
        missing("the model files of robot 'panda'", str(error))
    result = run_model(ASSEMBLE_RAIL, [], [], adapter, robot="panda")
    assert result.outcome == "assembled", result
    assert scene("din_rail").goal_met(result.measurements), result.measurements
