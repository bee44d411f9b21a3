"""Execution control of a run: pause, resume, step one transition, breakpoints and abort.

Requests come from any thread; the run's thread asks ``stops_at`` at every state entry and
transition and ``wait``s at every trace record and control tick. While it waits the
simulated time stands still and the arm holds its pose.
"""

from __future__ import annotations

import threading
from collections.abc import Iterable
from typing import Any

ENDINGS = ("interrupted", "aborted", "finished")
"""Records after which the run only ends: nothing pauses it any more."""


def state_path(name: str) -> str:
    """``Task.Skill.Action`` (as on the command line) as the path the trace uses."""
    return name.replace(".", "/")


def place(record: dict[str, Any]) -> str:
    """Where a state entry or a transition happens, as a breakpoint names it; else ''."""
    if record["kind"] == "enter":
        return record["state"]
    if record["kind"] == "transition":
        owner = record["state"]
        return f"{owner}/{record['source']}->{owner}/{record['target']}"
    return ""


class RunControl:
    def __init__(
        self, breakpoints: Iterable[str] = (), paused: bool = False, aborts: Iterable[str] = ()
    ) -> None:
        self.breakpoints = {state_path(b) for b in breakpoints}
        self.aborts = {state_path(a) for a in aborts}
        """Where the run is aborted as soon as it gets there."""
        self._running = threading.Event()
        self._stepping = False
        self.aborting = False
        """Abort was asked for and the run has not stopped yet."""
        self.where = ""
        """The breakpoint or step the run stopped at, for the page."""
        self.ending = False
        """The run is ending (Ctrl-C, an abort, its end): it pauses no more."""
        self._lock = threading.Lock()
        """Orders a page's pause against the run's end."""
        if not paused:
            self._running.set()

    @property
    def paused(self) -> bool:
        return not self._running.is_set()

    def end(self) -> None:
        """Let the run end without pausing again, whatever the page asks."""
        with self._lock:
            self.ending = True
            self._stepping = False
            self._running.set()

    def pause(self) -> None:
        with self._lock:
            if not self.ending:
                self.where = ""
                self._running.clear()

    def resume(self) -> None:
        self._stepping = False
        self._running.set()

    def step(self) -> None:
        """Run until the next transition or state entry, then pause again."""
        self._stepping = True
        self._running.set()

    def abort(self) -> None:
        """Stop the run safely at its next record or control tick, paused or not."""
        self.aborting = True
        self._running.set()

    def toggle_breakpoint(self, name: str) -> bool:
        path = state_path(name)
        if path in self.breakpoints:
            self.breakpoints.discard(path)
            return False
        self.breakpoints.add(path)
        return True

    # -- asked by the run's thread --------------------------------------------------------

    def stops_at(self, record: dict[str, Any]) -> bool:
        """Whether the run pauses at this record: a breakpoint, or the end of a step; at an
        abort point the run is aborted instead."""
        if record["kind"] in ENDINGS:
            self.end()
        if self.ending:
            return False
        where = place(record)
        if where in self.aborts:
            self.abort()
            return False
        if not where or not (where in self.breakpoints or self._stepping):
            return False
        self._stepping = False
        self.where = where
        self._running.clear()
        return True

    def wait(self) -> None:
        """Hold the run's thread until Resume, Step or Abort. Ctrl-C ends the run: the
        executor stops it safely and no later record pauses it again. The wait wakes ten
        times a second: a signal that another thread received is handled only when the run's
        thread runs Python code."""
        try:
            while not self._running.wait(0.1):
                pass
        except KeyboardInterrupt:
            self.end()
            raise
