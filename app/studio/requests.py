"""The studio's requests besides the edits (:mod:`.operations`), one typed schema each,
checked once on arrival (:func:`lightrocks.app.web.schema.parsed`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal


@dataclass(frozen=True)
class Chart:
    """``?chart=NAME``: the chart a diagram or state is asked of."""

    chart: str


@dataclass(frozen=True)
class Target:
    """Where an edit, a preview or a rename applies: the chart, the version of its file the
    page shows (the edit is refused when the file changed since) and the level in view."""

    chart: str
    version: str
    level: str


@dataclass(frozen=True)
class Rename:
    """A state or condition of the level (``element``; '' the chart itself) renamed ``to``,
    in every file that names it."""

    element: str
    to: str


@dataclass(frozen=True)
class NewChart:
    """A new, empty chart; no package, no layer and no cell are '' each."""

    name: str
    package: str = ""
    layer: str = ""
    cell: str = ""


@dataclass(frozen=True)
class HistoryStep:
    """``history/undo`` or ``history/redo``."""

    way: Literal["undo", "redo"]


@dataclass(frozen=True)
class StartRun:
    """A run of the chart ('' the default adapter, no outcome script, the cell's robot)."""

    chart: str
    adapter: str = ""
    script: str = ""
    robot: str = ""
    paused: bool = False
