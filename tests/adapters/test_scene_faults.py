"""A scene whose MJCF does not load, or whose per-step hook raises, is the scene's fault: a
``SceneFault`` naming the scene (and its file or hook) in one line, not MuJoCo's raw
multi-line message and not an error of the adapter or of the model."""

from __future__ import annotations

from pathlib import Path

import mujoco
import pytest

from lightrocks.adapters import scene_registry
from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.robots.common import MODELS_DIR
from lightrocks.adapters.scene import Scene, SceneFault
from lightrocks.adapters.scene_registry import UnknownScene, load_model
from lightrocks.runtime.contract import Command

EMPTY = (MODELS_DIR / "empty.xml").read_text()


@pytest.fixture
def register(monkeypatch: pytest.MonkeyPatch):
    """``register(name, scene)``: the registry as installed plus ``scene`` under ``name``."""
    known = dict(scene_registry.scenes())
    monkeypatch.setattr(scene_registry, "scenes", lambda: known)

    def add(name: str, scene: Scene) -> None:
        known[name] = scene

    return add


def mjcf(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "part.xml"
    path.write_text(text)
    return path


def test_an_include_of_another_file_than_robot_xml_names_the_scene_file_and_the_rule(
    tmp_path: Path, register
) -> None:
    path = mjcf(tmp_path, EMPTY.replace('file="robot.xml"', 'file="lwr_robot.xml"'))
    register("part", Scene(path))
    with pytest.raises(SceneFault) as caught:
        load_model("part")
    message = str(caught.value)
    assert message.startswith(f"scene 'part': {path} does not load: ")
    assert "Error opening file 'lwr_robot.xml'" in message
    assert 'includes the robot of the run as <include file="robot.xml"/>' in message
    assert "\n" not in message


def test_malformed_xml_names_the_scene_file_and_the_line(tmp_path: Path, register) -> None:
    broken = EMPTY.replace("</body>", "</bodyx>", 1)
    path = mjcf(tmp_path, broken)
    register("part", Scene(path))
    with pytest.raises(SceneFault) as caught:
        load_model("part")
    message = str(caught.value)
    lines = broken.splitlines()
    opened = 1 + lines.index(next(t for t in lines if "<body" in t))  # TinyXML names it
    assert message.startswith(f"scene 'part': {path} does not load: XML parse error")
    assert f"Line number={opened}: XMLElement name=body" in message
    assert "\n" not in message and "robot.xml" not in message


def test_a_missing_mjcf_file_and_a_scene_without_the_robot_are_named(
    tmp_path: Path, register
) -> None:
    register("gone", Scene(tmp_path / "gone.xml"))
    with pytest.raises(SceneFault, match=r"scene 'gone': its MJCF file .*gone\.xml does not"):
        load_model("gone")
    register("bare", Scene(mjcf(tmp_path, EMPTY.replace('<include file="robot.xml"/>', ""))))
    with pytest.raises(SceneFault, match=r"scene 'bare': .* does not include the robot 'lwr'"):
        load_model("bare")


def test_an_unknown_scene_stays_the_caller_s_mistake() -> None:
    with pytest.raises(UnknownScene):
        load_model("atlantis")


class Stepping(Scene):
    """Raises from its per-step hook once the simulation has passed ``after`` seconds."""

    after = 0.5

    def step(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        if data.time > self.after:
            raise KeyError("screw")


def test_a_step_hook_that_raises_is_the_scene_s_fault(register) -> None:
    register("stepping", Stepping(MODELS_DIR / "empty.xml"))
    adapter = MujocoAdapter(scene="stepping")  # settles 0.3 s: before the hook raises
    try:
        hold = Command("gripper", "open", {}, [], 1.0)
        with pytest.raises(SceneFault, match=r"^scene 'stepping': step\(\) raised KeyError: "):
            adapter.execute([hold])
    finally:
        adapter.close()


def test_a_step_hook_that_raises_while_the_cell_settles_stops_the_adapter(register) -> None:
    register("stepping", type("Early", (Stepping,), {"after": -1.0})(MODELS_DIR / "empty.xml"))
    with pytest.raises(SceneFault, match=r"^scene 'stepping': step\(\) raised KeyError: "):
        MujocoAdapter(scene="stepping")
