"""The scene's ground truth of a run: what the adapter measured and whether that shows the
scene's goal met, so that a report tells a run that reached the goal from one that only
believes so. A scene hook that raises is the scene's fault, reported beside the run's
outcome instead of ending the report."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class GroundTruth:
    measurements: dict[str, Any] = field(default_factory=dict)
    goal: bool | None = None
    """Whether the scene's ``goal_met`` holds; ``None`` without an adapter that measures,
    without a scene, for a scene that states no goal, or when a hook raised."""
    fault: str = ""
    """What the scene's hook that raised said, named with the scene and the hook."""


def ground_truth(adapter: Any, scene: str | None) -> GroundTruth:
    """The measurements of ``adapter`` (read before it is closed) and the judgement of
    ``scene``'s ``goal_met`` on them."""
    measure = getattr(adapter, "measurements", None)
    if measure is None:
        return GroundTruth()
    try:
        measured = dict(measure())
    except Exception as error:
        return GroundTruth(fault=_raised(scene, "measurements", error))
    judge = _goal_met(scene)
    if judge is None:
        return GroundTruth(measured)
    try:
        return GroundTruth(measured, bool(judge(measured)))
    except Exception as error:
        return GroundTruth(measured, fault=_raised(scene, "goal_met", error))


def _goal_met(scene: str | None) -> Callable[[Mapping[str, Any]], Any] | None:
    """The scene's ``goal_met``, unless it keeps the base class's, which states no goal."""
    if scene is None:
        return None
    from lightrocks.adapters.scene import Scene
    from lightrocks.adapters.scene_registry import scene as registered

    found = registered(scene)
    return None if type(found).goal_met is Scene.goal_met else found.goal_met


def _raised(scene: str | None, hook: str, error: Exception) -> str:
    from lightrocks.adapters.scene import hook_fault

    return str(hook_fault(scene or "(none)", hook, error))
