"""The properties a statechart states (``property name: formula;``), proved, refuted or left
undecided on the configurations the model checker explored (:mod:`.checker`).

A property is judged at *moments*: every explored configuration, and every *ending* (the
step that ends the run, with the store after it). A predicate names the chart's own states
(true while active), its outcomes (true at an ending with that outcome) and its values. At a
moment a value is known (the store, the parameters' values) or free (a sensor, a value the
checker does not track); the solver then says whether the predicate holds for every free
value, for none, or for some only. At an ending it knows more: what the step that ended the
run guarantees — the end condition that ended the action (and that the ones before it did
not hold), and the guards of the statechart's own transitions that fired (and that the
earlier ones on the same stimulus did not hold), each as long as the step wrote nothing it
reads afterwards. A step reads one set of sensor values: those of the tick that ended the
command.

Verdicts: *refuted* where a moment falsifies the predicate for every free value (the path to
it is the counterexample); *undecided* where it holds for some free values only, or the
exploration stopped at its limit; *proved* otherwise. A reachability is proved by a moment
where its predicate holds, refuted when the complete exploration has none where it may.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from itertools import pairwise

import networkx as nx
import z3

from lightrocks.languages.lightrocks.access import names_of
from lightrocks.languages.lightrocks.behaviour.checker import (
    RAISE_LIMIT,
    START,
    Counterexample,
    Exploration,
)
from lightrocks.languages.lightrocks.behaviour.flow import FINAL, Flow, Step
from lightrocks.languages.lightrocks.behaviour.judge import constants
from lightrocks.languages.lightrocks.behaviour.liveness import Liveness, Read
from lightrocks.languages.lightrocks.behaviour.store import (
    WINDOW,
    Beyond,
    Frame,
    Store,
    constant,
    fact,
    resolve,
)
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.languages.lightrocks.properties import KINDS, outcome_names, state_names
from lightrocks.metamodel import ast

REFUTED = {
    "ensures": "LR0710",
    "always": "LR0711",
    "never": "LR0712",
    "after": "LR0713",
    "reachable": "LR0714",
    "exclusive": "LR0715",
}
"""The code of a refuted property, by the keyword of its formula."""
UNDECIDED = "LR0716"


@dataclass(frozen=True)
class Verdict:
    """A property that is not proved: refuted (its code in :data:`REFUTED`) or undecided."""

    code: str
    property: ast.Property
    message: str
    hint: str
    counterexample: Counterexample | None


@dataclass(frozen=True)
class Moment:
    """A configuration (``step`` None), or the step from ``node`` that ends the run with
    ``outcome``; ``store`` is what is known then, ``facts`` what the step guarantees."""

    node: object
    tree: tuple
    store: Store
    step: Step | None = None
    outcome: str = ""
    facts: tuple[z3.BoolRef, ...] = ()


class PropertyLiveness(Liveness):
    """Keeps the values the root's properties read, which nothing of the flow may read."""

    def __init__(self, root: Component) -> None:
        super().__init__()
        self.root = root
        self._property_reads: frozenset[Read] | None = None

    def reads(self, component: Component) -> frozenset[Read]:
        found = super().reads(component)
        if component is not self.root:
            return found
        if self._property_reads is None:
            pairs: set[Read] = set()
            for own in component.region.properties:
                for path in component.access(own.expressions).reads:
                    head, _, rest = path.partition(".")
                    pairs.add(("", head))
                    if rest:
                        pairs.add((head, rest.partition(".")[0]))
            self._property_reads = frozenset(pairs)
        return found | self._property_reads


class Properties:
    """The verdicts on the properties of the chart at the root of ``flow``."""

    def __init__(self, flow: Flow, exploration: Exploration) -> None:
        self.flow = flow
        self.exploration = exploration
        self.root = flow.root
        self.evaluator = flow.evaluator(self.root.region)
        self.terms = self.evaluator.terms
        self.judge = self.evaluator.judge
        self.atoms = set(state_names(self.root.region)) | set(outcome_names(self.root.region))
        self._own = {id(t) for t in self.root.region.transitions}
        self._moments: list[Moment] | None = None
        self._answers: dict[tuple, tuple[bool | None, object]] = {}
        self._parents: dict[object, object] | None = None
        self._read: dict[tuple, frozenset[str]] = {}
        self._commands: dict[tuple, list[z3.BoolRef]] = {}
        named = {
            str(c)
            for p in self.root.region.properties
            for e in p.expressions
            for c in constants(self._term(e))
        }
        self._ends = set(self.root.region.outcomes) | ({"error"} & named)
        """The endings judged: the declared ones, and ``error`` where a property names it (a
        run that ends with ``error`` is judged at its last configuration otherwise)."""

    def verdicts(self) -> list[Verdict]:
        found = []
        for own in self.root.region.properties:
            verdict = self._judge(own)
            if verdict is not None:
                found.append(verdict)
        return found

    # -- the kinds ------------------------------------------------------------------------

    def _judge(self, own: ast.Property) -> Verdict | None:
        terms = [self._term(e) for e in own.expressions]
        if own.kind == "reachable":
            return self._reachable(own, terms[0])
        if own.kind == "after":
            return self._response(own, terms[0], terms[1])
        if own.kind == "never":
            formula = z3.Not(terms[0])
        elif own.kind == "exclusive":
            formula = z3.AtMost(*terms, 1)
        else:
            formula = terms[0]
        moments = self.moments()
        if own.kind == "ensures":
            moments = [m for m in moments if m.step is not None and m.outcome == own.outcome]
        return self._everywhere(own, formula, moments)

    def _everywhere(
        self, own: ast.Property, formula: z3.BoolRef, moments: list[Moment]
    ) -> Verdict | None:
        """Refuted at the first moment that falsifies ``formula``, undecided at the first
        where it may fail, proved when it holds at every one of a complete exploration."""
        doubtful = None
        for moment in moments:
            holds, why = self._holds(formula, moment)
            if holds is False:
                return Verdict(
                    REFUTED[own.kind],
                    own,
                    f"property '{own.name}' ({KINDS[own.kind]}) is refuted: "
                    f"{self._where(moment)}{why}",
                    "the property or the chart is wrong: the run shown is the shortest that "
                    "refutes it",
                    self._run(moment),
                )
            if holds is None and doubtful is None:
                doubtful = (moment, why)
        if doubtful is not None:
            return self._undecided(own, *doubtful)
        return None if self.exploration.complete else self._unfinished(own)

    def _reachable(self, own: ast.Property, formula: z3.BoolRef) -> Verdict | None:
        doubtful = None
        for moment in self.moments():
            holds, why = self._holds(formula, moment)
            if holds is True:
                return None
            if holds is None and doubtful is None:
                doubtful = (moment, why)
        if doubtful is not None:
            return self._undecided(own, *doubtful)
        if not self.exploration.complete:
            return self._unfinished(own)
        return Verdict(
            REFUTED["reachable"],
            own,
            f"property '{own.name}' ({KINDS['reachable']}) is refuted: no run of "
            f"'{self.root.name}' reaches a configuration or an end where it holds",
            "check the guards and outcomes on the way there",
            None,
        )

    def _response(
        self, own: ast.Property, trigger: z3.BoolRef, response: z3.BoolRef
    ) -> Verdict | None:
        """Every run from a moment where ``trigger`` holds reaches one where ``response``
        holds. Refuted by a run from such a moment that avoids it to an end, to a
        configuration with no step, or around a loop."""
        moments = self.moments()
        triggers = [self._holds(trigger, m)[0] for m in moments]
        responses = [self._holds(response, m)[0] for m in moments]
        successors = self._successors(moments)
        for strict in (True, False):
            avoiding = {
                i for i, r in enumerate(responses) if r is False or (not strict and r is None)
            }
            starts = [
                i
                for i, t in enumerate(triggers)
                if i in avoiding and (t is True or (not strict and t is not False))
            ]
            escape = self._escape(starts, avoiding, successors, moments)
            if escape is None:
                continue
            start, path, loop = escape
            if not strict:
                return self._undecided(
                    own, moments[start], ": the values read there are not all known"
                )
            run = self._run(moments[path[-1]], [moments[i] for i in path[:-1]], loop)
            fate = "repeats forever" if loop else "ends" if moments[path[-1]].step else "stops"
            return Verdict(
                REFUTED["after"],
                own,
                f"property '{own.name}' ({KINDS['after']}) is refuted: from "
                f"{self._where(moments[start]).removeprefix('in ')} a run {fate} without "
                "the response",
                "the property or the chart is wrong: the run shown is the shortest that refutes it",
                run,
            )
        return None if self.exploration.complete else self._unfinished(own)

    def _escape(
        self, starts: list[int], avoiding: set[int], successors: list[list[int]], moments
    ) -> tuple[int, list[int], tuple[Step, ...]] | None:
        """A way from one of ``starts`` that stays in ``avoiding`` up to an ending, a
        configuration without steps (after a complete exploration) or a loop."""
        if not starts:
            return None
        inner = nx.DiGraph()
        inner.add_nodes_from(avoiding)
        for i in avoiding:
            inner.add_edges_from((i, j) for j in successors[i] if j in avoiding)
        looping = set()
        for component in nx.strongly_connected_components(inner):
            some = next(iter(component))
            if len(component) > 1 or inner.has_edge(some, some):
                looping |= component
        for start in starts:
            parents = {start: None}
            pending = deque([start])
            while pending:
                i = pending.popleft()
                dead = not successors[i] and (moments[i].step or self.exploration.complete)
                if i in looping or dead:
                    path = [i]
                    while parents[path[-1]] is not None:
                        path.append(parents[path[-1]])
                    path.reverse()
                    loop = self._loop(inner, i, moments) if i in looping else ()
                    return start, path, loop
                for j in successors[i]:
                    if j in avoiding and j not in parents:
                        parents[j] = i
                        pending.append(j)
        return None

    def _loop(self, inner: nx.DiGraph, head: int, moments: list[Moment]) -> tuple[Step, ...]:
        cycle = nx.find_cycle(inner, head)
        graph = self.exploration.graph
        return tuple(graph.edges[moments[u].node, moments[v].node]["step"] for u, v in cycle)

    def _successors(self, moments: list[Moment]) -> list[list[int]]:
        index = {m.node: i for i, m in enumerate(moments) if m.step is None}
        endings: dict[object, list[int]] = {}
        for i, moment in enumerate(moments):
            if moment.step is not None:
                endings.setdefault(moment.node, []).append(i)
        graph = self.exploration.graph
        found = []
        for moment in moments:
            if moment.step is not None:
                found.append([])
                continue
            nexts = [index[n] for n in graph.successors(moment.node) if n in index]
            found.append(nexts + endings.get(moment.node, []))
        return found

    def _undecided(self, own: ast.Property, moment: Moment, why: str) -> Verdict:
        return Verdict(
            UNDECIDED,
            own,
            f"property '{own.name}' ({KINDS[own.kind]}) cannot be decided: "
            f"{self._where(moment)}{why}",
            "state what it needs in an end condition or a guard on the way, or keep the "
            "value in an attribute the model assigns (values beyond ±10⁶ or computed from "
            "sensors are not tracked)",
            self._run(moment),
        )

    def _unfinished(self, own: ast.Property) -> Verdict:
        return Verdict(
            UNDECIDED,
            own,
            f"property '{own.name}' ({KINDS[own.kind]}) cannot be decided: the exploration of "
            f"'{self.root.name}' stopped at its limit of {self.exploration.limit:,} "
            "configurations",
            RAISE_LIMIT,
            None,
        )

    # -- moments --------------------------------------------------------------------------

    def moments(self) -> list[Moment]:
        """Every explored configuration and every ending, nearest to the start first."""
        if self._moments is not None:
            return self._moments
        graph = self.exploration.graph
        tree = self.exploration.tree
        order = list(nx.bfs_tree(graph, START))
        found: list[Moment] = []
        for node in order:
            if node == START or tree(node)[0] == "END":
                continue
            configuration, store = self.exploration.configurations[node]
            found.append(Moment(node, configuration, store))
            for step, outcome, kept in self.exploration.endings.get(node, ()):
                if outcome in self._ends:
                    facts = self._facts(configuration, step)
                    found.append(Moment(node, configuration, kept, step, outcome, facts))
        for node in graph.successors(START):
            if tree(node)[0] == "END" and tree(node)[1] in self._ends:  # ends as it starts
                found.append(Moment(START, (), (), Step((), "", "start"), tree(node)[1]))
        self._moments = found
        return found

    def _facts(self, tree: tuple, step: Step) -> tuple[z3.BoolRef, ...]:
        """What the step that ends the run guarantees at its end."""
        own = []
        for transition in reversed(step.fired):
            if id(transition) not in self._own:
                break
            own.insert(0, transition)
        facts = self._command_facts(tree, step)  # sensors and constants: nothing writes them
        written: set[str] = set()
        for transition in reversed(own):
            written |= self._writes(transition)
            for guaranteed, expression in self._guard_facts(transition):
                if not (self._reads(expression) & written):
                    facts.append(guaranteed)
        return tuple(facts)

    def _guard_facts(self, transition: ast.Transition) -> list[tuple[z3.BoolRef, object]]:
        """The guard of a transition that fired, and that the earlier ones from its source
        on its stimulus did not hold."""
        region = self.root.region
        found = []
        if transition.guard is not None:
            found.append((self.evaluator._condition(transition.guard), transition.guard))
        source = transition.source
        choice = source in region.pseudostates
        info = region.states.get(source)
        declared = (info.outcomes or ()) if info is not None else ()
        for earlier in region.transitions:
            if earlier is transition:
                break
            if earlier.source != source or earlier.guard is None:
                continue
            same = earlier.stimulus == transition.stimulus
            completion = not earlier.stimulus and transition.stimulus in declared
            if choice or same or completion:
                term = z3.Not(self.evaluator._condition(earlier.guard))
                found.append((term, earlier.guard))
        return found

    def _command_facts(self, tree: tuple, step: Step) -> list[z3.BoolRef]:
        """The end condition that ended the action, and that the earlier ones did not hold,
        where they read sensors and the action's parameters only."""
        if not step.command:
            return []
        located = _action(self.root.region, tree, step.where)
        if located is None:
            return []
        action, frame = located
        key = (action.qualified_name, step.stimulus, frame)
        if key not in self._commands:
            self._commands[key] = self._ended(action, frame, step.stimulus)
        return list(self._commands[key])

    def _ended(self, action: Component, frame: Frame, stimulus: str) -> list[z3.BoolRef]:
        evaluator = self.flow.evaluator(action.region)
        found = []
        for condition in action.region.end_conditions:
            if condition.expression is not None:
                term = evaluator.terms.condition(condition.expression)
                known = self._command_term(term, evaluator, frame)
                if known is not None:
                    found.append(known if condition.name == stimulus else z3.Not(known))
            if condition.name == stimulus:
                return found
        return []

    def _command_term(self, term: z3.BoolRef, evaluator, frame: Frame) -> z3.BoolRef | None:
        names = {str(c) for c in constants(term)}
        pairs = []
        for path, (variable, symbol) in evaluator.terms.read.items():
            if path not in names:
                continue
            if variable.kind == "sensor":
                continue
            if variable.kind == "parameter" and "." not in path:
                value = frame.value(path)
                if value is None:
                    return None
                pairs.append((symbol, constant(symbol, value)))
                continue
            return None
        return z3.substitute(term, *pairs) if pairs else term

    def _writes(self, transition: ast.Transition) -> set[str]:
        frame = self.flow.root_frame
        found = set()
        for statement in transition.action or ():
            chain = names_of(statement.target) if isinstance(statement, ast.Assignment) else None
            if chain is not None:
                found.add(resolve(".".join(chain), frame))
        return found

    def _reads(self, expression: ast.Expression) -> set[str]:
        frame = self.flow.root_frame
        return {resolve(p, frame) for p in self.root.access(expression).reads}

    # -- predicates at a moment -----------------------------------------------------------

    def _term(self, expression: ast.Expression) -> z3.BoolRef:
        return self.evaluator._condition(expression)

    def _holds(self, formula: z3.BoolRef, moment: Moment) -> tuple[bool | None, str]:
        """Whether ``formula`` holds at ``moment`` for every free value (True), for none
        (False) or for some (None), and what the answer rests on."""
        names = self._names(formula, moment.facts)
        active = _active(self.root.region, moment.tree) if moment.step is None else set()
        atoms = []
        pairs = []
        shown = []
        bounds = []
        for path, (variable, symbol) in sorted(self.terms.read.items()):
            if path not in names:
                continue
            if variable.kind == "unknown" and path in self.atoms:
                value = path in active or path == moment.outcome
                atoms.append((path, value))
                pairs.append((symbol, z3.BoolVal(value)))
                continue
            value = self._known(path, variable.kind, moment.store)
            if isinstance(value, Beyond):
                shown.append((path, value))
                bounds.append(fact(symbol, value))
            elif value is not None:
                shown.append((path, value))
                pairs.append((symbol, constant(symbol, value)))
        key = (
            formula.get_id(),
            tuple(atoms),
            tuple(shown),
            tuple(f.get_id() for f in moment.facts),
        )
        if key not in self._answers:
            term = z3.simplify(z3.substitute(formula, *pairs) if pairs else formula)
            facts = [z3.substitute(f, *pairs) if pairs else f for f in moment.facts] + bounds
            if z3.is_true(term) or z3.is_false(term):
                answer: bool | None = z3.is_true(term)
                why = ""
            elif self.judge.always(term, *facts):
                answer, why = True, ""
            else:
                model = self.judge.possible(term, *facts)
                answer = None if model is not False else False
                if answer is None:
                    free = sorted(str(c) for c in constants(term))
                    why = f": the value of {', '.join(free)} is not known there"
                else:
                    why = ""
            self._answers[key] = (answer, why, term)
        answer, why, _ = self._answers[key]
        if answer is False and not why:
            why = _shown(shown) if shown else ""
        return answer, why

    def _names(self, formula: z3.BoolRef, facts: tuple[z3.BoolRef, ...]) -> frozenset[str]:
        """The variables a formula and the facts beside it read, found once per question."""
        key = (formula.get_id(), *(f.get_id() for f in facts))
        if key not in self._read:
            found = {str(c) for term in (formula, *facts) for c in constants(term)}
            self._read[key] = frozenset(found)
        return self._read[key]

    def _known(self, path: str, kind: str, store: Store):
        frame = self.flow.root_frame
        if kind == "parameter" and "." not in path:
            return frame.value(path)
        return dict(store).get(resolve(path, frame))

    # -- runs -----------------------------------------------------------------------------

    def _where(self, moment: Moment) -> str:
        """The moment as a reader finds it: the states active, or the step that ended."""
        if moment.step is not None:
            where = "/".join(moment.step.where) or self.root.name
            return (
                f"where '{self.root.name}' ends with '{moment.outcome}' "
                f"({where}: {moment.step.stimulus})"
            )
        states = sorted(_active(self.root.region, moment.tree))
        return f"in {', '.join(states)}"

    def _run(
        self, moment: Moment, before: list[Moment] | None = None, loop: tuple[Step, ...] = ()
    ) -> Counterexample:
        """The shortest run to ``moment`` (through ``before`` when given), ending with its
        step and outcome when it is an ending."""
        graph = self.exploration.graph
        if before:
            nodes = self._path(before[0].node)[:-1] + [m.node for m in before]
            if moment.step is None:
                nodes.append(moment.node)
        else:
            nodes = self._path(moment.node) if moment.node != START else [START]
        steps = [graph.edges[u, v]["step"] for u, v in pairwise(nodes)]
        if moment.step is not None and moment.node != START:
            steps.append(moment.step)
        steps = [s for s in steps if s.stimulus != "start"]
        return Counterexample(self.root.qualified_name, tuple(steps), loop, moment.outcome)

    def _path(self, node: object) -> list:
        if self._parents is None:
            self._parents = {START: None}
            for parent, child in nx.bfs_edges(self.exploration.graph, START):
                self._parents[child] = parent
        path = [node]
        while self._parents.get(path[-1]) is not None:
            path.append(self._parents[path[-1]])
        return path[::-1]


def _active(region: Region, tree: tuple) -> set[str]:
    """The chart's own states active in a configuration (not those of imported charts)."""
    found: set[str] = set()
    if not tree or tree[0] not in ("S", "P"):
        return found
    if tree[0] == "P":
        for (name, info), inner in zip(region.states.items(), tree[1], strict=False):
            found.add(name)
            found |= _active(info.region, inner)
        return found
    _, name, _, inner = tree
    found.add(name)
    info = region.states[name]
    if info.imported is None and info.region is not None and isinstance(inner, tuple):
        found |= _active(info.region, inner)
    return found


def _action(region: Region, tree: tuple, where: tuple[str, ...]):
    """The action that acted at the end of ``where`` and its instance frame."""
    node = tree
    for name in where:
        while node[0] == "P":
            index = next((i for i, n in enumerate(node[1]) if n[0] == "S" and n[1] == name), None)
            if index is None:
                return None
            region = list(region.states.values())[index].region
            node = node[1][index]
        if node[0] != "S" or node[1] != name:
            return None
        info = region.states[name]
        if isinstance(node[3], tuple):
            region = info.imported.region if info.imported is not None else info.region
            node = node[3]
        elif node[3] != FINAL and info.imported is not None and info.imported.layer == "action":
            return info.imported, node[2]
        else:
            return None
    return None


def _shown(shown: list[tuple[str, object]]) -> str:
    parts = []
    for path, value in shown:
        if isinstance(value, Beyond):
            parts.append(f"{path} {'>' if value.sign > 0 else '<'} {value.sign * WINDOW}")
            continue
        if isinstance(value, tuple):
            value = f"{value[0]}/{value[1]}"
        elif isinstance(value, bool):
            value = "true" if value else "false"
        parts.append(f"{path} = {value}")
    return " where " + ", ".join(parts)
