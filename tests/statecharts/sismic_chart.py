"""A plain LightRocks statechart as a sismic statechart, for differential runs.

States are named by their LightRocks path (``Chart/Composite/Child``), so configurations of
both interpreters compare directly. A LightRocks outcome transition becomes a sismic
eventless transition guarded by ``active(<final state>)``: sismic has no completion events,
and its eventless transitions fire as soon as the final state is active, which is the
moment a LightRocks composite completes. End conditions become final states, a choice a
state left by eventless transitions whose guards exclude the earlier branches, ``after(d)``
sismic's ``after(seconds)`` guard with a flag that makes it occur once, and an internal
transition a transition without target. Later transitions with the trigger of an earlier
one from the same source exclude it in their guards: the first declared wins.
Regions become sismic's parallel states, one compound state per region; the join of a
LightRocks orthogonal state is an eventless transition guarded by every region being final.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from sismic.interpreter import Interpreter
from sismic.io.datadict import import_from_dict
from sismic.model import FinalState, MicroStep, OrthogonalState, Statechart

from lightrocks.metamodel import ast

OPERATORS = {"&&": "and", "||": "or"}


def to_sismic(chart: ast.Statechart) -> Statechart:
    root = _state(chart.name, chart.name, chart.elements)
    if "transitions" in root:  # internal transitions of the statechart itself
        root["transitions"] = _prioritised(_timed(root, root["transitions"]))
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
    outcomes = _outcomes(body or ())
    for transition in internal:  # a completed state is left before its time events fire
        if outcomes and transition["trigger"].startswith("after("):
            transition["completed"] = _reached(path, body, outcomes)
    if internal:
        state["transitions"] = internal
    regions = [e for e in body or () if isinstance(e, ast.Region)]
    if regions:
        state["parallel states"] = [_state(f"{path}/{r.name}", r.name, r.elements) for r in regions]
        return state
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
        outgoing.setdefault(transition.source, []).append(_transition(path, source, transition))
    for child in state["states"]:
        child_name = child["name"].rpartition("/")[2]
        transitions = child.get("transitions", []) + outgoing.get(child_name, [])
        if transitions:
            child["transitions"] = _prioritised(_timed(child, transitions))
    return state


def _internal(transition: ast.InternalTransition) -> dict:
    result: dict[str, Any] = {"trigger": transition.stimulus}
    guards = [python(transition.guard)] if transition.guard is not None else []
    if transition.stimulus == "after":
        result["trigger"] = f"after({python(transition.stimulus_arguments[0])})"
    else:
        result["event"] = transition.stimulus
    if guards:
        result["guard"] = " and ".join(guards)
    if transition.action:
        result["action"] = "\n".join(statement(s) for s in transition.action)
    return result


def _timed(state: dict, transitions: list[dict]) -> list[dict]:
    """A time event occurs once, at its deadline, and is dropped unless its guard holds then;
    sismic's ``after()`` guard stays true from then on. So each time event gets a flag, set
    on entry of its source and cleared when it fires or, at the same deadline, by an extra
    internal transition tried after every other one."""
    dropped = []
    for number, transition in enumerate(transitions):
        if not transition["trigger"].startswith("after("):
            continue
        flag = f"_armed_{state['name'].replace('/', '_')}_{number}"
        due = f"{flag} and {transition['trigger']}"
        if "completed" in transition:
            due += f" and not {transition.pop('completed')}"
        state["on entry"] = "\n".join([f"{flag} = True", state.get("on entry", "")]).strip()
        transition["guard"] = " and ".join([due, *filter(None, [transition.get("guard")])])
        transition["action"] = "\n".join([f"{flag} = False", transition.get("action", "")])
        dropped.append(
            {"trigger": transition["trigger"], "guard": due, "action": f"{flag} = False"}
        )
    return transitions + dropped


def _prioritised(transitions: list[dict]) -> list[dict]:
    """The first declared of several transitions with the same trigger from one source
    wins (internal ones declared first); sismic would report non-determinism, so each
    transition's guard excludes the earlier ones."""
    earlier: dict[str, list[str]] = {}
    for transition in transitions:
        before = earlier.setdefault(transition.pop("trigger"), [])
        guard = transition.get("guard", "True")
        if before:
            transition["guard"] = " and ".join([guard, *(f"not ({g})" for g in before)])
        before.append(guard)
    return transitions


def _outcomes(body: tuple[Any, ...]) -> list[str]:
    """The outcomes a state with this body completes with."""
    ends = [e.name for e in body if isinstance(e, ast.Condition) and e.kind == "end"]
    regions = [e for e in body if isinstance(e, ast.Region)]
    if regions:
        return ends + _finals(regions[0].elements)
    return ends + _finals(body)


def _finals(body: tuple[Any, ...]) -> list[str]:
    return [e.name for e in body if isinstance(e, ast.State) and e.is_final]


def _reached(here: str, body: tuple[Any, ...], outcomes: list[str]) -> str:
    """The guard that the state at ``here`` with ``body`` has completed with one of
    ``outcomes``: in a final state, or with every region final and the first one in one of
    ``outcomes``."""
    regions = [e for e in body if isinstance(e, ast.Region)]
    if not regions:
        return "(" + " or ".join(f"active('{here}/{o}')" for o in outcomes) + ")"
    first, *others = regions
    joined = [[f"{first.name}/{o}" for o in outcomes if o in _finals(first.elements)]]
    joined += [[f"{r.name}/{f}" for f in _finals(r.elements)] for r in others]
    parts = ["(" + " or ".join(f"active('{here}/{f}')" for f in finals) + ")" for finals in joined]
    return "(" + " and ".join(parts) + ")"


def _transition(path: str, source: ast.State | None, transition: ast.Transition) -> dict:
    target = f"{path}/{transition.target}"
    if transition.target_history:
        target += f"/{transition.target_history}"
    result: dict[str, Any] = {"target": target, "trigger": ""}
    body = source.body or () if source is not None else ()
    outcomes = _outcomes(body)
    completes = bool(outcomes) and transition.stimulus in ("", *outcomes)
    after_exit = _after_exit(source) if completes else {}
    guards = [python(transition.guard, after_exit)] if transition.guard is not None else []
    here = f"{path}/{transition.source}"
    if transition.stimulus == "after":
        delay = python(transition.stimulus_arguments[0])
        result["trigger"] = f"after({delay})"
        if outcomes:  # LightRocks takes a completion in the step that completes the source
            result["completed"] = _reached(here, body, outcomes)
    elif outcomes and not transition.stimulus:
        guards.insert(0, _reached(here, body, outcomes))
    elif transition.stimulus in outcomes:
        guards.insert(0, _reached(here, body, [transition.stimulus]))
    elif transition.stimulus:  # an event; the branches of a choice have none
        result["event"] = result["trigger"] = transition.stimulus
    if guards:
        result["guard"] = " and ".join(guards)
    if transition.action:
        result["action"] = "\n".join(statement(s) for s in transition.action)
    return result


def _after_exit(source: ast.State) -> dict[str, str]:
    """The parameters as the exit action of ``source`` leaves them, in terms of their values
    before: LightRocks evaluates the guard of a completion transition once the completed
    state is left (docs/language.md §15.1), sismic before it leaves the state."""
    values: dict[str, str] = {}
    for action in (e for e in source.body or () if isinstance(e, ast.Action)):
        if action.kind == "exit":
            for assignment in action.statements:
                values[python(assignment.target)] = python(assignment.value, values)
    return values


def statement(node: ast.Statement) -> str:
    if isinstance(node, ast.Assignment):
        return f"{python(node.target)} = {python(node.value)}"
    raise ValueError(f"no sismic counterpart for {node!r}")


def python(node: ast.Expression, values: dict[str, str] | None = None) -> str:
    """The Python text sismic evaluates; only what the differential charts use. ``values``
    replaces names by expressions."""
    values = values or {}
    match node:
        case ast.Binary(operator=operator, left=left, right=right):
            operator = OPERATORS.get(operator, operator)
            return f"({python(left, values)} {operator} {python(right, values)})"
        case ast.Unary(operator="!", operand=operand):
            return f"(not {python(operand, values)})"
        case ast.Unary(operator=operator, operand=operand):
            return f"({operator}{python(operand, values)})"
        case ast.Quantity(value=value):  # in SI, as the generated code has it
            return repr(int(value)) if value == int(value) else repr(value)
        case ast.BooleanLiteral(value=value):
            return repr(value)
        case ast.Name(name=name):
            return values.get(name, name)
    raise ValueError(f"no sismic counterpart for {node!r}")


class Reference(Interpreter):
    """sismic's interpreter with two rules of LightRocks (docs/language.md §7): a composite
    whose last active child was a final state has no memory there and is entered at its
    initial state (sismic remembers the final state and would complete again), and a
    statechart of regions ends when every region rests in a final state (sismic has no
    join; a state's join is an eventless transition, but the statechart has none)."""

    def _create_stabilization_step(self, names: Iterable[str]) -> MicroStep | None:
        chart, names = self._statechart, list(names)
        root = chart.root
        regions = chart.children_for(root) if root in names else []
        resting = [
            any(
                isinstance(chart.state_for(c), FinalState) and c in names
                for c in chart.children_for(r)
            )
            for r in regions
        ]
        if isinstance(chart.state_for(root), OrthogonalState) and resting and all(resting):
            depth = chart.depth_for
            return MicroStep(exited_states=sorted(names, key=lambda n: (-depth(n), n)))
        return super()._create_stabilization_step(names)

    def _apply_step(self, step: MicroStep) -> MicroStep:
        applied = super()._apply_step(step)
        for history, remembered in self._memory.items():
            if remembered is not None:
                self._memory[history] = [self._forget_final(name) for name in remembered]
        return applied

    def _forget_final(self, name: str) -> str:
        if not isinstance(self._statechart.state_for(name), FinalState):
            return name
        parent = self._statechart.parent_for(name)
        return self._statechart.state_for(parent).initial
