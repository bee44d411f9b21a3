"""A plain LightRocks statechart (``.lr``) as a UML/P chart: states, transitions, events and
actions convert one to one, their expressions and statements through
:mod:`languages.umlp.lr_to_java`, the chart's entry action as the ante block of its initial
state. A LightRocks component (layers, ``<<import>>``, start and end conditions) or a
construct MontiCore's statecharts lack (regions, choice, history, time events) is refused
(LR2121); parameters are dropped with a warning (LR2122).
"""

from __future__ import annotations

from collections.abc import Sequence

from lightrocks.languages.lightrocks.model import COMPONENT_STEREOTYPES
from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.literals import java_string_literal
from lightrocks.languages.umlp.lr_to_java import java_expression, java_statement
from lightrocks.languages.umlp.refusal import Findings
from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Diagnostic


class _ToUMLP:
    def __init__(self, unit: ast.StatechartUnit) -> None:
        self.unit = unit
        self.findings = Findings()

    def run(self) -> n.SCArtifact:
        unit, chart = self.unit, self.unit.statechart
        for item in unit.imports:
            self.findings.lacks(
                item.position,
                f"import {item.name}: a plain statechart imports no models; UML/P imports "
                "Java types",
            )
        stereotype = self.stereotypes(chart.stereotypes)
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
                    else "internal transition"
                )
                self.findings.lacks(
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
            self.findings.lacks(
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

    def stereotypes(self, stereotypes: Sequence[ast.Stereotype]) -> tuple[n.StereoValue, ...]:
        values = []
        for s in stereotypes:
            if s.name in COMPONENT_STEREOTYPES:
                self.findings.lacks(
                    s.position,
                    f"<<{s.name}>> makes a LightRocks component, not a plain statechart: "
                    "only plain statecharts convert to UML/P",
                )
                continue
            content = java_string_literal(s.value) if s.value is not None else None
            values.append(n.StereoValue(s.name, content, s.position))
        return tuple(values)

    def block(self, statements: Sequence[ast.Statement]) -> list[n.JStatement] | None:
        converted = [self.findings.guarded(java_statement, s) for s in statements]
        return None if None in converted else converted

    def expression(self, node: ast.Expression | None) -> n.JExpression | None:
        return None if node is None else self.findings.guarded(java_expression, node)

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
                self.findings.lacks(
                    node.position,
                    f"the {kind} condition {name} belongs to a LightRocks component; a UML/P "
                    "chart has none",
                )
            case ast.Region(name=name):
                self.findings.lacks(
                    node.position,
                    f"region {name}: MontiCore's UML/P statecharts have no orthogonal regions",
                )
            case ast.Pseudostate(kind=kind, name=name):
                self.findings.lacks(
                    node.position,
                    f"{kind} {name}: MontiCore's UML/P statecharts have no {kind} pseudostates",
                )
            case ast.Invariant():
                self.findings.lacks(
                    node.position,
                    "an invariant statement stands beside other elements of a state; UML/P "
                    "writes the invariant after the state's name",
                )
            case _:
                self.findings.lacks(
                    getattr(node, "position", ast.NOWHERE),
                    f"{type(node).__name__} has no UML/P counterpart",
                )
        return []

    def state(self, node: ast.State) -> n.SCState | None:
        if node.arguments:
            self.findings.lacks(
                node.position, f"the arguments of {node.name} bind an imported chart"
            )
        stereotype = self.stereotypes(node.stereotypes)
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
            self.findings.lacks(
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
            self.findings.lacks(
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
        converter.findings.lacks(
            getattr(node, "position", ast.NOWHERE),
            f"'{type(node).__name__}' comes from a language extension; UML/P has no counterpart",
        )
    result = converter.run()
    return result, converter.findings.items
