"""The top-hat rail case study on the Franka Emika Panda (``--robot panda``).

The task as shipped is refused for the Panda: Seat.lr and SnapOn.lr push with 5000 N/m along
z, beyond the Panda's 3000 N/m. With those pushes at 3000 N/m and their goals deeper, so that
they push as hard as before (SnapOn up to 3000 N/m x 17 mm = 51 N, the shipped 50 N; Seat
3000 N/m x 5 mm = 15 N, as shipped), the unchanged rest of the task, skills and cell snaps
all three terminals on, judged by the scene's ground truth (docs/adapters.md, "The Panda").
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from judges import missing

from lightrocks.adapters.robot import RobotDataMissing
from lightrocks.adapters.scene_registry import robot, scene
from lightrocks.app.errors import ModelError
from lightrocks.app.pipeline import run_model

ROOT = Path(__file__).resolve().parents[2]
DIN_RAIL = ROOT / "examples" / "din_rail"
FOR_THE_PANDA = {
    "SnapOn.lr": [("5000 N/m", "3000 N/m"), ("overpress = 10 mm", "overpress = 17 mm")],
    "Seat.lr": [("5000 N/m", "3000 N/m"), ("overpress = 3 mm", "overpress = 5 mm")],
}


@pytest.fixture(autouse=True)
def private_cache(tmp_path_factory, monkeypatch) -> None:
    """Generated code goes to a cache of this test session, not the working tree."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "cache"))


@pytest.fixture
def panda() -> None:
    try:
        robot("panda").mjcf()
    except RobotDataMissing as error:
        missing("the model files of robot 'panda'", str(error))


def test_the_shipped_rail_task_pushes_harder_than_the_panda_may(panda) -> None:
    with pytest.raises(ModelError, match=r"SnapOn\.lr:\d+:\d+: error LR0505.*5000 N/m"):
        run_model(DIN_RAIL / "tasks" / "AssembleRail.lr", [], [], "pinocchio", robot="panda")


@pytest.mark.slow
@pytest.mark.parametrize("adapter", ["mujoco", "pinocchio"])
def test_the_panda_snaps_all_three_terminals_onto_the_rail(
    adapter: str, tmp_path: Path, panda
) -> None:
    copy = tmp_path / "din_rail"
    shutil.copytree(DIN_RAIL, copy)
    for name, changes in FOR_THE_PANDA.items():
        action = copy / "actions" / name
        text = action.read_text()
        for old, new in changes:
            assert old in text
            text = text.replace(old, new)
        action.write_text(text)
    task = copy / "tasks" / "AssembleRail.lr"
    result = run_model(task, [tmp_path], [], adapter, robot="panda")
    assert result.outcome == "assembled", result
    assert scene("din_rail").goal_met(result.measurements), result.measurements
