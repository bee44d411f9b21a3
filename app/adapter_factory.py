"""Adapters by name, from the ``lightrocks.adapters`` entry points, with the options their
signature accepts."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from importlib.metadata import entry_points
from typing import Any

from lightrocks.app.errors import RunError, SceneError
from lightrocks.app.script import Script
from lightrocks.app.values import Noise


def adapter_factory(name: str) -> Callable[..., Any]:
    found = {e.name: e for e in entry_points(group="lightrocks.adapters")}
    if name not in found:
        raise RunError(f"unknown adapter '{name}'; known: {', '.join(sorted(found))}")
    return found[name].load()


def adapter_options(
    name: str | None,
    seed: int = 0,
    noise: Noise = (0.0, 0.0),
    video: str | None = None,
    script: Script | None = None,
    robot: str | None = None,
) -> dict[str, Any]:
    """Keyword arguments for the adapter, read off its signature so that nothing it cannot
    honour (noise, a video, another robot) is silently dropped; the seed only matters to
    adapters that draw random numbers."""
    if name is None:
        if any(noise) or video is not None or script is not None:
            raise RunError("perception noise, video and script need an adapter (--adapter)")
        if robot is not None:
            raise RunError("--robot chooses the robot an adapter simulates: give --adapter")
        return {}
    accepted = inspect.signature(adapter_factory(name)).parameters
    options: dict[str, Any] = {"seed": seed} if "seed" in accepted else {}
    if any(noise):
        if "perception_noise" not in accepted:
            raise RunError(f"adapter '{name}' has no perception noise")
        options["perception_noise"] = noise
    if video is not None:
        if "video" not in accepted:
            raise RunError(f"adapter '{name}' cannot record a video")
        options["video"] = video
    if script is not None:
        if not {"outcomes", "sensors"} <= set(accepted):
            raise RunError(f"adapter '{name}' cannot follow a script (the dry run can)")
        options.update(script)
    if robot is not None:
        if "robot" not in accepted:
            able = ", ".join(_taking("robot")) or "none"
            raise RunError(
                f"adapter '{name}' has no choice of robot; --robot needs one that has: {able}"
            )
        options["robot"] = robot
    return options


def _taking(option: str) -> list[str]:
    """The registered adapters whose signature takes ``option``."""
    names = sorted(e.name for e in entry_points(group="lightrocks.adapters"))
    return [n for n in names if option in inspect.signature(adapter_factory(n)).parameters]


def adapter_for(name: str, scene: str | None, **options: Any) -> Any:
    """The adapter on the model's scene; adapters reject an unknown scene with ValueError
    (the user's mistake) and a scene that does not load with ``SceneFault`` (its author's)."""
    factory = adapter_factory(name)
    try:
        return factory(scene=scene, **options)
    except ValueError as error:
        raise RunError(f"adapter '{name}': {error}") from None
    except Exception as error:
        from lightrocks.adapters.scene import SceneFault  # loads MuJoCo: not for the dry run

        if isinstance(error, SceneFault):
            raise SceneError(str(error)) from None
        raise


def scene_of(cls: type) -> str | None:
    return cls.CELL.SCENE if cls.CELL is not None else None
