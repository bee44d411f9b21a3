"""The run trace: one JSON object per line (time, kind, state, …) that tools and tests read."""

from __future__ import annotations

import contextlib
import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

import numpy as np

from lightrocks.runtime.contract import Snapshot, TickListener, Vector3, Wrench
from lightrocks.runtime.environment import SceneObject, object_name
from lightrocks.runtime.frames import Frame

Record = dict[str, Any]


def to_json(value: Any) -> Any:
    """A JSON-friendly copy of a sensor or parameter value (frames as their translation)."""
    if isinstance(value, bool | str) or value is None:
        return value
    if isinstance(value, int | float | np.floating | np.integer):
        number = float(value)
        return number if math.isfinite(number) else str(number)
    if isinstance(value, Frame):
        return [float(v) for v in value.translation]
    if isinstance(value, Vector3):
        return [value.x, value.y, value.z]
    if isinstance(value, Wrench):
        return {"force": to_json(value.force), "torque": to_json(value.torque)}
    if isinstance(value, SceneObject):
        return object_name(value)
    if isinstance(value, np.ndarray | list | tuple):
        return [to_json(v) for v in value]
    return repr(value)


RecordListener = Callable[[Record], None]
"""Told of every trace record as it is written."""


class Trace:
    """What a run tells the outside: its records, kept in memory and told to the record
    listeners (a JSON-lines file among them), and its control ticks, told to the tick
    listeners (sampling, a monitor's pauses). Listeners run on the run's thread: one that
    blocks pauses the run, one that raises ``runtime.Abort`` stops it safely."""

    def __init__(self, file: str | Path | IO[str] | None = None, *, keep: bool = True) -> None:
        self.keep = keep
        """Whether records stay in memory (``records``); without it, a file or a listener, the
        trace is disabled and the executor builds no record at all."""
        self.records: list[Record] = []
        self.listeners: list[RecordListener] = []
        self.tick_listeners: list[TickListener] = []
        self._file = None if file is None else TraceFile(file)
        if self._file is not None:
            self.listeners.append(self._file.write)
        self._time, self._rounded = math.nan, math.nan  # the last time written, and as written

    @property
    def enabled(self) -> bool:
        """Whether a record would go anywhere."""
        return self.keep or bool(self.listeners)

    @property
    def time(self) -> float:
        """The time of the last record written (0 before the first)."""
        return 0.0 if math.isnan(self._rounded) else self._rounded

    @property
    def failure(self) -> OSError | None:
        """Why the file could not be written (see ``TraceFile.failure``)."""
        return None if self._file is None else self._file.failure

    def write(self, time: float, kind: str, **fields: Any) -> None:
        self.record(time, kind, fields)

    def record(self, time: float, kind: str, fields: dict[str, Any]) -> None:
        """``write`` with the fields as one dict (the executor's path, called per record)."""
        if time != self._time:  # a step writes several records at one time
            self._time, self._rounded = time, round(time, 9)
        record: Record = {"time": self._rounded, "kind": kind, **fields}
        if self.keep:
            self.records.append(record)
        for listener in self.listeners:
            listener(record)

    @property
    def on_tick(self) -> TickListener | None:
        """What ``Adapter.execute`` tells of the control ticks: nothing without a tick
        listener, the one listener itself (a call less on every tick), or ``tick``."""
        if not self.tick_listeners:
            return None
        return self.tick_listeners[0] if len(self.tick_listeners) == 1 else self.tick

    def tick(self, snapshot: Snapshot) -> None:
        """A control tick of a running command: told to every tick listener."""
        for listener in self.tick_listeners:
            listener(snapshot)

    def close(self) -> None:
        if self._file is not None:
            self._file.close()

    def of_kind(self, *kinds: str) -> list[Record]:
        return [r for r in self.records if r["kind"] in kinds]


class TraceFile:
    """Writes records as JSON lines to a file (opened and closed here) or an open stream.

    Every record reaches the file as it is written, one whole line at a time: a run that is
    paused, or killed at any moment, leaves a trace that can be read up to its last record.
    """

    def __init__(self, file: str | Path | IO[str]) -> None:
        self._owned = isinstance(file, str | Path)
        self._stream: IO[str] | None = (
            open(file, "w", encoding="utf-8", buffering=1)  # noqa: SIM115 (line-buffered)
            if isinstance(file, str | Path)
            else file
        )
        self.failure: OSError | None = None
        """Why the file could not be written (a full disk): the records stay in memory and
        the run goes on, since a trace must never stop a robot half-way."""

    def write(self, record: Record) -> None:
        if self._stream is not None:
            self._guarded(self._stream.write, json.dumps(record) + "\n")
        if self._stream is not None and not self._owned:
            self._guarded(self._stream.flush)

    def close(self) -> None:
        if self._stream is not None and self._owned:
            self._guarded(self._stream.close)
        self._stream = None

    def _guarded(self, action: Callable[..., Any], *args: Any) -> None:
        try:
            action(*args)
        except OSError as error:
            self.failure = self.failure or error
            stream, self._stream = self._stream, None
            if self._owned and stream is not None:
                with contextlib.suppress(OSError):
                    stream.close()
