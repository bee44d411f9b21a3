"""Execution control of a run: pause, resume, step one transition and breakpoints.

The run thread consults the control at every trace record (each transition and state
entry) and at every control tick of a running command; while paused it waits there, so
the simulated time stands still and the arm holds its pose. Requests come from any thread.
"""

from __future__ import annotations

import threading
from collections.abc import Iterable
from typing import Any

STOPPING_KINDS = ("enter", "transition")


def state_path(name: str) -> str:
    """``Task.Skill.Action`` (as on the command line) as the path the trace uses."""
    return name.replace(".", "/")


class RunControl:
    def __init__(self, breakpoints: Iterable[str] = (), paused: bool = False) -> None:
        self.breakpoints = {state_path(b) for b in breakpoints}
        self._running = threading.Event()
        self._stepping = False
        self.where = ""
        """The state the run stopped at, for the page."""
        if not paused:
            self._running.set()

    @property
    def paused(self) -> bool:
        return not self._running.is_set()

    def pause(self) -> None:
        self._running.clear()

    def resume(self) -> None:
        self._stepping = False
        self._running.set()

    def step(self) -> None:
        """Run until the next transition or state entry, then pause again."""
        self._stepping = True
        self._running.set()

    def toggle_breakpoint(self, name: str) -> bool:
        path = state_path(name)
        if path in self.breakpoints:
            self.breakpoints.discard(path)
            return False
        self.breakpoints.add(path)
        return True

    # -- consulted by the run thread ------------------------------------------------------

    def on_record(self, record: dict[str, Any]) -> None:
        """Stop at a breakpoint (a state entered, a transition taken) or after a step."""
        kind, owner = record["kind"], record.get("state", "")
        if kind == "enter":
            where = owner
        elif kind == "transition":
            where = f"{owner}/{record['source']}->{owner}/{record['target']}"
        else:
            return
        if where in self.breakpoints or self._stepping:
            self._stepping = False
            self.where = where
            self._running.clear()
        self._running.wait()

    def on_tick(self) -> None:
        self._running.wait()
