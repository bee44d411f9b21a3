"""SCXML ``<transition>`` s back to LightRocks transitions: on events (one transition per
name), on a time event of the source, on its completion (``done.state.<source>``, the
outcome read from ``In('<final>')``), the branches of a choice, internal transitions, and
the ``error`` transitions the target writes as the parent's on ``lr-error.<child>``.

A target of the generator's own (a postcondition check, a detour into a history) is
followed to the state it stands for; a transition between states of different parents is
refused, since LightRocks transitions connect states of one level.
"""

from __future__ import annotations

from lightrocks.languages.scxml.markup import ERROR_EVENT, lightrocks_event
from lightrocks.languages.scxml.read_actions import ActionReader
from lightrocks.languages.scxml.read_context import ReadContext, Refused
from lightrocks.languages.scxml.read_expressions import ExpressionReader
from lightrocks.languages.scxml.read_names import IDENTIFIER
from lightrocks.languages.scxml.read_time_events import TimeEventReader, Timer
from lightrocks.languages.scxml.xml_tree import Element, descendants
from lightrocks.metamodel import ast

_Arguments = tuple[ast.Expression, ...]
_Target = tuple[str, str, ast.Expression | None, tuple[ast.Assignment, ...] | None]
"""Target name, history name, postcondition and actions of a transition."""


class TransitionReader:
    """The transitions of one document; ``scope`` is the id of the state whose body holds
    a transition (``""`` for the top of the chart)."""

    def __init__(
        self,
        context: ReadContext,
        expressions: ExpressionReader,
        actions: ActionReader,
        timers: TimeEventReader,
    ) -> None:
        self.context = context
        self.expressions = expressions
        self.actions = actions
        self.timers = timers

    def _stimulus(self, transition: Element, timers: list[Timer]) -> tuple[str, _Arguments]:
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
        if event.startswith(("done.", "error.", ERROR_EVENT)) or not IDENTIFIER.fullmatch(
            lightrocks_event(event)
        ):
            raise Refused(
                element,
                f"the event '{event}': LightRocks events are names (no '.', no '*'), and "
                "done.* and error.* events belong to the SCXML engine",
            )
        return lightrocks_event(event)

    def internal(self, transition: Element, timers: list[Timer]) -> ast.InternalTransition | None:
        """The internal transition ``transition`` (a transition without target)."""
        try:
            if not transition.get("event"):
                raise Refused(transition, "an eventless transition without target never rests")
            stimulus, arguments = self._stimulus(transition, timers)
            guard = self.expressions.guard(transition)
            action = self.actions.statements(transition) or None
            return ast.InternalTransition(stimulus, guard, arguments, action)
        except Refused as problem:
            self.context.refused(problem)
            return None

    def leaving(self, scope: str, element: Element, name: str) -> list[ast.Transition]:
        """The transitions of state ``element`` that have a target (in its parent's body)."""
        timers = self.timers.of(element)
        found = []
        for transition in element.all("transition"):
            event = transition.get("event") or ""
            if transition.lr("helper") or not transition.get("target"):
                continue
            if event.startswith(ERROR_EVENT):
                continue  # an error transition of a child (see Reader._finish)
            try:
                found += self._transition(scope, element, name, transition, timers)
            except Refused as problem:
                self.context.refused(problem)
        return found

    def _transition(
        self,
        scope: str,
        element: Element,
        name: str,
        transition: Element,
        timers: list[Timer],
    ) -> list[ast.Transition]:
        if transition.get("type") == "internal":
            raise Refused(transition, "an internal transition to a state inside its source")
        event = transition.get("event") or ""
        outcome = ""
        if event.startswith("done.state."):
            if event != f"done.state.{element.get('id')}":
                raise Refused(transition, f"'{event}': a completion of another state")
            guard, finals = self.expressions.completion_guard(transition)
            if len(finals) == 1 and transition.lr("outcome") != "any":
                outcome = self._outcome_name(finals[0], transition)
            self._completion_guard(transition, element, guard)
            stimuli: list[tuple[str, _Arguments]] = [(outcome, ())]
        elif not event:
            raise Refused(
                transition,
                "an eventless transition from a state that is not a choice (LightRocks "
                "leaves a state on an event, a time event or its completion)",
            )
        else:
            guard = self.expressions.guard(transition)
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
        if final not in self.context.name_of:
            raise Refused(transition, f"In('{final}') names no final state")
        return self.context.name_of[final]

    def _completion_guard(
        self, transition: Element, source: Element, guard: ast.Expression | None
    ) -> None:
        """SCXML evaluates a completion's condition before the exit actions, LightRocks
        after them: refuse a condition that reads what they write."""
        if guard is None or transition.lr("guard") is not None:
            return
        written = set()
        for element in [source, *descendants(source)]:
            for exit_ in element.all("onexit"):
                written |= {a.get("location") for a in exit_.all("assign")}
        read = {n.name for n in ast.walk(guard) if isinstance(n, ast.Name)}
        names = {self.context.variables.get(w, w) for w in written}
        if read & names and not self.context.generated:
            raise Refused(
                transition,
                f"a completion condition reads {', '.join(sorted(read & names))}, which an "
                "exit action of the completed state writes: SCXML evaluates it before the exit "
                "actions, LightRocks after them",
            )

    def _target(self, scope: str, transition: Element) -> _Target:
        """(target name, history name, postcondition, actions) in ``scope``; a target of
        the generator's own (a detour, a postcondition check) is followed."""
        actions = self.actions.statements(transition) or None
        post = None
        target = transition.get("target") or ""
        if len(target.split()) > 1:
            raise Refused(transition, "several targets (LightRocks enters one state)")
        element = self.context.states.get(target)
        if element is not None and element.lr("helper") == "postcondition":
            checks = [t for t in element.all("transition") if not t.lr("helper")]
            if not checks:
                raise Refused(element, "a postcondition check without its transition")
            post = self.expressions.guard(checks[0])
            target = checks[0].get("target") or ""
            element = self.context.states.get(target)
        if element is not None and element.lr("helper") == "history-action":
            onward = element.all("transition")
            if not onward:
                raise Refused(element, "a detour into a history without its transition")
            target = onward[0].get("target") or ""
            element = self.context.states.get(target)
        if element is None or target not in self.context.name_of:
            raise Refused(transition, f"no state '{target}' to go to")
        history = ""
        if element.tag == "history":
            history = self.context.name_of[target]
            target = self.context.scope_of[target]
        if self.context.scope_of.get(target) != scope:
            raise Refused(
                transition,
                "a transition to a state of another parent: LightRocks transitions connect "
                "states of one level",
            )
        return self.context.name_of[target], history, post, actions

    def branch(self, scope: str, name: str, transition: Element) -> ast.Transition | None:
        """A branch of the choice ``name`` (``None`` for the generator's own, or refused)."""
        if transition.lr("helper"):
            return None
        return self._from(scope, name, "", transition)

    def error_handler(self, scope: str, transition: Element, event: str) -> ast.Transition | None:
        """``<child> -> X error`` from ``scope``'s transition on ``lr-error.<child>``."""
        child = event[len(ERROR_EVENT) :]
        if self.context.scope_of.get(child) != scope:
            self.context.refuse(transition, f"'{event}' names no state of this level")
            return None
        return self._from(scope, self.context.name_of[child], "error", transition)

    def _from(
        self, scope: str, source: str, stimulus: str, transition: Element
    ) -> ast.Transition | None:
        """``source -> <its target>`` on ``stimulus`` (``None`` when refused)."""
        try:
            guard = self.expressions.guard(transition)
            target, history, post, actions = self._target(scope, transition)
        except Refused as problem:
            self.context.refused(problem)
            return None
        return ast.Transition(
            source, target, guard, stimulus, (), actions, post, target_history=history
        )

    def ends_chart(self, transition: Element) -> bool:
        target = self.context.states.get(transition.get("target") or "")
        return target is not None and target.tag == "final" and bool(target.lr("helper"))
