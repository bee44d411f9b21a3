"""The run's records for the page: appended by the run thread without ever waiting, read
by the server thread; the oldest are dropped when nobody reads."""

from __future__ import annotations

import itertools
from collections import deque
from typing import Any

CAPACITY = 20_000


class Feed:
    def __init__(self) -> None:
        self._records: deque[tuple[int, dict[str, Any]]] = deque(maxlen=CAPACITY)
        self._numbers = itertools.count(1)
        self.last = 0
        """The number of the newest record."""
        self._history: list[tuple[int, dict[str, Any]]] = []
        """Every state-level record (no samples), so a late page can rebuild the view."""

    def publish(self, record: dict[str, Any]) -> None:
        number = next(self._numbers)
        self._records.append((number, record))
        if record["kind"] != "sample":
            self._history.append((number, record))
        self.last = number

    def history(self) -> tuple[int, list[dict[str, Any]]]:
        """The state-level records so far and the number of the last one, to go on from
        with ``since`` without missing or repeating a record."""
        copied = self._history.copy()
        return (copied[-1][0] if copied else 0), [r for _, r in copied]

    def since(self, number: int) -> tuple[int, list[dict[str, Any]]]:
        """Records after ``number`` and the number of the last one."""
        fresh = [(n, r) for n, r in list(self._records) if n > number]
        return (fresh[-1][0] if fresh else number), [r for _, r in fresh]
