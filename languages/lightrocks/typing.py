"""Typing of expressions, statements and calls in LightRocks components.

One pass over every component types each expression once and records findings by code;
the type-related CoCos report their share of them. Names resolve through the component's
parameters (inner regions first), the devices and objects of the imported cells, and the
built-in functions.
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass, field

from lightrocks.languages.domain.ranges import Range, command_ranges
from lightrocks.languages.domain.types import (
    ANGLE_T,
    BOOLEAN,
    BUILTIN_FUNCTIONS,
    BUILTIN_TYPES,
    FRAME,
    FRAME_MEMBERS,
    LENGTH_T,
    NUMBER,
    STRING,
    UNKNOWN,
    CommandT,
    DeviceT,
    FunctionT,
    ObjectT,
    QuantityT,
    StructT,
    Type,
    Types,
    VectorT,
    common_number,
    compatible,
    describe,
    narrows,
    quantity_of,
)
from lightrocks.languages.lightrocks.model import Component, ModelSet, Region, visible_cells
from lightrocks.languages.lightrocks.properties import predicate_names
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import beyond_a_real, overflow
from lightrocks.metamodel.units import ONE, UnitError, lookup
from lightrocks.workbench.diagnostics import did_you_mean
from lightrocks.workbench.workspace import Loaded

DURATION = QuantityT("Duration", lookup("s").dimension)
Finding = tuple[ast.Position, str, str]
_BUILTINS: dict[str, Type] = {name: FunctionT(name) for name in BUILTIN_FUNCTIONS}
"""The names every expression may use; scopes add theirs to a copy."""


@dataclass
class Parameterized:
    """Something called with named or positional arguments: a command or a component."""

    title: str
    parameters: list[tuple[str, Type, bool]]
    ranges: dict[str, Range] = field(default_factory=dict)


class Typing:
    """Types every component of a model set once; findings are grouped by CoCo code."""

    def __init__(self, models: ModelSet) -> None:
        self.models = models
        self.types = Types(models.workspace)
        self.findings: dict[str, list[Finding]] = defaultdict(list)
        self.inferred: dict[str, list[tuple[ast.Expression, Type]]] = defaultdict(list)
        self._by_file: dict[str, Loaded] = {}
        for component in models.components:
            for region in component.region.regions():
                if region.loaded is component.loaded:
                    self._region(component, region)
        for loaded in models.workspace.checked_units():
            if isinstance(loaded.unit, ast.DomainUnit):
                self._object_defaults(loaded)

    def report(self, code: str, position: ast.Position, message: str, hint: str = "") -> None:
        self.findings[code].append((position, message, hint))

    # -- scopes ---------------------------------------------------------------------------

    def environment(self, region: Region) -> dict[str, Type]:
        env = dict(_BUILTINS)
        workspace = self.models.workspace
        for symbol in visible_cells(workspace, region.loaded):
            workspace.use(region.loaded, symbol)
            env.update(self._cell_members(symbol.loaded, symbol.node))
        chain = []
        current: Region | None = region
        while current is not None:
            chain.append(current)
            current = current.parent
        for scope in reversed(chain):
            for parameter in scope.parameters.values():
                env[parameter.name] = self.types.resolve(scope.loaded, parameter.type) or UNKNOWN
        return env

    def _cell_members(self, loaded: Loaded, cell: ast.Cell) -> dict[str, Type]:
        members: dict[str, Type] = {}
        for device in cell.devices:
            members[device.name] = self.types.resolve(loaded, device.type) or UNKNOWN
        for obj in cell.objects:
            attributes = tuple(
                (a.name, self.types.resolve(loaded, a.type) or UNKNOWN) for a in obj.attributes
            )
            members[obj.name] = ObjectT(obj.name, (("pose", FRAME), *attributes))
        return members

    def _object_defaults(self, loaded: Loaded) -> None:
        """A scene object's attribute defaults are constants of the attribute's type: they
        initialise the environment model before any component runs."""
        for declaration in loaded.unit.declarations:
            if not isinstance(declaration, ast.Cell):
                continue
            for obj in declaration.objects:
                for attribute in obj.attributes:
                    declared = self.types.resolve(loaded, attribute.type)
                    if declared is not None and attribute.default is not None:
                        what = f"default of '{obj.name}.{attribute.name}'"
                        self.expect(attribute.default, declared, _BUILTINS, what)

    # -- regions --------------------------------------------------------------------------

    def _region(self, component: Component, region: Region) -> None:
        env = self.environment(region)
        loaded = region.loaded
        for parameter in region.parameters.values():
            if parameter.position.file != _file(loaded):
                continue
            declared = self.types.resolve(loaded, parameter.type)
            if declared is None:
                self._unresolved_type(loaded, parameter.type, parameter.position)
                declared = UNKNOWN
            if parameter.default is not None:
                self.expect(parameter.default, declared, env, f"default of '{parameter.name}'")
        for condition in region.conditions.values():
            if condition.expression is not None:
                self.boolean(condition.expression, env, f"condition '{condition.name}'")
        for invariant in region.invariants:
            self.boolean(invariant.expression, env, "invariant")
        if region.properties:  # predicates name states and outcomes too; values come first
            named = {**predicate_names(region), **env}
            for own in (p for p in region.properties if p.position.file == _file(loaded)):
                for predicate in own.expressions:
                    self.boolean(predicate, named, f"property '{own.name}'")
        for info in region.states.values():
            if info.state.invariant is not None:
                self.boolean(info.state.invariant, env, f"invariant of '{info.name}'")
            if info.imported is not None:
                self.arguments(
                    info.state.arguments,
                    self.component_signature(info.imported),
                    env,
                    info.state.position,
                )
            elif info.state.arguments and not ast.stereotype(info.state.stereotypes, "import"):
                # an unresolved <<import>> is reported once, as LR0104
                self.report(
                    "LR0301",
                    info.state.position,
                    f"state '{info.name}' takes no arguments: it does not <<import>> a statechart",
                )
        for transition in [*region.transitions, *region.internal]:
            if transition.guard is not None:
                self.boolean(transition.guard, env, "guard")
            if getattr(transition, "postcondition", None) is not None:
                self.boolean(transition.postcondition, env, "postcondition")
            if transition.stimulus == "after":
                self.time_event(transition, env)
            for statement in transition.action or ():
                self.statement(statement, env)
        for action in region.actions:
            for statement in action.statements:
                if action.kind == "do":
                    self.do_statement(statement, env)
                else:
                    self.statement(statement, env)

    def time_event(
        self, transition: ast.Transition | ast.InternalTransition, env: dict[str, Type]
    ) -> None:
        """``after(d)`` waits one duration, a constant or an expression over parameters."""
        if len(transition.stimulus_arguments) != 1:
            self.report(
                "LR0301", transition.stimulus_position, "after(…) takes exactly one duration"
            )
            return
        self.expect(transition.stimulus_arguments[0], DURATION, env, "delay of after(…)")

    def _unresolved_type(self, loaded: Loaded, name: str, position: ast.Position) -> None:
        candidates = [*BUILTIN_TYPES, *self.models.workspace.scope(loaded)]
        self.report("LR0105", position, f"unknown type '{name}'", did_you_mean(name, candidates))

    # -- statements -----------------------------------------------------------------------

    def statement(self, statement: ast.Statement, env: dict[str, Type]) -> None:
        if isinstance(statement, ast.ExtensionNode):
            statement.infer(lambda part: self.infer(part, env))
        elif isinstance(statement, ast.Assignment):
            target = self.assignable(statement.target, env)
            self.expect(statement.value, target, env, "assigned value")
        else:
            self.infer(statement.expression, env)

    def do_statement(self, statement: ast.Statement, env: dict[str, Type]) -> None:
        """A ``do`` runs one device command, optionally storing what it returns."""
        if isinstance(statement, ast.ExtensionNode):
            self.report("LR0307", statement.position, "a do action must call a device command")
            return
        call = ast.evaluated(statement)
        target = (
            self.assignable(statement.target, env)
            if isinstance(statement, ast.Assignment)
            else None
        )
        if not isinstance(call, ast.Call):
            where = (call or statement).position
            self.report("LR0307", where, "a do action must call a device command")
            return
        callee = self.infer(call.function, env, allow_command=True)
        if callee is UNKNOWN:
            return
        if not isinstance(callee, CommandT) or callee.command is None:
            self.report("LR0307", call.position, "a do action must call a device command")
            return
        owner = call.function.target if isinstance(call.function, ast.Member) else None
        device = owner.name if isinstance(owner, ast.Name) else callee.name
        returns = self.command_signature(callee, device)
        self.arguments(call.arguments, returns[0], env, call.position)
        if target is not None:
            if returns[1] is None:
                self.report(
                    "LR0302",
                    statement.position,
                    f"command '{callee.command.name}' returns nothing to assign",
                )
            elif not compatible(target, returns[1]):
                self.mismatch(statement.position, target, returns[1], "returned value")
            elif narrows(target, returns[1]):
                self.narrowing(statement.position, target, returns[1], "returned value")

    def assignable(self, target: ast.Expression, env: dict[str, Type]) -> Type:
        """The type of an assignment target; sensors and devices cannot be assigned."""
        if isinstance(target, ast.Member):
            owner = self.infer(target.target, env)
            if isinstance(owner, DeviceT):
                self.report(
                    "LR0306",
                    target.position,
                    f"'{target.name}' of device '{owner.name}' is a sensor: it cannot be assigned",
                )
                return UNKNOWN
            return self.infer(target, env)
        if isinstance(target, ast.Name):
            kind = env.get(target.name)
            if isinstance(kind, DeviceT | ObjectT | FunctionT):
                self.report("LR0306", target.position, f"'{target.name}' cannot be assigned")
                return UNKNOWN
            return self.infer(target, env)
        self.report("LR0306", target.position, "only names and attributes can be assigned")
        return UNKNOWN

    # -- calls ----------------------------------------------------------------------------

    def command_signature(
        self, command: CommandT, device: str
    ) -> tuple[Parameterized, Type | None]:
        """The command's parameters; ``device`` is the instance called, for its ranges."""
        loaded = self._declaring(command.device)
        parameters = [
            (
                p.name,
                self.types.resolve(loaded, p.type) or UNKNOWN,
                p.default is not None,
            )
            for p in command.command.parameters
        ]
        returns = None
        if command.command.returns:
            returns = self.types.resolve(loaded, command.command.returns) or UNKNOWN
        title = f"command '{command.name}.{command.command.name}'"
        ranges = command_ranges(device, command.command)
        return Parameterized(title, parameters, ranges), returns

    def component_signature(self, component: Component) -> Parameterized:
        parameters = [
            (
                p.name,
                self.types.resolve(self._loaded_of(component, p), p.type) or UNKNOWN,
                p.default is not None,
            )
            for p in component.region.parameters.values()
        ]
        return Parameterized(f"statechart '{component.name}'", parameters)

    def _loaded_of(self, component: Component, parameter: ast.Parameter) -> Loaded:
        current: Component | None = component
        while current is not None:
            if parameter.position.file == _file(current.loaded):
                return current.loaded
            current = current.base
        return component.loaded

    def _declaring(self, device: ast.Device | None) -> Loaded:
        if device.position.file not in self._by_file:  # files load lazily during typing
            self._by_file = {_file(u): u for u in self.models.workspace.loaded_units()}
        return self._by_file[device.position.file]

    def arguments(
        self,
        arguments: Iterable[ast.Argument],
        signature: Parameterized,
        env: dict[str, Type],
        position: ast.Position,
    ) -> None:
        """Match arguments to parameters by name or position; check types and safe ranges."""
        names = [p[0] for p in signature.parameters]
        bound: dict[str, ast.Argument] = {}
        for index, argument in enumerate(arguments):
            if argument.name:
                if argument.name not in names:
                    self.report(
                        "LR0301",
                        argument.position,
                        f"{signature.title} has no parameter '{argument.name}'",
                        did_you_mean(argument.name, names),
                    )
                    self.infer(argument.value, env)
                    continue
                name = argument.name
            elif index < len(names):
                name = names[index]
            else:
                self.report(
                    "LR0301",
                    argument.position,
                    f"{signature.title} takes {len(names)} arguments",
                )
                continue
            if name in bound:
                self.report("LR0301", argument.position, f"parameter '{name}' is given twice")
            bound[name] = argument
        for name, declared, has_default in signature.parameters:
            argument = bound.get(name)
            if argument is None:
                if not has_default:
                    self.report(
                        "LR0301",
                        position,
                        f"{signature.title} needs a value for parameter '{name}'",
                    )
                continue
            self.expect(argument.value, declared, env, f"argument '{name}'")
            if name in signature.ranges:
                self.in_range(argument.value, signature.ranges[name])

    def in_range(self, value: ast.Expression, safe: Range) -> None:
        breach = safe.breach(value)
        if breach is not None:
            self.report("LR0305", value.position, breach)

    # -- expressions ----------------------------------------------------------------------

    def boolean(self, expression: ast.Expression, env: dict[str, Type], what: str) -> None:
        actual = self.infer(expression, env)
        if actual is not UNKNOWN and actual != BOOLEAN:
            self.report(
                "LR0303", expression.position, f"{what} must be Boolean, not {describe(actual)}"
            )

    def expect(
        self, expression: ast.Expression, expected: Type, env: dict[str, Type], what: str
    ) -> None:
        actual = self.infer(expression, env)
        if not compatible(expected, actual, _is_zero(expression)):
            self.mismatch(expression.position, expected, actual, what)
        elif narrows(expected, actual):
            self.narrowing(expression.position, expected, actual, what)

    def mismatch(self, position: ast.Position, expected: Type, actual: Type, what: str) -> None:
        both_quantities = isinstance(expected, QuantityT) and isinstance(actual, QuantityT)
        code = "LR0304" if both_quantities or _vectors_of_quantities(expected, actual) else "LR0302"
        self.report(
            code, position, f"{what}: expected {describe(expected)}, found {describe(actual)}"
        )

    def narrowing(self, position: ast.Position, expected: Type, actual: Type, what: str) -> None:
        self.report(
            "LR0308",
            position,
            f"{what}: expected {describe(expected)}, found {describe(actual)}: "
            "a Real value does not fit an Integer",
            "declare the target Real, or compute the value from Integers with + - * %",
        )

    def infer(
        self, expression: ast.Expression, env: dict[str, Type], allow_command: bool = False
    ) -> Type:
        """The type of an expression, kept by file for editors to show."""
        found = self._infer(expression, env, allow_command)
        self.inferred[expression.position.file].append((expression, found))
        return found

    def _infer(self, expression: ast.Expression, env: dict[str, Type], allow_command: bool) -> Type:
        match expression:
            case ast.Quantity():
                result = quantity_of(expression)
                if result is UNKNOWN:
                    self._unknown_unit(expression)
                if not math.isfinite(expression.value):
                    self.report(
                        "LR0302",
                        expression.position,
                        f"'{expression.text}' is beyond the largest number a Real holds "
                        "(about 1.8e308 in SI units)",
                    )
                return result
            case ast.BooleanLiteral():
                return BOOLEAN
            case ast.StringLiteral():
                return STRING
            case ast.VectorLiteral():
                return VectorT("vector", tuple(self.infer(e, env) for e in expression.elements))
            case ast.Name():
                if expression.name in env:
                    return env[expression.name]
                self.report(
                    "LR0103",
                    expression.position,
                    f"unknown name '{expression.name}'",
                    did_you_mean(expression.name, env),
                )
                return UNKNOWN
            case ast.Member():
                return self._member(expression, env, allow_command)
            case ast.Index():
                owner = self.infer(expression.target, env)
                self.infer(expression.index, env)
                if isinstance(owner, VectorT) and owner.elements:
                    return owner.elements[0]
                return UNKNOWN
            case ast.Call():
                return self._call(expression, env)
            case ast.Unary():
                operand = self.infer(expression.operand, env)
                if expression.operator == "!":
                    if operand not in (BOOLEAN, UNKNOWN):
                        self.report(
                            "LR0303", expression.position, f"'!' needs Boolean, not {operand}"
                        )
                    return BOOLEAN
                return operand
            case ast.Binary():
                return self._binary(expression, env)
            case ast.ExtensionNode():
                return expression.infer(lambda part: self.infer(part, env))
        return UNKNOWN

    def _unknown_unit(self, literal: ast.Quantity) -> None:
        try:
            lookup(literal.unit)
        except UnitError as error:
            hint = (
                ("did you mean " + " or ".join(f"'{s}'" for s in error.suggestions) + "?")
                if (error.suggestions)
                else ""
            )
            self.report("LR0107", literal.position, f"unknown unit '{literal.unit}'", hint)

    def _member(self, member: ast.Member, env: dict[str, Type], allow_command: bool) -> Type:
        owner = self.infer(member.target, env)
        if owner is UNKNOWN:
            return UNKNOWN
        choices: dict[str, Type] = {}
        if isinstance(owner, DeviceT) and owner.device is not None:
            loaded = self._declaring(owner.device)
            for sensor in owner.device.sensors:
                choices[sensor.name] = self.types.resolve(loaded, sensor.type) or UNKNOWN
            for command in owner.device.commands:
                choices[command.name] = CommandT(owner.name, owner.device, command)
        elif isinstance(owner, ObjectT):
            if owner.attributes is None:
                return FRAME if member.name == "pose" else UNKNOWN
            choices = dict(owner.attributes)
        elif isinstance(owner, StructT):
            choices = dict(owner.fields)
        elif owner == FRAME:
            choices = dict(FRAME_MEMBERS)
        if member.name not in choices:
            self.report(
                "LR0106",
                member.position,
                f"'{describe(owner)}' has no member '{member.name}'",
                did_you_mean(member.name, choices),
            )
            return UNKNOWN
        result = choices[member.name]
        if isinstance(result, CommandT) and not allow_command:
            self.report(
                "LR0307",
                member.position,
                f"device command '{member.name}' can only be called in a do action",
            )
            return UNKNOWN
        return result

    def _call(self, call: ast.Call, env: dict[str, Type]) -> Type:
        callee = self.infer(call.function, env)
        arguments = [self.infer(a.value, env) for a in call.arguments]
        if not isinstance(callee, FunctionT):
            if callee is not UNKNOWN:
                self.report("LR0302", call.position, f"'{describe(callee)}' is not a function")
            return UNKNOWN
        name = callee.name
        expected = {
            "abs": 1,
            "min": 2,
            "max": 2,
            "rotX": 1,
            "rotY": 1,
            "rotZ": 1,
            "transl": 3,
        }[name]
        if len(arguments) != expected:
            self.report("LR0301", call.position, f"'{name}' takes {expected} arguments")
            return UNKNOWN
        if name.startswith("rot"):
            self._expect_type(call.arguments[0].value, arguments[0], ANGLE_T, f"'{name}'")
            return FRAME
        if name == "transl":
            for argument, actual in zip(call.arguments, arguments, strict=True):
                self._expect_type(argument.value, actual, LENGTH_T, "'transl'")
            return FRAME
        if name in ("min", "max"):
            left, right = arguments
            if not compatible(left, right):
                self.mismatch(call.position, left, right, f"'{name}'")
            elif _dimensionless(left) and _dimensionless(right):
                return common_number(left, right)
        return arguments[0]

    def _expect_type(self, node: ast.Expression, actual: Type, expected: Type, what: str) -> None:
        if not compatible(expected, actual, _is_zero(node)):
            self.mismatch(node.position, expected, actual, f"argument of {what}")

    def _binary(self, binary: ast.Binary, env: dict[str, Type]) -> Type:
        left = self.infer(binary.left, env)
        right = self.infer(binary.right, env)
        operator = binary.operator
        beyond = overflow(binary)
        if beyond is not None:
            self.report("LR0302", binary.position, beyond_a_real(binary, beyond))
        if operator in ("&&", "||"):
            for side, node in ((left, binary.left), (right, binary.right)):
                if side not in (BOOLEAN, UNKNOWN):
                    self.report(
                        "LR0303",
                        node.position,
                        f"'{operator}' needs Boolean operands, not {describe(side)}",
                    )
            return BOOLEAN
        if UNKNOWN in (left, right):
            return BOOLEAN if operator in ("==", "!=", "<", "<=", ">", ">=") else UNKNOWN
        if operator == "*" and left == FRAME and right == FRAME:
            return FRAME
        if isinstance(left, QuantityT) and isinstance(right, QuantityT):
            if operator in ("*", "/"):
                dimension = (
                    left.dimension * right.dimension
                    if operator == "*"
                    else left.dimension / right.dimension
                )
                if dimension == ONE:
                    return NUMBER if operator == "/" else common_number(left, right)
                return self.types.quantity(dimension)
            zero = _is_zero(binary.left) or _is_zero(binary.right)
            if left.dimension != right.dimension and not zero:
                self.report(
                    "LR0304",
                    binary.position,
                    f"'{operator}' mixes {describe(left)} and {describe(right)}",
                )
            if operator in ("==", "!=", "<", "<=", ">", ">="):
                return BOOLEAN
            if _dimensionless(left) and _dimensionless(right):
                return common_number(left, right)
            return left if not left.dimension.dimensionless else right
        if operator in ("==", "!="):
            if not compatible(left, right):
                self.mismatch(binary.position, left, right, f"'{operator}'")
            return BOOLEAN
        self.report(
            "LR0302",
            binary.position,
            f"'{operator}' is not defined for {describe(left)} and {describe(right)}",
        )
        return UNKNOWN


def _file(loaded: Loaded) -> str:
    return loaded.unit.package_position.file


def _is_zero(expression: ast.Expression | None) -> bool:
    return isinstance(expression, ast.Quantity) and expression.value == 0 and not expression.unit


def _dimensionless(t: Type) -> bool:
    return isinstance(t, QuantityT) and t.dimension.dimensionless


def _vectors_of_quantities(expected: Type, actual: Type) -> bool:
    return isinstance(expected, VectorT) and isinstance(actual, VectorT)
