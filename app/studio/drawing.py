"""A chart's diagram for the studio, drawn level by level with the ``dot`` target's own
functions (``all_levels``, ``draw``, the level template: what ``generate --target dot
--option levels=yes`` writes), keeping each level's picture while the level stays the same.

After an edit only the levels it changed are drawn again: a task's diagram shows every
level of the skills and actions it imports, which an edit of the task leaves alone.
"""

from __future__ import annotations

import os
import threading
from concurrent.futures import ThreadPoolExecutor

from lightrocks.app.diagram import Diagram
from lightrocks.generators.graphviz.drawing import Drawing, draw, level_template
from lightrocks.generators.graphviz.levels import Level, all_levels
from lightrocks.generators.outputs import shortened
from lightrocks.languages.lightrocks.model import Component

KEPT = 2000
"""Pictures kept; the oldest go first."""


class Drawings:
    def __init__(self) -> None:
        self._template = level_template()
        self._pictures: dict[str, Drawing] = {}
        self._lock = threading.Lock()

    def bundle(self, component: Component) -> str:
        """The diagram of the chart, every level of it and of what it imports, as one SVG
        document (see :mod:`app.diagram`)."""
        levels = all_levels(component)
        keys = {key: repr(level) for key, level in levels.items()}  # a level's whole content
        with self._lock:
            missing = {k: levels[k] for k, same in keys.items() if same not in self._pictures}
        with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
            drawn = dict(zip(missing, pool.map(self._draw, missing.values()), strict=True))
        with self._lock:
            for key, drawing in drawn.items():
                self._pictures[keys[key]] = drawing
            pictures = {key: self._pictures[same] for key, same in keys.items()}
            while len(self._pictures) > KEPT:
                del self._pictures[next(iter(self._pictures))]
        index = []
        for key, level in levels.items():
            name = "/".join(shortened(part) for part in key.split("/"))
            entry = {"key": key, "title": level.title, "layer": level.layer}
            entry.update(file=f"{name}.svg", layout=pictures[key].how, drills=level.drills)
            index.append(entry)
        texts = {}
        for key, drawing in pictures.items():
            text = drawing.svg.decode("utf-8")
            texts[key] = text[text.index("<svg") :]
        return Diagram(component.qualified_name, index, texts).bundle()

    def _draw(self, level: Level) -> Drawing:
        return draw(level, self._template)
