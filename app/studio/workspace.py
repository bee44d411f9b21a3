"""The models the studio shows and edits: the statecharts below its folders, checked once per
change of the files on disk, drawn per chart, edited through :mod:`edits`.

The files stay the source of truth. Every page request first compares the files' sizes and
modification times with those of the last check; a change (an edit here, an editor, ``git``)
checks again, so what the page shows is always what is on disk. An edit names the version
(the hash of the file's text) it was made on and is refused when the file has changed since.
"""

from __future__ import annotations

import hashlib
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.app.diagram import of_files
from lightrocks.app.studio import edits
from lightrocks.app.studio.findings import placed, places
from lightrocks.generators.selection import selected
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.metamodel import ast
from lightrocks.workbench.check import CheckContext, check
from lightrocks.workbench.files import write_atomic
from lightrocks.workbench.generators import GenerationRequest, load_generator, run_generator
from lightrocks.workbench.languages import extensions
from lightrocks.workbench.modelpath import model_files

USES = {"task": ("task", "skill"), "skill": ("skill", "action"), "action": (), "": ("",)}
"""Which layers a chart of each layer may import (a plain chart: plain charts)."""


class Conflict(Exception):
    """The file changed on disk since the page loaded it."""


@dataclass
class Snapshot:
    fingerprint: tuple
    context: CheckContext
    components: dict[str, Component]
    bundles: dict[str, str] = field(default_factory=dict)
    """Chart -> its diagram, drawn when first asked for."""


class Studio:
    def __init__(self, folders: list[Path]) -> None:
        self.folders = [f.resolve() for f in folders]
        self._snapshot: Snapshot | None = None
        self._lock = threading.Lock()

    def files(self) -> list[Path]:
        return sorted(
            {f.resolve() for folder in self.folders for f in model_files(folder, extensions())}
        )

    def snapshot(self) -> Snapshot:
        """The checked models as they are on disk now."""
        with self._lock:
            files = self.files()
            fingerprint = tuple((str(f), *_stamp(f)) for f in files)
            if self._snapshot is None or self._snapshot.fingerprint != fingerprint:
                context = check(self.folders, self.folders)
                request = GenerationRequest(context, [f for f in files if f.suffix == ".lr"])
                components = {c.qualified_name: c for c in selected(request)}
                self._snapshot = Snapshot(fingerprint, context, components)
            return self._snapshot

    def charts(self) -> list[dict[str, str]]:
        return [
            {"name": name, "layer": c.layer or "", "file": str(c.loaded.path)}
            for name, c in sorted(self.snapshot().components.items())
        ]

    def component(self, chart: str) -> Component:
        found = self.snapshot().components.get(chart)
        if found is None:
            raise KeyError(f"no statechart '{chart}' below the studio's folders")
        return found

    def diagram(self, chart: str) -> str:
        """The chart's diagram as one SVG document (see :mod:`app.diagram`)."""
        snapshot = self.snapshot()
        if chart not in snapshot.bundles:
            component = self.component(chart)
            request = GenerationRequest(
                snapshot.context, [component.loaded.path], {"levels": "yes"}
            )
            files = run_generator(load_generator("dot"), request)
            snapshot.bundles[chart] = of_files(files, chart).bundle()
        return snapshot.bundles[chart]

    def state(self, chart: str) -> dict[str, Any]:
        """What the page needs besides the picture: the file's version, the findings placed
        on the diagram, the palette of charts to import, the outcomes of each box."""
        snapshot = self.snapshot()
        component = self.component(chart)
        file = component.loaded.path
        marks = places(chart, component.unit)
        layer = component.layer or ""
        palette = [
            {"name": name, "layer": c.layer or ""}
            for name, c in sorted(snapshot.components.items())
            if (c.layer or "") in USES.get(layer, ()) and name != chart
        ]
        return {
            "chart": chart,
            "file": self.shown(file),
            "layer": layer,
            "version": version(file.read_text(encoding="utf-8")),
            "findings": placed(snapshot.context.diagnostics.items, file, marks),
            "palette": palette,
            "outcomes": outcomes(component),
        }

    def shown(self, file: Path) -> str:
        """``file`` as below the folder the studio was given that holds it."""
        folder = next((f for f in self.folders if file.is_relative_to(f)), None)
        return str(file.relative_to(folder.parent) if folder else file)

    def edit(self, chart: str, seen: str, level: str, request: dict[str, Any]) -> str:
        """Apply one edit to the chart's file, made on version ``seen`` of it, at the level
        ``level``; the new version."""
        component = self.component(chart)
        file = component.loaded.path
        with self._lock:
            text = file.read_text(encoding="utf-8")
            if version(text) != seen:
                raise Conflict(f"{file.name} changed on disk since the page loaded it")
            place = level[len(chart) + 1 :].split("/") if level != chart else []
            if level != chart and not level.startswith(chart + "/"):
                raise edits.EditError(f"level '{level}' is not one of {chart}")
            new = edits.edited(text, str(file), operation(place, request))
            write_atomic(file, new)
            return version(new)


def operation(place: list[str], request: dict[str, Any]) -> Callable:
    """The change of the chart a page's edit request asks for."""
    kind = request.get("op")

    def inside(element: str) -> tuple[list[str], str]:
        """``Arm/Snap`` on an orthogonal state's level: region ``Arm``, state ``Snap``."""
        *regions, name = element.split("/")
        return place + regions, name

    if kind == "add-state":
        where, name = inside(request["name"])

        def add(unit: ast.StatechartUnit) -> ast.StatechartUnit:
            unit, imported = edits.with_import(unit, request["imports"])
            return edits.at(where, edits.add_state(name, imported))(unit)

        return add
    if kind == "add-transition":
        where, source = inside(request["source"])
        there, target = inside(request["target"])
        if where != there:
            raise edits.EditError("a transition joins two states of one region")
        return edits.at(where, edits.add_transition(source, target, request.get("stimulus", "")))
    if kind == "delete":
        element = request["element"]
        if "->" in element:
            source, _, target = element.partition("->")
            where, source = inside(source)
            _, target = inside(target)
            return edits.at(where, edits.delete_transitions(source, target))
        where, name = inside(element)
        return edits.at(where, edits.delete_state(name))
    if kind == "move":
        where, name = inside(request["state"])
        return edits.at(where, edits.move_in_chain(name, int(request["steps"])))
    raise edits.EditError(f"no edit '{kind}'")


def outcomes(component: Component) -> dict[str, dict[str, list[str]]]:
    """Level key -> box -> the outcomes it can end with (a transition's stimuli from it)."""
    found: dict[str, dict[str, list[str]]] = {}

    def visit(region: Region, key: str, prefix: str) -> None:
        boxes = found.setdefault(key, {})
        for name, info in region.states.items():
            if region.orthogonal and info.region is not None:
                visit(info.region, key, f"{prefix}{name}/")
                continue
            boxes[prefix + name] = list(info.outcomes or ())
            if info.imported is None and info.region is not None:
                visit(info.region, f"{key}/{prefix}{name}", "")

    visit(component.region, component.qualified_name, "")
    return found


def version(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def _stamp(file: Path) -> tuple[int, int]:
    try:
        status = file.stat()
    except OSError:
        return (0, 0)
    return (status.st_mtime_ns, status.st_size)
