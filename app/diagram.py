"""The diagram of a model as pages show it: one picture per chart level, drilled into.

The pictures come from the one check → generate path (the ``dot`` target with
``levels=yes``), so the monitor, replay and the studio draw what ``generate`` writes. A page
gets them as one SVG document: the index of the levels (their keys, titles and which box
opens which level) as JSON in its ``<metadata>``, then one nested ``<svg class="level">``
per level, in the index's order.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from html import escape
from pathlib import Path
from typing import Any

from lightrocks.workbench.generators import GenerationError

LEVELS = "levels.json"


@dataclass(frozen=True)
class Diagram:
    root: str
    """The key of the top level: the statechart's qualified name."""
    levels: list[dict[str, Any]]
    """The index's entries (key, title, layer, layout, drills), in the index's order."""
    pictures: dict[str, str]
    """Level key -> its SVG element (no XML prolog)."""

    def bundle(self) -> str:
        """The whole diagram as one SVG document for a page."""
        index = json.dumps({"root": self.root, "levels": self.levels}, ensure_ascii=False)
        parts = [
            '<svg xmlns="http://www.w3.org/2000/svg" class="diagram">',
            f'<metadata id="levels">{escape(index, quote=False)}</metadata>',
        ]
        for entry in self.levels:
            picture = self.pictures[entry["key"]]
            parts.append(picture.replace("<svg ", '<svg class="level" ', 1))
        parts.append("</svg>\n")
        return "\n".join(parts)


def drawn(model: Path, search_path: Sequence[Path], name: str = "") -> Diagram:
    """The diagram of the statechart in ``model`` (the one named ``name`` when the model is
    a folder); a model with errors is a ``ModelError``."""
    from lightrocks.app import pipeline
    from lightrocks.app.specs import generate_spec

    spec = generate_spec([model], search_path, "dot", {"levels": "yes"})
    return of_files(pipeline.generate(spec), name)


def of_files(files: dict[str, str | bytes], name: str = "") -> Diagram:
    """The diagram among the generated files: of the chart whose simple or qualified name is
    ``name``, or of the only one."""
    indexes = {k: json.loads(_text(v)) for k, v in files.items() if k.endswith(f"/{LEVELS}")}
    chosen = [
        (k, i) for k, i in indexes.items() if not name or name in (i["root"], _simple(i["root"]))
    ]
    if not chosen:
        raise GenerationError(f"no diagram of a statechart '{name}' among the models")
    path, index = chosen[0]
    folder = path[: -len(LEVELS)]
    pictures = {}
    for entry in index["levels"]:
        text = _text(files[folder + entry["file"]])
        pictures[entry["key"]] = text[text.index("<svg") :]
    return Diagram(index["root"], index["levels"], pictures)


def _text(content: str | bytes) -> str:
    return content.decode("utf-8") if isinstance(content, bytes) else content


def _simple(qualified: str) -> str:
    return qualified.rpartition(".")[2]
