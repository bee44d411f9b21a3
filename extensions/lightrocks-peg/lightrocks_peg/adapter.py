"""A MuJoCo adapter with a force guard, registered as the ``mujoco-guarded`` adapter.

Every command gets one more stop predicate, checked on every control tick before the
command's own: a contact force above ``FORCE_LIMIT`` ends the command with the outcome
``overload``. Like every ending of a command, the device layer then holds the robot still
and compliant, so a jammed peg is not pushed further.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.runtime.contract import (
    Command,
    CommandResult,
    Snapshot,
    StopCondition,
    TickListener,
)

FORCE_LIMIT = 80.0
"""Contact force [N] beyond which a command is stopped."""
OVERLOAD = "overload"


def overloaded(snapshot: Snapshot) -> bool:
    return snapshot.robot.wrench.force.norm() > FORCE_LIMIT


class GuardedMujocoAdapter(MujocoAdapter):
    def execute(
        self, commands: Sequence[Command], on_tick: TickListener | None = None
    ) -> list[CommandResult]:
        guard = StopCondition(OVERLOAD, overloaded)
        guarded = [replace(c, stop=[guard, *c.stop]) for c in commands]
        return super().execute(guarded, on_tick)
