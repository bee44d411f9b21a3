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

import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from lightrocks.languages.scxml.markup import ERROR_EVENT, SCXML, lightrocks_event
from lightrocks.languages.scxml.read_actions import ActionReader
from lightrocks.languages.scxml.read_context import DROPPED, OUTSIDE, ReadContext, Refused
from lightrocks.languages.scxml.read_data import DataReader
from lightrocks.languages.scxml.read_expressions import ExpressionReader
from lightrocks.languages.scxml.read_names import NameReader
from lightrocks.languages.scxml.read_time_events import TimeEventReader
from lightrocks.languages.scxml.read_transitions import TransitionReader
from lightrocks.languages.scxml.xml_tree import (
    Element,
    XmlError,
    parse_xml,
    state_children,
    written_by_target,
)
from lightrocks.metamodel import ast
from lightrocks.workbench.conversions import Conversion, Converted
from lightrocks.workbench.diagnostics import Diagnostic, Severity


@dataclass(eq=False)
class Scope:
    """A state's (or region's, or the chart's) body being built."""

    id: str
    element: Element | None
    body: list[object] = field(default_factory=list)
    transitions: list[ast.Transition] = field(default_factory=list)
    parent: Scope | None = None


class Reader:
    """Reads one SCXML document into a LightRocks statechart, reporting to ``context``."""

    def __init__(self, shown: str) -> None:
        self.context = ReadContext(shown)
        self.names = NameReader(self.context)
        self.expressions = ExpressionReader(self.context)
        self.data = DataReader(self.context, self.names, self.expressions)
        self.actions = ActionReader(self.context, self.expressions)
        self.timers = TimeEventReader(self.context)
        self.transitions = TransitionReader(
            self.context, self.expressions, self.actions, self.timers
        )
        self.wrapper_id = ""

    @property
    def findings(self) -> list[Diagnostic]:
        return self.context.findings

    # -- document -----------------------------------------------------------------------

    def read(self, root: Element, fallback_name: str) -> ast.StatechartUnit | None:
        if root.tag != "scxml" or root.namespace not in (SCXML, ""):
            self.context.refuse(root, f"<{root.tag}> is not an SCXML document (<scxml> expected)")
            return None
        self.context.generated = written_by_target(root)
        name = root.get("name") or fallback_name
        chart_name = self.names.rename(root, name)
        tops = [c for c in root.scxml() if c.tag in ("state", "parallel", "final")]
        wrapper = self._wrapper(root, tops, name)
        self.wrapper_id = wrapper.get("id") if wrapper is not None else ""
        self._index(root, wrapper)
        parameters = self.data.parameters(root)
        chart = Scope("", root)
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
                self.context.outside(child, "at the top of the document")
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
                self.context.states[identifier] = child
                if child is wrapper:
                    visit(child, identifier)
                    continue
                if child.lr("helper"):
                    continue
                self.context.scope_of[identifier] = scope
                self.context.name_of[identifier] = self.names.state(scope, child)
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
                self.context.refuse(
                    tags[0], "an <initial> with executable content or several targets"
                )
                return None
            initial = transitions[0].get("target")
        if initial and len(initial.split()) > 1:
            self.context.refuse(element, "several initial states (LightRocks enters one)")
            return None
        if not initial:
            first = next((c for c in children if c.tag in ("state", "parallel", "final")), None)
            return first.get("id") if first is not None else None
        return initial

    def paths(self, chart: str) -> dict[str, tuple[str, ...]]:
        """State id -> LightRocks path (chart name first), as the runtime names states."""
        found = {}
        for identifier in self.context.name_of:
            path, current = [], identifier
            while current:
                path.insert(0, self.context.name_of[current])
                current = self.context.scope_of.get(current, "")
                if current == self.wrapper_id:
                    break
            found[identifier] = (chart, *path)
        if self.wrapper_id:
            found[self.wrapper_id] = (chart,)
        return found

    # -- states -------------------------------------------------------------------------

    def _child(self, scope: Scope, element: Element, initial: str | None) -> None:
        identifier = element.get("id")
        if element.lr("helper"):
            return
        if not identifier:
            self.context.refuse(element, f"<{element.tag}> without id")
            return
        name = self.context.name_of.get(identifier) or self.names.state(scope.id, element)
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
                branch = self.transitions.branch(scope.id, name, transition)
                if branch is not None:
                    scope.transitions.append(branch)
            return
        inner = Scope(identifier, element, parent=scope)
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
        scope.transitions += self.transitions.leaving(scope.id, element, name)

    def _history(self, scope: Scope, element: Element, name: str) -> None:
        kind = "deep history" if element.get("type") == "deep" else "history"
        defaults = element.all("transition")
        initial = self._initial(scope.element, state_children(scope.element))
        for default in defaults:
            if default.get("target") != initial or default.scxml():
                self.context.refuse(
                    default,
                    "a history whose default is not the initial state, or has actions: a "
                    "LightRocks history without memory enters its state as usual",
                )
        finals = [c for c in scope.element.all("final") if not c.lr("helper")]
        if finals and not self.context.generated:
            self.context.finding(
                element,
                DROPPED,
                Severity.WARNING,
                "a history beside final states: LightRocks forgets what was active when the "
                "state was left through a final state and enters it at its initial state, where "
                "SCXML enters that final state again",
            )
        scope.body.append(ast.Pseudostate(kind, name))

    def _final_content(
        self, element: Element, allow_entry: bool
    ) -> tuple[list[ast.Action], list[ast.Action]]:
        """The entry and exit actions of a ``<final>``."""
        entry: list[ast.Action] = []
        exit_: list[ast.Action] = []
        for child in element.scxml():
            if child.tag in ("onentry", "onexit"):
                statements = self.actions.statements(child, ignore_flags=True)
                if statements and (allow_entry or child.tag == "onexit"):
                    kind = "entry" if child.tag == "onentry" else "exit"
                    (entry if kind == "entry" else exit_).append(ast.Action(kind, statements))
                elif statements:
                    self.context.outside(child, "on an end condition")
            elif child.tag == "donedata":
                self.context.refuse(child, "<donedata>: LightRocks outcomes carry no data")
            else:
                self.context.outside(child, "in a <final>")
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

    def _state_body(self, scope: Scope, element: Element, chart_root: bool = False) -> str | None:
        """Fill ``scope`` with the body of ``element``; for the chart's own state the
        ``<<timeout>>`` value, if it has a budget."""
        timers = self.timers.of(element)
        budget = None
        entry, exit_ = [], []
        for child in element.scxml():
            if child.tag == "onentry":
                entry += self.actions.statements(child, ignore_flags=True, timers=timers)
            elif child.tag == "onexit":
                exit_ += self.actions.statements(child, ignore_flags=True, timers=timers)
        if entry:
            scope.body.append(ast.Action("entry", tuple(entry)))
        if exit_:
            scope.body.append(ast.Action("exit", tuple(exit_)))
        for transition in element.all("transition"):
            helper = transition.lr("helper")
            if helper == "invariant":
                try:
                    scope.body.append(self.expressions.invariant(transition))
                except Refused as problem:
                    self.context.refused(problem)
            elif helper:
                continue
            elif chart_root and self.transitions.ends_chart(transition):
                timer = next((t for t in timers if transition.get("event") in t.events), None)
                if timer is not None:
                    budget = f"{timer.delay.text}".replace(" ", " ")
                continue
            elif not transition.get("target"):
                internal = self.transitions.internal(transition, timers)
                if internal is not None:
                    scope.body.append(internal)
            elif chart_root and not (transition.get("event") or "").startswith(ERROR_EVENT):
                self.context.refuse(transition, "a transition that leaves the chart itself")
        if element.tag == "parallel":
            for region in element.scxml():
                if region.tag == "state" and not region.lr("helper"):
                    scope.body.append(self._region(scope, region))
                elif region.tag in ("parallel", "final", "history"):
                    self.context.refuse(
                        region, f"a <{region.tag}> in a <parallel>: a region is a <state>"
                    )
                elif region.tag not in ("onentry", "onexit", "transition", "datamodel"):
                    self.context.outside(region, "in a <parallel>")
        else:
            children = state_children(element)
            initial = self._initial(element, children) if children else None
            for child in element.scxml():
                if child.tag in ("state", "parallel", "final", "history"):
                    self._child(scope, child, initial)
                elif child.tag not in ("onentry", "onexit", "transition", "initial", "datamodel"):
                    self.context.outside(child, f"in a <{element.tag}>")
        self._finish(scope)
        return budget

    def _region(self, scope: Scope, element: Element) -> ast.Region:
        if not element.get("id"):
            self.context.refuse(element, "a region without id: LightRocks names every region")
            return ast.Region("region", ())
        name = self.context.name_of.get(element.get("id")) or self.names.state(scope.id, element)
        inner = Scope(element.get("id"), element, parent=scope)
        children = state_children(element)
        if not children:
            self.context.refuse(element, "a region without states")
        for child in element.scxml():
            if child.tag == "transition" and child.lr("helper"):
                continue
            if child.tag in ("onentry", "onexit", "transition"):
                self.context.refuse(child, "a region's own actions or transitions")
        initial = self._initial(element, children)
        for child in element.scxml():
            if child.tag in ("state", "parallel", "final", "history"):
                self._child(inner, child, initial)
        self._finish(inner)
        return ast.Region(name, tuple(inner.body))

    def _finish(self, scope: Scope) -> None:
        """The transitions between the children of ``scope``, after them; and the ``error``
        transitions, which the target writes as ``scope``'s own on ``lr-error.<child>``."""
        if scope.element is not None:
            for transition in scope.element.all("transition"):
                event = transition.get("event") or ""
                if event.startswith(ERROR_EVENT) and not transition.lr("helper"):
                    handler = self.transitions.error_handler(scope.id, transition, event)
                    if handler is not None:
                        scope.transitions.append(handler)
        scope.body += scope.transitions
        scope.transitions = []


def _stereotypes(text: str | None) -> Iterator[ast.Stereotype]:
    for match in re.finditer(r'(\w+)(?:\s*=\s*"((?:[^"\\]|\\.)*)")?', (text or "").strip("<>")):
        yield ast.Stereotype(match.group(1), match.group(2))


def convert_scxml_to_lr(path: Path, text: str, shown: str) -> Converted:
    """``X.scxml`` to the text of ``<chart name>.lr`` (``None`` when refused)."""
    from lightrocks.languages.lightrocks.printer import print_statechart

    reader = Reader(shown)
    try:
        root = parse_xml(text)
    except XmlError as problem:
        where = ast.Position(shown, problem.line, problem.column)
        finding = Diagnostic.at(where, OUTSIDE, Severity.ERROR, problem.message)
        return Converted(f"{path.stem}.lr", None, [finding])
    try:
        unit = reader.read(root, path.stem)
    except Refused as problem:  # one that no element above stopped
        reader.context.refused(problem)
        unit = None
    name = f"{unit.statechart.name if unit else path.stem}.lr"
    if unit is None or any(f.severity is Severity.ERROR for f in reader.findings):
        return Converted(name, None, reader.findings, unit)
    return Converted(name, print_statechart(unit), reader.findings, unit)


SCXML_TO_LR = Conversion(
    ".scxml",
    "lr",
    "SCXML (W3C) of the subset the scxml target writes to LightRocks",
    convert_scxml_to_lr,
)
