"""A plain LightRocks statechart as a sismic statechart, for differential runs.

States are named by their LightRocks path (``Chart/Composite/Child``), so configurations of
both interpreters compare directly. A LightRocks outcome transition becomes a sismic
eventless transition guarded by ``active(<final state>)``: sismic has no completion events,
and its eventless transitions fire as soon as the final state is active, which is the
moment a LightRocks composite completes. End conditions become final states, a choice a
state left by eventless transitions whose guards exclude the earlier branches, ``after(d)``
sismic's ``after(seconds)`` guard, and an internal transition a transition without target.
"""

from __future__ import annotations

from typing import Any

from sismic.io.datadict import import_from_dict
from sismic.model import Statechart

from lightrocks.metamodel import ast

OPERATORS = {"&&": "and", "||": "or"}


def to_sismic(chart: ast.Statechart) -> Statechart:
    root = _state(chart.name, chart.name, chart.elements)
    parameters = [
        p for e in chart.elements if isinstance(e, ast.ParameterBlock) for p in e.parameters
    ]
    preamble = "\n".join(f"{p.name} = {python(p.default)}" for p in parameters if p.default)
    return import_from_dict(
        {"statechart": {"name": chart.name, "preamble": preamble, "root state": root}}
    )


def _state(path: str, name: str, body: tuple[Any, ...] | None, final: bool = False) -> dict:
    state: dict[str, Any] = {"name": path}
    if final:
        state["type"] = "final"
    for action in (e for e in body or () if isinstance(e, ast.Action)):
        state[f"on {action.kind}"] = "\n".join(statement(s) for s in action.statements)
    internal = [_internal(e) for e in body or () if isinstance(e, ast.InternalTransition)]
    if internal:
        state["transitions"] = internal
    children = [e for e in body or () if isinstance(e, ast.State)]
    pseudostates = [e for e in body or () if isinstance(e, ast.Pseudostate)]
    ends = [e.name for e in body or () if isinstance(e, ast.Condition) and e.kind == "end"]
    if not children:
        return state
    initial = next(f"{path}/{c.name}" for c in children if c.is_initial)
    state["initial"] = initial
    state["states"] = [_state(f"{path}/{c.name}", c.name, c.body, c.is_final) for c in children]
    state["states"] += [{"name": f"{path}/{end}", "type": "final"} for end in ends]
    for p in pseudostates:
        kind = {"history": "shallow history", "deep history": "deep history"}.get(p.kind)
        extra = {"type": kind, "memory": initial} if kind else {}
        state["states"].append({"name": f"{path}/{p.name}", **extra})
    outgoing: dict[str, list[dict]] = {}
    for transition in (e for e in body if isinstance(e, ast.Transition)):
        source = next((c for c in children if c.name == transition.source), None)
        earlier = outgoing.setdefault(transition.source, [])
        earlier.append(_transition(path, source, transition, earlier))
    for child in state["states"]:
        child_name = child["name"].rpartition("/")[2]
        child.setdefault("transitions", []).extend(outgoing.get(child_name, []))
    return state


def _internal(transition: ast.InternalTransition) -> dict:
    result: dict[str, Any] = {}
    guards = [python(transition.guard)] if transition.guard is not None else []
    if transition.stimulus == "after":
        guards.insert(0, f"after({python(transition.stimulus_arguments[0])})")
    else:
        result["event"] = transition.stimulus
    if guards:
        result["guard"] = " and ".join(guards)
    if transition.action:
        result["action"] = "\n".join(statement(s) for s in transition.action)
    return result


def _outcomes(source: ast.State | None) -> list[str]:
    body = source.body or () if source is not None else ()
    ends = [e.name for e in body if isinstance(e, ast.Condition) and e.kind == "end"]
    return ends + [e.name for e in body if isinstance(e, ast.State) and e.is_final]


def _transition(
    path: str, source: ast.State | None, transition: ast.Transition, earlier: list[dict]
) -> dict:
    target = f"{path}/{transition.target}"
    if transition.target_history:
        target += f"/{transition.target_history}"
    result: dict[str, Any] = {"target": target}
    guards = [python(transition.guard)] if transition.guard is not None else []
    outcomes = _outcomes(source)
    here = f"{path}/{transition.source}"
    if source is None:  # a choice: the first branch that holds wins
        guards += [f"not ({e['guard']})" for e in earlier if "guard" in e]
    elif transition.stimulus == "after":
        guards.insert(0, f"after({python(transition.stimulus_arguments[0])})")
    elif outcomes and not transition.stimulus:
        reached = " or ".join(f"active('{here}/{o}')" for o in outcomes)
        guards.insert(0, f"({reached})")
    elif transition.stimulus in outcomes:
        guards.insert(0, f"active('{here}/{transition.stimulus}')")
    else:
        result["event"] = transition.stimulus
    if guards:
        result["guard"] = " and ".join(guards)
    if transition.action:
        result["action"] = "\n".join(statement(s) for s in transition.action)
    return result


def statement(node: ast.Statement) -> str:
    if isinstance(node, ast.Assignment):
        return f"{python(node.target)} = {python(node.value)}"
    raise ValueError(f"no sismic counterpart for {node!r}")


def python(node: ast.Expression) -> str:
    """The Python text sismic evaluates; only what the differential charts use."""
    match node:
        case ast.Binary(operator=operator, left=left, right=right):
            return f"({python(left)} {OPERATORS.get(operator, operator)} {python(right)})"
        case ast.Unary(operator="!", operand=operand):
            return f"(not {python(operand)})"
        case ast.Unary(operator=operator, operand=operand):
            return f"({operator}{python(operand)})"
        case ast.Quantity(value=value):  # in SI, as the generated code has it
            return repr(int(value)) if value == int(value) else repr(value)
        case ast.BooleanLiteral(value=value):
            return repr(value)
        case ast.Name(name=name):
            return name
    raise ValueError(f"no sismic counterpart for {node!r}")
