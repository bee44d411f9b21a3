"""The module views of the python target: a class per statechart and per state.

An ``<<import>>`` state is an instance of the imported statechart's class, an
``<<extends>>`` statechart or state a subclass of the extended class (with the merged tables
of the derived model)."""

from __future__ import annotations

from collections.abc import Callable

from lightrocks.generators.python import expressions as code
from lightrocks.generators.python.expressions import CompileError, Scope
from lightrocks.generators.python.names import DOMAIN, alias, identifier, module_parts, nested
from lightrocks.generators.python.values import (
    python_type,
    safe_range,
    value_type,
)
from lightrocks.generators.python.views import (
    ClassView,
    ExtensionView,
    Method,
    ModuleView,
    docstring_text,
    tuple_code,
)
from lightrocks.languages.domain.ranges import command_ranges
from lightrocks.languages.domain.types import DeviceT
from lightrocks.languages.lightrocks.model import Component, Region, StateInfo, running_cell
from lightrocks.languages.lightrocks.ranges import Flows
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast
from lightrocks.workbench.extensions import template_name
from lightrocks.workbench.generators import GenerationError


class Builder:
    """Builds the module views of every component of one check run."""

    def __init__(
        self, typing: Typing, extension: Callable[[ast.ExtensionNode, Scope], str] | None = None
    ) -> None:
        self.typing = typing
        self.extension = extension
        self.flows = Flows(typing)
        self.workspace = typing.models.workspace
        self.classes: dict[int, tuple[str, str]] = {}  # id(StateInfo) -> (module, class)
        self.components = sorted(typing.models.components, key=lambda c: c.qualified_name)
        for component in self.components:
            module = component.qualified_name
            self._register(module, _component_class(component), component.region)

    def _scope(self, region: Region, offset: int = 0) -> Scope:
        return Scope(self.typing, region, offset, self.extension)

    def _register(self, module: str, outer: str, region: Region) -> None:
        for info in region.states.values():
            if id(info) not in self.classes:
                self.classes[id(info)] = (module, nested(outer, info.name))
                if info.region is not None:
                    self._register(module, nested(outer, info.name), info.region)

    # -- modules --------------------------------------------------------------------------

    def module(self, component: Component) -> ModuleView:
        self.imports: dict[str, tuple[str, str]] = {}  # alias -> (module, name)
        self.current = component.qualified_name
        self.local = {_component_class(component)} | {
            name for module, name in self.classes.values() if module == self.current
        }
        view = ModuleView(source=docstring_text(component.region.position.file))
        own = component.loaded
        classes: list[ClassView] = []
        self._states(component.region, own, classes)
        classes.append(self._component(component))
        view.classes = classes
        depth = component.qualified_name.count(".")
        for used, (module, name) in sorted(self.imports.items(), key=lambda i: (i[1], i[0])):
            dots = "." * (depth + 1)
            path = ".".join(module_parts(module))
            named = name if used == name else f"{name} as {used}"
            view.imports.append(f"from {dots}{path} import {named}")
        # the component class annotates PARAMETERS with ClassVar, and its BINDINGS (a
        # composite) or its arguments (an action) with Any
        view.typing_names = ["Any", "ClassVar"]
        return view

    def _use(self, module: str, name: str) -> str:
        """A class of another module: under its own name while that is free in this module,
        else under an alias of the generator's own."""
        if module == self.current:
            return name
        used = name
        if name in self.local or self.imports.get(name, (module, name)) != (module, name):
            used = alias(module_parts(module), name)
        self.imports[used] = (module, name)
        return used

    def _class_of(self, info: StateInfo) -> str:
        if info.imported is not None and info.region is None:
            return self._use(info.imported.qualified_name, _component_class(info.imported))
        module, name = self.classes[id(info)]
        return self._use(module, name)

    def _states(self, region: Region, own: object, out: list[ClassView]) -> None:
        """Classes of the states declared in ``region`` (inner states first)."""
        for info in region.states.values():
            module, name = self.classes[id(info)]
            if module != self.current or (info.imported is not None and info.region is None):
                continue
            if info.region is not None:
                self._states(info.region, own, out)
            out.append(self._state(info, name, region))

    def _state(self, info: StateInfo, name: str, parent: Region) -> ClassView:
        state = info.state
        doc = f"State {docstring_text(state.name)}."
        base = "rt.State"
        if state.is_final:
            base = "rt.Final"
        elif _extends(state):
            base = self._extended_base(state, parent) or "rt.Composite"
        elif info.region is not None and info.region.orthogonal:
            base = "rt.Parallel"
        elif info.region is not None and info.region.states:
            base = "rt.Composite"
        view = ClassView(name, [base], doc)
        view.constants += [f"NAME = {state.name!r}", f"LOCATION = {str(state.position)!r}"]
        invariants = []
        if state.invariant is not None:
            scope = self._scope(parent, offset=1)
            invariants.append((state.invariant, scope, state.position))
        if base != "rt.State" and info.region is not None:
            self._region(info.region, view, invariants)
        elif info.region is not None:  # a body with actions only: still a simple state
            scope = self._scope(info.region)
            self._actions(info.region, view, scope)
            self._internal(info.region, view, scope)
            inner = [(i.expression, scope, i.position) for i in info.region.invariants]
            self._invariants(view, invariants + inner)
        elif invariants:
            self._invariants(view, invariants)
        if info.region is not None:
            view.extensions = _extension_views(info.region)
        return view

    def _extended_base(self, state: ast.State, parent: Region) -> str | None:
        reference = ast.stereotype(state.stereotypes, "extends")
        component = (
            self.typing.models.resolve_statechart(parent.loaded, reference.value)
            if reference and reference.value
            else None
        )
        return self._class_of_component(component) if component else None

    def _class_of_component(self, component: Component) -> str:
        return self._use(component.qualified_name, _component_class(component))

    def _component(self, component: Component) -> ClassView:
        region = component.region
        is_action = component.layer == "action"
        if component.base is not None:
            base = self._class_of_component(component.base)
        else:
            base = "rt.ActionComponent" if is_action else "rt.CompositeComponent"
            if region.orthogonal:
                base = "rt.ParallelComponent"
        layer = f"<<{component.layer}>> " if component.layer else ""
        doc = f"{layer}statechart {component.qualified_name}."
        view = ClassView(_component_class(component), [base], doc)
        view.constants += [
            f"NAME = {component.name!r}",
            f"LOCATION = {str(component.statechart.position)!r}",
            f"LAYER = {component.layer!r}",
        ]
        cell = running_cell(self.workspace, component.loaded)
        if cell is not None:
            view.constants.append(f"CELL = {self._use(DOMAIN, identifier(cell.node.name))}")
        if region.events is not None:
            view.constants.append(f"EVENTS = {tuple_code(repr(e) for e in region.events)}")
        mapping = ", ".join(f"{n!r}: {identifier(n)!r}" for n in region.parameters)
        view.constants.append(f"PARAMETERS: ClassVar[dict[str, str]] = {{{mapping}}}")
        declared_types = {
            name: value_type(self.typing.types.resolve(region.loaded, parameter.type))
            for name, parameter in region.parameters.items()
        }
        view.constants.append(f"PARAMETER_TYPES: ClassVar[dict[str, tuple]] = {declared_types!r}")
        reached = {
            name: tuple_code(filter(None, map(safe_range, ranges)))
            for name, ranges in self.flows.of(component).items()
        }
        mapping = ", ".join(f"{n!r}: {r}" for n, r in reached.items() if r != "()")
        view.constants.append(
            f"PARAMETER_RANGES: ClassVar[dict[str, tuple[rt.SafeRange, ...]]] = {{{mapping}}}"
        )
        scope = self._scope(region)
        for parameter in region.parameters.values():
            declared = self.typing.types.resolve(region.loaded, parameter.type)
            view.fields.append(f"{identifier(parameter.name)}: {python_type(declared)}")
        body = [
            f"self.{identifier(p.name)} = {self.compile(p.default, scope)}"
            for p in region.parameters.values()
            if p.default is not None
        ]
        if body:
            view.methods.append(Method("defaults", ", s: rt.Snapshot", "None", body))
        if is_action:
            self._action(component, view, scope)
        else:
            self._region(region, view, [])
            budget = component.time_budget
            if budget is not None:  # <<timeout>> on a skill or task
                view.constants.append(f"BUDGET = {budget!r}")
        view.extensions = _extension_views(region)
        return view

    # -- regions --------------------------------------------------------------------------

    def _region(self, region: Region, view: ClassView, invariants: list) -> None:
        scope = self._scope(region)
        self._actions(region, view, scope)
        invariants = invariants + [(i.expression, scope, i.position) for i in region.invariants]
        self._invariants(view, invariants)
        outcomes = region.outcomes
        view.constants.append(f"OUTCOMES = {tuple_code(repr(o) for o in outcomes)}")
        initial = next((s.name for s in region.states.values() if s.state.is_initial), None)
        if initial is not None:
            view.constants.append(f"INITIAL = {initial!r}")
        children = ", ".join(
            [f"{n!r}: {self._class_of(i)}" for n, i in region.states.items()]
            + [
                f"{n!r}: {_choice(n, p)}"
                for n, p in region.pseudostates.items()
                if p.kind == "choice"
            ]
        )
        view.tables.append(f"CHILDREN: ClassVar[dict[str, type[rt.State]]] = {{{children}}}")
        bindings = []
        for info in region.states.values():
            if info.imported is not None and info.state.arguments:
                method = f"_bind_{identifier(info.name)}"
                body = [self._bindings(info, scope)]
                view.methods.append(Method(method, ", s: rt.Snapshot", "dict[str, Any]", body))
                bindings.append(f"{info.name!r}: {method}")
        view.tables.append("BINDINGS: ClassVar[dict[str, Any]] = {" + ", ".join(bindings) + "}")
        view.tables.append("STARTS = " + self._conditions(region.start_conditions, view, scope))
        view.tables.append("ENDS = " + self._conditions(region.end_conditions, view, scope))
        view.tables.append("TRANSITIONS = " + self._transitions(region, view, scope))
        self._internal(region, view, scope)

    def _internal(self, region: Region, view: ClassView, scope: Scope) -> None:
        """The internal transitions of the state that owns ``region``."""
        items = []
        for index, t in enumerate(region.internal):
            named = self._reaction(t, f"internal_{index}", view, scope)
            extra = "".join(f", {k}={v}" for k, v in named.items() if v != "None")
            items.append(
                f"rt.Transition('', '', {t.stimulus!r}{extra}, location={str(t.position)!r})"
            )
        if items:
            view.tables.append(f"INTERNAL = {tuple_code(items)}")

    def _reaction(
        self,
        t: ast.Transition | ast.InternalTransition,
        suffix: str,
        view: ClassView,
        scope: Scope,
    ) -> dict[str, str]:
        """Methods for the guard, action and delay of a transition, by keyword."""
        guard = action = delay = "None"
        if t.guard is not None:
            guard = f"_guard_{suffix}"
            body = [f"return {self.compile(t.guard, scope)}"]
            view.methods.append(Method(guard, ", s: rt.Snapshot", "bool", body))
        if t.action:
            action = f"_action_{suffix}"
            body = self._statements(t.action, scope)
            view.methods.append(Method(action, ", s: rt.Snapshot", "None", body))
        if t.stimulus == "after" and len(t.stimulus_arguments) == 1:
            delay = f"_delay_{suffix}"
            body = [f"return {self.compile(t.stimulus_arguments[0], scope)}"]
            view.methods.append(Method(delay, ", s: rt.Snapshot", "float", body))
        return {"guard": guard, "action": action, "delay": delay}

    def _bindings(self, info: StateInfo, scope: Scope) -> str:
        names = list(info.imported.region.parameters)
        items = []
        for index, argument in enumerate(info.state.arguments):
            name = argument.name or names[index]
            items.append(f"{identifier(name)!r}: {self.compile(argument.value, scope)}")
        return "return {" + ", ".join(items) + "}"

    def _conditions(self, conditions: list[ast.Condition], view: ClassView, scope: Scope) -> str:
        items = []
        for condition in conditions:
            holds = "None"
            if condition.expression is not None:
                holds = f"_{condition.kind}_{identifier(condition.name)}"
                body = [f"return {self.compile(condition.expression, scope)}"]
                view.methods.append(Method(holds, ", s: rt.Snapshot", "bool", body))
            location = str(condition.position)
            items.append(f"rt.Condition({condition.name!r}, {holds}, {location!r})")
        return tuple_code(items)

    def _transitions(self, region: Region, view: ClassView, scope: Scope) -> str:
        items = []
        for index, t in enumerate(region.transitions):
            named = self._reaction(t, str(index), view, scope)
            if t.postcondition is not None:
                named["post"] = f"_post_{index}"
                body = [f"return {self.compile(t.postcondition, scope)}"]
                view.methods.append(Method(named["post"], ", s: rt.Snapshot", "bool", body))
            if t.target_history:
                inner = region.states[t.target].region
                kind = inner.pseudostates[t.target_history].kind if inner else "history"
                named["history"] = repr("deep" if kind == "deep history" else "shallow")
            extra = "".join(f", {k}={v}" for k, v in named.items() if v != "None")
            items.append(
                f"rt.Transition({t.source!r}, {t.target!r}, {t.stimulus!r}{extra}, "
                f"location={str(t.position)!r})"
            )
        return tuple_code(items)

    def _actions(self, region: Region, view: ClassView, scope: Scope) -> None:
        for action in region.actions:
            if action.kind in ("entry", "exit"):
                name = "on_entry" if action.kind == "entry" else "on_exit"
                body = self._statements(action.statements, scope) or ["pass"]
                view.methods.append(Method(name, ", s: rt.Snapshot", "None", body))
                where = f"{action.kind.upper()}_LOCATION = {str(action.position)!r}"
                view.constants.append(where)

    def _invariants(self, view: ClassView, invariants: list) -> None:
        items = []
        for index, (expression, scope, position) in enumerate(invariants):
            name = f"_invariant_{index}"
            body = [f"return {self.compile(expression, scope)}"]
            view.methods.append(Method(name, ", s: rt.Snapshot", "bool", body))
            items.append(f"rt.Invariant({name}, {str(position)!r})")
        if items or not view.bases[0].startswith("rt."):  # a subclass must not inherit them
            view.tables.append(f"INVARIANTS = {tuple_code(items)}")

    # -- elemental actions ----------------------------------------------------------------

    def _action(self, component: Component, view: ClassView, scope: Scope) -> None:
        region = component.region
        do = next((a for a in region.actions if a.kind == "do"), None)
        if do is None or len(do.statements) != 1:
            raise GenerationError(f"{region.position}: an action needs exactly one do command")
        statement = do.statements[0]
        call = ast.evaluated(statement)
        if not (isinstance(call, ast.Call) and isinstance(call.function, ast.Member)):
            raise GenerationError(f"{statement.position}: a do action must call a device command")
        device_name = call.function.target
        device_type = scope.type_of(device_name)
        device = getattr(device_type, "device", None)
        if not isinstance(device_name, ast.Name) or device is None:
            raise GenerationError(f"{call.position}: a do action must call a device command")
        command = next(c for c in device.commands if c.name == call.function.name)
        budget = component.command_budget(device)
        view.constants += [
            f"DEVICE = {device_name.name!r}",
            f"COMMAND = {command.name!r}",
            "BUDGET = rt.DEFAULT_BUDGET"
            if budget.stereotype is None
            else f"BUDGET = {budget.seconds!r}",
        ]
        view.constants.append(f"SENSORS = {tuple_code(repr(s) for s in _sensors(region, scope))}")
        ranges = {n: safe_range(r) for n, r in command_ranges(device_name.name, command).items()}
        mapping = ", ".join(f"{n!r}: {r}" for n, r in ranges.items() if r is not None)
        if mapping:
            view.constants.append(f"RANGES: ClassVar[dict[str, rt.SafeRange]] = {{{mapping}}}")
        names = [p.name for p in command.parameters]
        items = [
            f"{(a.name or names[i])!r}: {self.compile(a.value, scope)}"
            for i, a in enumerate(call.arguments)
        ]
        body = ["return {" + ", ".join(items) + "}"]
        view.methods.append(Method("arguments", ", s: rt.Snapshot", "dict[str, Any]", body))
        if isinstance(statement, ast.Assignment):
            stored = code.target(statement.target, scope)
            view.methods.append(Method("store", ", value: Any", "None", [f"{stored} = value"]))
        self._actions(region, view, scope)
        self._invariants(view, [(i.expression, scope, i.position) for i in region.invariants])
        view.constants.append(f"OUTCOMES = {tuple_code(repr(o) for o in region.outcomes)}")
        view.tables.append("ENDS = " + self._conditions(region.end_conditions, view, scope))

    # -- compiling ------------------------------------------------------------------------

    def compile(self, expression: ast.Expression, scope: Scope) -> str:
        """``expression`` as Python; one the compiler refuses is a generation error."""
        try:
            return code.expression(expression, scope)
        except CompileError as error:
            raise GenerationError(str(error)) from None

    def _statements(self, body: tuple[ast.Statement, ...], scope: Scope) -> list[str]:
        try:
            return code.statements(body, scope)
        except CompileError as error:
            raise GenerationError(str(error)) from None


def _extension_views(region: Region) -> list[ExtensionView]:
    """The region's extension elements grouped by node type, in order of first appearance."""
    groups: dict[type, ExtensionView] = {}
    for element in region.extensions:
        kind = type(element)
        if kind not in groups:
            groups[kind] = ExtensionView(template_name("python", element), [])
        groups[kind].elements.append(element)
    return list(groups.values())


def _component_class(component: Component) -> str:
    return identifier(component.name)


def _choice(name: str, choice: ast.Pseudostate) -> str:
    """A choice pseudostate's class, made where it is named: its ``LOCATION`` is where a
    choice none of whose branches holds is reported."""
    constants = f"{{'NAME': {name!r}, 'LOCATION': {str(choice.position)!r}}}"
    return f"type({name!r}, (rt.Choice,), {constants})"


def _extends(state: ast.State) -> bool:
    return ast.stereotype(state.stereotypes, "extends") is not None


def _sensors(region: Region, scope: Scope) -> list[tuple[str, str]]:
    """The sensors the end conditions and exit actions read: recorded in the trace."""
    found: list[tuple[str, str]] = []
    nodes: list[object] = [c.expression for c in region.end_conditions]
    nodes += [a for a in region.actions if a.kind == "exit"]
    for node in _walk(nodes):
        device = isinstance(node, ast.Member) and isinstance(node.target, ast.Name)
        if device and isinstance(scope.env.get(node.target.name), DeviceT):
            pair = (node.target.name, node.name)
            if pair not in found:
                found.append(pair)
    return found


def _walk(nodes: list[object]) -> list[object]:
    out, stack = [], list(nodes)
    while stack:
        node = stack.pop(0)
        if node is None:
            continue
        out.append(node)
        for name in getattr(node, "__dataclass_fields__", {}):
            if name == "position":
                continue
            value = getattr(node, name)
            if isinstance(value, tuple):
                stack.extend(v for v in value if hasattr(v, "__dataclass_fields__"))
            elif hasattr(value, "__dataclass_fields__"):
                stack.append(value)
    return out
