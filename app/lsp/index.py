"""Every declared and referenced name of the checked files, with its range and declaration.

Navigation, rename, hover, completion and semantic tokens all answer from this index. A
declaration is identified by the file and start of its name, so an occurrence in one file
points at a declaration in another without holding on to parse trees. Files are indexed
again whenever a check loads them; files that no longer parse keep their last index, so an
editor still completes and navigates while the user is typing.
"""

from __future__ import annotations

from collections import ChainMap
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

from lsprotocol import types as lsp

from lightrocks.app.lsp.spans import span
from lightrocks.app.lsp.text import Text, contains
from lightrocks.languages.domain.types import UNKNOWN, Type, describe
from lightrocks.languages.lightrocks.model import BUILTIN_OUTCOMES
from lightrocks.metamodel import ast, printer
from lightrocks.workbench.extensions import symbol_kind
from lightrocks.workbench.workspace import Loaded, Workspace, shown_name

Key = tuple[Path, int, int]  # the file and 0-based start of a declared name


@dataclass(frozen=True)
class Occurrence:
    path: Path
    range: lsp.Range
    name: str
    kind: str
    key: Key
    declaration: bool = False


@dataclass(frozen=True)
class Declared:
    """A declaration with what hover and completion need to describe it."""

    kind: str
    node: Any
    loaded: Loaded = field(compare=False)


@dataclass
class FileIndex:
    occurrences: list[Occurrence] = field(default_factory=list)
    names: dict[str, str] = field(default_factory=dict)  # visible name -> kind
    outcomes: dict[str, tuple[str, ...]] = field(default_factory=dict)  # state -> outcomes
    members: dict[str, dict[str, str]] = field(default_factory=dict)  # instance -> member kinds
    outline: dict[Key | None, list[Key]] = field(default_factory=dict)  # declarations by parent
    scopes: list[tuple[lsp.Range, frozenset[str]]] = field(default_factory=list)  # states seen
    expressions: list[tuple[lsp.Range, str]] = field(default_factory=list)  # typed expressions

    def expression_at(self, position: lsp.Position) -> tuple[lsp.Range, str] | None:
        """The innermost typed expression around a position, with its text and type."""
        around = [item for item in self.expressions if contains(item[0], position)]
        return min(around, key=lambda item: _length(item[0]), default=None)

    def states_at(self, position: lsp.Position) -> frozenset[str] | None:
        """The states visible at a position: those of the innermost region around it and of
        the regions enclosing that one; ``None`` outside every statechart body."""
        around = [(r, names) for r, names in self.scopes if contains(r, position)]
        if not around:
            return None
        return max(around, key=lambda item: (item[0].start.line, item[0].start.character))[1]


class Index:
    def __init__(self) -> None:
        self.files: dict[Path, FileIndex] = {}
        self.declared: dict[Key, Declared] = {}

    def update(
        self,
        workspace: Workspace,
        text_of: Callable[[Path], Text],
        inferred: Mapping[str, list[tuple[ast.Expression, Type]]] | None = None,
    ) -> None:
        """Index again the files the check reported on, and files loaded for the first time;
        ``inferred`` holds the types of the expressions of the checked files, by the file
        name positions show."""
        checked = workspace.checked_units()
        known = {loaded.path for loaded in checked} | set(self.files)
        units = checked + [u for u in workspace.loaded_units() if u.path not in known]
        paths = {loaded.path for loaded in units}
        self.declared = {k: d for k, d in self.declared.items() if k[0] not in paths}
        for loaded in units:
            builder = _Builder(workspace, loaded, text_of)
            file = self.files[loaded.path] = builder.build()
            self.declared.update(builder.declared)
            typed = (inferred or {}).get(shown_name(loaded.path), ())
            file.expressions = _typed_expressions(text_of(loaded.path), typed)

    def at(self, path: Path, position: lsp.Position) -> Occurrence | None:
        file = self.files.get(path.resolve())
        if file is None:
            return None
        return next((o for o in file.occurrences if contains(o.range, position)), None)

    def references(self, key: Key) -> list[Occurrence]:
        return [o for file in self.files.values() for o in file.occurrences if o.key == key]


class _Builder:
    """Walks one parsed file, resolving its references through the workspace."""

    def __init__(
        self, workspace: Workspace, loaded: Loaded, text_of: Callable[[Path], Text]
    ) -> None:
        self.workspace = workspace
        self.loaded = loaded
        self.text_of = text_of
        self.index = FileIndex()
        self.declared: dict[Key, Declared] = {}
        self.members: dict[str, dict[str, tuple[Key, str, Any, Loaded]]] = {}
        self.parent: Key | None = None  # the declaration enclosing the ones declared now

    # -- keys -----------------------------------------------------------------------------

    def key(self, loaded: Loaded, node: Any, name: str) -> tuple[Key, lsp.Range]:
        found = self.text_of(loaded.path).name_in(node.position, name, True)
        return (loaded.path, found.start.line, found.start.character), found

    def declare(self, node: Any, kind: str, name: str | None = None) -> Key:
        name = name or node.name
        key, found = self.key(self.loaded, node, name)
        self.index.occurrences.append(Occurrence(self.loaded.path, found, name, kind, key, True))
        self.declared[key] = Declared(kind, node, self.loaded)
        self.index.outline.setdefault(self.parent, []).append(key)
        return key

    def inside(self, parent: Key, walk: Callable[[], None]) -> None:
        """Run ``walk`` with its declarations nested below ``parent`` in the outline."""
        outer, self.parent = self.parent, parent
        walk()
        self.parent = outer

    def refer(self, position: ast.Position, name: str, kind: str, key: Key | None) -> None:
        if key is None or position.line <= 0:
            return
        found = self.text_of(self.loaded.path).name_in(position, name)
        last = name.rpartition(".")[2]
        self.index.occurrences.append(Occurrence(self.loaded.path, found, last, kind, key))

    def symbol_key(self, name: str) -> tuple[Key, str, Any, Loaded] | None:
        """A name resolved through the file's scope to its declaration."""
        symbol = self.workspace.resolve(self.loaded, name)
        if symbol is None or not hasattr(symbol.node, "position"):
            return None
        node = symbol.node
        kind = _KINDS.get(type(node), "type")
        return self.key(symbol.loaded, node, symbol.name)[0], kind, node, symbol.loaded

    def refer_symbol(self, position: ast.Position, name: str) -> tuple[Any, Loaded] | None:
        found = self.symbol_key(name) if name else None
        if found is None:
            return None
        key, kind, node, loaded = found
        self.refer(position, name, kind, key)
        return node, loaded

    # -- files ----------------------------------------------------------------------------

    def build(self) -> FileIndex:
        unit = self.loaded.unit
        for imported in unit.imports:
            if not imported.wildcard:
                self.refer_symbol(imported.position, imported.name)
        for name, symbol in self.workspace.scope(self.loaded).items():
            self.index.names.setdefault(name, _KINDS.get(type(symbol.node), "type"))
        if isinstance(unit, ast.StatechartUnit):
            self.statechart(unit.statechart)
        else:
            for declaration in unit.declarations:
                self.domain(declaration)
        self.index.occurrences.sort(key=lambda o: (o.range.start.line, o.range.start.character))
        return self.index

    def statechart(self, chart: ast.Statechart) -> None:
        key = self.declare(chart, "statechart")
        inherited: dict[str, tuple[Key, str]] = {}
        base = self.stereotype_target(chart.stereotypes, "extends")
        if base is not None and isinstance(base[0], ast.Statechart):
            inherited = self.foreign_scope(base[1], base[0].elements)
        values: ChainMap[str, tuple[Key, str]] = ChainMap(self.cell_scope())
        walk = partial(self.region, chart.elements, ChainMap(inherited), values, chart.position)
        self.inside(key, walk)

    def stereotype_target(
        self, stereotypes: Iterable[ast.Stereotype], *names: str
    ) -> tuple[Any, Loaded] | None:
        target = None
        for stereotype in stereotypes:
            if stereotype.name in names and stereotype.value:
                target = self.refer_symbol(stereotype.position, stereotype.value) or target
        return target

    def foreign_scope(self, loaded: Loaded, elements: Iterable[Any]) -> dict[str, tuple[Key, str]]:
        """Top-level names of another chart, keyed where that chart declares them."""
        scope = {}
        for element, kind in _declarations(elements):
            scope[element.name] = (self.key(loaded, element, element.name)[0], kind)
        return scope

    def cell_scope(self) -> dict[str, tuple[Key, str]]:
        """Device instances and scene objects of the cells in scope, with their members."""
        scope = {}
        for symbol in self.workspace.scope(self.loaded).values():
            if not isinstance(symbol.node, ast.Cell):
                continue
            for member in symbol.node.members:
                kind = "instance" if isinstance(member, ast.DeviceInstance) else "object"
                scope[member.name] = (self.key(symbol.loaded, member, member.name)[0], kind)
                self.index.names[member.name] = kind
                if isinstance(member, ast.DeviceInstance):
                    found = self.device_members(symbol.loaded, member.type)
                    self.members[member.name] = found
                    self.index.members[member.name] = {n: m[1] for n, m in found.items()}
        return scope

    def device_members(
        self, loaded: Loaded, type_name: str
    ) -> dict[str, tuple[Key, str, Any, Loaded]]:
        symbol = self.workspace.resolve(loaded, type_name)
        if symbol is None or not isinstance(symbol.node, ast.Device):
            return {}
        found = {}
        for member in symbol.node.members:
            kind = "command" if isinstance(member, ast.Command) else "sensor"
            key = self.key(symbol.loaded, member, member.name)[0]
            found[member.name] = (key, kind, member, symbol.loaded)
        return found

    def region(
        self,
        elements: Iterable[Any],
        states: ChainMap[str, tuple[Key, str]],
        values: ChainMap[str, tuple[Key, str]],
        owner: ast.Position,
    ) -> None:
        """Index one region: the body of ``owner`` (a statechart, a composite state or an
        orthogonal region), whose states hide those of sibling regions."""
        elements = list(_flatten(elements))
        states, values = states.new_child(), values.new_child()
        imported: dict[str, tuple[Any, Loaded]] = {}
        keys: dict[int, Key] = {}
        for element, kind in _declarations(elements):
            key = keys[id(element)] = self.declare(element, kind)
            (values if kind == "parameter" else states)[element.name] = (key, kind)
            self.index.names[element.name] = kind
            if isinstance(element, ast.State):
                target = self.stereotype_target(element.stereotypes, "import")
                if target is not None:
                    imported[element.name] = target
        block = self.text_of(self.loaded.path).span(owner)
        seen = frozenset(n for n, (_, kind) in states.items() if state_kind(kind) == "state")
        if block is not None:
            self.index.scopes.append((block, seen))
        for element in elements:
            if isinstance(element, ast.Parameter):
                self.refer_symbol(element.position, element.type)
                self.expressions(element.default, values)
            elif isinstance(element, ast.State):
                target = imported.get(element.name)
                walk = partial(self.state, element, target, states, values)
                self.inside(keys[id(element)], walk)
            elif isinstance(element, ast.Transition):
                self.transition(element, imported, states, values)
            elif isinstance(element, ast.Region):
                self.region(element.elements, states, values, element.position)
            elif not isinstance(element, ast.Condition | ast.Pseudostate | ast.Event):
                self.expressions(element, values)
            elif isinstance(element, ast.Condition):
                self.expressions(element.expression, values)

    def state(
        self,
        state: ast.State,
        imported: tuple[Any, Loaded] | None,
        states: ChainMap[str, tuple[Key, str]],
        values: ChainMap[str, tuple[Key, str]],
    ) -> None:
        if imported is not None and isinstance(imported[0], ast.Statechart):
            chart, loaded = imported
            scope = self.foreign_scope(loaded, chart.elements)
            outcomes = [n for n, (_, kind) in scope.items() if kind == "end"]
            self.index.outcomes[state.name] = (*outcomes, *BUILTIN_OUTCOMES)
            for argument in state.arguments:
                if argument.name in scope:
                    self.refer(
                        argument.position, argument.name, "parameter", scope[argument.name][0]
                    )
        elif state.body:
            ends = [e.name for e in state.body if isinstance(e, ast.Condition) and e.kind == "end"]
            if ends:
                self.index.outcomes[state.name] = (*ends, *BUILTIN_OUTCOMES)
        for argument in state.arguments:
            self.expressions(argument.value, values)
        self.expressions(state.invariant, values)
        if state.body:
            self.region(state.body, states, values, state.position)

    def transition(
        self,
        transition: ast.Transition,
        imported: dict[str, tuple[Any, Loaded]],
        states: ChainMap[str, tuple[Key, str]],
        values: ChainMap[str, tuple[Key, str]],
    ) -> None:
        for name, position in (
            (transition.source, transition.source_position),
            (transition.target, transition.target_position),
        ):
            if name in states:
                key, kind = states[name]
                self.refer(position, name, state_kind(kind), key)
        source = imported.get(transition.source)
        if transition.stimulus and source and isinstance(source[0], ast.Statechart):
            outcomes = self.foreign_scope(source[1], source[0].elements)
            if transition.stimulus in outcomes:
                key, _ = outcomes[transition.stimulus]
                self.refer(transition.stimulus_position, transition.stimulus, "end", key)
        elif transition.stimulus in states:
            key, kind = states[transition.stimulus]
            self.refer(transition.stimulus_position, transition.stimulus, state_kind(kind), key)
        for part in (transition.guard, transition.stimulus_arguments, transition.action):
            self.expressions(part, values)
        self.expressions(transition.postcondition, values)

    def expressions(self, node: Any, values: ChainMap[str, tuple[Key, str]]) -> None:
        """Resolve every name and device member below a node of an expression or statement."""
        for found in ast.walk(node):
            if isinstance(found, ast.Name) and found.name in values:
                key, kind = values[found.name]
                self.refer(found.position, found.name, kind, key)
            elif isinstance(found, ast.Member) and isinstance(found.target, ast.Name):
                member = self.members.get(found.target.name, {}).get(found.name)
                if member is not None:  # the member's own span: its dot and name
                    self.refer(found.position, found.name, member[1], member[0])
            elif isinstance(found, ast.Call) and isinstance(found.function, ast.Member):
                self.command_arguments(found)

    def command_arguments(self, call: ast.Call) -> None:
        function = call.function
        if not isinstance(function, ast.Member) or not isinstance(function.target, ast.Name):
            return
        member = self.members.get(function.target.name, {}).get(function.name)
        if member is None or not isinstance(member[2], ast.Command):
            return
        _, _, command, loaded = member
        parameters = {p.name: p for p in command.parameters}
        for argument in call.arguments:
            if argument.name in parameters:
                parameter = parameters[argument.name]
                key = self.key(loaded, parameter, parameter.name)[0]
                self.refer(argument.position, argument.name, "parameter", key)

    # -- domain models --------------------------------------------------------------------

    def domain(self, declaration: Any) -> None:
        key = self.declare(declaration, _KINDS.get(type(declaration), "type"))
        self.inside(key, partial(self.domain_members, declaration))

    def domain_members(self, declaration: Any) -> None:
        if isinstance(declaration, ast.VectorType) and declaration.element_type:
            self.refer_symbol(declaration.position, declaration.element_type)
        for member in getattr(declaration, "members", getattr(declaration, "fields", ())):
            key = self.declare(member, _KINDS.get(type(member), "field"))
            self.inside(key, partial(self.member_parameters, member))

    def member_parameters(self, member: Any) -> None:
        if hasattr(member, "type"):
            self.refer_symbol(member.position, member.type)
        for parameter in (*getattr(member, "parameters", ()), *getattr(member, "attributes", ())):
            self.declare(parameter, "parameter")
            self.refer_symbol(parameter.position, parameter.type)
        if getattr(member, "returns", ""):
            self.refer_symbol(member.position, member.returns)


_KINDS = {
    ast.Statechart: "statechart",
    ast.Device: "device",
    ast.Cell: "cell",
    ast.Command: "command",
    ast.Sensor: "sensor",
    ast.DeviceInstance: "instance",
    ast.SceneObject: "object",
    ast.Field: "field",
}


def _typed_expressions(
    text: Text, typed: Iterable[tuple[ast.Expression, Type]]
) -> list[tuple[lsp.Range, str]]:
    found = []
    for expression, type_ in typed:
        where = span(text, expression)
        if where is not None and type_ is not UNKNOWN:
            found.append((where, f"{printer.expression(expression)} : {describe(type_)}"))
    return found


def _length(where: lsp.Range) -> tuple[int, int]:
    return (where.end.line - where.start.line, where.end.character - where.start.character)


def state_kind(kind: str) -> str:
    return "state" if kind in ("state", "pseudostate") else kind


def _flatten(elements: Iterable[Any]) -> Iterator[Any]:
    for element in elements:
        if isinstance(element, ast.ParameterBlock):
            yield from element.parameters
        elif isinstance(element, ast.EventBlock):
            yield from element.events
        else:
            yield element


def _declarations(elements: Iterable[Any]) -> Iterator[tuple[Any, str]]:
    """The named elements a region declares, with their kinds (conditions as start/end)."""
    for element in _flatten(elements):
        if isinstance(element, ast.State):
            yield element, "state"
        elif isinstance(element, ast.Parameter):
            yield element, "parameter"
        elif isinstance(element, ast.Condition):
            yield element, element.kind
        elif isinstance(element, ast.Pseudostate):
            yield element, "pseudostate"
        elif isinstance(element, ast.Event):
            yield element, "event"
        elif (kind := symbol_kind(element)) is not None:
            yield element, kind
