"""The transitions of a chart as SCXML ``<transition>`` s: on events, on time events, on
completion (``done.state.<source>``, the guard read before the exit actions), the branches of
a choice, transitions into a history, postconditions, and the ``error`` transitions a parent
takes on ``lr-error.<child>`` (docs/interchange.md, section SCXML).

This is where LightRocks' semantics are spelled out in SCXML's; the states the transitions
need besides the chart's own come from :mod:`generators.scxml.helper_states`.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Iterator, Mapping, Sequence

from lightrocks.generators.scxml import elements
from lightrocks.generators.scxml.chart_tree import Node
from lightrocks.generators.scxml.expressions import Translator, Untranslatable
from lightrocks.generators.scxml.helper_states import HelperStates
from lightrocks.generators.scxml.names import Names
from lightrocks.generators.scxml.time_events import BUDGET, TimeEvents
from lightrocks.languages.scxml.markup import ERROR_EVENT, event_name, lr
from lightrocks.metamodel import ast

_REFUSED_STIMULI = ("timeout", "preempted")


class TransitionWriter:
    """The ``<transition>`` elements of one chart, node by node."""

    def __init__(
        self,
        names: Names,
        translate: Translator,
        flags: Mapping[Node, str],
        helpers: HelperStates,
        time_events: TimeEvents,
    ) -> None:
        self.names = names
        self.translate = translate
        self.flags = flags
        self.helpers = helpers
        self.time_events = time_events

    def _id(self, node: Node) -> str:
        return self.names.state(node.path)

    def transitions(self, node: Node) -> Iterator[ET.Element]:
        for internal in node.internal:
            yield from self._internal(node, internal)
        for invariant in node.invariants:
            target, content = self.helpers.failure(node)
            cond = f"not {self.translate.cond(invariant)}"
            yield elements.transition(None, cond, target, content, helper="invariant")
        if node.kind == "choice":
            yield from self._branches(node)
            return
        for transition in node.leaving():
            yield from self._leaving(node, transition)
        if node.kind not in ("chart", "region") and node.completes() and not self._handled(node):
            target, content = self.helpers.failure(node.parent)
            yield elements.transition(
                f"done.state.{self._id(node)}", None, target, content, helper="unhandled"
            )

    def _internal(self, node: Node, internal: ast.InternalTransition) -> Iterator[ET.Element]:
        guard = self.translate.cond(internal.guard) if internal.guard is not None else None
        if internal.stimulus == "after":
            event = self.time_events.event_of(internal)
            if event is None:
                return
        else:
            self._plain_stimulus(internal)
            event = event_name(internal.stimulus)
            guard = _conjunction(guard, *self._suppressors(node, internal.stimulus, False))
        element = elements.transition(event, guard, None, [])
        self._actions(element, internal.action)
        yield element

    def _plain_stimulus(self, transition: ast.Transition | ast.InternalTransition) -> None:
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
            target, content = self.helpers.failure(owner)
            yield elements.transition(None, None, target, content, helper="no branch")

    def _leaving(self, node: Node, transition: ast.Transition) -> Iterator[ET.Element]:
        owner = node.parent
        stimulus = transition.stimulus
        if stimulus == "error":
            return  # an internal transition of the parent (see error_handlers)
        if stimulus == "after":
            event = self.time_events.event_of(transition)
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
        event = f"done.state.{self._id(node)}"
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
        tests = [f"In('{self._id(f)}')" for f in finals]
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
                        inside = f"In('{self._id(child)}')"
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
        helper = self.helpers.postcondition(owner)
        post = self.translate.cond(transition.postcondition)
        for element in self._enter(owner, transition, target, None, post, False, False):
            helper.append(element)
        fail, content = self.helpers.failure(owner)
        helper.append(elements.transition(None, None, fail, content, helper="postcondition"))
        self.helpers.add(owner, helper)
        main = elements.transition(event, cond, helper.get("id"), [], internal=internal)
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
        found = []
        if transition.target_history:
            history = target.children.get(transition.target_history)
            if history is None or history.kind != "history":
                raise Untranslatable(
                    transition.target_position, f"no history '{transition.target_history}'"
                )
            flag = self.flags.get(target)
            into = self._id(history)
            if act and transition.action:
                into = self.helpers.detour(owner, into)
            if flag is None:
                found.append(elements.transition(event, cond, into, [], internal))
            else:
                remembered = _conjunction(cond, f"not {flag}")
                forgotten = _conjunction(cond, flag)
                found.append(elements.transition(event, remembered, into, [], internal))
                found.append(
                    elements.transition(event, forgotten, self._id(target), [], internal, "history")
                )
        else:
            found.append(elements.transition(event, cond, self._id(target), [], internal))
        if act:
            for element in found:
                self._actions(element, transition.action)
        return found

    def _actions(self, element: ET.Element, statements: Sequence[ast.Statement] | None) -> None:
        for statement in statements or ():
            element.append(elements.statement(self.translate, statement))

    def error_handlers(self, owner: Node) -> Iterator[ET.Element]:
        """``S -> X error`` as internal transitions of ``owner`` on ``lr-error.S``, and one
        more that ends ``owner`` with error when none takes it."""
        for child in [*owner.children.values(), *owner.regions]:
            handlers = [t for t in owner.transitions if t.source == child.name]
            handlers = [t for t in handlers if t.stimulus == "error"]
            event = ERROR_EVENT + self._id(child)
            for handler in handlers:  # the failed child has been left: as in LightRocks,
                guard = handler.guard  # the guard sees what its exit actions wrote
                cond = self.translate.cond(guard) if guard is not None else None
                yield from self.take(owner, handler, event, cond, internal=True)
        for child in self.helpers.failing.get(owner, []):
            handlers = [t for t in owner.transitions if t.source == child.name]
            handled = any(
                t.stimulus == "error" and t.guard is None and t.postcondition is None
                for t in handlers
            )
            if not handled:
                target, content = self.helpers.failure(owner)
                yield elements.transition(
                    ERROR_EVENT + self._id(child), None, target, content, helper="error"
                )

    def chart_transitions(self, chart: Node) -> Iterator[ET.Element]:
        if chart.completes():
            chart_id = self._id(chart)
            yield elements.transition(f"done.state.{chart_id}", None, self.helpers.end("end"), [])
        event = self.time_events.event_of(BUDGET)
        if self.time_events.budget is not None and event is not None:
            yield elements.transition(event, None, self.helpers.end("timeout"), [])
        yield elements.transition(
            "error.execution", None, self.helpers.end("error"), [], helper="fault"
        )


def _conjunction(*parts: str | None) -> str | None:
    present = [p for p in parts if p]
    if not present:
        return None
    return present[0] if len(present) == 1 else " and ".join(f"({p})" for p in present)
