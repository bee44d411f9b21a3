"""The peg-in-hole scene: its MJCF and its ground truth, registered as a LightRocks scene."""

from __future__ import annotations

from pathlib import Path

import mujoco

from lightrocks.adapters.scene_registry import Scene

INSERTED_DEPTH = 0.02
"""The peg counts as inserted once its bottom is this deep [m] below the hole mouth."""
CENTRED = 0.003
"""Largest offset [m] of the peg's axis from the hole's on either axis (clearance is 2 mm)."""


def measurements(model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, float | bool]:
    """``peg_depth`` [m] of the peg's bottom below the hole mouth and ``peg_inserted``."""
    peg, hole = data.body("peg"), data.body("hole")
    depth = float(hole.xpos[2] - peg.xpos[2])
    inside = bool(max(abs(peg.xpos[:2] - hole.xpos[:2])) <= CENTRED)
    return {"peg_depth": depth, "peg_inserted": inside and depth >= INSERTED_DEPTH}


SCENE = Scene(Path(__file__).with_name("peg_in_hole.xml"), measurements=measurements)
