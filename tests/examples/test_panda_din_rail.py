"""The top-hat rail case study on the Franka Emika Panda (``--robot panda``), judged by the
scene's ground truth.

SnapOn and Seat push along z with the Panda's largest Cartesian stiffness, 3000 N/m, and their
goals deep enough to push as hard as on the LWR (SnapOn up to 3000 N/m x 17 mm = 51 N, Seat
3000 N/m x 5 mm = 15 N); the copy of the models run here makes sure of that, whatever the
shipped actions say (they pushed with 5000 N/m, which the Panda refuses: docs/adapters.md, "The
Panda"). Everything else is the shipped task, skills and cell.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
from judges import missing

from lightrocks.adapters.robot import RobotDataMissing
from lightrocks.adapters.scene_registry import robot, scene
from lightrocks.app.pipeline import run_model

ROOT = Path(__file__).resolve().parents[2]
DIN_RAIL = ROOT / "examples" / "din_rail"
PUSHES = {"SnapOn.lr": "17 mm", "Seat.lr": "5 mm"}
"""The actions that push along z with the hand soft sideways, and how far below they aim."""


@pytest.fixture(autouse=True)
def private_cache(tmp_path_factory, monkeypatch) -> None:
    """Generated code goes to a cache of this test session, not the working tree."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "cache"))


def for_the_panda(folder: Path) -> None:
    """The pushes of the rail's actions at 3000 N/m along z, aiming deep enough."""
    for name, overpress in PUSHES.items():
        action = folder / "actions" / name
        text, stiffened = re.subn(
            r"(\[100 N/m, 100 N/m, )\d+ N/m", r"\g<1>3000 N/m", action.read_text()
        )
        text, deepened = re.subn(
            r"Length overpress = \d+ mm", f"Length overpress = {overpress}", text
        )
        assert stiffened == deepened == 1, name
        action.write_text(text)


@pytest.mark.slow
@pytest.mark.parametrize("adapter", ["mujoco", "pinocchio"])
def test_the_panda_snaps_all_three_terminals_onto_the_rail(adapter: str, tmp_path: Path) -> None:
    try:
        robot("panda").mjcf()
    except RobotDataMissing as error:
        missing("the model files of robot 'panda'", str(error))
    shutil.copytree(DIN_RAIL, tmp_path / "din_rail")
    for_the_panda(tmp_path / "din_rail")
    task = tmp_path / "din_rail" / "tasks" / "AssembleRail.lr"
    result = run_model(task, [tmp_path], [], adapter, robot="panda")
    assert result.outcome == "assembled", result
    assert scene("din_rail").goal_met(result.measurements), result.measurements
