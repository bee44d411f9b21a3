"""Canonical text of LightRocks action components (``.lr``), used by ``lightrocks fmt``.

Elements keep their order (declaration order decides ties in the semantics); layout is
fixed: two-space indentation, one element per line, a blank line between groups of
different kinds and around blocks. Comments of the source are re-attached as described in
:mod:`metamodel.printer`.
"""

from __future__ import annotations

from collections.abc import Sequence

from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.comments import Comments
from lightrocks.metamodel.printer import (
    Writer,
    argument_parts,
    block,
    expression,
    fit,
    header,
    parameter,
    statement,
    stereotypes,
)
from lightrocks.workbench.extensions import extension_of


def format_statechart_text(text: str, file: str) -> str:
    """The canonical text of a ``.lr`` file with its comments; raises ``SyntaxProblem``."""
    return print_statechart(parse_statechart(text, file), Comments(text))


def print_statechart(unit: ast.StatechartUnit, comments: Comments | None = None) -> str:
    """The canonical text of ``unit``; ``comments`` are those of the text it was parsed from."""
    writer = Writer(comments)
    header(writer, unit)
    chart = unit.statechart
    writer.item(chart.position, "statechart")
    _body(writer, [_prefixed(chart.stereotypes, f"statechart {chart.name}")], chart)
    return writer.finish()


def _prefixed(items: Sequence[ast.Stereotype], text: str) -> str:
    return f"{stereotypes(items)} {text}" if items else text


def _body(
    writer: Writer, head: Sequence[str], node: ast.Statechart | ast.State | ast.Region
) -> None:
    """The elements of a statechart, hierarchical state or region in braces after ``head``."""
    elements = node.body or () if isinstance(node, ast.State) else node.elements
    if not elements and not writer.comments_within(node.position):
        writer.line([*head[:-1], head[-1] + " { }"], node.position.line)
        return
    writer.open([*head[:-1], head[-1] + " {"], node.position.line)
    for element in elements:
        _element(writer, element)
    writer.close(node.position)


def _element(writer: Writer, node: ast.Element | ast.ParameterBlock | ast.EventBlock) -> None:
    where = node.position
    match node:
        case ast.ParameterBlock(parameters=parameters):
            writer.item(where, "parameters", spaced=True)
            if not parameters and not writer.comments_within(where):
                writer.line(["parameters { }"], where.line)
                return
            writer.open(["parameters {"], where.line)
            for item in parameters:
                writer.item(item.position, "parameter")
                writer.line([parameter(item)], item.position.line)
            writer.close(where)
        case ast.Condition(kind=kind, name=name, expression=condition):
            writer.item(where, "condition")
            writer.line([f"{kind} condition {name}{_bracketed(condition)};"], where.line)
        case ast.Property():
            writer.item(where, "property")
            writer.line([f"property {node.name}: {_formula(node)};"], where.line)
        case ast.State():
            _state(writer, node)
        case ast.Region(name=name):
            writer.item(where, "region", spaced=True)
            _body(writer, [f"region {name}"], node)
        case ast.Action(kind=kind, statements=statements, block=True):
            writer.item(where, "action")
            block(writer, f"{kind} /", statements, where)
        case ast.Action(kind=kind, statements=statements):
            writer.item(where, "action")
            writer.line(statement(statements[0], f"{kind} / ", writer.width), where.line)
        case ast.Invariant(expression=invariant):
            writer.item(where, "invariant")
            writer.line([f"invariant [{expression(invariant)}];"], where.line)
        case ast.Transition():
            _transition(writer, node)
        case ast.InternalTransition():
            writer.item(where, "transition")
            text = f"internal{_bracketed(node.guard)} {_stimulus(node)}"
            if node.action is None:
                writer.line([text + ";"], where.line)
            else:
                block(writer, f"{text} /", node.action, where, ";")
        case ast.Pseudostate(kind=kind, name=name):
            writer.item(where, "state")
            writer.line([f"{kind} {name};"], where.line)
        case ast.EventBlock(events=events):
            writer.item(where, "events", spaced=True)
            if not events and not writer.comments_within(where):
                writer.line(["events { }"], where.line)
                return
            writer.open(["events {"], where.line)
            for event in events:
                writer.item(event.position, "event")
                writer.line([f"{event.name};"], event.position.line)
            writer.close(where)
        case _:
            extension = extension_of(node)
            if extension is None:
                raise TypeError(f"not an element: {node!r}")
            extension.printers[type(node)](writer, node)


def _state(writer: Writer, node: ast.State) -> None:
    writer.item(node.position, "state", spaced=node.body is not None)
    head = _prefixed(node.stereotypes, " ".join([*node.modifiers, "state", node.name]))
    tail = _bracketed(node.invariant) + (";" if node.body is None else " {")
    if node.arguments:
        lines = fit(f"{head}(", argument_parts(node.arguments), f"){tail}", writer.width)
    else:
        lines = [head + tail]
    if node.body is None:
        writer.line(lines, node.position.line)
    else:
        _body(writer, [*lines[:-1], lines[-1].removesuffix(" {")], node)


def _transition(writer: Writer, node: ast.Transition) -> None:
    writer.item(node.position, "transition")
    target = f"{node.target}.{node.target_history}" if node.target_history else node.target
    text = f"{node.source} -> {target}{_bracketed(node.guard)}"
    if node.stimulus:
        text += f" {_stimulus(node)}"
    tail = _bracketed(node.postcondition) + ";"
    if node.action is None:
        writer.line([text + tail], node.position.line)
    else:
        block(writer, f"{text} /", node.action, node.position, tail)


def _stimulus(node: ast.Transition | ast.InternalTransition) -> str:
    args = node.stimulus_arguments
    return node.stimulus + (f"({', '.join(map(expression, args))})" if args else "")


def _formula(node: ast.Property) -> str:
    """A property's formula: its keyword around its bracketed predicates."""
    parts = [f"[{expression(e)}]" for e in node.expressions]
    if node.kind == "ensures":
        return f"{node.outcome} ensures {parts[0]}"
    if node.kind == "after":
        return f"after {parts[0]} eventually {parts[1]}"
    return f"{node.kind} {', '.join(parts)}"


def _bracketed(node: ast.Expression | None) -> str:
    """`` [expression]`` of a guard, invariant or condition, or nothing."""
    return f" [{expression(node)}]" if node is not None else ""
