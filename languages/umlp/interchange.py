"""Conversion between UML/P statecharts as MontiCore writes them (``.sc``) and LightRocks
(``.lr``), for every construct the two languages share; docs/interchange.md lists what maps
to what.

``.sc → .lr`` translates the Java of guards, actions and invariants into LightRocks
expressions and statements where LightRocks has the construct (names, member access, calls,
the operators both share, literals, assignments, ``x++`` and ``x += e``), and refuses the
rest with a finding at its position (LR2120): a chart whose actions are all expressible
runs in the Python runtime. A call of a method of the class the chart describes converts to
a call, with a warning (LR2124): the LightRocks check reports it until it is replaced.
Variables the chart assigns or tests but does not declare (UML/P takes them from the class
the chart describes) become parameters of the types their uses show (LR2123). ``.lr → .sc``
takes plain statecharts: a LightRocks component (layers, ``<<import>>``, start and end
conditions) or a construct MontiCore's statecharts lack (regions, choice, history, time
events) is refused (LR2121).

Findings: LR2120 (error) Java code without LightRocks counterpart, or LightRocks code
without Java counterpart; LR2121 (error) a construct the target language lacks; LR2122
(warning) something dropped that the target cannot say and that does not change what the
chart does; LR2123 (info) a parameter declared for an undeclared variable; LR2124 (warning)
a call of a method LightRocks does not have.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from lightrocks.languages.domain.types import BUILTIN_FUNCTIONS
from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.printer import expression as java_text
from lightrocks.languages.umlp.printer import inline, print_sc, stereotype
from lightrocks.languages.umlp.typing import JAVA_LANG_TYPES, type_of
from lightrocks.metamodel import ast
from lightrocks.metamodel.convert import PRECEDENCE
from lightrocks.metamodel.printer import expression as printed
from lightrocks.workbench.diagnostics import Diagnostic, Severity

LAYERS = ("task", "skill", "action")
COMPONENT_STEREOTYPES = ("import", "extends")
LR_NUMBER = re.compile(r"(\d+(\.\d+)?|\.\d+)([eE][-+]?\d+)?")
_OPERATORS = tuple(PRECEDENCE)  # the binary operators both languages write alike
_ATOM = 9
_COMPOUND = {"+=": "+", "-=": "-", "*=": "*", "/=": "/", "%=": "%"}
_DEFAULTS = {"Integer": "0", "Real": "0.0", "Boolean": "false", "String": '""'}
_JAVA = {"Integer": "int", "Real": "double", "Boolean": "boolean", "String": "String"}


class Refused(Exception):
    """A construct without counterpart; ``code`` LR2120 or LR2121."""

    def __init__(self, position: ast.Position, message: str, code: str = "LR2120") -> None:
        super().__init__(message)
        self.position = position
        self.message = message
        self.code = code


@dataclass
class Conversion:
    """The result of converting one file: the target's file name and text (``None`` when an
    error refuses the conversion) and the findings."""

    name: str
    text: str | None
    findings: list[Diagnostic] = field(default_factory=list)
    unit: object = None


class _Findings:
    def __init__(self) -> None:
        self.items: list[Diagnostic] = []

    def add(self, position: ast.Position, code: str, severity: Severity, message: str) -> None:
        self.items.append(Diagnostic.at(position, code, severity, message))

    def refused(self, problem: Refused) -> None:
        self.add(problem.position, problem.code, Severity.ERROR, problem.message)

    def dropped(self, position: ast.Position, message: str) -> None:
        self.add(position, "LR2122", Severity.WARNING, message)


# --- Java strings ---------------------------------------------------------------------------

_ESCAPES = {"b": "\b", "t": "\t", "n": "\n", "f": "\f", "r": "\r", '"': '"', "'": "'", "\\": "\\"}


def java_string_value(literal: str) -> str:
    """The value of a Java string literal (with its quotes)."""
    body = literal[1:-1]

    def unescape(match: re.Match[str]) -> str:
        text = match.group(0)
        if text[1] == "u":
            return chr(int(text.lstrip("\\u")[:4], 16))
        if text[1] in "01234567":
            return chr(int(text[1:], 8))
        return _ESCAPES.get(text[1], text[1])

    return re.sub(r"\\(u+[0-9a-fA-F]{4}|[0-3][0-7]{0,2}|[4-7][0-7]?|.)", unescape, body)


def java_string_literal(value: str) -> str:
    """A Java string literal whose value is ``value``."""
    out = []
    for char in value:
        reverse = {v: k for k, v in _ESCAPES.items() if k != "'"}
        if char in reverse:
            out.append("\\" + reverse[char])
        elif ord(char) < 0x20:
            out.append(f"\\u{ord(char):04x}")
        else:
            out.append(char)
    return '"' + "".join(out) + '"'


# --- .sc to .lr: expressions and statements ------------------------------------------------


def lr_expression(node: n.JExpression) -> ast.Expression:
    """The LightRocks expression of a Java expression; raises :class:`Refused`."""
    where = node.position
    match node:
        case n.JLiteral(kind="boolean", text=text):
            return ast.BooleanLiteral(text == "true", where)
        case n.JLiteral(kind="number", text=text):
            if not LR_NUMBER.fullmatch(text):
                raise Refused(where, f"the number {text} has no LightRocks counterpart")
            return ast.Quantity(float(text), "", text, where)
        case n.JLiteral(kind="string", text=text):
            value = java_string_value(text)
            if value.endswith("\\"):
                raise Refused(where, f"the string {text} cannot be written in LightRocks")
            return ast.StringLiteral(value, where)
        case n.JLiteral(kind=kind, text=text):
            raise Refused(where, f"the {kind} literal {text} has no LightRocks counterpart")
        case n.JName(name=name):
            return ast.Name(name, where)
        case n.JFieldAccess(target=target, name=name):
            return ast.Member(lr_expression(target), name, where)
        case n.JCall(target=target, arguments=arguments):
            values = tuple(ast.Argument(lr_expression(a), "", a.position) for a in arguments)
            return ast.Call(lr_expression(target), values, where)
        case n.JArrayAccess(target=target, index=index):
            return ast.Index(lr_expression(target), lr_expression(index), where)
        case n.JBracket(expression=inner):
            return lr_expression(inner)
        case n.JPrefix(operator=operator, operand=operand) if operator in ("!", "+", "-"):
            operand_lr = lr_expression(operand)
            if operator == "-" and isinstance(operand_lr, ast.Quantity):
                text = "-" + operand_lr.text
                return ast.Quantity(-operand_lr.value, "", text, where)
            return ast.Unary(operator, operand_lr, where)
        case n.JBinary(operator=operator, left=left, right=right) if operator in _OPERATORS:
            return ast.Binary(operator, lr_expression(left), lr_expression(right), where)
    raise Refused(where, f"the Java expression '{java_text(node)}' has no LightRocks counterpart")


def _increment(target: n.JExpression, operator: str, where: ast.Position) -> ast.Assignment:
    value = lr_expression(target)
    one = ast.Quantity(1.0, "", "1", where)
    return ast.Assignment(value, ast.Binary(operator, value, one, where), where)


def _assignable(target: n.JExpression) -> bool:
    while isinstance(target, n.JFieldAccess | n.JArrayAccess):
        target = target.target
    return isinstance(target, n.JName)


def lr_statements(node: n.JStatement) -> list[ast.Statement]:
    """The LightRocks statements of a Java statement (a block's in order, an empty
    statement none); raises :class:`Refused`."""
    where = node.position
    match node:
        case n.JBlock(statements=statements):
            return [s for statement in statements for s in lr_statements(statement)]
        case n.JEmpty():
            return []
        case n.JExpressionStatement(expression=value):
            match value:
                case n.JAssignment(operator="=", target=target, value=assigned) if _assignable(
                    target
                ):
                    return [ast.Assignment(lr_expression(target), lr_expression(assigned), where)]
                case n.JAssignment(operator=operator, target=target, value=assigned) if (
                    operator in _COMPOUND and _assignable(target)
                ):
                    lr_target = lr_expression(target)
                    binary = ast.Binary(
                        _COMPOUND[operator], lr_target, lr_expression(assigned), where
                    )
                    return [ast.Assignment(lr_target, binary, where)]
                case (
                    n.JPostfix(operator=operator, operand=target)
                    | n.JPrefix(operator=operator, operand=target)
                ) if operator in ("++", "--") and _assignable(target):
                    return [_increment(target, operator[0], where)]
            return [ast.ExpressionStatement(lr_expression(value), where)]
    kind = {
        n.JLocalVariable: "local variable declaration",
        n.JIf: "if statement",
        n.JWhile: "while loop",
        n.JDoWhile: "do-while loop",
        n.JFor: "for loop",
        n.JForEach: "for loop",
        n.JSwitch: "switch statement",
        n.JJump: "jump statement",
        n.JReturn: "return statement",
    }.get(type(node), "statement")
    raise Refused(where, f"the Java {kind} '{inline(node)}' has no LightRocks counterpart")


# --- .sc to .lr: the chart -------------------------------------------------------------------


class _ToLightRocks:
    def __init__(self, unit: n.SCArtifact, name: str) -> None:
        self.unit = unit
        self.name = name
        self.findings = _Findings()
        self.variables: dict[str, set[str]] = {}  # undeclared variable -> LightRocks types
        self.known: dict[str, str] = {}  # the guesses so far, as Java types

    def guarded(self, convert, *args):
        """``convert(*args)``, or None after recording why it is refused."""
        try:
            return convert(*args)
        except Refused as problem:
            self.findings.refused(problem)
            return None

    def run(self) -> ast.StatechartUnit:
        unit, chart = self.unit, self.unit.statechart
        for item in unit.type_imports:
            self.findings.dropped(
                item.position,
                f"import {item.name}{'.*' if item.star else ''}: LightRocks imports models, "
                "not Java types; dropped",
            )
        elements = self.elements(chart.elements, top=True)
        self.infer(chart.elements)
        declared = self.parameters(chart.position)
        if declared is not None:
            elements.insert(0, declared)
        stereotypes = self.stereotypes(chart.stereotype)
        name = chart.name or self.name
        lr_chart = ast.Statechart(name, tuple(elements), stereotypes, chart.position)
        self.methods(lr_chart)
        return ast.StatechartUnit(unit.package, (), lr_chart, unit.file, unit.package_position)

    def methods(self, chart: ast.Statechart) -> None:
        """Warn of calls of methods of the class the chart describes: LightRocks calls only
        its built-in functions, so its check reports them (LR0103) until they are replaced."""
        for node in ast.walk(chart.elements):
            if not isinstance(node, ast.Call):
                continue
            function = node.function
            if isinstance(function, ast.Name) and function.name in BUILTIN_FUNCTIONS:
                continue
            self.findings.add(
                node.position,
                "LR2124",
                Severity.WARNING,
                f"{printed(node)} calls a method of the class the chart describes; LightRocks "
                "has no such function, so its check reports the call until it is replaced",
            )

    def stereotypes(self, values: Sequence[n.StereoValue]) -> tuple[ast.Stereotype, ...]:
        return tuple(
            ast.Stereotype(
                v.name,
                java_string_value(v.content) if v.content is not None else None,
                v.position,
            )
            for v in values
        )

    def elements(self, elements: Sequence[n.SCElement], top: bool) -> list:
        result: list = []
        events: list[ast.Event] = []
        for element in elements:
            match element:
                case n.SCFuncEventDef():
                    if not events:
                        result.append(None)  # where the events block goes
                    events.append(self.event_definition(element))
                case n.SCCompleteness(complete=complete):
                    marker = "(c)" if complete else "(...)"
                    self.findings.dropped(
                        element.position,
                        f"the completeness marker {marker} says whether a list of the chart is "
                        "complete; LightRocks has no such marker: dropped",
                    )
                case n.SCState():
                    result += self.state(element, top)
                case n.SCTransition():
                    converted = self.transition(element)
                    if converted is not None:
                        result.append(converted)
                case n.SCInternTransition():
                    converted = self.intern_transition(element)
                    if converted is not None:
                        result.append(converted)
                case n.SCAction():
                    converted = self.action(element)
                    if converted is not None:
                        result.append(converted)
        if events:
            where = next(e.position for e in elements if isinstance(e, n.SCFuncEventDef))
            result[result.index(None)] = ast.EventBlock(tuple(events), where)
        return result

    def event_definition(self, node: n.SCFuncEventDef) -> ast.Event:
        if node.return_type is not None or node.parameters:
            self.findings.dropped(
                node.position,
                f"event {node.name}: LightRocks events have no parameters and no return type; "
                "declared by name",
            )
        return ast.Event(node.name, node.position)

    def state(self, node: n.SCState, top: bool) -> list:
        before = []
        if node.ante is not None:
            if top and node.initial:
                statements = self.statements(n.JBlock(node.ante, node.ante_position))
                if statements is not None:
                    before.append(ast.Action("entry", tuple(statements), True, node.ante_position))
            else:
                why = "a state that is not initial" if not node.initial else "a nested state"
                self.findings.refused(
                    Refused(
                        node.ante_position,
                        f"the ante block of {node.name}, {why}, has no LightRocks counterpart "
                        "(the ante block of the initial state of the chart becomes the chart's "
                        "entry action)",
                        "LR2121",
                    )
                )
        modifiers = ("initial",) * node.initial + ("final",) * node.final
        invariant = None
        if node.invariant is not None:
            invariant = self.guarded(lr_expression, node.invariant)
        body = None if node.body is None else tuple(self.elements(node.body, top=False))
        state = ast.State(
            node.name,
            self.stereotypes(node.stereotype),
            modifiers,
            (),
            invariant,
            body,
            node.position,
        )
        return [*before, state]

    def statements(self, statement: n.JStatement) -> list[ast.Statement] | None:
        return self.guarded(lr_statements, statement)

    def event(self, event: n.SCEvent | None) -> tuple[str, tuple[ast.Expression, ...]] | None:
        if event is None:
            return "", ()
        if "." in event.name:
            self.findings.refused(
                Refused(
                    event.position,
                    f"the qualified event name {event.name} has no LightRocks counterpart",
                    "LR2121",
                )
            )
            return None
        arguments = []
        for argument in event.arguments or ():
            converted = self.guarded(lr_expression, argument)
            if converted is None:
                return None
            arguments.append(converted)
        return event.name, tuple(arguments)

    def transition_action(
        self, action: n.SCActionBody | None
    ) -> tuple[bool, tuple[ast.Statement, ...] | None, ast.Expression | None]:
        """(converted, LightRocks action, postcondition)."""
        if action is None:
            return True, None, None
        statements: list[ast.Statement] | None = []
        if action.statement is not None:
            statements = self.statements(action.statement)
        post = None
        if action.post is not None:
            post = self.guarded(lr_expression, action.post)
            if post is None:
                return False, None, None
        return statements is not None, tuple(statements or ()), post

    def drop_stereotype(self, node: n.SCTransition | n.SCInternTransition) -> None:
        if node.stereotype:
            self.findings.dropped(
                node.position,
                f"LightRocks transitions carry no stereotypes: {stereotype(node.stereotype)} "
                "dropped",
            )

    def transition(self, node: n.SCTransition) -> ast.Transition | None:
        self.drop_stereotype(node)
        guard = self.guarded(lr_expression, node.pre) if node.pre is not None else None
        event = self.event(node.event)
        converted, action, post = self.transition_action(node.action)
        if event is None or not converted or (node.pre is not None and guard is None):
            return None
        return ast.Transition(
            node.source,
            node.target,
            guard,
            event[0],
            event[1],
            action,
            post,
            node.position,
            node.source_position,
            node.target_position,
            node.event.position if node.event else ast.NOWHERE,
        )

    def intern_transition(self, node: n.SCInternTransition) -> ast.InternalTransition | None:
        self.drop_stereotype(node)
        if node.event is None:
            self.findings.refused(
                Refused(
                    node.position,
                    "an internal transition without event has no LightRocks counterpart "
                    "(LightRocks' internal transitions react to an event)",
                    "LR2121",
                )
            )
            return None
        if node.action is not None and node.action.post is not None:
            self.findings.refused(
                Refused(
                    node.action.post.position,
                    "a postcondition of an internal transition has no LightRocks counterpart",
                    "LR2121",
                )
            )
            return None
        guard = self.guarded(lr_expression, node.pre) if node.pre is not None else None
        event = self.event(node.event)
        converted, action, _ = self.transition_action(node.action)
        if event is None or not converted or (node.pre is not None and guard is None):
            return None
        return ast.InternalTransition(
            event[0], guard, event[1], action, node.position, node.event.position
        )

    def action(self, node: n.SCAction) -> ast.Action | None:
        body = node.body
        if body.post is not None:
            self.findings.refused(
                Refused(
                    body.post.position,
                    f"a postcondition of an {node.kind} action has no LightRocks counterpart",
                    "LR2121",
                )
            )
            return None
        if body.statement is None:
            return ast.Action(node.kind, (), True, node.position)
        statements = self.statements(body.statement)
        if statements is None:
            return None
        block = isinstance(body.statement, n.JBlock) or len(statements) != 1
        return ast.Action(node.kind, tuple(statements), block, node.position)

    # -- variables the chart does not declare ----------------------------------------------

    def infer(self, elements: Sequence[n.SCElement]) -> None:
        """Guess the types of undeclared variables from their uses, again while a guess
        types more (``n = n + 1`` is an Integer once ``n = 0`` is)."""
        parts = list(_java_parts(elements))
        known: dict[str, str] = {}
        for _ in range(len(parts) + 1):
            for part in parts:
                if isinstance(part, tuple):  # (expression, needs a boolean)
                    self.condition(*part)
                else:
                    self.statement_types(part)
            guessed = {
                name: _JAVA[kind]
                for name, kinds in self.variables.items()
                if (kind := _joined(kinds)) is not None
            }
            if guessed == known:
                return
            known = self.known = guessed

    def note(self, name: str, kind: str | None) -> None:
        if kind is not None and name not in JAVA_LANG_TYPES:
            self.variables.setdefault(name, set()).add(kind)

    def condition(self, node: n.JExpression, boolean: bool) -> None:
        """Types shown by an expression in a condition (guard, invariant, postcondition)."""
        match node:
            case n.JName(name=name) if boolean:
                self.note(name, "Boolean")
            case n.JBracket(expression=inner):
                self.condition(inner, boolean)
            case n.JPrefix(operator="!", operand=operand):
                self.condition(operand, True)
            case n.JBinary(operator=operator, left=left, right=right):
                if operator in ("&&", "||"):
                    self.condition(left, True)
                    self.condition(right, True)
                else:
                    self.compared(left, right)
                    self.compared(right, left)
                    self.condition(left, False)
                    self.condition(right, False)

    def compared(self, name: n.JExpression, other: n.JExpression) -> None:
        if isinstance(name, n.JName):
            self.note(name.name, _lr_type(type_of(other, names=self.known)))

    def statement_types(self, node: n.JStatement) -> None:
        match node:
            case n.JBlock(statements=statements):
                for statement in statements:
                    self.statement_types(statement)
            case n.JExpressionStatement(expression=value):
                match value:
                    case n.JAssignment(operator=operator, target=n.JName(name=name), value=v):
                        kind = _lr_type(type_of(v, names=self.known))
                        self.note(name, kind if operator == "=" else kind or "Integer")
                    case (
                        n.JPostfix(operand=n.JName(name=name))
                        | n.JPrefix(operator="++" | "--", operand=n.JName(name=name))
                    ):
                        self.note(name, "Integer")

    def parameters(self, where: ast.Position) -> ast.ParameterBlock | None:
        declared = []
        for name, kinds in self.variables.items():
            kind = _joined(kinds)
            if kind is None:
                continue
            default = _DEFAULTS[kind]
            declared.append(
                ast.Parameter(kind, name, _literal(kind, default), where),
            )
            self.findings.add(
                where,
                "LR2123",
                Severity.INFO,
                f"'{name}' is not declared in the UML/P chart (it belongs to the class the chart "
                f"describes): declared as parameter {kind} {name} = {default}",
            )
        return ast.ParameterBlock(tuple(declared), where) if declared else None


def _java_parts(elements: Sequence[n.SCElement]) -> Iterator[object]:
    """Statements, and (condition, is Boolean) pairs, of every element at any depth."""
    for element in elements:
        match element:
            case n.SCState():
                if element.ante is not None:
                    yield n.JBlock(element.ante)
                if element.invariant is not None:
                    yield element.invariant, True
                yield from _java_parts(element.body or ())
            case n.SCTransition() | n.SCInternTransition():
                if element.pre is not None:
                    yield element.pre, True
                if element.action is not None:
                    if element.action.statement is not None:
                        yield element.action.statement
                    if element.action.post is not None:
                        yield element.action.post, True
            case n.SCAction(body=body):
                if body.statement is not None:
                    yield body.statement


def _lr_type(java: str) -> str | None:
    if java in ("int", "long", "short", "byte"):
        return "Integer"
    if java in ("double", "float"):
        return "Real"
    return {"boolean": "Boolean", "String": "String"}.get(java)


def _joined(kinds: set[str]) -> str | None:
    if len(kinds) == 1:
        return next(iter(kinds))
    if kinds == {"Integer", "Real"}:
        return "Real"
    return None


def _literal(kind: str, text: str) -> ast.Expression:
    if kind == "Boolean":
        return ast.BooleanLiteral(False)
    if kind == "String":
        return ast.StringLiteral("")
    return ast.Quantity(float(text), "", text)


def sc_to_lr(unit: n.SCArtifact, name: str) -> tuple[ast.StatechartUnit, list[Diagnostic]]:
    """The LightRocks unit of a UML/P chart (``name``: the chart's name when it has none)
    and the findings of the conversion; the unit is incomplete when an error was found."""
    converter = _ToLightRocks(unit, name)
    result = converter.run()
    return result, converter.findings.items


# --- .lr to .sc ----------------------------------------------------------------------------


def _precedence(node: ast.Expression) -> int:
    if isinstance(node, ast.Binary):
        return PRECEDENCE[node.operator]
    return _ATOM - 1 if isinstance(node, ast.Unary) else _ATOM


def _bracketed(node: ast.Expression, needed: bool) -> n.JExpression:
    converted = java_expression(node)
    return n.JBracket(converted, node.position) if needed else converted


def _number_text(node: ast.Quantity) -> str:
    """The magnitude of a unitless number as Java writes it."""
    text = node.text.lstrip("-") if node.text else ""
    if LR_NUMBER.fullmatch(text):
        return text
    value = abs(node.value)
    return str(int(value)) if value.is_integer() else repr(value)


def java_expression(node: ast.Expression) -> n.JExpression:
    """The Java expression of a LightRocks expression, with the brackets Java's precedence
    needs; raises :class:`Refused`."""
    where = node.position
    match node:
        case ast.Quantity(unit=unit, value=value, text=text) if not unit:
            literal = n.JLiteral("number", _number_text(node), where)
            if value < 0 or text.startswith("-"):
                return n.JPrefix("-", literal, where)
            return literal
        case ast.Quantity(text=text):
            raise Refused(where, f"the quantity {text} has a unit; Java numbers have none")
        case ast.BooleanLiteral(value=value):
            return n.JLiteral("boolean", "true" if value else "false", where)
        case ast.StringLiteral(value=value):
            return n.JLiteral("string", java_string_literal(value), where)
        case ast.Name(name=name):
            return n.JName(name, where)
        case ast.Member(target=target, name=name):
            return n.JFieldAccess(_bracketed(target, _precedence(target) < _ATOM), name, where)
        case ast.Index(target=target, index=index):
            return n.JArrayAccess(
                _bracketed(target, _precedence(target) < _ATOM), java_expression(index), where
            )
        case ast.Call(function=function, arguments=arguments):
            named = [a for a in arguments if a.name]
            if named:
                raise Refused(
                    named[0].position,
                    f"the named argument {named[0].name} = … has no Java counterpart",
                )
            values = tuple(java_expression(a.value) for a in arguments)
            return n.JCall(_bracketed(function, _precedence(function) < _ATOM), values, where)
        case ast.Unary(operator=operator, operand=operand):
            return n.JPrefix(operator, _bracketed(operand, _precedence(operand) < _ATOM), where)
        case ast.Binary(operator=operator, left=left, right=right):
            level = PRECEDENCE[operator]
            return n.JBinary(
                operator,
                _bracketed(left, _precedence(left) < level),
                _bracketed(right, _precedence(right) <= level),
                where,
            )
        case ast.VectorLiteral():
            raise Refused(where, "a vector literal has no Java counterpart in a UML/P chart")
    raise Refused(where, f"the LightRocks expression {type(node).__name__} has no Java counterpart")


def java_statement(node: ast.Statement) -> n.JStatement:
    where = node.position
    match node:
        case ast.Assignment(target=target, value=value):
            assignment = n.JAssignment("=", java_expression(target), java_expression(value), where)
            return n.JExpressionStatement(assignment, where)
        case ast.ExpressionStatement(expression=value):
            return n.JExpressionStatement(java_expression(value), where)
    raise Refused(where, f"the statement {type(node).__name__} has no Java counterpart")


class _ToUMLP:
    def __init__(self, unit: ast.StatechartUnit) -> None:
        self.unit = unit
        self.findings = _Findings()

    def guarded(self, convert, *args):
        try:
            return convert(*args)
        except Refused as problem:
            self.findings.refused(problem)
            return None

    def refuse(self, position: ast.Position, message: str) -> None:
        self.findings.refused(Refused(position, message, "LR2121"))

    def run(self) -> n.SCArtifact:
        unit, chart = self.unit, self.unit.statechart
        for item in unit.imports:
            self.refuse(
                item.position,
                f"import {item.name}: a plain statechart imports no models; UML/P imports "
                "Java types",
            )
        stereotype = self.stereotypes(chart.stereotypes, "statechart")
        entry: list[n.JStatement] = []
        elements = []
        for element in chart.elements:
            if isinstance(element, ast.Action) and element.kind == "entry":
                converted = self.block(element.statements)
                entry += converted or []
                continue
            if isinstance(element, ast.Action | ast.InternalTransition):
                what = (
                    f"{element.kind} action"
                    if isinstance(element, ast.Action)
                    else ("internal transition")
                )
                self.refuse(
                    element.position,
                    f"an {what} of the statechart itself has no UML/P counterpart (UML/P "
                    "puts them in states)",
                )
                continue
            elements += self.element(element)
        if any(isinstance(e, ast.Action) and e.kind == "entry" for e in chart.elements):
            elements = self.ante(elements, entry, chart)
        sc_chart = n.SCStatechart(
            chart.name, tuple(elements), stereotype, "statechart", chart.position
        )
        return n.artifact(unit.package, (), sc_chart, unit.file, unit.package_position)

    def ante(self, elements: list, entry: list[n.JStatement], chart: ast.Statechart) -> list:
        """The chart's entry action as the ante block of its initial state."""
        initial = [i for i, e in enumerate(elements) if isinstance(e, n.SCState) and e.initial]
        where = next(e.position for e in chart.elements if isinstance(e, ast.Action))
        if len(initial) != 1:
            self.refuse(
                where,
                "the entry action of a statechart becomes the ante block of its initial state, "
                "and the chart has no single initial state on its top level",
            )
            return elements
        state = elements[initial[0]]
        if state.ante is not None:
            entry = [*entry, *state.ante]
        elements[initial[0]] = n.SCState(
            state.name,
            state.initial,
            state.final,
            state.stereotype,
            tuple(entry),
            state.invariant,
            state.body,
            state.position,
            state.name_position,
            state.body_position,
            where,
        )
        return elements

    def stereotypes(
        self, stereotypes: Sequence[ast.Stereotype], where: str
    ) -> tuple[n.StereoValue, ...]:
        values = []
        for s in stereotypes:
            if s.name in LAYERS or s.name in COMPONENT_STEREOTYPES:
                self.refuse(
                    s.position,
                    f"<<{s.name}>> makes a LightRocks component, not a plain statechart: "
                    "only plain statecharts convert to UML/P",
                )
                continue
            content = java_string_literal(s.value) if s.value is not None else None
            values.append(n.StereoValue(s.name, content, s.position))
        return tuple(values)

    def block(self, statements: Sequence[ast.Statement]) -> list[n.JStatement] | None:
        converted = [self.guarded(java_statement, s) for s in statements]
        return None if None in converted else converted

    def expression(self, node: ast.Expression | None) -> n.JExpression | None:
        return None if node is None else self.guarded(java_expression, node)

    def element(self, node: object) -> list:
        match node:
            case ast.ParameterBlock(parameters=parameters):
                for parameter in parameters:
                    self.findings.dropped(
                        parameter.position,
                        f"parameter {parameter.name}: UML/P charts declare no variables (they "
                        "are attributes of the class the chart describes): dropped",
                    )
                return []
            case ast.EventBlock(events=events):
                return [n.SCFuncEventDef(e.name, None, (), e.position) for e in events]
            case ast.State():
                state = self.state(node)
                return [state] if state is not None else []
            case ast.Transition():
                transition = self.transition(node)
                return [transition] if transition is not None else []
            case ast.InternalTransition():
                transition = self.internal(node)
                return [transition] if transition is not None else []
            case ast.Action():
                return [self.action(node)] if node.statements is not None else []
            case ast.Condition(kind=kind, name=name):
                self.refuse(
                    node.position,
                    f"the {kind} condition {name} belongs to a LightRocks component; a UML/P "
                    "chart has none",
                )
            case ast.Region(name=name):
                self.refuse(
                    node.position,
                    f"region {name}: MontiCore's UML/P statecharts have no orthogonal regions",
                )
            case ast.Pseudostate(kind=kind, name=name):
                self.refuse(
                    node.position,
                    f"{kind} {name}: MontiCore's UML/P statecharts have no {kind} pseudostates",
                )
            case ast.Invariant():
                self.refuse(
                    node.position,
                    "an invariant statement stands beside other elements of a state; UML/P "
                    "writes the invariant after the state's name",
                )
            case _:
                self.refuse(
                    getattr(node, "position", ast.NOWHERE),
                    f"{type(node).__name__} has no UML/P counterpart",
                )
        return []

    def state(self, node: ast.State) -> n.SCState | None:
        if node.arguments:
            self.refuse(node.position, f"the arguments of {node.name} bind an imported chart")
        stereotype = self.stereotypes(node.stereotypes, "state")
        invariant = node.invariant
        body = None
        if node.body is not None:
            elements = []
            for element in node.body:
                if isinstance(element, ast.Invariant) and invariant is None:
                    invariant = element.expression
                    continue
                elements += self.element(element)
            body = tuple(elements)
        return n.SCState(
            node.name,
            node.is_initial,
            node.is_final,
            stereotype,
            None,
            self.expression(invariant),
            body,
            node.position,
            node.position,
            node.position,
        )

    def event(
        self, stimulus: str, arguments: Sequence[ast.Expression], where: ast.Position
    ) -> n.SCEvent | None:
        if not stimulus:
            return None
        if stimulus == "after" and len(arguments) == 1:
            self.refuse(
                where,
                "the time event after(…) has no counterpart in MontiCore's UML/P statecharts",
            )
            return None
        values = tuple(self.expression(a) for a in arguments)
        return n.SCEvent(stimulus, values or None, where)

    def action_body(
        self, action: tuple[ast.Statement, ...] | None, post: ast.Expression | None
    ) -> n.SCActionBody | None:
        if action is None and post is None:
            return None
        statements = self.block(action or ())
        block = n.JBlock(tuple(statements or ()))
        return n.SCActionBody(block, self.expression(post))

    def transition(self, node: ast.Transition) -> n.SCTransition | None:
        if node.target_history:
            self.refuse(
                node.position,
                f"{node.target}.{node.target_history}: MontiCore's UML/P statecharts have no "
                "history",
            )
            return None
        return n.SCTransition(
            node.source,
            node.target,
            self.expression(node.guard),
            self.event(node.stimulus, node.stimulus_arguments, node.stimulus_position),
            self.action_body(node.action, node.postcondition),
            (),
            node.position,
            node.source_position,
            node.target_position,
        )

    def internal(self, node: ast.InternalTransition) -> n.SCInternTransition:
        return n.SCInternTransition(
            self.expression(node.guard),
            self.event(node.stimulus, node.stimulus_arguments, node.stimulus_position),
            self.action_body(node.action, None),
            (),
            node.position,
        )

    def action(self, node: ast.Action) -> n.SCAction:
        statements = self.block(node.statements) or []
        if node.block or len(statements) != 1:
            statement: n.JStatement = n.JBlock(tuple(statements), node.position)
        else:
            statement = statements[0]
        return n.SCAction(node.kind, n.SCActionBody(statement, None, node.position), node.position)


def lr_to_sc(unit: ast.StatechartUnit) -> tuple[n.SCArtifact, list[Diagnostic]]:
    """The UML/P chart of a plain LightRocks statechart and the findings of the conversion;
    the chart is incomplete when an error was found."""
    converter = _ToUMLP(unit)
    if any(ast.is_extension(node) for node in ast.walk(unit)):
        node = next(node for node in ast.walk(unit) if ast.is_extension(node))
        converter.refuse(
            getattr(node, "position", ast.NOWHERE),
            f"'{type(node).__name__}' comes from a language extension; UML/P has no counterpart",
        )
    result = converter.run()
    return result, converter.findings.items


# --- files ------------------------------------------------------------------------------------


def _has_errors(findings: Sequence[Diagnostic]) -> bool:
    return any(f.severity is Severity.ERROR for f in findings)


def convert_sc_to_lr(path: Path, text: str, shown: str) -> Conversion:
    """``A.sc`` to the text of ``<chart name>.lr`` (``None`` when refused)."""
    from lightrocks.languages.lightrocks.printer import print_statechart
    from lightrocks.languages.umlp.syntax import parse_sc

    unit = parse_sc(text, shown)
    name = unit.statechart.name or path.stem
    result, findings = sc_to_lr(unit, name)
    if _has_errors(findings):
        return Conversion(f"{name}.lr", None, findings, result)
    return Conversion(f"{name}.lr", print_statechart(result), findings, result)


def convert_lr_to_sc(path: Path, text: str, shown: str) -> Conversion:
    """A plain ``A.lr`` to the text of ``A.sc`` (``None`` when refused)."""
    from lightrocks.languages.lightrocks.syntax import parse_statechart

    unit = parse_statechart(text, shown)
    result, findings = lr_to_sc(unit)
    name = f"{unit.statechart.name or path.stem}.sc"
    if _has_errors(findings):
        return Conversion(name, None, findings, result)
    return Conversion(name, print_sc(result), findings, result)
