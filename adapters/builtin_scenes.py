"""The scenes of this package, registered as ``lightrocks.scenes`` entry points."""

from __future__ import annotations

from functools import partial

from lightrocks.adapters import scenes
from lightrocks.adapters.robot_model import MODELS_DIR
from lightrocks.adapters.scene_registry import Scene

EMPTY = Scene(MODELS_DIR / "empty.xml")
SCREWING = Scene(
    MODELS_DIR / "screwing.xml",
    measurements=partial(scenes.measurements, "screwing"),
    step=partial(scenes.scene_step, "screwing"),
    twin=partial(scenes.make_twin, "screwing"),
)
DIN_RAIL = Scene(
    MODELS_DIR / "din_rail.xml",
    measurements=partial(scenes.measurements, "din_rail"),
    twin=partial(scenes.make_twin, "din_rail"),
)
