"""The studio's session: the statecharts below its folders, checked once per change of the
files on disk, drawn per chart, edited through :mod:`.operations` and :mod:`.rename`, with
their edits kept for undo (:mod:`.history`).

The files stay the source of truth. Every page request first compares the files' sizes and
modification times with those of the last check; a change (an edit here, an editor, ``git``)
checks again, so what the page shows is always what is on disk. An edit names the version
(the hash of the file's text) it was made on and is refused when the file has changed since.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.app.studio import edits
from lightrocks.app.studio.drawing import Drawings
from lightrocks.app.studio.findings import placed, places
from lightrocks.app.studio.history import Conflict, FileChange, History, Unwritten
from lightrocks.app.studio.operations import Operation
from lightrocks.app.studio.texts import file_stamp, stamp, version
from lightrocks.app.studio.views import levels, outcomes, palette, parameters
from lightrocks.generators.selection import selected
from lightrocks.languages.lightrocks.model import Component
from lightrocks.metamodel import ast
from lightrocks.workbench.check import CheckContext, check
from lightrocks.workbench.diagnostics import Diagnostic
from lightrocks.workbench.generators import GenerationRequest
from lightrocks.workbench.incremental import IncrementalCheck
from lightrocks.workbench.languages import extensions
from lightrocks.workbench.modelpath import model_files
from lightrocks.workbench.workspace import Loaded


class NoSuchChart(LookupError):
    """A chart the page names that is not below the studio's folders."""


@dataclass
class Snapshot:
    fingerprint: tuple
    findings: list[Diagnostic]
    """Of every file below the folders."""
    components: dict[str, Component]
    contexts: dict[str, CheckContext]
    """Chart -> the check it was last checked in (what its diagram is generated from)."""
    loaded: list[Loaded]
    """The latest load of every file."""
    bundles: dict[str, str] = field(default_factory=dict)
    """Chart -> its diagram, drawn when first asked for."""


class Studio:
    def __init__(self, folders: list[Path]) -> None:
        self.folders = [f.resolve() for f in folders]
        self._snapshot: Snapshot | None = None
        self._checker: IncrementalCheck | None = None
        self._drawings = Drawings()
        self._lock = threading.RLock()
        self.edits = History(self.shown)

    def files(self) -> list[Path]:
        return sorted(
            {f.resolve() for folder in self.folders for f in model_files(folder, extensions())}
        )

    def fingerprint(self) -> tuple:
        """The model files with their modification times and sizes."""
        return tuple((str(f), *file_stamp(f)) for f in self.files())

    def snapshot(self) -> Snapshot:
        """The checked models as they are on disk now: after a change of files, only the
        files it can affect are checked again (the language server's incremental check),
        and only the diagrams of charts among them are drawn again."""
        with self._lock:
            fingerprint = self.fingerprint()
            old = self._snapshot
            if old is not None and old.fingerprint == fingerprint:
                return old
            before = {f[0]: f[1:] for f in old.fingerprint} if old else {}
            now = {f[0]: f[1:] for f in fingerprint}
            if old is None or self._checker is None or set(before) != set(now):
                self._checker = IncrementalCheck(self.folders, self.folders)
                self._checker.full()
                files = [Path(f) for f in now]
                kept_components, kept_contexts, bundles = {}, {}, {}
            else:
                changed = {Path(f) for f in now if before[f] != now[f]}
                self._checker.update({f: None for f in changed})
                files = sorted(self._checker.rechecked)
                stale = {str(f) for f in files}
                kept = {n for n, c in old.components.items() if str(c.loaded.path) not in stale}
                kept_components = {n: old.components[n] for n in kept}
                kept_contexts = {n: old.contexts[n] for n in kept}
                bundles = {n: b for n, b in old.bundles.items() if n in kept}
            context = self._checker.context
            request = GenerationRequest(context, [f for f in files if f.suffix == ".lr"])
            fresh = {c.qualified_name: c for c in selected(request)}
            self._snapshot = Snapshot(
                fingerprint,
                self._checker.items,
                {**kept_components, **fresh},
                {**kept_contexts, **dict.fromkeys(fresh, context)},
                list(self._checker.loaded.values()),
                bundles,
            )
            return self._snapshot

    def charts(self) -> list[dict[str, str]]:
        return [
            {"name": name, "layer": c.layer or "", "file": str(c.loaded.path)}
            for name, c in sorted(self.snapshot().components.items())
        ]

    def component(self, chart: str) -> Component:
        found = self.snapshot().components.get(chart)
        if found is None:
            raise NoSuchChart(f"no statechart '{chart}' below the studio's folders")
        return found

    def diagram(self, chart: str) -> str:
        """The chart's diagram as one SVG document (see :mod:`app.diagram`)."""
        snapshot = self.snapshot()
        if chart not in snapshot.bundles:
            snapshot.bundles[chart] = self._drawings.bundle(self.component(chart))
        return snapshot.bundles[chart]

    def state(self, chart: str) -> dict[str, Any]:
        """What the page needs besides the picture: the file's version, the findings placed
        on the diagram, the palette of charts to import with their parameters and outcomes,
        and what the forms show of each level."""
        snapshot = self.snapshot()
        component = self.component(chart)
        file = component.loaded.path
        marks = places(chart, component.unit)
        layer = component.layer or ""
        return {
            "chart": chart,
            "file": self.shown(file),
            "layer": layer,
            "version": version(file.read_text(encoding="utf-8")),
            "stamp": stamp(snapshot.fingerprint),
            "findings": placed(snapshot.findings, file, marks),
            "palette": palette(chart, layer, snapshot.components),
            "outcomes": outcomes(component),
            "levels": levels(component),
            "parameters": parameters(component, inherited=False),
            "history": self.history(),
        }

    def shown(self, file: Path) -> str:
        """``file`` as below the folder the studio was given that holds it."""
        folder = next((f for f in self.folders if file.is_relative_to(f)), None)
        return str(file.relative_to(folder.parent) if folder else file)

    def history(self) -> dict[str, str]:
        """What undo and redo would do next ('' for nothing)."""
        return self.edits.next()

    def catalogue(self) -> dict[str, Any]:
        """What a new chart can be: the packages below the folders and the cells to import."""
        snapshot = self.snapshot()
        packages = {c.unit.package for c in snapshot.components.values()}
        cells = []
        for loaded in snapshot.loaded:
            for declaration in getattr(loaded.unit, "declarations", ()):
                if isinstance(declaration, ast.Cell):
                    cells.append(f"{loaded.unit.package}.{declaration.name}")
        return {"packages": sorted(packages), "cells": sorted(cells), "layers": edits.LAYERS}

    # -- edits --------------------------------------------------------------------------

    def changed(self, chart: str, seen: str, level: str, edit: Operation) -> tuple[Path, str, str]:
        """The chart's file, its text and its text after the edit, made on version ``seen``
        of it at the level ``level``; nothing is written."""
        component = self.component(chart)
        file = component.loaded.path
        text = self._seen(file, seen)
        if level != chart and not level.startswith(chart + "/"):
            raise edits.EditError(f"level '{level}' is not one of {chart}")
        place = level[len(chart) + 1 :].split("/") if level != chart else []
        return file, text, edits.edited(text, str(file), edit.change(place))

    def edit(self, chart: str, seen: str, level: str, edit: Operation) -> str:
        """Apply one edit to the chart's file, made on version ``seen`` of it, at the level
        ``level``; the new version."""
        with self._lock:
            file, text, new = self.changed(chart, seen, level, edit)
            self.edits.commit(edit.label, [FileChange(file, text, new)])
            return version(new)

    def preview(self, chart: str, seen: str, level: str, edit: Operation) -> dict:
        """What an edit would do, checked by the language's own check with the edited text
        in place of the file: the findings of the file afterwards, those the edit brings
        marked ``new``. Nothing is written."""
        file, text, new = self.changed(chart, seen, level, edit)
        before = {(f["code"], f["message"]) for f in self.state(chart)["findings"]}
        context = check([file], self.folders, {file: new}, True)
        unit = edits.parse_statechart(new, str(file))
        found = placed(context.diagnostics.items, file, places(chart, unit))
        for finding in found:
            finding["new"] = (finding["code"], finding["message"]) not in before
        return {"findings": found, "unchanged": new == text}

    def rename(self, chart: str, seen: str, level: str, element: str, to: str) -> str:
        """Rename a state, condition or the chart (``element`` '') with the language
        server's rename: every file that names it changes; each file is printed again. The
        new version of the chart's file."""
        from lightrocks.app.studio.rename import renamed  # the language server's, when needed

        with self._lock:
            component = self.component(chart)
            file = component.loaded.path
            self._seen(file, seen)
            context = check(self.folders, self.folders)  # the index needs every file
            changes = renamed(context, component, level, element, to)
            self.edits.commit(f"rename {element or chart} to {to}", changes)
            after = next((c.after for c in changes if c.after and c.path == file), "")
            return version(after) if after else ""

    def create(self, package: str, name: str, layer: str, cell: str = "") -> str:
        """A new chart with nothing in it, in ``package`` (in the folder of that package
        below the studio's folders, else below the first folder); its qualified name."""
        text = edits.new_chart(package, name, layer, [cell] if cell else [])
        with self._lock:
            folders = [f for f in self.folders if f.joinpath(*package.split(".")).is_dir()]
            folder = (folders or self.folders)[0].joinpath(*package.split(".") if package else ())
            path = folder / f"{name}.lr"
            qualified = f"{package}.{name}" if package else name
            if path.exists() or qualified in self.snapshot().components:
                raise edits.EditError(f"{qualified} is there already ({self.shown(path)})")
            try:
                folder.mkdir(parents=True, exist_ok=True)
            except OSError as error:
                raise Unwritten(f"cannot make {self.shown(folder)}: {error.strerror}") from None
            self.edits.commit(f"new chart {qualified}", [FileChange(path, None, text)])
            return qualified

    def undo(self) -> str:
        """Take the last edit back; what was undone."""
        with self._lock:
            return self.edits.undo()

    def redo(self) -> str:
        with self._lock:
            return self.edits.redo()

    def _seen(self, file: Path, seen: str) -> str:
        """The file's text, when it is still version ``seen`` of it."""
        text = file.read_text(encoding="utf-8")
        if version(text) != seen:
            raise Conflict(f"{file.name} changed on disk since the page loaded it")
        return text
