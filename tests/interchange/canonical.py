"""Statecharts in a canonical order, for comparing a chart with its round trip.

LightRocks leaves free the order of a body's elements of different kinds, of the
transitions of different sources, and of a source's ``error`` transitions among its other
ones (they never compete). The canonical form puts each body in a fixed order of kinds,
transitions grouped by source in the order of the states, ``error`` transitions last; it
keeps every order that decides something (transitions of one source, branches of a choice,
states, regions, statements). Invariants all go into the body as ``invariant [e];``, empty
bodies and blocks become none, and actions are blocks.
"""

from __future__ import annotations

from dataclasses import replace

from lightrocks.metamodel import ast

_KINDS = (
    ast.EventBlock,
    ast.ParameterBlock,
    ast.Action,
    ast.Invariant,
    ast.InternalTransition,
    ast.Condition,
)


def canonical(unit: ast.StatechartUnit) -> ast.StatechartUnit:
    chart = unit.statechart
    return replace(unit, imports=(), statechart=replace(chart, elements=_body(chart.elements)))


def _body(elements) -> tuple:
    elements = [_element(e) for e in elements or ()]
    first = [e for kind in _KINDS for e in elements if isinstance(e, kind)]
    states = [e for e in elements if isinstance(e, ast.State | ast.Pseudostate | ast.Region)]
    order = {getattr(s, "name", ""): i for i, s in enumerate(states)}
    conditions = {c.name: -1 for c in first if isinstance(c, ast.Condition)}
    transitions = [e for e in elements if isinstance(e, ast.Transition)]
    transitions.sort(
        key=lambda t: ({**conditions, **order}.get(t.source, len(order)), t.stimulus == "error")
    )
    return tuple(first + states + transitions)


def _element(element):
    match element:
        case ast.State():
            body = list(element.body or ())
            if element.invariant is not None:
                body.insert(0, ast.Invariant(element.invariant))
            inner = _body(body)
            return replace(element, invariant=None, body=inner or None)
        case ast.Region():
            return replace(element, elements=_body(element.elements))
        case ast.Action():
            return replace(element, block=True)
        case ast.Transition():
            return replace(element, action=element.action or None)
        case ast.InternalTransition():
            return replace(element, action=element.action or None)
    return element
