"""A UML/P chart (``.sc``) as a LightRocks statechart: states, transitions, events and
actions convert one to one, their Java through :mod:`languages.umlp.java_to_lr`, and the
variables the chart does not declare become parameters (:mod:`languages.umlp.undeclared`).
What LightRocks lacks is refused (LR2121) or, where it does not change what the chart
does, dropped with a warning (LR2122); a call of a method of the class the chart describes
converts with a warning (LR2124).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

from lightrocks.languages.domain.types import BUILTIN_FUNCTIONS
from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.java_to_lr import lr_expression, lr_statements
from lightrocks.languages.umlp.literals import java_string_value
from lightrocks.languages.umlp.printer import stereotype
from lightrocks.languages.umlp.refusal import Findings
from lightrocks.languages.umlp.undeclared import undeclared_parameters
from lightrocks.metamodel import ast
from lightrocks.metamodel.printer import expression as printed
from lightrocks.workbench.diagnostics import Diagnostic, Severity


class _Reaction(NamedTuple):
    """What a transition of either kind reacts with, converted."""

    guard: ast.Expression | None
    stimulus: str
    arguments: tuple[ast.Expression, ...]
    action: tuple[ast.Statement, ...] | None
    postcondition: ast.Expression | None


class _ToLightRocks:
    def __init__(self, unit: n.SCArtifact, name: str) -> None:
        self.unit = unit
        self.name = name
        self.findings = Findings()

    def run(self) -> ast.StatechartUnit:
        unit, chart = self.unit, self.unit.statechart
        for item in unit.type_imports:
            self.findings.dropped(
                item.position,
                f"import {item.name}{'.*' if item.star else ''}: LightRocks imports models, "
                "not Java types; dropped",
            )
        elements = self.elements(chart.elements, top=True)
        declared = undeclared_parameters(chart.elements, chart.position, self.findings)
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
                self.findings.lacks(
                    node.ante_position,
                    f"the ante block of {node.name}, {why}, has no LightRocks counterpart "
                    "(the ante block of the initial state of the chart becomes the chart's "
                    "entry action)",
                )
        modifiers = ("initial",) * node.initial + ("final",) * node.final
        invariant = None
        if node.invariant is not None:
            invariant = self.findings.guarded(lr_expression, node.invariant)
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
        return self.findings.guarded(lr_statements, statement)

    def event(self, event: n.SCEvent | None) -> tuple[str, tuple[ast.Expression, ...]] | None:
        if event is None:
            return "", ()
        if "." in event.name:
            self.findings.lacks(
                event.position,
                f"the qualified event name {event.name} has no LightRocks counterpart",
            )
            return None
        arguments = []
        for argument in event.arguments or ():
            converted = self.findings.guarded(lr_expression, argument)
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
            post = self.findings.guarded(lr_expression, action.post)
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

    def reaction(self, node: n.SCTransition | n.SCInternTransition) -> _Reaction | None:
        """Guard, event and action of a transition; None when one of them is refused."""
        guard = self.findings.guarded(lr_expression, node.pre) if node.pre is not None else None
        event = self.event(node.event)
        converted, action, post = self.transition_action(node.action)
        if event is None or not converted or (node.pre is not None and guard is None):
            return None
        return _Reaction(guard, event[0], event[1], action, post)

    def transition(self, node: n.SCTransition) -> ast.Transition | None:
        self.drop_stereotype(node)
        reaction = self.reaction(node)
        if reaction is None:
            return None
        return ast.Transition(
            node.source,
            node.target,
            reaction.guard,
            reaction.stimulus,
            reaction.arguments,
            reaction.action,
            reaction.postcondition,
            node.position,
            node.source_position,
            node.target_position,
            node.event.position if node.event else ast.NOWHERE,
        )

    def intern_transition(self, node: n.SCInternTransition) -> ast.InternalTransition | None:
        self.drop_stereotype(node)
        if node.event is None:
            self.findings.lacks(
                node.position,
                "an internal transition without event has no LightRocks counterpart "
                "(LightRocks' internal transitions react to an event)",
            )
            return None
        if node.action is not None and node.action.post is not None:
            self.findings.lacks(
                node.action.post.position,
                "a postcondition of an internal transition has no LightRocks counterpart",
            )
            return None
        reaction = self.reaction(node)
        if reaction is None:
            return None
        guard, stimulus, arguments, action, _ = reaction
        return ast.InternalTransition(
            stimulus, guard, arguments, action, node.position, node.event.position
        )

    def action(self, node: n.SCAction) -> ast.Action | None:
        body = node.body
        if body.post is not None:
            self.findings.lacks(
                body.post.position,
                f"a postcondition of an {node.kind} action has no LightRocks counterpart",
            )
            return None
        if body.statement is None:
            return ast.Action(node.kind, (), True, node.position)
        statements = self.statements(body.statement)
        if statements is None:
            return None
        block = isinstance(body.statement, n.JBlock) or len(statements) != 1
        return ast.Action(node.kind, tuple(statements), block, node.position)


def sc_to_lr(unit: n.SCArtifact, name: str) -> tuple[ast.StatechartUnit, list[Diagnostic]]:
    """The LightRocks unit of a UML/P chart (``name``: the chart's name when it has none)
    and the findings of the conversion; the unit is incomplete when an error was found."""
    converter = _ToLightRocks(unit, name)
    result = converter.run()
    return result, converter.findings.items
