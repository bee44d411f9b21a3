"""The scene's ground truth of a run: what the adapter measured. A scene hook that raises is
the scene's fault, reported beside the run's outcome instead of ending the report."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class GroundTruth:
    measurements: dict[str, Any] = field(default_factory=dict)
    fault: str = ""
    """What the scene's hook that raised said, named with the scene and the hook."""


def ground_truth(adapter: Any, scene: str | None) -> GroundTruth:
    """The measurements of ``adapter`` (read before it is closed)."""
    measure = getattr(adapter, "measurements", None)
    if measure is None:
        return GroundTruth()
    try:
        return GroundTruth(dict(measure()))
    except Exception as error:
        return GroundTruth(fault=_raised(scene, "measurements", error))


def _raised(scene: str | None, hook: str, error: Exception) -> str:
    from lightrocks.adapters.scene import hook_fault

    return str(hook_fault(scene or "(none)", hook, error))
