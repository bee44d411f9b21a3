"""``lightrocks convert X.scxml --to lr``: SCXML back to a plain LightRocks statechart, for the
subset the SCXML target writes (docs/interchange.md, section SCXML).

The document is read with expat, so every element keeps its line and column, and a
``<!DOCTYPE>`` is refused (no entity of the document is ever expanded). It maps to
LightRocks as the target maps LightRocks to it, read backwards:

- ``<state>``, ``<parallel>`` (its child states are regions), ``<final>`` (``lr:kind="end
  condition"``: an end condition), ``<history>`` whose default is the initial state, a
  ``<state>`` left only by eventless transitions (a choice);
- ``<transition>``: on an event (one or more names, which become one transition each), on
  ``done.state.<its state>`` (a completion; ``In('<final>')`` names the outcome), on the
  event a delayed ``<send>`` of the state's ``<onentry>`` sends and its ``<onexit>``
  cancels (``after(d)``), without target (an internal transition), between states of one
  parent (LightRocks transitions stay on their level);
- ``<datamodel>``: ``<data>`` become parameters, typed by ``lr:type`` or by their value;
  ``<assign>`` an assignment; ``cond`` and ``expr`` are parsed as Python (``ast.parse``,
  never evaluated) and translated where LightRocks has the construct.

The generator's own elements (marked ``lr:helper``) are recognised and folded back into
what they stand for (postconditions, invariants, ``error`` transitions, the order of time
events at one deadline); anything else outside the subset is a finding at its element.

Findings: LR2130 (error) an SCXML element or attribute outside the subset; LR2131 (error)
an expression without LightRocks counterpart; LR2132 (warning) something dropped that does
not change what the chart does (``<log>``, elements of other namespaces); LR2133 (info) an
id renamed to a LightRocks name, a parameter's type taken from its value.
"""

from __future__ import annotations

import ast as py
import re
import xml.parsers.expat
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from lightrocks.generators.scxml.names import lightrocks_event
from lightrocks.generators.scxml.writer import ERROR_EVENT, LR, SCXML
from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Diagnostic, Severity

OUTSIDE, EXPRESSION, DROPPED, RENAMED = "LR2130", "LR2131", "LR2132", "LR2133"
_KEYWORDS = {
    "choice", "condition", "deep", "do", "end", "entry", "events", "exit", "final", "history",
    "import", "initial", "internal", "invariant", "package", "parameters", "region", "start",
    "state", "statechart", "true", "false", "after", "in", "error", "timeout", "preempted",
}  # fmt: skip
_IDENTIFIER = re.compile(r"[^\W\d]\w*")
_DELAY = re.compile(r"\s*(\d+(?:\.\d+)?|\.\d+)(ms|s)\s*")
_COND_WORDS = {"true": "True", "false": "False", "null": "None", "&&": "and", "||": "or"}
_COND_PATTERN = re.compile(r"\b(?:true|false|null)\b|===|!==|&&|\|\|")
_OPERATORS = {
    py.Add: "+", py.Sub: "-", py.Mult: "*", py.Div: "/", py.Mod: "%",
    py.Eq: "==", py.NotEq: "!=", py.Lt: "<", py.LtE: "<=", py.Gt: ">", py.GtE: ">=",
}  # fmt: skip
_TYPES = {bool: "Boolean", int: "Integer", float: "Real", str: "String"}


# --- XML with positions ----------------------------------------------------------------------


@dataclass(eq=False)
class Element:
    namespace: str
    tag: str
    attributes: dict[str, str]
    line: int
    column: int
    children: list[Element] = field(default_factory=list)
    text: str = ""

    def get(self, name: str, default: str | None = None) -> str | None:
        return self.attributes.get(name, default)

    def lr(self, name: str) -> str | None:
        return self.attributes.get(f"{{{LR}}}{name}")

    def scxml(self) -> list[Element]:
        """The children in the SCXML namespace (or none, as some tools write)."""
        return [c for c in self.children if c.namespace in (SCXML, "")]

    def all(self, tag: str) -> list[Element]:
        return [c for c in self.scxml() if c.tag == tag]


class Problem(Exception):
    def __init__(self, line: int, column: int, message: str) -> None:
        super().__init__(message)
        self.line, self.column, self.message = line, column, message


def parse_xml(text: str) -> Element:
    """The document as :class:`Element` s with 1-based lines and columns; raises
    :class:`Problem` for text that is no well-formed XML or holds a ``<!DOCTYPE>``."""
    parser = xml.parsers.expat.ParserCreate(namespace_separator=" ")
    stack: list[Element] = []
    roots: list[Element] = []

    def split(name: str) -> tuple[str, str]:
        namespace, _, local = name.rpartition(" ")
        return namespace, local

    def start(name: str, attributes: dict[str, str]) -> None:
        namespace, tag = split(name)
        named = {}
        for key, value in attributes.items():
            space, local = split(key)
            named[f"{{{space}}}{local}" if space else local] = value
        element = Element(
            namespace, tag, named, parser.CurrentLineNumber, parser.CurrentColumnNumber + 1
        )
        (stack[-1].children if stack else roots).append(element)
        stack.append(element)

    def end(_name: str) -> None:
        stack.pop()

    def characters(data: str) -> None:
        if stack:
            stack[-1].text += data

    def doctype(*_args) -> None:
        at = text.find("<!DOCTYPE")
        line = text.count("\n", 0, at) + 1 if at >= 0 else parser.CurrentLineNumber
        column = at - text.rfind("\n", 0, at) if at >= 0 else 1
        raise Problem(line, column, "a <!DOCTYPE> is not read: its entities could expand")

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = characters
    parser.StartDoctypeDeclHandler = doctype
    try:
        parser.Parse(text, True)
    except xml.parsers.expat.ExpatError as error:
        raise Problem(error.lineno, error.offset + 1, f"not well-formed XML: {error}") from None
    return roots[0]


# --- the conversion --------------------------------------------------------------------------


@dataclass
class Conversion:
    """The result of converting one file (see ``app/commands/convert.py``)."""

    name: str
    text: str | None
    findings: list[Diagnostic] = field(default_factory=list)
    unit: ast.StatechartUnit | None = None


class Refused(Exception):
    def __init__(self, element: Element, message: str, code: str = OUTSIDE) -> None:
        super().__init__(message)
        self.element, self.message, self.code = element, message, code


@dataclass(eq=False)
class _Scope:
    """A state's (or region's, or the chart's) body being built."""

    id: str
    element: Element | None
    body: list[object] = field(default_factory=list)
    transitions: list[ast.Transition] = field(default_factory=list)
    parent: _Scope | None = None


@dataclass
class _Timer:
    event: str
    send_id: str
    delay: ast.Quantity
    events: set[str] = field(default_factory=set)  # the sent event and its relays


def _identifier(text: str) -> str:
    name = re.sub(r"\W", "_", text)
    if not name or not _IDENTIFIER.fullmatch(name):
        name = "s_" + name
    return f"{name}_" if name in _KEYWORDS else name


class Reader:
    def __init__(self, shown: str) -> None:
        self.shown = shown
        self.findings: list[Diagnostic] = []
        self.variables: dict[str, str] = {}  # data id -> parameter name
        self.flags: set[str] = set()  # the generator's history variables
        self.states: dict[str, Element] = {}  # id -> element
        self.scope_of: dict[str, str] = {}  # id -> id of the state whose body holds it
        self.name_of: dict[str, str] = {}  # id -> LightRocks name
        self.taken: dict[str, set[str]] = {}
        self._timer_cache: dict[int, list[_Timer]] = {}
        self.wrapper_id = ""
        self.generated = False  # written by the LightRocks SCXML target

    # -- findings -----------------------------------------------------------------------

    def at(self, element: Element | None) -> ast.Position:
        if element is None:
            return ast.Position(self.shown, 1, 1)
        return ast.Position(self.shown, element.line, element.column)

    def finding(self, element: Element | None, code: str, severity: Severity, text: str) -> None:
        self.findings.append(Diagnostic.at(self.at(element), code, severity, text))

    def refuse(self, element: Element, message: str, code: str = OUTSIDE) -> None:
        self.finding(element, code, Severity.ERROR, message)

    # -- document -----------------------------------------------------------------------

    def read(self, root: Element, fallback_name: str) -> ast.StatechartUnit | None:
        if root.tag != "scxml" or root.namespace not in (SCXML, ""):
            self.refuse(root, f"<{root.tag}> is not an SCXML document (<scxml> expected)")
            return None
        self.generated = any(
            v for k, v in root.attributes.items() if k.startswith(f"{{{LR}}}")
        ) or _generated(root)
        name = root.get("name") or fallback_name
        chart_name = self.rename(root, name)
        tops = [c for c in root.scxml() if c.tag in ("state", "parallel", "final")]
        wrapper = self._wrapper(root, tops, name)
        self.wrapper_id = wrapper.get("id") if wrapper is not None else ""
        self._index(root, wrapper)
        parameters = self._datamodel(root)
        chart = _Scope("", root)
        elements: list[object] = []
        events = root.lr("events")
        if events:
            names = [lightrocks_event(e) for e in events.split()]
            elements.append(ast.EventBlock(tuple(ast.Event(e) for e in names)))
        if parameters:
            elements.append(ast.ParameterBlock(tuple(parameters)))
        stereotypes = list(_stereotypes(root.lr("stereotypes")))
        for child in root.scxml():
            if child.tag not in ("state", "parallel", "final", "datamodel"):
                self._outside(child, "at the top of the document")
        if wrapper is not None:
            chart.id = wrapper.get("id")
            chart.element = wrapper
            budget = self._state_body(chart, wrapper, chart_root=True)
            if budget is not None and not any(s.name == "timeout" for s in stereotypes):
                stereotypes.append(ast.Stereotype("timeout", budget))
        else:
            initial = self._initial(root, tops)
            for top in tops:
                self._child(chart, top, initial)
            self._finish(chart)
        elements += chart.body
        statechart = ast.Statechart(chart_name, tuple(elements), tuple(stereotypes))
        return ast.StatechartUnit(root.lr("package") or "", (), statechart)

    def rename(self, element: Element, name: str) -> str:
        if _IDENTIFIER.fullmatch(name) and name not in _KEYWORDS:
            return name
        renamed = _identifier(name)
        self.finding(element, RENAMED, Severity.INFO, f"'{name}' is named '{renamed}'")
        return renamed

    def _index(self, root: Element, wrapper: Element | None) -> None:
        """Every state's id, the id of the state whose body holds it (``""`` for the top of
        the chart) and its LightRocks name, unique in that body."""

        def visit(element: Element, scope: str) -> None:
            for child in element.scxml():
                if child.tag not in ("state", "parallel", "final", "history"):
                    continue
                identifier = child.get("id")
                if not identifier:
                    continue
                self.states[identifier] = child
                if child is wrapper:
                    visit(child, identifier)
                    continue
                if child.lr("helper"):
                    continue
                self.scope_of[identifier] = scope
                self.name_of[identifier] = self._name(scope, child)
                visit(child, identifier)

        visit(root, "")

    def _wrapper(self, root: Element, tops: list[Element], name: str) -> Element | None:
        """The one state that stands for the chart itself: named like the document, with
        the document's final states (when any) of the generator's own."""
        states = [t for t in tops if t.tag != "final"]
        others = [t for t in tops if t.tag == "final" and not t.lr("helper")]
        if len(states) == 1 and not others and states[0].get("id") == name:
            return states[0]
        return None

    def _initial(self, element: Element, children: list[Element]) -> str | None:
        initial = element.get("initial")
        tags = element.all("initial")
        if tags:
            transitions = tags[0].all("transition")
            if len(transitions) != 1 or transitions[0].scxml():
                self.refuse(tags[0], "an <initial> with executable content or several targets")
                return None
            initial = transitions[0].get("target")
        if initial and len(initial.split()) > 1:
            self.refuse(element, "several initial states (LightRocks enters one)")
            return None
        if not initial:
            first = next((c for c in children if c.tag in ("state", "parallel", "final")), None)
            return first.get("id") if first is not None else None
        return initial

    # -- data ---------------------------------------------------------------------------

    def _datamodel(self, root: Element) -> list[ast.Parameter]:
        found: list[ast.Parameter] = []
        tops = root.all("datamodel")
        for datamodel in _walk_tag(root, "datamodel"):
            if datamodel not in tops:
                self.refuse(
                    datamodel,
                    "a <datamodel> inside a state: LightRocks' parameters belong to the chart",
                )
                continue
            for data in datamodel.scxml():
                if data.tag != "data":
                    self._outside(data, "in <datamodel>")
                    continue
                parameter = self._data(data)
                if parameter is not None:
                    found.append(parameter)
        return found

    def _data(self, data: Element) -> ast.Parameter | None:
        identifier = data.get("id") or ""
        if data.lr("helper") == "history":
            self.flags.add(identifier)
            return None
        if data.get("src"):
            self.refuse(data, "<data src>: a value read from elsewhere")
            return None
        name = data.lr("name") or identifier
        name = self.rename(data, name) if name else "v"
        self.variables[identifier] = name
        text = data.get("expr") or (data.text.strip() or None)
        default = None
        if text is not None:
            try:
                default = self.expression(text, data)
            except Refused as problem:
                self.refuse(problem.element, problem.message, problem.code)
                return None
        kind = data.lr("type") or _type_of(text)
        if kind is None:
            self.refuse(
                data,
                f"the type of '{identifier}' is not known: give it a value (a number, a "
                "Boolean, a string) or lr:type",
            )
            return None
        if not data.lr("type"):
            self.finding(data, RENAMED, Severity.INFO, f"'{name}' is declared {kind}, as its value")
        elif kind not in _TYPES.values():
            self.finding(
                data,
                DROPPED,
                Severity.WARNING,
                f"'{name}' is a {kind}, whose unit SCXML does not carry: it is declared Real, "
                "and its values are SI values without unit",
            )
            kind = "Real"
        return ast.Parameter(kind, name, default)

    def paths(self, chart: str) -> dict[str, tuple[str, ...]]:
        """State id -> LightRocks path (chart name first), as the runtime names states."""
        found = {}
        for identifier in self.name_of:
            path, current = [], identifier
            while current:
                path.insert(0, self.name_of[current])
                current = self.scope_of.get(current, "")
                if current == self.wrapper_id:
                    break
            found[identifier] = (chart, *path)
        if self.wrapper_id:
            found[self.wrapper_id] = (chart,)
        return found

    # -- states -------------------------------------------------------------------------

    def _child(self, scope: _Scope, element: Element, initial: str | None) -> None:
        identifier = element.get("id")
        if element.lr("helper"):
            return
        if not identifier:
            self.refuse(element, f"<{element.tag}> without id")
            return
        name = self.name_of.get(identifier) or self._name(scope.id, element)
        if element.tag == "history":
            self._history(scope, element, name)
            return
        if element.tag == "final":
            if element.lr("kind") == "end condition":
                scope.body.append(ast.Condition("end", name))
                self._final_content(element, allow_entry=False)
                return
            entry, exit_ = self._final_content(element, allow_entry=True)
            body = tuple(entry + exit_) or None
            modifiers = ("initial", "final") if identifier == initial else ("final",)
            stereotypes = tuple(_stereotypes(element.lr("stereotypes")))
            scope.body.append(ast.State(name, stereotypes, modifiers, body=body))
            return
        if self._choice_like(element):
            scope.body.append(ast.Pseudostate("choice", name))
            for transition in element.all("transition"):
                self._branch(scope, element, name, transition)
            return
        inner = _Scope(identifier, element, parent=scope)
        self._state_body(inner, element)
        modifiers = ("initial",) if identifier == initial else ()
        stereotypes = tuple(_stereotypes(element.lr("stereotypes")))
        invariant = None
        body = list(inner.body)
        invariants = [e for e in body if isinstance(e, ast.Invariant)]
        if len(invariants) == 1:
            invariant = invariants[0].expression
            body.remove(invariants[0])
        state = ast.State(name, stereotypes, modifiers, (), invariant, tuple(body) or None)
        scope.body.append(state)
        scope.transitions += self._leaving(scope, element, name)

    def _name(self, scope: str, element: Element) -> str:
        identifier = element.get("id")
        prefix = f"{scope}-" if scope else ""
        own = identifier[len(prefix) :] if prefix and identifier.startswith(prefix) else ""
        if own and _IDENTIFIER.fullmatch(own) and own not in _KEYWORDS:
            name = own
        elif _IDENTIFIER.fullmatch(identifier) and identifier not in _KEYWORDS:
            name = identifier
        else:
            tail = identifier.rsplit("-", 1)[1] if "-" in identifier else identifier
            name = _identifier(tail if self.generated else identifier)
            self.finding(element, RENAMED, Severity.INFO, f"state '{identifier}' is named '{name}'")
        taken = self.taken.setdefault(scope, set())
        base, number = name, 1
        while name in taken:
            number += 1
            name = f"{base}_{number}"
        taken.add(name)
        return name

    def _history(self, scope: _Scope, element: Element, name: str) -> None:
        kind = "deep history" if element.get("type") == "deep" else "history"
        defaults = element.all("transition")
        initial = self._initial(scope.element, _state_children(scope.element))
        for default in defaults:
            if default.get("target") != initial or default.scxml():
                self.refuse(
                    default,
                    "a history whose default is not the initial state, or has actions: a "
                    "LightRocks history without memory enters its state as usual",
                )
        finals = [c for c in scope.element.all("final") if not c.lr("helper")]
        if finals and not self.generated:
            self.finding(
                element,
                DROPPED,
                Severity.WARNING,
                "a history beside final states: LightRocks forgets what was active when the "
                "state was left through a final state and enters it at its initial state, where "
                "SCXML enters that final state again",
            )
        scope.body.append(ast.Pseudostate(kind, name))

    def _final_content(self, element: Element, allow_entry: bool):
        entry: list[ast.Action] = []
        exit_: list[ast.Action] = []
        for child in element.scxml():
            if child.tag in ("onentry", "onexit"):
                statements = self._statements(child, ignore_flags=True)
                if statements and (allow_entry or child.tag == "onexit"):
                    kind = "entry" if child.tag == "onentry" else "exit"
                    (entry if kind == "entry" else exit_).append(ast.Action(kind, statements))
                elif statements:
                    self._outside(child, "on an end condition")
            elif child.tag == "donedata":
                self.refuse(child, "<donedata>: LightRocks outcomes carry no data")
            else:
                self._outside(child, "in a <final>")
        return entry, exit_

    def _choice_like(self, element: Element) -> bool:
        """A ``<state>`` with nothing but eventless transitions: left as soon as entered."""
        transitions = element.all("transition")
        own = [t for t in transitions if not t.lr("helper")]
        return (
            element.tag == "state"
            and bool(own)
            and all(not t.get("event") for t in own)
            and not any(t.lr("helper") == "invariant" for t in transitions)
            and not [c for c in element.scxml() if c.tag != "transition"]
        )

    def _state_body(self, scope: _Scope, element: Element, chart_root: bool = False) -> str | None:
        """Fill ``scope`` with the body of ``element``; for the chart's own state the
        ``<<timeout>>`` value, if it has a budget."""
        timers = self._timers(element)
        budget = None
        entry, exit_ = [], []
        for child in element.scxml():
            if child.tag == "onentry":
                entry += self._statements(child, ignore_flags=True, timers=timers)
            elif child.tag == "onexit":
                exit_ += self._statements(child, ignore_flags=True, timers=timers)
        if entry:
            scope.body.append(ast.Action("entry", tuple(entry)))
        if exit_:
            scope.body.append(ast.Action("exit", tuple(exit_)))
        for transition in element.all("transition"):
            helper = transition.lr("helper")
            if helper == "invariant":
                try:
                    scope.body.append(self._invariant(transition))
                except Refused as problem:
                    self.refuse(problem.element, problem.message, problem.code)
            elif helper:
                continue
            elif chart_root and self._chart_ending(transition):
                timer = next((t for t in timers if transition.get("event") in t.events), None)
                if timer is not None:
                    budget = f"{timer.delay.text}".replace(" ", " ")
                continue
            elif not transition.get("target"):
                internal = self._internal(transition, timers)
                if internal is not None:
                    scope.body.append(internal)
            elif chart_root and not (transition.get("event") or "").startswith(ERROR_EVENT):
                self.refuse(transition, "a transition that leaves the chart itself")
        if element.tag == "parallel":
            for region in element.scxml():
                if region.tag == "state" and not region.lr("helper"):
                    scope.body.append(self._region(scope, region))
                elif region.tag in ("parallel", "final", "history"):
                    self.refuse(region, f"a <{region.tag}> in a <parallel>: a region is a <state>")
                elif region.tag not in ("onentry", "onexit", "transition", "datamodel"):
                    self._outside(region, "in a <parallel>")
        else:
            children = _state_children(element)
            initial = self._initial(element, children) if children else None
            for child in element.scxml():
                if child.tag in ("state", "parallel", "final", "history"):
                    self._child(scope, child, initial)
                elif child.tag not in ("onentry", "onexit", "transition", "initial", "datamodel"):
                    self._outside(child, f"in a <{element.tag}>")
        self._finish(scope)
        return budget

    def _region(self, scope: _Scope, element: Element) -> ast.Region:
        if not element.get("id"):
            self.refuse(element, "a region without id: LightRocks names every region")
            return ast.Region("region", ())
        name = self.name_of.get(element.get("id")) or self._name(scope.id, element)
        inner = _Scope(element.get("id"), element, parent=scope)
        children = _state_children(element)
        if not children:
            self.refuse(element, "a region without states")
        for child in element.scxml():
            if child.tag == "transition" and child.lr("helper"):
                continue
            if child.tag in ("onentry", "onexit", "transition"):
                self.refuse(child, "a region's own actions or transitions")
        initial = self._initial(element, children)
        for child in element.scxml():
            if child.tag in ("state", "parallel", "final", "history"):
                self._child(inner, child, initial)
        self._finish(inner)
        return ast.Region(name, tuple(inner.body))

    def _finish(self, scope: _Scope) -> None:
        """The transitions between the children of ``scope``, after them; and the ``error``
        transitions, which the target writes as ``scope``'s own on ``lr-error.<child>``."""
        if scope.element is not None:
            for transition in scope.element.all("transition"):
                event = transition.get("event") or ""
                if event.startswith(ERROR_EVENT) and not transition.lr("helper"):
                    handler = self._error_handler(scope, transition, event)
                    if handler is not None:
                        scope.transitions.append(handler)
        scope.body += scope.transitions
        scope.transitions = []

    # -- transitions --------------------------------------------------------------------

    def _timers(self, element: Element) -> list[_Timer]:
        """The delayed ``<send>`` s of ``element``'s ``<onentry>`` that its ``<onexit>``
        cancels: its time events (with the events the generator relays them by)."""
        if id(element) not in self._timer_cache:
            self._timer_cache[id(element)] = self._find_timers(element)
        return self._timer_cache[id(element)]

    def _find_timers(self, element: Element) -> list[_Timer]:
        cancelled = {
            c.get("sendid")
            for exit_ in element.all("onexit")
            for c in exit_.all("cancel")
            if c.get("sendid")
        }
        timers = []
        for entry in element.all("onentry"):
            for send in entry.all("send"):
                if send.get("id") in cancelled and send.get("event") and send.get("delay"):
                    delay = _delay(send.get("delay"))
                    if delay is None:
                        self.refuse(send, f"a delay '{send.get('delay')}' that is no CSS2 time")
                        continue
                    timer = _Timer(send.get("event"), send.get("id"), delay, {send.get("event")})
                    timers.append(timer)
        for transition in element.all("transition"):
            if transition.lr("helper") == "tie":
                for timer in timers:
                    if transition.get("event") in timer.events:
                        timer.events |= {s.get("event") for s in transition.all("send")}
        return timers

    def _stimulus(self, transition: Element, timers: list[_Timer]) -> tuple[str, tuple]:
        """(stimulus, arguments) of a transition on an event or a time event."""
        event = transition.get("event") or ""
        timer = next((t for t in timers if event in t.events), None)
        if timer is not None:
            return "after", (timer.delay,)
        names = event.split()
        if len(names) != 1:
            raise Refused(transition, "several events on one transition")
        return self._event(transition, names[0]), ()

    def _event(self, element: Element, event: str) -> str:
        if event.startswith(("done.", "error.", ERROR_EVENT)) or not _IDENTIFIER.fullmatch(
            lightrocks_event(event)
        ):
            raise Refused(
                element,
                f"the event '{event}': LightRocks events are names (no '.', no '*'), and "
                "done.* and error.* events belong to the SCXML engine",
            )
        return lightrocks_event(event)

    def _internal(self, transition: Element, timers: list[_Timer]) -> object | None:
        try:
            if not transition.get("event"):
                raise Refused(transition, "an eventless transition without target never rests")
            stimulus, arguments = self._stimulus(transition, timers)
            guard = self._cond(transition)
            action = self._statements(transition) or None
            return ast.InternalTransition(stimulus, guard, arguments, action)
        except Refused as problem:
            self.refuse(problem.element, problem.message, problem.code)
            return None

    def _leaving(self, scope: _Scope, element: Element, name: str) -> list[ast.Transition]:
        """The transitions of state ``element`` that have a target (in its parent's body)."""
        timers = self._timers(element)
        found = []
        for transition in element.all("transition"):
            event = transition.get("event") or ""
            if transition.lr("helper") or not transition.get("target"):
                continue
            if event.startswith(ERROR_EVENT):
                continue  # an error transition of a child (see _finish)
            try:
                found += self._transition(scope, element, name, transition, timers)
            except Refused as problem:
                self.refuse(problem.element, problem.message, problem.code)
        return found

    def _transition(
        self, scope: _Scope, element: Element, name: str, transition: Element, timers
    ) -> list[ast.Transition]:
        if transition.get("type") == "internal":
            raise Refused(transition, "an internal transition to a state inside its source")
        event = transition.get("event") or ""
        outcome = ""
        if event.startswith("done.state."):
            if event != f"done.state.{element.get('id')}":
                raise Refused(transition, f"'{event}': a completion of another state")
            guard, finals = self._cond(transition, completion=True)
            if len(finals) == 1 and transition.lr("outcome") != "any":
                outcome = self._outcome_name(finals[0], transition)
            self._completion_guard(transition, element, guard)
            stimuli: list[tuple[str, tuple]] = [(outcome, ())]
        elif not event:
            raise Refused(
                transition,
                "an eventless transition from a state that is not a choice (LightRocks "
                "leaves a state on an event, a time event or its completion)",
            )
        else:
            guard = self._cond(transition)
            if len(event.split()) > 1:
                stimuli = [(self._event(transition, e), ()) for e in event.split()]
            else:
                stimuli = [self._stimulus(transition, timers)]
        target, history, post, actions = self._target(scope, transition)
        return [
            ast.Transition(
                name,
                target,
                guard,
                stimulus,
                arguments,
                actions,
                post,
                target_history=history,
            )
            for stimulus, arguments in stimuli
        ]

    def _outcome_name(self, final: str, transition: Element) -> str:
        if final not in self.name_of:
            raise Refused(transition, f"In('{final}') names no final state")
        return self.name_of[final]

    def _completion_guard(self, transition: Element, source: Element, guard) -> None:
        """SCXML evaluates a completion's condition before the exit actions, LightRocks
        after them: refuse a condition that reads what they write."""
        if guard is None or transition.lr("guard") is not None:
            return
        written = set()
        for element in [source, *_descendants(source)]:
            for exit_ in element.all("onexit"):
                written |= {a.get("location") for a in exit_.all("assign")}
        read = {n.name for n in ast.walk(guard) if isinstance(n, ast.Name)}
        names = {self.variables.get(w, w) for w in written}
        if read & names and not self.generated:
            raise Refused(
                transition,
                f"a completion condition reads {', '.join(sorted(read & names))}, which an "
                "exit action of the completed state writes: SCXML evaluates it before the exit "
                "actions, LightRocks after them",
            )

    def _target(self, scope: _Scope, transition: Element):
        """(target name, history name, postcondition, actions) in ``scope``; a target of
        the generator's own (a detour, a postcondition check) is followed."""
        actions = self._statements(transition) or None
        post = None
        target = transition.get("target") or ""
        if len(target.split()) > 1:
            raise Refused(transition, "several targets (LightRocks enters one state)")
        element = self.states.get(target)
        if element is not None and element.lr("helper") == "postcondition":
            checks = [t for t in element.all("transition") if not t.lr("helper")]
            if not checks:
                raise Refused(element, "a postcondition check without its transition")
            post = self._cond(checks[0])
            target = checks[0].get("target") or ""
            element = self.states.get(target)
        if element is not None and element.lr("helper") == "history-action":
            onward = element.all("transition")
            if not onward:
                raise Refused(element, "a detour into a history without its transition")
            target = onward[0].get("target") or ""
            element = self.states.get(target)
        if element is None or target not in self.name_of:
            raise Refused(transition, f"no state '{target}' to go to")
        history = ""
        if element.tag == "history":
            history = self.name_of[target]
            target = self.scope_of[target]
        if self.scope_of.get(target) != scope.id:
            raise Refused(
                transition,
                "a transition to a state of another parent: LightRocks transitions connect "
                "states of one level",
            )
        return self.name_of[target], history, post, actions

    def _branch(self, scope: _Scope, choice: Element, name: str, transition: Element) -> None:
        if transition.lr("helper"):
            return
        try:
            guard = self._cond(transition)
            target, history, post, actions = self._target(scope, transition)
            scope.transitions.append(
                ast.Transition(name, target, guard, "", (), actions, post, target_history=history)
            )
        except Refused as problem:
            self.refuse(problem.element, problem.message, problem.code)

    def _error_handler(self, scope: _Scope, transition: Element, event: str):
        child = event[len(ERROR_EVENT) :]
        if self.scope_of.get(child) != scope.id:
            self.refuse(transition, f"'{event}' names no state of this level")
            return None
        try:
            guard = self._cond(transition)
            target, history, post, actions = self._target(scope, transition)
        except Refused as problem:
            self.refuse(problem.element, problem.message, problem.code)
            return None
        source = self.name_of[child]
        return ast.Transition(source, target, guard, "error", (), actions, post,
                              target_history=history)  # fmt: skip

    def _invariant(self, transition: Element) -> ast.Invariant:
        text = transition.get("cond") or ""
        tree = _parse(_normalized(text), transition)
        if isinstance(tree, py.UnaryOp) and isinstance(tree.op, py.Not):
            return ast.Invariant(self._expression(tree.operand, transition))
        raise Refused(transition, "an invariant check that is not 'not (…)'")

    def _chart_ending(self, transition: Element) -> bool:
        target = self.states.get(transition.get("target") or "")
        return target is not None and target.tag == "final" and bool(target.lr("helper"))

    # -- executable content -------------------------------------------------------------

    def _statements(self, element: Element, ignore_flags=False, timers=()) -> tuple:
        statements = []
        sends = {t.event for t in timers}
        ids = {t.send_id for t in timers}
        for child in element.children:
            if child.namespace not in (SCXML, ""):
                self.finding(child, DROPPED, Severity.WARNING,
                             f"<{child.tag}> of another namespace is dropped")  # fmt: skip
                continue
            try:
                if child.tag == "assign":
                    if ignore_flags and child.get("location") in self.flags:
                        continue
                    statements.append(self._assign(child))
                elif (child.tag == "send" and child.get("event") in sends) or (
                    child.tag == "cancel" and child.get("sendid") in ids
                ):
                    continue
                elif child.tag == "log":
                    self.finding(child, DROPPED, Severity.WARNING,
                                 "<log> is dropped: LightRocks actions print nothing")  # fmt: skip
                else:
                    self._outside(child, f"in <{element.tag}>")
            except Refused as problem:
                self.refuse(problem.element, problem.message, problem.code)
        return tuple(statements)

    def _assign(self, element: Element) -> ast.Assignment:
        location = element.get("location") or ""
        if location not in self.variables:
            raise Refused(element, f"<assign> to '{location}', which is no <data> of the chart")
        text = element.get("expr")
        if text is None:
            raise Refused(element, "<assign> without expr (content is not read)")
        value = self.expression(text, element)
        return ast.Assignment(ast.Name(self.variables[location]), value)

    def _outside(self, element: Element, where: str) -> None:
        reasons = {
            "script": "arbitrary code",
            "invoke": "another state machine as a service",
            "raise": "an internal event (LightRocks events come from outside)",
            "send": "an event sent elsewhere than a time event of its state",
            "cancel": "a cancel that is not the one of a time event of its state",
            "if": "conditional actions (LightRocks actions are assignments)",
            "foreach": "a loop (LightRocks actions are assignments)",
            "donedata": "data of an outcome",
            "content": "content",
            "param": "a parameter of an event or service",
        }
        reason = reasons.get(element.tag, "outside the SCXML that LightRocks reads")
        self.refuse(element, f"<{element.tag}> {where}: {reason}")

    # -- expressions --------------------------------------------------------------------

    def _cond(self, transition: Element, completion: bool = False):
        """The guard of ``transition`` (and, for a completion, the finals ``In()`` names);
        the generator's own parts of a condition (history variables, the exclusions of
        other regions) are dropped, and ``lr:guard`` is the guard as the model wrote it
        where the condition had to read it before the exit actions."""
        text = transition.get("cond")
        finals: list[str] = []
        if not text:
            return (None, finals) if completion else None
        tree = _parse(_normalized(text), transition)
        parts = self._parts(tree)
        kept = []
        for part in parts:
            ins = _in_states(part)
            if ins is not None and completion and not finals:
                finals = ins
                continue
            if self.generated and (self._flag(part) or _suppressor(part)):
                continue
            kept.append(part)
        if transition.lr("guard"):
            guard = self.expression(transition.lr("guard"), transition)
        elif len(kept) == len(parts) and len(parts) > 1:
            guard = self._expression(tree, transition)
        elif kept:
            guard = self._expression(kept[0], transition)
            for part in kept[1:]:
                guard = ast.Binary("&&", guard, self._expression(part, transition))
        else:
            guard = None
        return (guard, finals) if completion else guard

    def _parts(self, tree: py.expr) -> list[py.expr]:
        """The conjuncts of a condition, the generator's own ones (``In()``, history
        variables, exclusions of other regions) taken out of the conjunctions it nests them
        in; a guard of the model stays whole."""
        if not (isinstance(tree, py.BoolOp) and isinstance(tree.op, py.And)):
            return [tree]
        found: list[py.expr] = []
        for value in tree.values:
            inner = self._parts(value)
            if len(inner) > 1 and any(self._own(p) for p in inner):
                found += inner
            else:
                found.append(value)
        return found

    def _own(self, part: py.expr) -> bool:
        return _in_states(part) is not None or (
            self.generated and (self._flag(part) or _suppressor(part))
        )

    def _flag(self, part: py.expr) -> bool:
        inner = (
            part.operand if isinstance(part, py.UnaryOp) and isinstance(part.op, py.Not) else part
        )
        return isinstance(inner, py.Name) and inner.id in self.flags

    def expression(self, text: str, element: Element) -> ast.Expression:
        return self._expression(_parse(text, element), element)

    def _expression(self, node: py.expr, element: Element) -> ast.Expression:
        special = _function(node)
        if special is not None:
            name, arguments = special
            return ast.Call(
                ast.Name(name),
                tuple(ast.Argument(self._expression(a, element)) for a in arguments),
            )
        match node:
            case py.BoolOp(op=op, values=values):
                operator = "&&" if isinstance(op, py.And) else "||"
                result = self._expression(values[0], element)
                for value in values[1:]:
                    result = ast.Binary(operator, result, self._expression(value, element))
                return result
            case py.UnaryOp(op=py.Not(), operand=operand):
                return ast.Unary("!", self._expression(operand, element))
            case py.UnaryOp(op=py.USub() | py.UAdd() as op, operand=operand):
                sign = "-" if isinstance(op, py.USub) else "+"
                return ast.Unary(sign, self._expression(operand, element))
            case py.BinOp(op=op, left=left, right=right) if type(op) in _OPERATORS:
                return ast.Binary(
                    _OPERATORS[type(op)],
                    self._expression(left, element),
                    self._expression(right, element),
                )
            case py.Compare(left=left, ops=ops, comparators=comparators):
                if not all(type(o) in _OPERATORS for o in ops):
                    raise Refused(element, "a comparison LightRocks does not have (in, is)",
                                  EXPRESSION)  # fmt: skip
                terms, before = [], left
                for op, after in zip(ops, comparators, strict=True):
                    terms.append(
                        ast.Binary(
                            _OPERATORS[type(op)],
                            self._expression(before, element),
                            self._expression(after, element),
                        )
                    )
                    before = after
                result = terms[0]
                for term in terms[1:]:
                    result = ast.Binary("&&", result, term)
                return result
            case py.Constant(value=bool() as value):
                return ast.BooleanLiteral(value)
            case py.Constant(value=int() as value):
                return ast.Quantity(float(value), "", str(value))
            case py.Constant(value=float() as value) if value == value and abs(value) != float(
                "inf"
            ):
                return ast.Quantity(value, "", repr(value))
            case py.Constant(value=str() as value):
                return ast.StringLiteral(value)
            case py.Name(id=name) if name in self.variables:
                return ast.Name(self.variables[name])
            case py.Name(id=name):
                raise Refused(element, f"'{name}' is no <data> of the document", EXPRESSION)
        raise Refused(
            element,
            f"'{py.unparse(node)}' has no LightRocks counterpart (names, numbers, Booleans, "
            "strings, and, or, not, comparisons, + - * / %, abs, min, max)",
            EXPRESSION,
        )


def _walk_tag(element: Element, tag: str) -> Iterator[Element]:
    for child in element.scxml():
        if child.tag == tag:
            yield child
        yield from _walk_tag(child, tag)


def _descendants(element: Element) -> Iterator[Element]:
    for child in element.scxml():
        yield child
        yield from _descendants(child)


def _state_children(element: Element | None) -> list[Element]:
    if element is None:
        return []
    return [c for c in element.scxml() if c.tag in ("state", "parallel", "final")]


def _generated(root: Element) -> bool:
    return any(k.startswith(f"{{{LR}}}") for e in _descendants(root) for k in e.attributes)


def _normalized(text: str) -> str:
    """What python-statemachine makes of a condition: ``true``, ``false``, ``null``,
    ``&&``, ``||``, ``===`` and ``!==`` as Python."""
    replace = {**_COND_WORDS, "===": "==", "!==": "!="}
    return _COND_PATTERN.sub(lambda m: replace[m.group(0)], text)


def _parse(text: str, element: Element) -> py.expr:
    try:
        return py.parse(text.strip(), mode="eval").body
    except SyntaxError as error:
        raise Refused(element, f"'{text}' is no Python expression: {error.msg}",
                      EXPRESSION) from None  # fmt: skip


def _in_states(node: py.expr) -> list[str] | None:
    """The states ``In('a')`` or ``(In('a') or In('b'))`` names."""
    if isinstance(node, py.BoolOp) and isinstance(node.op, py.Or):
        found = [_in_states(v) for v in node.values]
        if all(f is not None and len(f) == 1 for f in found):
            return [f[0] for f in found]  # type: ignore[index]
        return None
    if (
        isinstance(node, py.Call)
        and isinstance(node.func, py.Name)
        and node.func.id == "In"
        and len(node.args) == 1
        and isinstance(node.args[0], py.Constant)
        and isinstance(node.args[0].value, str)
    ):
        return [node.args[0].value]
    return None


def _suppressor(node: py.expr) -> bool:
    """``not (In('X') [and …])``: the target's exclusion of another region's transition."""
    if not (isinstance(node, py.UnaryOp) and isinstance(node.op, py.Not)):
        return False
    inner = node.operand
    if isinstance(inner, py.BoolOp) and isinstance(inner.op, py.And):
        inner = inner.values[0]
    return _in_states(inner) is not None


def _same(a: py.expr, b: py.expr) -> bool:
    return py.dump(a) == py.dump(b)


def _compare(node: py.expr, op: type, left: py.expr, right: py.expr | int) -> bool:
    if not (isinstance(node, py.Compare) and len(node.ops) == 1 and type(node.ops[0]) is op):
        return False
    other = node.comparators[0]
    if isinstance(right, int):
        matches = isinstance(other, py.Constant) and other.value == right
    else:
        matches = _same(other, right)
    return _same(node.left, left) and matches


def _function(node: py.expr) -> tuple[str, list[py.expr]] | None:
    """``abs``, ``min``, ``max`` as the target writes them with comparisons."""
    if isinstance(node, py.BinOp) and isinstance(node.op, py.Mult):
        x, sign = node.left, node.right
        if (
            isinstance(sign, py.BinOp)
            and isinstance(sign.op, py.Sub)
            and _compare(sign.left, py.Gt, x, 0)
            and _compare(sign.right, py.Lt, x, 0)
        ):
            return "abs", [x]
    if isinstance(node, py.BinOp) and isinstance(node.op, py.Add):
        first, second = node.left, node.right
        if all(isinstance(p, py.BinOp) and isinstance(p.op, py.Mult) for p in (first, second)):
            a, b = first.left, second.left
            for name, ops in (("min", (py.LtE, py.Lt)), ("max", (py.GtE, py.Gt))):
                if _compare(first.right, ops[0], a, b) and _compare(second.right, ops[1], b, a):
                    return name, [a, b]
    return None


def _type_of(text: str | None) -> str | None:
    """The type of a literal value (``-2`` Integer, ``0.5`` Real …), read from its syntax."""
    if text is None:
        return None
    try:
        node = py.parse(text.strip(), mode="eval").body
    except SyntaxError:
        return None
    if isinstance(node, py.UnaryOp) and isinstance(node.op, py.USub | py.UAdd):
        node = node.operand
        if isinstance(node, py.Constant) and isinstance(node.value, bool):
            return None
    return _TYPES.get(type(node.value)) if isinstance(node, py.Constant) else None


def _delay(text: str) -> ast.Quantity | None:
    match = _DELAY.fullmatch(text)
    if match is None:
        return None
    number, unit = match.groups()
    value = float(number)
    seconds = value / 1000 if unit == "ms" else value
    return ast.Quantity(seconds, unit, f"{number} {unit}")


def _stereotypes(text: str | None) -> Iterator[ast.Stereotype]:
    for match in re.finditer(r'(\w+)(?:\s*=\s*"((?:[^"\\]|\\.)*)")?', (text or "").strip("<>")):
        yield ast.Stereotype(match.group(1), match.group(2))


def convert_scxml_to_lr(path: Path, text: str, shown: str) -> Conversion:
    """``X.scxml`` to the text of ``<chart name>.lr`` (``None`` when refused)."""
    from lightrocks.languages.lightrocks.printer import print_statechart

    reader = Reader(shown)
    try:
        root = parse_xml(text)
    except Problem as problem:
        where = ast.Position(shown, problem.line, problem.column)
        finding = Diagnostic.at(where, OUTSIDE, Severity.ERROR, problem.message)
        return Conversion(f"{path.stem}.lr", None, [finding])
    try:
        unit = reader.read(root, path.stem)
    except Refused as problem:  # one that no element above stopped
        reader.refuse(problem.element, problem.message, problem.code)
        unit = None
    name = f"{unit.statechart.name if unit else path.stem}.lr"
    if unit is None or any(f.severity is Severity.ERROR for f in reader.findings):
        return Conversion(name, None, reader.findings, unit)
    return Conversion(name, print_statechart(unit), reader.findings, unit)
