"""The minimal scene of docs/scenes.md ("Writing a scene for a new part") works as written:
registered as a scene, it loads with every registered robot, offers its table and part to a
cell, and the part rests on the table where it stands."""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

import mujoco
import numpy as np
import pytest

from lightrocks.adapters import scene_registry
from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.robots.robot import RobotDataMissing
from lightrocks.adapters.scene import Scene

ROOT = Path(__file__).resolve().parents[2]
GUIDE = (ROOT / "docs" / "scenes.md").read_text(encoding="utf-8")
SECTION = GUIDE.split("## Writing a scene for a new part", 1)[1].split("\n## ", 1)[0]
SKELETON = textwrap.dedent(re.search(r"```xml\n(.*?)```", SECTION, re.DOTALL).group(1))


@pytest.fixture
def skeleton(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> str:
    """The documented MJCF registered as the scene ``skeleton``."""
    path = tmp_path / "my_part.xml"
    path.write_text(SKELETON)
    known = {**scene_registry.scenes(), "skeleton": Scene(path)}
    monkeypatch.setattr(scene_registry, "scenes", lambda: known)
    return "skeleton"


def test_the_documented_skeleton_is_short() -> None:
    assert len(SKELETON.splitlines()) <= 20
    assert '<include file="robot.xml"/>' in SKELETON


@pytest.mark.parametrize("robot", sorted(scene_registry.robots()))
def test_the_skeleton_loads_with_every_robot(skeleton: str, robot: str) -> None:
    try:
        model = scene_registry.load_model(skeleton, robot)
    except RobotDataMissing as error:
        pytest.skip(str(error))
    root = scene_registry.robot(robot).root
    assert scene_registry.objects(model, root) == ["table", "part"]
    assert model.opt.timestep == 0.001
    assert model.opt.cone == mujoco.mjtCone.mjCONE_ELLIPTIC
    assert model.opt.impratio == 10


def test_the_part_rests_on_the_table_where_it_stands(skeleton: str) -> None:
    adapter = MujocoAdapter(scene=skeleton)  # settles the cell for 0.3 s
    try:
        part = adapter.scene_pose("part")
        assert np.allclose(part.translation, [0.5, 0.0, 0.115], atol=5e-4)
        assert abs(part.rotation[2, 2] - 1.0) < 1e-4  # upright
    finally:
        adapter.close()
