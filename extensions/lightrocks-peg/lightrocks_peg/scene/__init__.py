"""The peg-in-hole scene: its MJCF and its ground truth, registered as a LightRocks scene."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import mujoco

from lightrocks.adapters.scene import Scene

INSERTED_DEPTH = 0.02
"""The peg counts as inserted once its bottom is this deep [m] below the hole mouth."""
CENTRED = 0.003
"""Largest offset [m] of the peg's axis from the hole's on either axis (clearance is 2 mm)."""


class PegInHole(Scene):
    """Plain physics; the ground truth tells an inserted peg from one that only believes so."""

    def measurements(self, model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, Any]:
        """``peg_depth`` [m] of the peg's bottom below the hole mouth and ``peg_inserted``."""
        peg, hole = data.body("peg"), data.body("hole")
        depth = float(hole.xpos[2] - peg.xpos[2])
        inside = bool(max(abs(peg.xpos[:2] - hole.xpos[:2])) <= CENTRED)
        return {"peg_depth": depth, "peg_inserted": inside and depth >= INSERTED_DEPTH}

    def goal_met(self, values: Mapping[str, Any]) -> bool:
        """The peg is in the hole, centred and deep enough."""
        return bool(values.get("peg_inserted"))


SCENE = PegInHole(Path(__file__).with_name("peg_in_hole.xml"))
