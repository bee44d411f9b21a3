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

This module writes the document, its data model and its states; the chart's tree is
:mod:`generators.scxml.chart_tree`, the transitions :mod:`generators.scxml.transitions`, the
time events :mod:`generators.scxml.time_events` and the generator's own states
:mod:`generators.scxml.helper_states`.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from lightrocks.generators.scxml import elements
from lightrocks.generators.scxml.chart_tree import ChartBuilder, Node, Refusal, may_fail
from lightrocks.generators.scxml.expressions import Translator, Untranslatable
from lightrocks.generators.scxml.helper_states import HelperStates
from lightrocks.generators.scxml.names import Names
from lightrocks.generators.scxml.time_events import TimeEvents
from lightrocks.generators.scxml.transitions import TransitionWriter
from lightrocks.languages.scxml.markup import LR, SCXML, event_name, lr, q
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import fold
from lightrocks.metamodel.printer import stereotypes as stereotype_text


@dataclass
class Document:
    """The generated document and what a reader of it needs: state id -> LightRocks path,
    parameter -> data-model variable."""

    text: str
    paths: dict[str, tuple[str, ...]]
    variables: dict[str, str]


class Writer:
    """Writes one plain statechart; :meth:`document` raises the first :class:`Refusal` with
    the others attached (``refusals``)."""

    def __init__(self, unit: ast.StatechartUnit, budget: ast.Stereotype | None = None) -> None:
        self.unit = unit
        self.chart_ast = unit.statechart
        self.refusals: list[Refusal] = []
        self.names = Names()
        blocks = [e for e in self.chart_ast.elements if isinstance(e, ast.ParameterBlock)]
        self.parameters = {p.name: p for b in blocks for p in b.parameters}
        for name in self.parameters:
            self.names.data(name)
        self.translate = Translator(self.names, self.parameters)
        self.chart = ChartBuilder(self.refusals).chart(self.chart_ast)
        self.chart_id = self.names.state(self.chart.path)
        self._ids(self.chart)
        self.flags: dict[Node, str] = {}
        self._flags(self.chart)
        self.helpers = HelperStates(self.names, self.chart_id, self.flags)
        self.time_events = TimeEvents(
            self.chart_ast, self.chart, self.names, self.parameters, budget, self.refuse
        )
        self.transitions = TransitionWriter(
            self.names, self.translate, self.flags, self.helpers, self.time_events
        )

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
            if histories and (child.finals() or may_fail(child)):
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
        for end in self.helpers.ends.values():
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

    def _guarded(self, write: Callable[..., ET.Element], *args: object) -> ET.Element:
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
        onentry = self._onentry(node)
        if len(onentry):
            element.append(onentry)
        onexit = ET.Element(q("onexit"))
        for statement in node.exit:
            onexit.append(self._guarded(elements.statement, self.translate, statement))
        onexit.extend(self.time_events.cancels(node))
        if len(onexit):
            element.append(onexit)
        for transition in self.time_events.ties(node):
            element.append(transition)
        for transition in self._guarded_all(self.transitions.transitions, node):
            element.append(transition)
        for child in node.children.values():
            element.append(self._guarded(self.write, child))
        for region in node.regions:
            element.append(self._guarded(self.write, region))
        for transition in self._guarded_all(self.transitions.error_handlers, node):
            element.append(transition)
        for helper in self.helpers.inside.get(node, []):
            element.append(helper)
        if node.kind == "chart":
            for transition in self.transitions.chart_transitions(node):
                element.append(transition)
        return element

    def _guarded_all(
        self, write: Callable[[Node], Iterable[ET.Element]], node: Node
    ) -> list[ET.Element]:
        try:
            return list(write(node))
        except Untranslatable as problem:
            self.refuse(problem.position, problem.message)
            return []

    def _onentry(self, node: Node) -> ET.Element:
        onentry = ET.Element(q("onentry"))
        if node in self.flags:
            onentry.append(elements.assign(self.flags[node], "False"))
        if node.kind in ("final", "end") and node.parent in self.flags:
            onentry.append(elements.assign(self.flags[node.parent], "True"))
        for statement in node.entry:
            onentry.append(self._guarded(elements.statement, self.translate, statement))
        onentry.extend(self.time_events.sends(node))
        return onentry

    def _history(self, node: Node) -> ET.Element:
        parent = node.parent
        element = ET.Element(
            q("history"), {"id": self.id(node), "type": "deep" if node.deep else "shallow"}
        )
        if parent.initial is not None:
            default = ET.SubElement(element, q("transition"))
            default.set("target", self.id(parent.children[parent.initial]))
        return element
