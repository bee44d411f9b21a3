"""The states the SCXML writer adds to a chart's own (marked ``lr:helper``): the resting
state a parent enters when a child ends with ``error``, the final states of the document,
the states that check a postcondition and the detours into a history.

The reader folds each of them back into what it stands for; here they are made, each id
allocated once and in the order the writer asks for it.
"""

from __future__ import annotations

import itertools
import xml.etree.ElementTree as ET
from collections.abc import Mapping

from lightrocks.generators.scxml import elements
from lightrocks.generators.scxml.chart_tree import Node
from lightrocks.generators.scxml.names import Names
from lightrocks.languages.scxml.markup import ERROR_EVENT, lr, q


class HelperStates:
    """The generator's own states of one document, by the node whose body holds them."""

    def __init__(self, names: Names, chart_id: str, flags: Mapping[Node, str]) -> None:
        self.names = names
        self.chart_id = chart_id
        self.flags = flags
        self.inside: dict[Node, list[ET.Element]] = {}
        self.ends: dict[str, ET.Element] = {}
        self.failing: dict[Node, list[Node]] = {}
        self._resting: dict[Node, str] = {}
        self._numbers = itertools.count(1)

    def add(self, owner: Node, state: ET.Element) -> None:
        self.inside.setdefault(owner, []).append(state)

    def postcondition(self, owner: Node) -> ET.Element:
        """A new state in ``owner`` that checks a postcondition (not yet added)."""
        helper_id = self.names.helper(self.names.state(owner.path), f"post{next(self._numbers)}")
        return ET.Element(q("state"), {"id": helper_id, lr("helper"): "postcondition"})

    def detour(self, owner: Node, history: str) -> str:
        """A state in ``owner`` left at once for ``history``: a transition with actions goes
        there instead of into the history itself. Equivalent in SCXML; python-statemachine
        3.2.2 runs the actions of a transition into a history twice (it counts the
        transition as the history's default content as well)."""
        owner_id = self.names.state(owner.path)
        helper_id = self.names.helper(owner_id, f"history{next(self._numbers)}")
        helper = ET.Element(q("state"), {"id": helper_id, lr("helper"): "history-action"})
        helper.append(elements.transition(None, None, history, []))
        self.add(owner, helper)
        return helper_id

    def failure(self, node: Node) -> tuple[str, list[ET.Element]]:
        """Target and content of a transition that ends ``node`` with ``error``."""
        while node.kind == "region":
            node = node.parent
        if node.kind == "chart":
            return self.end("error"), []
        owner = node.parent
        if owner not in self._resting:
            resting = self.names.helper(self.names.state(owner.path), "failing")
            self._resting[owner] = resting
            element = ET.Element(q("state"), {"id": resting, lr("helper"): "error"})
            if owner in self.flags:
                onentry = ET.SubElement(element, q("onentry"))
                onentry.append(elements.assign(self.flags[owner], "True"))
            self.add(owner, element)
        failing = self.failing.setdefault(owner, [])
        if node not in failing:
            failing.append(node)
        raised = ET.Element(q("raise"), {"event": ERROR_EVENT + self.names.state(node.path)})
        return self._resting[owner], [raised]

    def end(self, outcome: str) -> str:
        """A final state of the document: the chart has ended (``end``), or ended with
        ``error`` or ``timeout``."""
        if outcome not in self.ends:
            end_id = self.names.helper(self.chart_id, outcome)
            self.ends[outcome] = ET.Element(q("final"), {"id": end_id, lr("helper"): outcome})
        return self.ends[outcome].get("id")
