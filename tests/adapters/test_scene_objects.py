"""Scenes are objects: the registry hands out each registered scene, and adapters and tests
ask it for its hooks instead of switching on its name."""

from __future__ import annotations

import mujoco
import pytest

from lightrocks.adapters.scene import Scene
from lightrocks.adapters.scene_registry import load_model, scene, scenes


def at_start(name: str) -> tuple[mujoco.MjModel, mujoco.MjData]:
    model = load_model(name)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


def test_every_registered_scene_is_a_scene_object_with_its_mjcf() -> None:
    assert {"empty", "screwing", "din_rail"} <= set(scenes())
    for name, registered in scenes().items():
        assert isinstance(registered, Scene), name
        assert registered.mjcf.is_file(), name


@pytest.mark.parametrize(
    ("name", "done", "not_done"),
    [
        ("screwing", {"screw_bottomed": True}, {"screw_bottomed": False}),
        ("din_rail", {"terminals_latched": 3.0}, {"terminals_latched": 2.0}),
        ("empty", None, {}),
    ],
)
def test_each_scene_judges_its_own_goal(name: str, done: dict | None, not_done: dict) -> None:
    assert not scene(name).goal_met(not_done)
    if done is not None:
        assert scene(name).goal_met(done)


def test_the_empty_scene_is_plain_physics() -> None:
    model, data = at_start("empty")
    scene("empty").step(model, data)
    assert scene("empty").measurements(model, data) == {}
    assert scene("empty").twin() is None


@pytest.mark.parametrize("name", ["screwing", "din_rail"])
def test_a_twin_is_a_fresh_fixture_with_the_keys_of_the_scene(name: str) -> None:
    model, data = at_start(name)
    twin = scene(name).twin()
    assert twin is not scene(name).twin()
    assert set(twin.measurements()) == set(scene(name).measurements(model, data))
    assert not scene(name).goal_met(twin.measurements())
