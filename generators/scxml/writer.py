"""A plain LightRocks statechart as an SCXML document (docs/interchange.md, section SCXML).

The chart becomes one ``<state>`` (``<parallel>`` when it has regions) named like it, inside
``<scxml>``; every LightRocks state, region, final state and end condition an element of
the same structure, with the id of its path (:mod:`generators.scxml.names`). What SCXML says
differently is written out so that an SCXML engine does what the LightRocks runtime does:

- **Completion.** A transition without stimulus, or with an outcome of its source, takes the
  engine's ``done.state.<source>`` event; the outcome is ``In('<its final state>')``. The
  guard is evaluated by LightRocks once the completed state has been left, by SCXML before:
  the generator writes it in terms of the values before the exit actions.
- **Errors.** A composite whose outcome no transition takes, a choice none of whose branches
  holds, a violated invariant or postcondition end a state with the outcome ``error``. The
  state is left for a resting state of its parent (``<parent>.failing``) and the event
  ``lr-error.<state>`` is raised; the transitions ``S -> X error`` are the parent's internal
  transitions on that event, and one more leaves the parent with ``error`` when none takes
  it. An error that leaves the chart ends the document in the final ``<chart>.error``.
- **Time events.** ``after(d)`` is a ``<send>`` of ``after-<state>-<n>`` with that delay on
  entry of its state and a ``<cancel>`` on exit. The delay must be known when generating:
  a constant, or an expression of parameters the chart never assigns (their defaults).
- **Choice** is a ``<state>`` left by eventless transitions; **history** a ``<history>``
  whose default is the initial state. LightRocks forgets the history of a composite left
  through a final state or an end condition; the variable ``lr_done_<state>`` remembers that
  here, and a transition into the history then enters the composite at its initial state.
- **Regions.** An enclosing transition takes an event only when no state inside takes it;
  SCXML also fires it beside a targetless transition of another region, so its condition
  excludes those.

Constructs the target cannot express are :class:`Refusal` s, collected with their positions.
"""

from __future__ import annotations

import itertools
import math
import re
import xml.etree.ElementTree as ET
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

from lightrocks.generators.scxml.expressions import Translator, Untranslatable
from lightrocks.generators.scxml.names import Names, event_name
from lightrocks.metamodel import ast, units
from lightrocks.metamodel.constants import fold
from lightrocks.metamodel.printer import expression as lightrocks_text
from lightrocks.metamodel.printer import stereotypes as stereotype_text

SCXML = "http://www.w3.org/2005/07/scxml"
LR = "urn:lightrocks:scxml"
"""The namespace of the annotations that carry what SCXML has no place for (the package,
declared events, types of parameters, stereotypes) and mark the generator's own elements.
SCXML engines ignore attributes of other namespaces."""

ERROR_EVENT = "lr-error."
COMPONENT_STEREOTYPES = ("import", "extends", "task", "skill", "action")
_REFUSED_STIMULI = ("timeout", "preempted")


def q(name: str) -> str:
    return f"{{{SCXML}}}{name}"


def lr(name: str) -> str:
    return f"{{{LR}}}{name}"


class Refusal(Exception):
    """A construct the SCXML target cannot express."""

    def __init__(self, position: ast.Position, message: str) -> None:
        super().__init__(f"{position}: {message}")
        self.position = position
        self.message = message


@dataclass(eq=False)
class Node:
    """A state, region, final state, end condition, choice or history of the chart."""

    kind: str  # chart | state | region | final | end | choice | history
    name: str
    path: tuple[str, ...]
    position: ast.Position
    parent: Node | None = None
    state: ast.State | None = None
    children: dict[str, Node] = field(default_factory=dict)
    regions: list[Node] = field(default_factory=list)
    transitions: list[ast.Transition] = field(default_factory=list)
    internal: list[ast.InternalTransition] = field(default_factory=list)
    entry: list[ast.Statement] = field(default_factory=list)
    exit: list[ast.Statement] = field(default_factory=list)
    invariants: list[ast.Expression] = field(default_factory=list)
    initial: str | None = None
    deep: bool = False
    stereotypes: tuple[ast.Stereotype, ...] = ()

    @property
    def composite(self) -> bool:
        return any(c.kind in ("state", "final", "end", "choice") for c in self.children.values())

    def finals(self) -> list[Node]:
        return [c for c in self.children.values() if c.kind in ("final", "end")]

    def leaving(self) -> list[ast.Transition]:
        """The transitions whose source is this node, in declaration order."""
        if self.parent is None or self.kind == "region":
            return []
        return [t for t in self.parent.transitions if t.source == self.name]

    def completes(self) -> bool:
        if self.regions:
            return all(r.finals() for r in self.regions)
        return bool(self.finals())

    def outcomes(self) -> dict[str, Node]:
        """Outcome -> the final state (or end condition) that ends this node with it."""
        if self.regions:
            return {f.name: f for f in self.regions[0].finals() if f.kind == "final"}
        ends = [f for f in self.finals() if f.kind == "end"]
        finals = [f for f in self.finals() if f.kind == "final"]
        return {f.name: f for f in ends + finals}

    def descendants(self) -> Iterator[Node]:
        for child in [*self.regions, *self.children.values()]:
            yield child
            yield from child.descendants()


# --- the chart as nodes --------------------------------------------------------------------


class _Builder:
    def __init__(self, refusals: list[Refusal]) -> None:
        self.refusals = refusals

    def refuse(self, position: ast.Position, message: str) -> None:
        self.refusals.append(Refusal(position, message))

    def chart(self, chart: ast.Statechart) -> Node:
        node = Node("chart", chart.name, (chart.name,), chart.position)
        self.body(node, chart.elements)
        return node

    def body(self, node: Node, elements: Sequence[object]) -> None:
        for element in elements:
            match element:
                case ast.ParameterBlock() | ast.EventBlock() if node.kind == "chart":
                    pass
                case ast.State():
                    self.state(node, element)
                case ast.Pseudostate(kind=kind, name=name):
                    child = Node(
                        "choice" if kind == "choice" else "history",
                        name,
                        (*node.path, name),
                        element.position,
                        node,
                    )
                    child.deep = kind == "deep history"
                    node.children[name] = child
                case ast.Transition():
                    node.transitions.append(element)
                case ast.InternalTransition():
                    node.internal.append(element)
                case ast.Action(kind="do"):
                    self.refuse(
                        element.position,
                        "a 'do' action: SCXML has no activity that runs while a state is "
                        "active (a plain statechart's 'do' calls no device command either)",
                    )
                case ast.Action(kind=kind, statements=statements):
                    (node.entry if kind == "entry" else node.exit).extend(statements)
                case ast.Invariant(expression=expression):
                    node.invariants.append(expression)
                case ast.Region(name=name, elements=inner):
                    region = Node("region", name, (*node.path, name), element.position, node)
                    self.body(region, inner)
                    node.regions.append(region)
                case ast.Condition(kind="start"):
                    self.refuse(
                        element.position,
                        "a start condition: SCXML enters a state at its initial state only "
                        "(an <initial> transition has no condition)",
                    )
                case ast.Condition(kind="end", name=name, expression=expression):
                    if expression is not None:
                        self.refuse(
                            element.position,
                            "an end condition with a condition: SCXML has no condition that "
                            "ends a state by itself holding",
                        )
                    end = Node("end", name, (*node.path, name), element.position, node)
                    node.children[name] = end
                case _:
                    self.refuse(
                        getattr(element, "position", node.position),
                        f"'{type(element).__name__}' (syntax of a language extension) has no "
                        "mapping to SCXML",
                    )
        if node.kind == "region" and (node.internal or node.entry or node.exit):
            self.refuse(node.position, "a region's own actions or internal transitions")
        if node.regions and any(c.kind in ("final", "end") for c in node.children.values()):
            end = next(c for c in node.children.values() if c.kind in ("final", "end"))
            self.refuse(
                end.position,
                "an end condition beside regions: SCXML's <parallel> holds no <final>",
            )

    def state(self, parent: Node, state: ast.State) -> None:
        final = "final" in state.modifiers
        node = Node(
            "final" if final else "state",
            state.name,
            (*parent.path, state.name),
            state.position,
            parent,
            state,
        )
        for stereotype in state.stereotypes:
            if stereotype.name in COMPONENT_STEREOTYPES:
                self.refuse(
                    stereotype.position,
                    f"<<{stereotype.name}>>: a LightRocks component, not a plain statechart; "
                    "SCXML has no instance of another chart",
                )
        node.stereotypes = tuple(
            s for s in state.stereotypes if s.name not in COMPONENT_STEREOTYPES
        )
        if state.arguments:
            self.refuse(state.arguments[0].position, "arguments of a state (<<import>>)")
        if state.invariant is not None:
            node.invariants.append(state.invariant)
        self.body(node, state.body or ())
        if final and (node.children or node.regions or node.transitions or node.internal):
            self.refuse(state.position, "a final state with states, regions or transitions")
        if "initial" in state.modifiers:
            parent.initial = state.name
        parent.children[state.name] = node


# --- writing -------------------------------------------------------------------------------


@dataclass
class Document:
    """The generated document and what a reader of it needs: state id -> LightRocks path,
    parameter -> data-model variable."""

    text: str
    paths: dict[str, tuple[str, ...]]
    variables: dict[str, str]


def _conjunction(*parts: str | None) -> str | None:
    present = [p for p in parts if p]
    if not present:
        return None
    return present[0] if len(present) == 1 else " and ".join(f"({p})" for p in present)


def _assigned(node: object) -> set[str]:
    return {
        n.target.name
        for n in ast.walk(node)
        if isinstance(n, ast.Assignment) and isinstance(n.target, ast.Name)
    }


def _substituted(node: ast.Expression, values: dict[str, ast.Expression]) -> ast.Expression:
    """``node`` with names replaced by expressions (defaults of parameters)."""
    match node:
        case ast.Name(name=name) if name in values:
            return values[name]
        case ast.Binary(operator=operator, left=left, right=right):
            return ast.Binary(operator, _substituted(left, values), _substituted(right, values))
        case ast.Unary(operator=operator, operand=operand):
            return ast.Unary(operator, _substituted(operand, values))
        case ast.Call(function=function, arguments=arguments):
            return ast.Call(
                function,
                tuple(ast.Argument(_substituted(a.value, values), a.name) for a in arguments),
            )
    return node


class Writer:
    """Writes one plain statechart; :meth:`document` raises the first :class:`Refusal` with
    the others attached (``refusals``)."""

    def __init__(self, unit: ast.StatechartUnit, budget: ast.Stereotype | None = None) -> None:
        self.unit = unit
        self.chart_ast = unit.statechart
        self.budget = budget
        self.refusals: list[Refusal] = []
        self.names = Names()
        blocks = [e for e in self.chart_ast.elements if isinstance(e, ast.ParameterBlock)]
        self.parameters = {p.name: p for b in blocks for p in b.parameters}
        for name in self.parameters:
            self.names.data(name)
        self.translate = Translator(self.names, self.parameters)
        self.assigned = _assigned(self.chart_ast)
        self.chart = _Builder(self.refusals).chart(self.chart_ast)
        self.chart_id = self.names.state(self.chart.path)
        self._ids(self.chart)
        self.flags: dict[Node, str] = {}
        self._flags(self.chart)
        self.helpers: dict[Node, list[ET.Element]] = {}
        self.resting: dict[Node, str] = {}
        self.failing: dict[Node, list[Node]] = {}
        self.ends: dict[str, ET.Element] = {}
        self._timer_events: dict[int, str] = {}
        self._posts = itertools.count(1)
        self.timers = {n: self._timers(n) for n in [self.chart, *self.chart.descendants()]}
        timed = [len(n.path) for n, found in self.timers.items() if found]
        self.deepest = max(timed, default=0)

    # -- names and analysis -------------------------------------------------------------

    def _ids(self, node: Node) -> None:
        for child in node.descendants():
            self.names.state(child.path)

    def id(self, node: Node) -> str:
        return self.names.state(node.path)

    def refuse(self, position: ast.Position, message: str) -> None:
        self.refusals.append(Refusal(position, message))

    def _flags(self, node: Node) -> None:
        """A composite with history that can be left through a final state, an end condition
        or an error remembers that (it then keeps no memory)."""
        for child in node.descendants():
            histories = [c for c in child.children.values() if c.kind == "history"]
            if histories and (child.finals() or _may_fail(child)):
                wanted = "lr_done_" + "_".join(child.path[1:])
                self.flags[child] = self.names.fresh_data(wanted)

    # -- the document ---------------------------------------------------------------------

    def document(self) -> Document:
        ET.register_namespace("", SCXML)
        ET.register_namespace("lr", LR)
        root = ET.Element(
            q("scxml"),
            {"version": "1.0", "datamodel": "python", "name": self.chart.name},
        )
        root.set("initial", self.chart_id)
        if self.unit.package:
            root.set(lr("package"), self.unit.package)
        events = [
            e.name
            for b in self.chart_ast.elements
            if isinstance(b, ast.EventBlock)
            for e in b.events
        ]
        if events:
            root.set(lr("events"), " ".join(event_name(e) for e in events))
        if self.chart_ast.stereotypes:
            root.set(lr("stereotypes"), stereotype_text(self.chart_ast.stereotypes))
        datamodel = self._datamodel()
        if len(datamodel):
            root.append(datamodel)
        root.append(self._guarded(self.write, self.chart))
        for end in self.ends.values():
            root.append(end)
        if self.refusals:
            self.refusals.sort(key=lambda r: (r.position.line, r.position.column))
            first = self.refusals[0]
            first.refusals = list(self.refusals)  # type: ignore[attr-defined]
            raise first
        ET.indent(root, space="  ")
        text = ET.tostring(root, encoding="unicode", short_empty_elements=True)
        return Document(
            '<?xml version="1.0" encoding="UTF-8"?>\n' + text + "\n",
            self.names.paths,
            self.names.variables,
        )

    def _guarded(self, write, *args):
        """``write(*args)``; an expression without counterpart becomes a refusal."""
        try:
            return write(*args)
        except Untranslatable as problem:
            self.refuse(problem.position, problem.message)
            return ET.Element(q("state"))

    def _datamodel(self) -> ET.Element:
        datamodel = ET.Element(q("datamodel"))
        for name, parameter in self.parameters.items():
            data = ET.SubElement(datamodel, q("data"), {"id": self.names.data(name)})
            if parameter.default is not None:
                try:
                    data.set("expr", self._initial_value(parameter))
                except Untranslatable as problem:
                    self.refuse(problem.position, problem.message)
            data.set(lr("type"), parameter.type)
            if self.names.data(name) != name:
                data.set(lr("name"), name)
            if parameter.low is not None or parameter.high is not None:
                self.refuse(parameter.position, "a parameter's range: SCXML checks no range")
        for node, flag in self.flags.items():
            ET.SubElement(
                datamodel,
                q("data"),
                {"id": flag, "expr": "False", lr("helper"): "history", lr("of"): self.id(node)},
            )
        return datamodel

    def _initial_value(self, parameter: ast.Parameter) -> str:
        value = fold(parameter.default)
        if isinstance(value, bool):
            return "True" if value else "False"
        if isinstance(value, int) and parameter.type != "Real":
            return str(value)
        if isinstance(value, int | float):
            return repr(float(value))
        return self.translate.value(parameter.default)

    # -- states ---------------------------------------------------------------------------

    def write(self, node: Node) -> ET.Element:
        if node.kind == "history":
            return self._history(node)
        tag = "parallel" if node.regions else "final" if node.kind in ("final", "end") else "state"
        element = ET.Element(q(tag), {"id": self.id(node)})
        if node.kind == "end":
            element.set(lr("kind"), "end condition")
        if node.stereotypes:
            element.set(lr("stereotypes"), stereotype_text(node.stereotypes))
        if node.composite and not node.regions:
            if node.initial is None:
                self.refuse(node.position, "a composite state without initial state")
            else:
                element.set("initial", self.id(node.children[node.initial]))
        timers = self.timers[node]
        onentry = self._onentry(node, timers)
        if len(onentry):
            element.append(onentry)
        onexit = ET.Element(q("onexit"))
        for statement in node.exit:
            onexit.append(self._guarded(self._statement, statement))
        for index, _ in enumerate(timers):
            ET.SubElement(onexit, q("cancel"), {"sendid": self._send_id(node, index)})
        if len(onexit):
            element.append(onexit)
        for transition in self._ties(node, timers):
            element.append(transition)
        for transition in self._guarded_all(self._transitions, node):
            element.append(transition)
        for child in node.children.values():
            element.append(self._guarded(self.write, child))
        for region in node.regions:
            element.append(self._guarded(self.write, region))
        for transition in self._guarded_all(self._error_handlers, node):
            element.append(transition)
        for helper in self.helpers.get(node, []):
            element.append(helper)
        if node.kind == "chart":
            for transition in self._chart_transitions(node):
                element.append(transition)
        return element

    def _guarded_all(self, write, node: Node) -> list[ET.Element]:
        try:
            return list(write(node))
        except Untranslatable as problem:
            self.refuse(problem.position, problem.message)
            return []

    def _onentry(self, node: Node, timers: list[tuple[object, float, str]]) -> ET.Element:
        onentry = ET.Element(q("onentry"))
        if node in self.flags:
            onentry.append(self._assign(self.flags[node], "False"))
        if node.kind in ("final", "end") and node.parent in self.flags:
            onentry.append(self._assign(self.flags[node.parent], "True"))
        for statement in node.entry:
            onentry.append(self._guarded(self._statement, statement))
        for index, (source, delay, comment) in enumerate(timers):
            event = self._timer_event(node, index, source)
            if comment:
                onentry.append(ET.Comment(comment))
            ET.SubElement(
                onentry,
                q("send"),
                {
                    "event": event,
                    "id": self._send_id(node, index),
                    "delay": self._delay(delay, source),
                },
            )
        return onentry

    def _delay(self, seconds: float, source: object) -> str:
        """The CSS2 time SCXML takes: in the unit the model wrote, else milliseconds."""
        if source == "budget":
            written = re.fullmatch(r"\s*(\d+(?:\.\d+)?)\s*(ms|s)\s*", self.budget.value or "")
            if written is not None:
                return written.group(1) + written.group(2)
        return _delay(seconds, source)

    def _history(self, node: Node) -> ET.Element:
        parent = node.parent
        element = ET.Element(
            q("history"), {"id": self.id(node), "type": "deep" if node.deep else "shallow"}
        )
        if parent.initial is not None:
            default = ET.SubElement(element, q("transition"))
            default.set("target", self.id(parent.children[parent.initial]))
        return element

    # -- time events ----------------------------------------------------------------------

    def _timers(self, node: Node) -> list[tuple[object, float, str]]:
        """The time events armed on entering ``node``: its internal ones, the chart's budget,
        then those leaving it (the order in which LightRocks fires them at one deadline)."""
        found: list[tuple[object, float, str]] = []
        for transition in node.internal:
            if transition.stimulus == "after":
                found.append(self._timed(transition, transition.stimulus_arguments))
        if node.kind == "chart" and self.budget is not None:
            found.append(("budget", *self._budget()))
        for transition in node.leaving():
            if transition.stimulus == "after":
                found.append(self._timed(transition, transition.stimulus_arguments))
        return [f for f in found if f[1] is not None]

    def _timed(self, transition, arguments) -> tuple[object, float | None, str]:
        if len(arguments) != 1:
            self.refuse(transition.position, "after() takes one delay")
            return transition, None, ""
        delay = arguments[0]
        value = fold(delay)
        comment = ""
        if value is None:
            reads = {n.name for n in ast.walk(delay) if isinstance(n, ast.Name)}
            defaults = {
                name: self.parameters[name].default
                for name in reads
                if name in self.parameters
                and name not in self.assigned
                and self.parameters[name].default is not None
            }
            value = fold(_substituted(delay, defaults)) if defaults.keys() == reads else None
            if value is not None:
                comment = (
                    f" after({lightrocks_text(delay)}) at {delay.position}: the chart never "
                    f"assigns {', '.join(sorted(reads))}, so the delay is computed from the "
                    "defaults "
                ).replace("--", "- -")
        if not isinstance(value, int | float) or isinstance(value, bool) or value < 0:
            self.refuse(
                delay.position,
                f"after({lightrocks_text(delay)}): SCXML's delay must be known when the event "
                "is sent, and python-statemachine's data model cannot write a number as a "
                "time (delayexpr needs a string such as '300ms'); use a constant, or "
                "parameters the chart never assigns",
            )
            return transition, None, ""
        if not math.isfinite(value):
            self.refuse(delay.position, "an infinite delay")
            return transition, None, ""
        return transition, float(value), comment

    def _budget(self) -> tuple[float | None, str]:
        seconds = units.seconds(self.budget.value)
        if seconds is None:
            self.refuse(self.budget.position, "a <<timeout>> that is not a duration")
            return None, ""
        return float(seconds), ""

    def _timer_event(self, node: Node, index: int, source: object) -> str:
        """The event the delayed ``<send>`` sends; the transitions take it after
        :meth:`_ties` has sent it on as often as the state lies above the deepest."""
        if source == "budget":
            event = f"timeout-{self.chart_id}"
        else:
            event = f"after-{self.id(node)}-{index}"
        hops = self.deepest - len(node.path)
        self._timer_events[id(source)] = f"{event}-{hops}" if hops > 0 else event
        return event

    def _ties(self, node: Node, timers: list) -> Iterator[ET.Element]:
        """Of several time events due at one deadline LightRocks fires the innermost state's
        first; SCXML delivers delayed events in the order they were sent, and an enclosing
        state is entered (and sends) first. So each time event of a state above the deepest
        one that has time events is sent on with delay 0 once per level it lies above: the
        events of deeper states due at that deadline come first."""
        hops = self.deepest - len(node.path)
        if hops <= 0:
            return
        for index, (source, _, _) in enumerate(timers):
            base = (
                f"timeout-{self.chart_id}"
                if source == "budget"
                else (f"after-{self.id(node)}-{index}")
            )
            for hop in range(hops):
                event = f"{base}-{hop}" if hop else base
                element = self._element(event, None, None, [], helper="tie")
                ET.SubElement(
                    element,
                    q("send"),
                    {
                        "event": f"{base}-{hop + 1}",
                        "id": self._send_id(node, index),
                        "delay": "0ms",
                    },
                )
                yield element

    def _send_id(self, node: Node, index: int) -> str:
        return f"{self.id(node)}.after{index}"

    # -- transitions ----------------------------------------------------------------------

    def _transitions(self, node: Node) -> Iterator[ET.Element]:
        for internal in node.internal:
            yield from self._internal(node, internal)
        for invariant in node.invariants:
            target, content = self.failure(node)
            cond = f"not {self.translate.cond(invariant)}"
            yield self._element(None, cond, target, content, helper="invariant")
        if node.kind == "choice":
            yield from self._branches(node)
            return
        for transition in node.leaving():
            yield from self._leaving(node, transition)
        if node.kind not in ("chart", "region") and node.completes() and not self._handled(node):
            target, content = self.failure(node.parent)
            yield self._element(
                f"done.state.{self.id(node)}", None, target, content, helper="unhandled"
            )

    def _internal(self, node: Node, internal: ast.InternalTransition) -> Iterator[ET.Element]:
        guard = self.translate.cond(internal.guard) if internal.guard is not None else None
        if internal.stimulus == "after":
            event = self._timer_events.get(id(internal))
            if event is None:
                return
        else:
            self._plain_stimulus(internal)
            event = event_name(internal.stimulus)
            guard = _conjunction(guard, *self._suppressors(node, internal.stimulus, False))
        element = self._element(event, guard, None, [])
        self._actions(element, internal.action)
        yield element

    def _plain_stimulus(self, transition) -> None:
        if transition.stimulus in _REFUSED_STIMULI:
            raise Untranslatable(
                transition.stimulus_position,
                f"the outcome '{transition.stimulus}' never ends a state of a plain statechart",
            )
        if transition.stimulus_arguments:
            raise Untranslatable(
                transition.stimulus_position,
                "an event's arguments: SCXML transitions match events by name alone, so the "
                "arguments would be lost",
            )

    def _branches(self, choice: Node) -> Iterator[ET.Element]:
        owner = choice.parent
        branches = choice.leaving()
        for branch in branches:
            if branch.stimulus:
                raise Untranslatable(branch.stimulus_position, "a choice's branch has a stimulus")
            guard = self.translate.cond(branch.guard) if branch.guard is not None else None
            yield from self.take(owner, branch, None, guard)
        if all(b.guard is not None for b in branches):
            target, content = self.failure(owner)
            yield self._element(None, None, target, content, helper="no branch")

    def _leaving(self, node: Node, transition: ast.Transition) -> Iterator[ET.Element]:
        owner = node.parent
        stimulus = transition.stimulus
        if stimulus == "error":
            return  # an internal transition of the parent (see _error_handlers)
        if stimulus == "after":
            event = self._timer_events.get(id(transition))
            if event is not None:
                guard = transition.guard
                cond = self.translate.cond(guard) if guard is not None else None
                yield from self.take(owner, transition, event, cond)
            return
        outcomes = node.outcomes() if node.completes() else {}
        if node.completes() and (not stimulus or stimulus in outcomes):
            yield from self._completion(node, transition, outcomes)
            return
        if not stimulus:
            raise Untranslatable(
                transition.position, "a completion transition from a state that never completes"
            )
        self._plain_stimulus(transition)
        guard = self.translate.cond(transition.guard) if transition.guard is not None else None
        cond = _conjunction(guard, *self._suppressors(node, stimulus, True))
        yield from self.take(owner, transition, event_name(stimulus), cond)

    def _completion(
        self, node: Node, transition: ast.Transition, outcomes: dict[str, Node]
    ) -> Iterator[ET.Element]:
        """``done.state.<node>``: the outcome as ``In(final)``, the guard in terms of the
        values before the exit actions."""
        event = f"done.state.{self.id(node)}"
        chosen = [outcomes[transition.stimulus]] if transition.stimulus else list(outcomes.values())
        guard = transition.guard
        if guard is None:
            cond = self._in(chosen) if transition.stimulus else None
            yield from self.take(node.parent, transition, event, cond)
            return
        plain = self.translate.cond(guard)
        per_final = [self._exits_after(node, final) for final in chosen]
        if all(v == per_final[0] for v in per_final):
            read = self.translate.cond(guard, per_final[0])
            cond = _conjunction(self._in(chosen) if transition.stimulus else None, read)
            for element in self.take(node.parent, transition, event, cond):
                if read != plain:
                    element.set(lr("guard"), plain)
                yield element
            return
        for number, (final, values) in enumerate(zip(chosen, per_final, strict=True)):
            cond = _conjunction(self._in([final]), self.translate.cond(guard, values))
            for element in self.take(node.parent, transition, event, cond):
                element.set(lr("guard"), plain)
                if not transition.stimulus:
                    element.set(lr("outcome"), "any")
                if number:
                    element.set(lr("helper"), "outcome")
                yield element

    def _in(self, finals: Sequence[Node]) -> str:
        tests = [f"In('{self.id(f)}')" for f in finals]
        return tests[0] if len(tests) == 1 else "(" + " or ".join(tests) + ")"

    def _exits_after(self, node: Node, final: Node) -> dict[str, str]:
        """The parameters as the exit actions of ``final`` (and, for regions, of every
        region's final state) and of ``node`` leave them, in terms of their values before."""
        statements = list(final.exit)
        if node.regions:
            others = [f for r in node.regions[1:] for f in r.finals() if f.exit]
            if others:
                raise Untranslatable(
                    others[0].position,
                    "a final state of a region with an exit action, before a completion "
                    "guard: which final state each region rests in is not known in advance",
                )
        statements += node.exit
        values: dict[str, str] = {}
        for statement in statements:
            if isinstance(statement, ast.Assignment) and isinstance(statement.target, ast.Name):
                values[statement.target.name] = self.translate.cond(statement.value, values)
        return values

    def _handled(self, node: Node) -> bool:
        leaving = [t for t in node.leaving() if t.guard is None and not t.postcondition]
        if any(not t.stimulus for t in leaving):
            return True
        return all(any(t.stimulus == o for t in leaving) for o in node.outcomes())

    def _suppressors(self, node: Node, event: str, targeted: bool) -> list[str]:
        """Conditions that no state inside ``node`` in another region than the one SCXML
        looks at takes ``event`` (LightRocks' innermost-first rule across regions)."""
        terms: list[str] = []

        def visit(inner: Node, separated: bool) -> None:
            below = inner.regions or [
                c for c in inner.children.values() if c.kind in ("state", "final")
            ]
            for child in below:
                apart = separated or bool(inner.regions)
                if apart and child.kind != "region":
                    enabled = [t.guard for t in child.internal if t.stimulus == event]
                    if not targeted:
                        enabled += [
                            t.guard
                            for t in child.leaving()
                            if t.stimulus == event and t.stimulus not in child.outcomes()
                        ]
                    for guard in enabled:
                        inside = f"In('{self.id(child)}')"
                        if guard is not None:
                            inside = f"{inside} and {self.translate.cond(guard)}"
                        terms.append(f"not ({inside})")
                visit(child, apart)

        visit(node, False)
        return terms

    # -- taking a transition --------------------------------------------------------------

    def take(
        self,
        owner: Node,
        transition: ast.Transition,
        event: str | None,
        cond: str | None,
        internal: bool = False,
    ) -> list[ET.Element]:
        """The elements that take ``transition`` (declared in ``owner``'s body)."""
        target = owner.children.get(transition.target)
        if target is None or target.kind == "history":
            raise Untranslatable(
                transition.target_position, f"no state '{transition.target}' to go to"
            )
        if transition.postcondition is None:
            return self._enter(owner, transition, target, event, cond, internal, True)
        helper_id = self.names.helper(self.id(owner), f"post{next(self._posts)}")
        helper = ET.Element(q("state"), {"id": helper_id, lr("helper"): "postcondition"})
        post = self.translate.cond(transition.postcondition)
        for element in self._enter(owner, transition, target, None, post, False, False):
            helper.append(element)
        fail, content = self.failure(owner)
        helper.append(self._element(None, None, fail, content, helper="postcondition"))
        self.helpers.setdefault(owner, []).append(helper)
        main = self._element(event, cond, helper_id, [], internal=internal)
        self._actions(main, transition.action)
        return [main]

    def _enter(
        self,
        owner: Node,
        transition: ast.Transition,
        target: Node,
        event: str | None,
        cond: str | None,
        internal: bool,
        act: bool,
    ) -> list[ET.Element]:
        """Into ``target`` (through its history when the transition says so)."""
        elements = []
        if transition.target_history:
            history = target.children.get(transition.target_history)
            if history is None or history.kind != "history":
                raise Untranslatable(
                    transition.target_position, f"no history '{transition.target_history}'"
                )
            flag = self.flags.get(target)
            into = self.id(history)
            if act and transition.action:
                into = self._detour(owner, into)
            if flag is None:
                elements.append(self._element(event, cond, into, [], internal))
            else:
                remembered = _conjunction(cond, f"not {flag}")
                forgotten = _conjunction(cond, flag)
                elements.append(self._element(event, remembered, into, [], internal))
                elements.append(
                    self._element(event, forgotten, self.id(target), [], internal, "history")
                )
        else:
            elements.append(self._element(event, cond, self.id(target), [], internal))
        if act:
            for element in elements:
                self._actions(element, transition.action)
        return elements

    def _detour(self, owner: Node, history: str) -> str:
        """A state in ``owner`` left at once for ``history``: a transition with actions goes
        there instead of into the history itself. Equivalent in SCXML; python-statemachine
        3.2.2 runs the actions of a transition into a history twice (it counts the
        transition as the history's default content as well)."""
        helper_id = self.names.helper(self.id(owner), f"history{next(self._posts)}")
        helper = ET.Element(q("state"), {"id": helper_id, lr("helper"): "history-action"})
        helper.append(self._element(None, None, history, []))
        self.helpers.setdefault(owner, []).append(helper)
        return helper_id

    def _element(
        self,
        event: str | None,
        cond: str | None,
        target: str | None,
        content: list[ET.Element],
        internal: bool = False,
        helper: str = "",
    ) -> ET.Element:
        element = ET.Element(q("transition"))
        if event:
            element.set("event", event)
        if cond:
            element.set("cond", cond)
        if target:
            element.set("target", target)
            if internal:
                element.set("type", "internal")
        if helper:
            element.set(lr("helper"), helper)
        element.extend(content)
        return element

    def _actions(self, element: ET.Element, statements) -> None:
        for statement in statements or ():
            element.append(self._statement(statement))

    def _statement(self, statement: ast.Statement) -> ET.Element:
        if isinstance(statement, ast.Assignment):
            location = self.translate.variable(statement.target)
            return self._assign(location, self.translate.value(statement.value))
        raise Untranslatable(
            getattr(statement, "position", ast.NOWHERE),
            "a statement other than an assignment: SCXML's data model here runs no command "
            "or function",
        )

    @staticmethod
    def _assign(location: str, expr: str) -> ET.Element:
        return ET.Element(q("assign"), {"location": location, "expr": expr})

    # -- errors ---------------------------------------------------------------------------

    def failure(self, node: Node) -> tuple[str, list[ET.Element]]:
        """Target and content of a transition that ends ``node`` with ``error``."""
        while node.kind == "region":
            node = node.parent
        if node.kind == "chart":
            return self._end("error"), []
        owner = node.parent
        if owner not in self.resting:
            resting = self.names.helper(self.id(owner), "failing")
            self.resting[owner] = resting
            element = ET.Element(q("state"), {"id": resting, lr("helper"): "error"})
            if owner in self.flags:
                onentry = ET.SubElement(element, q("onentry"))
                onentry.append(self._assign(self.flags[owner], "True"))
            self.helpers.setdefault(owner, []).append(element)
        failing = self.failing.setdefault(owner, [])
        if node not in failing:
            failing.append(node)
        raised = ET.Element(q("raise"), {"event": ERROR_EVENT + self.id(node)})
        return self.resting[owner], [raised]

    def _error_handlers(self, owner: Node) -> Iterator[ET.Element]:
        """``S -> X error`` as internal transitions of ``owner`` on ``lr-error.S``, and one
        more that ends ``owner`` with error when none takes it."""
        for child in [*owner.children.values(), *owner.regions]:
            handlers = [t for t in owner.transitions if t.source == child.name]
            handlers = [t for t in handlers if t.stimulus == "error"]
            event = ERROR_EVENT + self.id(child)
            for handler in handlers:  # the failed child has been left: as in LightRocks,
                guard = handler.guard  # the guard sees what its exit actions wrote
                cond = self.translate.cond(guard) if guard is not None else None
                yield from self.take(owner, handler, event, cond, internal=True)
        for child in self.failing.get(owner, []):
            handlers = [t for t in owner.transitions if t.source == child.name]
            handled = any(
                t.stimulus == "error" and t.guard is None and t.postcondition is None
                for t in handlers
            )
            if not handled:
                target, content = self.failure(owner)
                yield self._element(
                    ERROR_EVENT + self.id(child), None, target, content, helper="error"
                )

    def _chart_transitions(self, chart: Node) -> Iterator[ET.Element]:
        if chart.completes():
            yield self._element(f"done.state.{self.chart_id}", None, self._end("end"), [])
        if self.budget is not None and id("budget") in self._timer_events:
            event = self._timer_events[id("budget")]
            yield self._element(event, None, self._end("timeout"), [])
        yield self._element("error.execution", None, self._end("error"), [], helper="fault")

    def _end(self, outcome: str) -> str:
        """A final state of the document: the chart has ended (``end``), or ended with
        ``error`` or ``timeout``."""
        if outcome not in self.ends:
            end_id = self.names.helper(self.chart_id, outcome)
            self.ends[outcome] = ET.Element(q("final"), {"id": end_id, lr("helper"): outcome})
        return self.ends[outcome].get("id")


def _may_fail(node: Node) -> bool:
    """Whether a child of ``node`` may end with error (over-approximated)."""
    for inner in node.descendants():
        if inner.kind == "choice" or inner.invariants or inner.completes():
            return True
        if any(t.postcondition is not None for t in inner.transitions):
            return True
    return any(t.postcondition is not None for t in node.transitions)


def _delay(seconds: float, source: object) -> str:
    """The CSS2 time SCXML takes: in the unit the model wrote, else milliseconds."""
    argument = getattr(source, "stimulus_arguments", ())
    unit = argument[0].unit if len(argument) == 1 and isinstance(argument[0], ast.Quantity) else ""
    if unit == "s":
        return _number(seconds) + "s"
    return _number(seconds * 1000) + "ms"


def _number(value: float) -> str:
    """12 significant digits: ``3 * 100 ms`` is 300 ms, not the 300.00000000000006 ms that
    the product of the doubles 3 and 0.1 s gives."""
    text = format(value, ".12g")
    return text if "e" not in text else repr(value)
