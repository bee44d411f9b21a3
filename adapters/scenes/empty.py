"""The empty cell (adapters/models/empty.xml): a table and a static box, plain physics."""

from __future__ import annotations

from lightrocks.adapters.robots.common import MODELS_DIR
from lightrocks.adapters.scene import Scene

SCENE = Scene(MODELS_DIR / "empty.xml")
