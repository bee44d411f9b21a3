"""The python target: one module per statechart, a class per statechart and per state.

An ``<<import>>`` state is an instance of the imported statechart's class, an
``<<extends>>`` statechart or state a subclass of the extended class (with the merged tables
of the derived model). Device types become ``typing.Protocol`` classes and cells
``runtime.Cell`` classes in ``_domain.py``. Output is formatted with ruff when it is
installed, and the same models always give the same bytes.
"""

from __future__ import annotations

import keyword
import re
import shutil
import subprocess
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path

import jinja2

from lightrocks.generators.python import expressions as code
from lightrocks.generators.python.expressions import CompileError, Scope
from lightrocks.generators.python.names import alias, identifier, nested
from lightrocks.languages.domain.ranges import Range, command_ranges
from lightrocks.languages.domain.types import (
    BOOLEAN,
    FRAME,
    STRING,
    DeviceT,
    ObjectT,
    QuantityT,
    StructT,
    Type,
    VectorT,
)
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.model import Component, Region, StateInfo
from lightrocks.languages.lightrocks.ranges import Flows
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import UnitError, lookup
from lightrocks.workbench.extensions import language_extensions, template_name
from lightrocks.workbench.generators import GenerationError, GenerationRequest, template_environment

TEMPLATES = Path(__file__).with_name("templates")
DOMAIN = "_domain"


@dataclass
class Method:
    name: str
    parameters: str
    returns: str
    body: list[str]


@dataclass
class ExtensionView:
    """Elements of one language-extension type, rendered by that extension's template; the
    template sees them as ``extension.elements`` (AST nodes) and indents its lines by 4."""

    template: str
    elements: list[object]


@dataclass
class ClassView:
    name: str
    bases: list[str]
    doc: str
    constants: list[str] = field(default_factory=list)
    fields: list[str] = field(default_factory=list)
    methods: list[Method] = field(default_factory=list)
    tables: list[str] = field(default_factory=list)
    extensions: list[ExtensionView] = field(default_factory=list)


@dataclass
class ModuleView:
    source: str
    imports: list[str] = field(default_factory=list)
    classes: list[ClassView] = field(default_factory=list)
    typing_names: list[str] = field(default_factory=list)


def module_parts(qualified_name: str) -> list[str]:
    """The package path of a statechart's module (the domain module is the generator's)."""
    if qualified_name == DOMAIN:
        return [DOMAIN]
    return [identifier(part) for part in qualified_name.split(".")]


def module_path(qualified_name: str) -> str:
    return "/".join(module_parts(qualified_name)) + ".py"


def python_type(t: Type | None) -> str:
    """The annotation of a value of model type ``t`` (SI floats, frames, tuples)."""
    if isinstance(t, QuantityT):
        return "int" if t.name == "Integer" else "float"
    if t == BOOLEAN:
        return "bool"
    if t == STRING:
        return "str"
    if t == FRAME:
        return "rt.Frame"
    if isinstance(t, ObjectT):
        return "rt.SceneObject"
    if isinstance(t, VectorT):
        return "tuple[" + ", ".join(python_type(e) for e in t.elements) + "]"
    if isinstance(t, StructT):
        if t.name == "Wrench":
            return "rt.Wrench"
        if {n for n, _ in t.fields} == {"x", "y", "z"}:
            return "rt.Vector3"
    return "Any"


def zero_value(t: Type | None) -> str | None:
    """What an attribute without default starts as: zero, false or empty, as a PLC
    variable starts; None for a type without such a value."""
    if isinstance(t, QuantityT):
        return "0" if t.name == "Integer" else "0.0"
    if t == BOOLEAN:
        return "False"
    if t == STRING:
        return "''"
    if t == FRAME:
        return "rt.Frame.Identity()"
    if isinstance(t, VectorT):
        elements = [zero_value(e) for e in t.elements]
        return None if None in elements else "(" + "".join(f"{e}, " for e in elements) + ")"
    return None


def value_type(t: Type | None) -> tuple:
    """What a run parameter of model type ``t`` accepts, as plain data for the generated
    class (``PARAMETER_TYPES``): kind, type name, and the dimension exponents of its
    numbers (one for a quantity, one per element for a vector)."""
    if isinstance(t, QuantityT):
        kind = "integer" if t.name == "Integer" else "quantity"
        return (kind, t.name, (t.dimension.exponents,))
    if isinstance(t, VectorT) and all(isinstance(e, QuantityT) for e in t.elements):
        return ("vector", t.name, tuple(e.dimension.exponents for e in t.elements))
    if t == BOOLEAN:
        return ("boolean", "Boolean", ())
    if t == STRING:
        return ("string", "String", ())
    return ("other", str(t), ())


def _safe_range(safe: Range) -> str | None:
    """A declared safe range as generated code (``rt.SafeRange``); None when not constant."""
    bounds = safe.elements()
    if not bounds:
        return None
    shown = _tuple(
        f"rt.Bound({lo!r}, {hi!r}, {unit!r}, {factor!r})" for lo, hi, unit, factor in bounds
    )
    return f"rt.SafeRange({safe.device!r}, {safe.command!r}, {safe.argument!r}, {shown})"


def seconds(text: str | None) -> float | None:
    """A ``<<timeout="5 s">>`` value in seconds."""
    if not text:
        return None
    match = re.fullmatch(r"\s*(\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)\s*([A-Za-z]*)\s*", text)
    if match is None:
        return None
    try:
        return float(match.group(1)) * lookup(match.group(2)).factor
    except UnitError:
        return None


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
        view = ModuleView(source=_safe(component.region.position.file))
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
        text = repr(view)
        view.typing_names = [n for n in ("Any", "ClassVar") if re.search(rf"\b{n}\b", text)]
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
        doc = f"State {_safe(state.name)}."
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
        cell = self._cell(component)
        if cell is not None:
            view.constants.append(f"CELL = {self._use(DOMAIN, cell)}")
        if region.events is not None:
            view.constants.append(f"EVENTS = {_tuple(repr(e) for e in region.events)}")
        mapping = ", ".join(f"{n!r}: {identifier(n)!r}" for n in region.parameters)
        view.constants.append(f"PARAMETERS: ClassVar[dict[str, str]] = {{{mapping}}}")
        declared_types = {
            name: value_type(self.typing.types.resolve(region.loaded, parameter.type))
            for name, parameter in region.parameters.items()
        }
        view.constants.append(f"PARAMETER_TYPES: ClassVar[dict[str, tuple]] = {declared_types!r}")
        reached = {
            name: _tuple(filter(None, map(_safe_range, ranges)))
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
            f"self.{identifier(p.name)} = {self._expr(p.default, scope)}"
            for p in region.parameters.values()
            if p.default is not None
        ]
        if body:
            view.methods.append(Method("defaults", ", s: rt.Snapshot", "None", body))
        if is_action:
            self._action(component, view, scope)
        else:
            self._region(region, view, [])
        view.extensions = _extension_views(region)
        return view

    # -- regions --------------------------------------------------------------------------

    def _region(self, region: Region, view: ClassView, invariants: list) -> None:
        scope = self._scope(region)
        self._actions(region, view, scope)
        invariants = invariants + [(i.expression, scope, i.position) for i in region.invariants]
        self._invariants(view, invariants)
        outcomes = region.outcomes
        view.constants.append(f"OUTCOMES = {_tuple(repr(o) for o in outcomes)}")
        initial = next((s.name for s in region.states.values() if s.state.is_initial), None)
        if initial is not None:
            view.constants.append(f"INITIAL = {initial!r}")
        children = ", ".join(
            [f"{n!r}: {self._class_of(i)}" for n, i in region.states.items()]
            + [f"{n!r}: rt.Choice" for n, p in region.pseudostates.items() if p.kind == "choice"]
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
            view.tables.append(f"INTERNAL = {_tuple(items)}")

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
            body = [f"return {self._expr(t.guard, scope)}"]
            view.methods.append(Method(guard, ", s: rt.Snapshot", "bool", body))
        if t.action:
            action = f"_action_{suffix}"
            body = self._statements(t.action, scope)
            view.methods.append(Method(action, ", s: rt.Snapshot", "None", body))
        if t.stimulus == "after" and len(t.stimulus_arguments) == 1:
            delay = f"_delay_{suffix}"
            body = [f"return {self._expr(t.stimulus_arguments[0], scope)}"]
            view.methods.append(Method(delay, ", s: rt.Snapshot", "float", body))
        return {"guard": guard, "action": action, "delay": delay}

    def _bindings(self, info: StateInfo, scope: Scope) -> str:
        names = list(info.imported.region.parameters)
        items = []
        for index, argument in enumerate(info.state.arguments):
            name = argument.name or names[index]
            items.append(f"{identifier(name)!r}: {self._expr(argument.value, scope)}")
        return "return {" + ", ".join(items) + "}"

    def _conditions(self, conditions: list[ast.Condition], view: ClassView, scope: Scope) -> str:
        items = []
        for condition in conditions:
            holds = "None"
            if condition.expression is not None:
                holds = f"_{condition.kind}_{identifier(condition.name)}"
                body = [f"return {self._expr(condition.expression, scope)}"]
                view.methods.append(Method(holds, ", s: rt.Snapshot", "bool", body))
            location = str(condition.position)
            items.append(f"rt.Condition({condition.name!r}, {holds}, {location!r})")
        return _tuple(items)

    def _transitions(self, region: Region, view: ClassView, scope: Scope) -> str:
        items = []
        for index, t in enumerate(region.transitions):
            named = self._reaction(t, str(index), view, scope)
            if t.postcondition is not None:
                named["post"] = f"_post_{index}"
                body = [f"return {self._expr(t.postcondition, scope)}"]
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
        return _tuple(items)

    def _actions(self, region: Region, view: ClassView, scope: Scope) -> None:
        for action in region.actions:
            if action.kind in ("entry", "exit"):
                name = "on_entry" if action.kind == "entry" else "on_exit"
                body = self._statements(action.statements, scope) or ["pass"]
                view.methods.append(Method(name, ", s: rt.Snapshot", "None", body))

    def _invariants(self, view: ClassView, invariants: list) -> None:
        items = []
        for index, (expression, scope, position) in enumerate(invariants):
            name = f"_invariant_{index}"
            body = [f"return {self._expr(expression, scope)}"]
            view.methods.append(Method(name, ", s: rt.Snapshot", "bool", body))
            items.append(f"rt.Invariant({name}, {str(position)!r})")
        if items or not view.bases[0].startswith("rt."):  # a subclass must not inherit them
            view.tables.append(f"INVARIANTS = {_tuple(items)}")

    # -- elemental actions ----------------------------------------------------------------

    def _action(self, component: Component, view: ClassView, scope: Scope) -> None:
        region = component.region
        do = next((a for a in region.actions if a.kind == "do"), None)
        if do is None or len(do.statements) != 1:
            raise GenerationError(f"{region.position}: an action needs exactly one do command")
        statement = do.statements[0]
        call = statement.value if isinstance(statement, ast.Assignment) else statement.expression
        if not (isinstance(call, ast.Call) and isinstance(call.function, ast.Member)):
            raise GenerationError(f"{statement.position}: a do action must call a device command")
        device_name = call.function.target
        device_type = scope.type_of(device_name)
        device = getattr(device_type, "device", None)
        if not isinstance(device_name, ast.Name) or device is None:
            raise GenerationError(f"{call.position}: a do action must call a device command")
        command = next(c for c in device.commands if c.name == call.function.name)
        budget = _budget(component) or seconds(_value(device.stereotypes, "timeout"))
        view.constants += [
            f"DEVICE = {device_name.name!r}",
            f"COMMAND = {command.name!r}",
            f"BUDGET = {budget!r}" if budget is not None else "BUDGET = rt.DEFAULT_BUDGET",
        ]
        view.constants.append(f"SENSORS = {_tuple(repr(s) for s in _sensors(region, scope))}")
        ranges = {n: _safe_range(r) for n, r in command_ranges(device_name.name, command).items()}
        mapping = ", ".join(f"{n!r}: {r}" for n, r in ranges.items() if r is not None)
        if mapping:
            view.constants.append(f"RANGES: ClassVar[dict[str, rt.SafeRange]] = {{{mapping}}}")
        names = [p.name for p in command.parameters]
        items = [
            f"{(a.name or names[i])!r}: {self._expr(a.value, scope)}"
            for i, a in enumerate(call.arguments)
        ]
        body = ["return {" + ", ".join(items) + "}"]
        view.methods.append(Method("arguments", ", s: rt.Snapshot", "dict[str, Any]", body))
        if isinstance(statement, ast.Assignment):
            stored = code.target(statement.target, scope)
            view.methods.append(Method("store", ", value: Any", "None", [f"{stored} = value"]))
        self._actions(region, view, scope)
        self._invariants(view, [(i.expression, scope, i.position) for i in region.invariants])
        view.constants.append(f"OUTCOMES = {_tuple(repr(o) for o in region.outcomes)}")
        view.tables.append("ENDS = " + self._conditions(region.end_conditions, view, scope))

    def _cell(self, component: Component) -> str | None:
        cells = sorted(
            (s for s in self.workspace.scope(component.loaded).values()
             if isinstance(s.node, ast.Cell)),
            key=lambda s: s.qualified_name,
        )  # fmt: skip
        return identifier(cells[0].node.name) if cells else None

    # -- compiling ------------------------------------------------------------------------

    def _expr(self, expression: ast.Expression, scope: Scope) -> str:
        try:
            return code.expression(expression, scope)
        except CompileError as error:
            raise GenerationError(str(error)) from None

    def _statements(self, body: tuple[ast.Statement, ...], scope: Scope) -> list[str]:
        try:
            return code.statements(body, scope)
        except CompileError as error:
            raise GenerationError(str(error)) from None


def _render(environment: jinja2.Environment, node: ast.ExtensionNode, scope: Scope) -> str:
    """Python for a statement or expression of a language extension, from its template:
    ``node`` is the AST node, ``code(e)`` compiles a sub-expression and ``target(e)`` an
    assignable one. Model text reaches the code only through those and ``| literal``."""
    template = environment.get_template(template_name("python", node))
    return template.render(
        node=node,
        code=lambda part: code.expression(part, scope),
        target=lambda part: code.target(part, scope),
    ).strip()


def _extension_views(region: Region) -> list[ExtensionView]:
    """The region's extension elements grouped by node type, in order of first appearance."""
    groups: dict[type, ExtensionView] = {}
    for element in region.extensions:
        kind = type(element)
        if kind not in groups:
            groups[kind] = ExtensionView(template_name("python", element), [])
        groups[kind].elements.append(element)
    return list(groups.values())


def _member_name(name: str) -> str:
    """A command, parameter or sensor name as the adapter knows it (only keywords change)."""
    return f"{name}_" if keyword.iskeyword(name) else name


def _component_class(component: Component) -> str:
    return identifier(component.name)


def _extends(state: ast.State) -> bool:
    return ast.stereotype(state.stereotypes, "extends") is not None


def _value(stereotypes: tuple[ast.Stereotype, ...], name: str) -> str | None:
    found = ast.stereotype(stereotypes, name)
    return found.value if found else None


def _budget(component: Component | None) -> float | None:
    while component is not None:
        found = seconds(_value(component.statechart.stereotypes, "timeout"))
        if found is not None:
            return found
        component = component.base
    return None


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


def _tuple(items) -> str:
    items = list(items)
    if not items:
        return "()"
    return "(" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"


def _safe(text: str) -> str:
    """Model-derived text for a docstring: printable, no quotes or backslashes."""
    return "".join(c if c.isprintable() and c not in "\"'\\" else "_" for c in text)


# -- the domain module --------------------------------------------------------------------


def domain_module(builder: Builder, environment) -> str | None:
    workspace = builder.workspace
    devices, cells = [], []
    for symbol in sorted(workspace.symbols.values(), key=lambda s: s.qualified_name):
        if isinstance(symbol.node, ast.Device):
            devices.append(_device_view(builder, symbol))
        elif isinstance(symbol.node, ast.Cell):
            cells.append(_cell_view(builder, symbol))
    if not devices and not cells:
        return None
    return environment.get_template("domain.py.jinja").render(devices=devices, cells=cells)


def _device_view(builder: Builder, symbol) -> dict:
    device: ast.Device = symbol.node
    types = builder.typing.types
    commands = []
    for command in device.commands:
        parameters = "".join(
            f", {_member_name(p.name)}: {python_type(types.resolve(symbol.loaded, p.type))}"
            + (" = ..." if p.default is not None else "")
            for p in command.parameters
        )
        returns = (
            python_type(types.resolve(symbol.loaded, command.returns))
            if command.returns
            else "None"
        )
        commands.append({"name": _member_name(command.name), "parameters": parameters,
                         "returns": returns})  # fmt: skip
    sensors = [
        {"name": _member_name(s.name), "type": python_type(types.resolve(symbol.loaded, s.type))}
        for s in device.sensors
    ]
    return {
        "name": identifier(device.name),
        "qualified": _safe(symbol.qualified_name),
        "type_name": repr(device.name),
        "commands": commands,
        "sensors": sensors,
    }


def _cell_view(builder: Builder, symbol) -> dict:
    cell: ast.Cell = symbol.node
    scope = Scope(None, None)
    devices = ", ".join(
        f"{d.name!r}: {identifier(d.type.rpartition('.')[2])}" for d in cell.devices
    )
    objects = []
    for obj in cell.objects:
        values = []
        for a in obj.attributes:
            if a.default is not None:
                value = builder._expr(a.default, scope)
            else:
                value = zero_value(builder.typing.types.resolve(symbol.loaded, a.type))
            if value is not None:
                values.append(f"{identifier(a.name)!r}: {value}")
        objects.append(f"{identifier(obj.name)!r}: {{{', '.join(values)}}}")
    return {
        "name": identifier(cell.name),
        "qualified": _safe(symbol.qualified_name),
        "scene": repr(_value(cell.stereotypes, "scene")),
        "devices": "{" + devices + "}",
        "objects": "{" + ", ".join(objects) + "}",
    }


# -- the generator ------------------------------------------------------------------------


def ruff_format(files: dict[str, str]) -> dict[str, str]:
    """Format with ruff (line length 100) when it is installed; otherwise leave as rendered."""
    ruff = Path(sys.executable).with_name("ruff")
    command = str(ruff) if ruff.exists() else shutil.which("ruff")
    if command is None:
        return files
    formatted = {}
    for path, text in files.items():
        result = subprocess.run(
            [command, "format", "--isolated", "--line-length", "100", "--stdin-filename", path],
            input=text,
            capture_output=True,
            text=True,
            check=False,
        )
        formatted[path] = result.stdout if result.returncode == 0 else text
    return formatted


class PythonGenerator:
    name = "python"
    description = "Python modules on the LightRocks state runtime (one per statechart)"

    def generate(self, request: GenerationRequest) -> dict[str, str]:
        folders = [e.templates for e in language_extensions() if e.templates is not None]
        environment = template_environment(TEMPLATES, request.templates, folders)
        environment.filters["literal"] = repr  # model text as a Python literal, never code
        builder = Builder(analysis(request.context).typing, partial(_render, environment))
        files: dict[str, str] = {"__init__.py": '"""Generated by LightRocks."""\n'}
        for component in builder.components:
            path = module_path(component.qualified_name)
            view = builder.module(component)
            files[path] = environment.get_template("module.py.jinja").render(module=view)
            parts = path.split("/")[:-1]
            for depth in range(1, len(parts) + 1):
                files.setdefault("/".join([*parts[:depth], "__init__.py"]), "")
        domain = domain_module(builder, environment)
        if domain is not None:
            files[f"{DOMAIN}.py"] = domain
        return ruff_format(files)


GENERATOR = PythonGenerator()
