"""The top-hat rail cell (adapters/models/din_rail.xml): terminal blocks snapped onto a rail.

MuJoCo snaps the terminals with spring-loaded latches and wedges; the Pinocchio twin moves
kinematic terminals instead (see docs/scenes.md). This module is the only code that knows the
cell's joint and body names.

Conventions: SI units, world frame, z up; the arm base is at the world origin.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import mujoco
import numpy as np

from lightrocks.adapters.robots.common import MODELS_DIR
from lightrocks.adapters.scene import Scene

TERMINALS = ("terminal1", "terminal2", "terminal3")
RAIL_X = 0.60
"""Rail centre line [m]; the rail runs along the world y axis."""
RAIL_LIP_TOP_Z = 0.1075
"""Height [m] of the rail lips' top face: a latched terminal's housing rests there."""
RAIL_HALF_LENGTH = 0.12
TERMINAL_Y = (-0.07, 0.0, 0.07)
"""y [m] of the terminals in the tray, and of their target slots on the rail."""
TRAY_X = 0.45
TERMINAL_TRAY_Z = 0.1101
"""Height [m] of a terminal's origin (housing underside) standing in the tray."""
SNAP_FORCE = 34.0
"""Designed snap-through force [N] of a terminal (measured: see docs/scenes.md)."""
LIPS = (0.0125, 0.0175)
"""Distance [m] of the rail lips' inner and outer edges from its centre line (din_rail.xml)."""
WEDGE_REACH = 0.0235
"""Distance [m] of the latch wedges' outer ends from the terminal's centre (din_rail.xml)."""
RAMP_BOTTOM = 0.0061
"""Depth [m] of the wedges' lowest point, their outer end, below the housing underside."""
LEAD_IN = WEDGE_REACH - LIPS[1]
"""A terminal set down closer than this [m] to the rail's centre line meets a lip with a latch
ramp, which pushes it onto the centre line; up to WEDGE_REACH - LIPS[0] off, a wedge's end
stands on a lip."""
LATCH_ENGAGED = 0.00075
"""A latch deflected less than this [m] has its catch under the lip (overlap is 1.5 mm)."""


def terminal_latched(model: mujoco.MjModel, data: mujoco.MjData, terminal: str) -> bool:
    """Whether ``terminal`` sits latched on the rail (see :meth:`DinRail.measurements`)."""
    pos = data.body(terminal).xpos
    rail = data.body("rail").xpos
    upright = float(data.body(terminal).xmat[8]) > 0.995
    on_rail = abs(pos[0] - rail[0]) < 0.0015 and abs(pos[1] - rail[1]) < RAIL_HALF_LENGTH - 0.005
    seated = abs(pos[2] - (rail[2] + 0.0075)) < 0.0006
    catches = all(
        float(data.qpos[model.jnt_qposadr[model.joint(f"{terminal}_latch_{side}").id]])
        < LATCH_ENGAGED
        for side in ("l", "r")
    )
    return bool(upright and on_rail and seated and catches)


# --- the analytic twin for the Pinocchio adapter ---------------------------------------------


@dataclass
class _Terminal:
    position: np.ndarray
    latched: bool = False
    carried: bool = False
    offset: np.ndarray = field(default_factory=lambda: np.zeros(3))


@dataclass
class RailTwin:
    """Kinematic terminals and rail for dry runs: a ``scene.FixtureTwin``, with ``reset()``.

    A closed gripper whose TCP is within 8 mm (x, y) and 12 mm (z) of a terminal's grasp point
    (25 mm above its underside, centre) carries that terminal rigidly. A carried terminal within
    LEAD_IN of the rail's centre line whose ramps reach the lips is slid onto the centre line
    in the grip (the lead-in; MuJoCo's soft hand moves sideways instead). Farther off, up to
    WEDGE_REACH - LIPS[0], the end of one wedge stands on a lip: a stiff upward force there,
    which twists the wrist. Over the rail, pushing
    a carried terminal down meets the snap-fit: the resisting force rises linearly to
    ``snap_force`` over the 1.5 mm ramp, falls to the ``friction`` plateau for the next
    1 mm, and the terminal latches when its underside is 0.1 mm above the lips; pushing on
    a latched terminal meets the rail (``seat_stiffness`` N/m). A latched terminal stays when
    the gripper opens and cannot be pulled off; a terminal released elsewhere stays where it
    is (no gravity in the twin).
    """

    snap_force: float = SNAP_FORCE
    friction: float = 4.5
    seat_stiffness: float = 2.0e5
    terminals: dict[str, _Terminal] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not self.terminals:
            self.reset()

    def reset(self) -> None:
        self.terminals = {
            name: _Terminal(np.array([TRAY_X, y, TERMINAL_TRAY_Z]))
            for name, y in zip(TERMINALS, TERMINAL_Y, strict=True)
        }

    @staticmethod
    def _near(term: _Terminal, tcp: np.ndarray) -> bool:
        near = np.abs(tcp - (term.position + np.array([0.0, 0.0, 0.025])))
        return bool(near[0] < 0.008 and near[1] < 0.008 and near[2] < 0.012)

    def graspable(self, tcp_position: np.ndarray) -> bool:
        """Whether a gripper closing at ``tcp_position`` would hold a terminal."""
        tcp = np.asarray(tcp_position, dtype=float)
        return any(self._near(term, tcp) for term in self.terminals.values())

    def _resistance(self, height: float) -> float:
        """Upward force [N] of the rail on a terminal whose underside is ``height`` above it."""
        if height >= 0.0026:
            return 0.0
        if height >= 0.0011:
            return self.snap_force * (0.0026 - height) / 0.0015
        if height >= 0.0001:
            return self.friction
        return self.seat_stiffness * max(-height, 0.0)

    def step(
        self, dt: float, tcp_position: np.ndarray, tcp_rotation: np.ndarray, holding: bool
    ) -> np.ndarray:
        tcp = np.asarray(tcp_position, dtype=float)
        wrench = np.zeros(6)
        for term in self.terminals.values():
            if not holding:
                term.carried = False
                continue
            if not term.carried:
                if self._near(term, tcp):
                    term.carried, term.offset = True, term.position - tcp
                continue
            wanted = tcp + term.offset
            across = float(wanted[0]) - RAIL_X
            height = float(wanted[2]) - RAIL_LIP_TOP_Z
            along_rail = abs(wanted[1]) < RAIL_HALF_LENGTH
            if along_rail and LEAD_IN <= abs(across) < WEDGE_REACH - LIPS[0]:
                term.position = wanted
                if height < RAMP_BOTTOM:
                    self._stand_on_lip(term, tcp, across, height, wrench)
                continue
            if not (along_rail and abs(across) < LEAD_IN):
                term.position = wanted
                continue
            if height < RAMP_BOTTOM:  # the ramps on the lips: the lead-in
                term.offset[0] -= across
                wanted[0] = RAIL_X
            if not term.latched and height < 0.0001:
                term.latched = True
            if term.latched:  # held down by the lips, held up by the catches
                term.position = np.array([RAIL_X, wanted[1], RAIL_LIP_TOP_Z])
                wrench[2] -= self.seat_stiffness * height
            else:
                term.position = wanted
                wrench[2] += self._resistance(height)
        return wrench

    def _stand_on_lip(
        self, term: _Terminal, tcp: np.ndarray, across: float, height: float, wrench: np.ndarray
    ) -> None:
        """A wedge's end on a lip: the terminal stays on it, pushed up (``seat_stiffness``) at
        that end, which adds a torque about the TCP."""
        term.position[2] = RAIL_LIP_TOP_Z + RAMP_BOTTOM
        push = self.seat_stiffness * (RAMP_BOTTOM - height)
        end = term.position - np.array([math.copysign(WEDGE_REACH, across), 0.0, 0.0])
        wrench[2] += push
        wrench[3:] += np.cross(end - tcp, (0.0, 0.0, push))

    def measurements(self) -> dict[str, float | bool]:
        values: dict[str, float | bool] = {}
        for name, term in self.terminals.items():
            values[f"{name}_latched"] = term.latched
            values[f"{name}_height"] = float(term.position[2]) - RAIL_LIP_TOP_Z
        values["terminals_latched"] = float(sum(t.latched for t in self.terminals.values()))
        return values


class DinRail(Scene):
    """The top-hat rail cell: the terminals' ground truth, the kinematic terminals of the
    twin, and the goal of all three terminals latched."""

    def measurements(self, model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, float | bool]:
        """``terminalN_latched`` (on the rail, upright, housing on the lips and both catches
        under the lips), ``terminalN_height`` [m] of the housing underside above the lips'
        top, and ``terminals_latched`` (how many are latched)."""
        values: dict[str, float | bool] = {}
        rail_top = float(data.body("rail").xpos[2]) + 0.0075
        count = 0
        for terminal in TERMINALS:
            latched = terminal_latched(model, data, terminal)
            count += latched
            values[f"{terminal}_latched"] = latched
            values[f"{terminal}_height"] = float(data.body(terminal).xpos[2]) - rail_top
        values["terminals_latched"] = float(count)
        return values

    def twin(self) -> RailTwin:
        return RailTwin()

    def goal_met(self, values: Mapping[str, Any]) -> bool:
        """All three terminals are latched."""
        return values.get("terminals_latched") == len(TERMINALS)


SCENE = DinRail(MODELS_DIR / "din_rail.xml")
