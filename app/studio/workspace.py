"""The models the studio shows and edits: the statecharts below its folders, checked once per
change of the files on disk, drawn per chart, edited through :mod:`edits`.

The files stay the source of truth. Every page request first compares the files' sizes and
modification times with those of the last check; a change (an edit here, an editor, ``git``)
checks again, so what the page shows is always what is on disk. An edit names the version
(the hash of the file's text) it was made on and is refused when the file has changed since;
every write checks once more, right before it, that the file still holds what the edit was
made on. Edits are kept for undo and redo, which are refused in turn when a file has changed
since the edit.
"""

from __future__ import annotations

import hashlib
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.app.studio import edits
from lightrocks.app.studio.drawing import Drawings
from lightrocks.app.studio.findings import placed, places
from lightrocks.generators.selection import selected
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.languages.lightrocks.printer import format_statechart_text
from lightrocks.metamodel import ast, printer
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench.check import CheckContext, check
from lightrocks.workbench.diagnostics import Diagnostic
from lightrocks.workbench.files import write_atomic
from lightrocks.workbench.generators import GenerationRequest
from lightrocks.workbench.incremental import IncrementalCheck
from lightrocks.workbench.languages import extensions
from lightrocks.workbench.modelpath import model_files
from lightrocks.workbench.workspace import Loaded

USES = {"task": ("task", "skill"), "skill": ("skill", "action"), "action": (), "": ("",)}
"""Which layers a chart of each layer may import (a plain chart: plain charts)."""
HISTORY = 100
"""Edits kept for undo."""


class Conflict(Exception):
    """The file changed on disk since the page loaded it."""


@dataclass(frozen=True)
class FileChange:
    """One file's text before and after an edit; ``None``: the file is not there."""

    path: Path
    before: str | None
    after: str | None


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
        self.done: list[tuple[str, list[FileChange]]] = []
        """Edits that undo takes back, the last last: what each did and to which files."""
        self.undone: list[tuple[str, list[FileChange]]] = []

    def files(self) -> list[Path]:
        return sorted(
            {f.resolve() for folder in self.folders for f in model_files(folder, extensions())}
        )

    def fingerprint(self) -> tuple:
        """The model files with their modification times and sizes."""
        return tuple((str(f), *_stamp(f)) for f in self.files())

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
            raise KeyError(f"no statechart '{chart}' below the studio's folders")
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
        palette = [
            {
                "name": name,
                "layer": c.layer or "",
                "parameters": parameters(c),
                "outcomes": list(c.region.outcomes),
            }
            for name, c in sorted(snapshot.components.items())
            if (c.layer or "") in USES.get(layer, ()) and name != chart
        ]
        return {
            "chart": chart,
            "file": self.shown(file),
            "layer": layer,
            "version": version(file.read_text(encoding="utf-8")),
            "stamp": stamp(snapshot.fingerprint),
            "findings": placed(snapshot.findings, file, marks),
            "palette": palette,
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
        return {
            "undo": self.done[-1][0] if self.done else "",
            "redo": self.undone[-1][0] if self.undone else "",
        }

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

    def changed(
        self, chart: str, seen: str, level: str, request: dict[str, Any]
    ) -> tuple[Path, str, str]:
        """The chart's file, its text and its text after the edit, made on version ``seen``
        of it at the level ``level``; nothing is written."""
        component = self.component(chart)
        file = component.loaded.path
        text = file.read_text(encoding="utf-8")
        if version(text) != seen:
            raise Conflict(f"{file.name} changed on disk since the page loaded it")
        if level != chart and not level.startswith(chart + "/"):
            raise edits.EditError(f"level '{level}' is not one of {chart}")
        place = level[len(chart) + 1 :].split("/") if level != chart else []
        return file, text, edits.edited(text, str(file), operation(place, request, component))

    def edit(self, chart: str, seen: str, level: str, request: dict[str, Any]) -> str:
        """Apply one edit to the chart's file, made on version ``seen`` of it, at the level
        ``level``; the new version."""
        with self._lock:
            if request.get("op") == "rename":
                return self.rename(chart, seen, level, str(request["element"]), request["to"])
            file, text, new = self.changed(chart, seen, level, request)
            self._commit(describe(request), [FileChange(file, text, new)])
            return version(new)

    def preview(self, chart: str, seen: str, level: str, request: dict[str, Any]) -> dict:
        """What an edit would do, checked by the language's own check with the edited text
        in place of the file: the findings of the file afterwards, those the edit brings
        marked ``new``. Nothing is written."""
        file, text, new = self.changed(chart, seen, level, request)
        before = {(f["code"], f["message"]) for f in self.state(chart)["findings"]}
        context = check([file], self.folders, {file: new}, True)
        unit = edits.parse_statechart(new, str(file))
        found = placed(context.diagnostics.items, file, places(chart, unit))
        for finding in found:
            finding["new"] = (finding["code"], finding["message"]) not in before
        return {"findings": found, "unchanged": new == text}

    def rename(self, chart: str, seen: str, level: str, element: str, to: Any) -> str:
        """Rename a state, condition or the chart (``element`` '') with the language
        server's rename: every file that names it changes; each file is printed again."""
        from lightrocks.app.studio.rename import renamed

        component = self.component(chart)
        file = component.loaded.path
        if version(file.read_text(encoding="utf-8")) != seen:
            raise Conflict(f"{file.name} changed on disk since the page loaded it")
        if not isinstance(to, str):
            raise edits.EditError("the new name is missing")
        context = check(self.folders, self.folders)  # the index needs every file
        changes = renamed(context, component, level, element, to)
        self._commit(f"rename {element or chart} to {to}", changes)
        return version(next((c.after for c in changes if c.after and c.path == file), "")) or ""

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
            folder.mkdir(parents=True, exist_ok=True)
            self._commit(f"new chart {qualified}", [FileChange(path, None, text)])
            return qualified

    def undo(self) -> str:
        """Take the last edit back; what was undone."""
        return self._turn(self.done, self.undone, lambda c: FileChange(c.path, c.after, c.before))

    def redo(self) -> str:
        return self._turn(self.undone, self.done, lambda c: c)

    def _turn(self, source: list, target: list, way: Callable[[FileChange], FileChange]) -> str:
        with self._lock:
            if not source:
                raise edits.EditError("nothing to " + ("undo" if source is self.done else "redo"))
            what, changes = source[-1]
            self._write([way(c) for c in changes])
            target.append(source.pop())
            return what

    def _commit(self, what: str, changes: list[FileChange]) -> None:
        self._write(changes)
        self.done = [*self.done, (what, changes)][-HISTORY:]
        self.undone = []

    def _write(self, changes: list[FileChange]) -> None:
        """Write every file of an edit, or none: each must still hold what the edit was made
        on."""
        for change in changes:
            if _text_of(change.path) != change.before:
                name = self.shown(change.path)
                raise Conflict(f"{name} changed on disk since; nothing was written")
        for change in changes:
            if change.after is None:
                change.path.unlink()
            else:
                write_atomic(change.path, change.after)


def operation(place: list[str], request: dict[str, Any], component: Component) -> Callable:
    """The change of the chart a page's edit request asks for."""
    kind = request.get("op")

    def inside(element: Any) -> tuple[list[str], str]:
        """``Arm/Snap`` on an orthogonal state's level: region ``Arm``, state ``Snap``."""
        *regions, name = text(element, "element").split("/")
        return place + regions, name

    def text(value: Any, what: str) -> str:
        if not isinstance(value, str):
            raise edits.EditError(f"{what} must be a text")
        return value

    if kind == "add-state":
        where, name = inside(request["name"])
        imported = text(request["imports"], "imports")
        if not edits.TYPE.match(imported):
            raise edits.EditError(f"imports '{imported}' is not a qualified chart name")

        def add(unit: ast.StatechartUnit) -> ast.StatechartUnit:
            unit, simple = edits.with_import(unit, imported)
            return edits.at(where, edits.add_state(name, simple))(unit)

        return add
    if kind == "add-transition":
        where, source = inside(request["source"])
        there, target = inside(request["target"])
        if where != there:
            raise edits.EditError("a transition joins two states of one region")
        fields = (text(request.get(f, ""), f) for f in ("stimulus", "guard", "action"))
        return edits.at(where, edits.add_transition(source, target, *fields))
    if kind == "set-transition":
        where, source = inside(request["source"])
        _, target = inside(request["target"])
        number = request.get("number", 0)
        if not isinstance(number, int) or isinstance(number, bool):
            raise edits.EditError("number must be a whole number")
        fields = (text(request.get(f, ""), f) for f in ("stimulus", "guard", "action"))
        return edits.at(where, edits.set_transition(source, target, number, *fields))
    if kind == "set-arguments":
        where, name = inside(request["state"])
        values = request["arguments"]
        if not isinstance(values, list) or not all(
            isinstance(v, list) and len(v) == 2 and all(isinstance(x, str) for x in v)
            for v in values
        ):
            raise edits.EditError("arguments must be a list of [parameter, value] texts")
        return edits.at(where, edits.set_arguments(name, [tuple(v) for v in values]))
    if kind == "set-parameters":
        if place:
            raise edits.EditError("parameters belong to the chart's own level")
        rows = request["parameters"]
        if not isinstance(rows, list) or not all(
            isinstance(r, list) and len(r) == 3 and all(isinstance(x, str) for x in r) for r in rows
        ):
            raise edits.EditError("parameters must be a list of [type, name, default] texts")
        return edits.at([], edits.set_parameters([tuple(r) for r in rows]))
    if kind == "add-condition":
        where, name = inside(request["name"])
        condition = text(request.get("expression", ""), "expression")
        return edits.at(where, edits.add_condition(text(request["kind"], "kind"), name, condition))
    if kind == "set-condition":
        where, name = inside(request["name"])
        condition = text(request.get("expression", ""), "expression")
        return edits.at(where, edits.set_condition(name, condition))
    if kind == "delete":
        element = text(request["element"], "element")
        if "->" in element:
            source, _, target = element.partition("->")
            where, source = inside(source)
            _, target = inside(target)
            return edits.at(where, edits.delete_transitions(source, target))
        where, name = inside(element)
        return edits.at(where, edits.delete_state(name))
    if kind == "move":
        where, name = inside(request["state"])
        steps = request["steps"]
        if not isinstance(steps, int) or isinstance(steps, bool):
            raise edits.EditError("steps must be a whole number")
        return edits.at(where, edits.move_in_chain(name, steps))
    raise edits.EditError(f"no edit '{kind}'")


def describe(request: dict[str, Any]) -> str:
    """An edit as undo and redo name it."""
    kind = request.get("op", "")
    subject = next((request[k] for k in ("name", "state", "element", "source") if k in request), "")
    if kind == "add-transition" or kind == "set-transition":
        subject = f"{request.get('source')} -> {request.get('target')}"
    return f"{kind} {subject}".strip()


def parameters(component: Component, inherited: bool = True) -> list[list[str]]:
    """``[type, name, default text]`` of each parameter of the chart (its own only unless
    ``inherited``)."""
    if inherited:
        found = list(component.region.parameters.values())
    else:
        blocks = [e for e in component.statechart.elements if isinstance(e, ast.ParameterBlock)]
        found = [p for block in blocks for p in block.parameters]
    return [
        [p.type, p.name, printer.expression(p.default) if p.default is not None else ""]
        for p in found
    ]


def levels(component: Component) -> dict[str, dict[str, Any]]:
    """Level key -> what its forms show: each box (a state with the chart it imports and its
    arguments, a condition with its expression) and each arrow with its transitions."""
    found: dict[str, dict[str, Any]] = {}

    def visit(region: Region, key: str, prefix: str) -> None:
        level = found.setdefault(key, {"boxes": {}, "arrows": {}})
        for name, condition in region.conditions.items():
            level["boxes"][prefix + name] = {
                "kind": f"{condition.kind} condition",
                "expression": _text(condition.expression),
            }
        for name, pseudostate in region.pseudostates.items():
            level["boxes"][prefix + name] = {"kind": pseudostate.kind}
        for transition in region.transitions:
            arrow = f"{prefix}{transition.source}->{prefix}{transition.target}"
            level["arrows"].setdefault(arrow, []).append(
                {
                    "stimulus": transition.stimulus,
                    "guard": _text(transition.guard),
                    "action": _statements(transition.action),
                }
            )
        for name, info in region.states.items():
            if region.orthogonal and info.region is not None:
                visit(info.region, key, f"{prefix}{name}/")
                continue
            box: dict[str, Any] = {"kind": "state", "outcomes": list(info.outcomes or ())}
            if info.imported is not None:
                box["imports"] = info.imported.qualified_name
                box["parameters"] = parameters(info.imported)
                box["arguments"] = [
                    [a.name, printer.expression(a.value)] for a in info.state.arguments
                ]
            level["boxes"][prefix + name] = box
            if info.imported is None and info.region is not None:
                visit(info.region, f"{key}/{prefix}{name}", "")

    visit(component.region, component.qualified_name, "")
    return found


def _text(node: ast.Expression | None) -> str:
    return printer.expression(node) if node is not None else ""


def _statements(statements: tuple[ast.Statement, ...] | None) -> str:
    return "\n".join(line for s in statements or () for line in printer.statement(s))


def outcomes(component: Component) -> dict[str, dict[str, list[str]]]:
    """Level key -> box -> the outcomes it can end with (a transition's stimuli from it)."""
    return {
        key: {
            name: box.get("outcomes", [])
            for name, box in level["boxes"].items()
            if box["kind"] == "state"
        }
        for key, level in levels(component).items()
    }


def canonical(path: Path, text: str) -> str:
    """``text`` printed canonically when it is a statechart's (comments kept)."""
    if path.suffix != ".lr":
        return text
    try:
        return format_statechart_text(text, str(path))
    except SyntaxProblem as problem:
        raise edits.EditError(f"{path.name} does not parse after the edit: {problem}") from None


def version(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def stamp(fingerprint: tuple) -> str:
    """A short name of the files' state on disk, the same for the same state."""
    return hashlib.sha256(repr(fingerprint).encode()).hexdigest()[:16]


def _text_of(path: Path) -> str | None:
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return None


def _stamp(file: Path) -> tuple[int, int]:
    try:
        status = file.stat()
    except OSError:
        return (0, 0)
    return (status.st_mtime_ns, status.st_size)
