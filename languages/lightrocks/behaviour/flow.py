"""The outcome flow of a statechart and everything it imports, as a transition system.

A configuration is the tree of active states (``("S", name, frame, inner)`` for the active
state of a region, ``("P", regions)`` for an orthogonal one; ``inner`` is ``"run"`` for a
running action, ``"wait"`` for a simple state, ``"final"`` for a region resting in a final
state) and the store of known values. A step is what the environment decides: a running
action ends with one of its end conditions that can hold, ``timeout`` or ``error``; a state
takes an event or a time event. The step then follows the execution semantics: exit actions,
the first transition whose guard can hold (each one that can is a branch), choices, entering
targets through start conditions or initial states, completion up the hierarchy. Orthogonal
regions interleave; history re-enters any state of its composite (both over-approximations).
"""

from __future__ import annotations

from dataclasses import dataclass

from lightrocks.languages.lightrocks.behaviour.liveness import Liveness, keeps
from lightrocks.languages.lightrocks.behaviour.store import (
    BOUNDED,
    MOVED,
    Evaluator,
    Frame,
    Store,
    fold_value,
)
from lightrocks.languages.lightrocks.model import Component, Region, visible_cells
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast

RUN, WAIT, FINAL = "run", "wait", "final"
BUILT_IN = ("timeout", "error")


@dataclass(frozen=True)
class Step:
    """What the environment decided, and the transitions that fired because of it."""

    where: tuple[str, ...]  # the states from the top to the one that acted
    command: str  # ``device.command`` of an action that ended, '' for an event
    stimulus: str  # the outcome or event
    fired: tuple[ast.Transition, ...] = ()
    marks: tuple[tuple[str, int], ...] = ()  # how it moved and bounded counters (store.py)


@dataclass(frozen=True)
class Result:
    """A region moved on (``node``), or its owner ended with ``outcome``."""

    node: tuple | None
    outcome: str
    store: Store
    fired: tuple[ast.Transition, ...]


class Flow:
    def __init__(self, typing: Typing, root: Component, liveness: Liveness) -> None:
        self.typing = typing
        self.root = root
        self.liveness = liveness
        self._evaluators: dict[int, Evaluator] = {}
        self._outcomes: dict[str, list[str]] = {}
        self._defaults: dict[int, object] = {}
        self._outcome_names: dict[tuple[int, str], tuple[str, ...]] = {}
        self.root_frame = Frame()
        self._by_source: dict[int, dict[str, list[ast.Transition]]] = {}

    # -- start ----------------------------------------------------------------------------

    def initial(self) -> list[tuple[tuple, Store]]:
        """The configurations the statechart starts in, its parameters at their defaults."""
        self.root_frame = self.frame(self.root, (), None, Frame(), ())
        store = self.initial_store()
        found = []
        for result in self._enter_region(self.root.region, self.root_frame, store):
            node = result.node if result.node is not None else ("END", result.outcome)
            found.append((node, self.project(node, result.store)))
        return found

    def initial_store(self) -> Store:
        """Every attribute of the scene objects the statechart sees, at its default."""
        values = {}
        workspace = self.typing.models.workspace
        for symbol in visible_cells(workspace, self.root.loaded):
            for obj in symbol.node.objects:
                for attribute in obj.attributes:
                    value = fold_value(attribute.default, attribute.type)
                    if value is not None:
                        values[f"{obj.name}.{attribute.name}"] = value
        return tuple(sorted(values.items()))

    def project(self, node: tuple, store: Store) -> Store:
        """The store without the values nothing active will read before writing."""
        active = [(self.root, ()), *self._active(node, self.root.region)]
        needed = self.liveness.needed(active)
        return tuple((path, value) for path, value in store if keeps(needed, path))

    def _active(self, node: tuple, region: Region) -> list[tuple[Component, tuple]]:
        if node[0] == "P":
            subs = [info.region for info in region.states.values()]
            pairs = zip(subs, node[1], strict=False)
            return [c for sub, inner in pairs for c in self._active(inner, sub)]
        if node[0] != "S":
            return []
        info = region.states[node[1]]
        found = []
        if info.imported is not None:
            found.append((info.imported, node[2].objects))
        if isinstance(node[3], tuple):
            inner = info.imported.region if info.imported is not None else info.region
            found += self._active(node[3], inner)
        return found

    # -- steps ----------------------------------------------------------------------------

    def successors(self, node: tuple, store: Store) -> list[tuple[Step, tuple, Store]]:
        """Every step the environment may take from a configuration, and where it leads."""
        found = []
        for step, result in self._step(node, self.root.region, self.root_frame, store):
            after = result.node if result.node is not None else ("END", result.outcome)
            fired = (*step.fired, *result.fired)
            marks = tuple((p, v) for p, v in result.store if p[0] in (MOVED, BOUNDED))
            step = Step(step.where, step.command, step.stimulus, fired, marks)
            found.append((step, after, self.project(after, result.store)))
        return found

    def _step(self, node: tuple, region: Region, frame: Frame, store: Store) -> list:
        if node[0] == "P":
            return self._step_parallel(node, region, frame, store)
        _, name, own, inner = node
        info = region.states[node[1]]
        found = []
        if inner == RUN:
            action = info.imported
            for outcome in self.outcomes(action):
                after = self._exit_actions(action.region, own, store)
                step = Step((name,), command_of(action), outcome)
                found += [(step, r) for r in self._react(region, name, outcome, frame, after)]
        elif isinstance(inner, tuple):
            child = info.imported.region if info.imported is not None else info.region
            child_frame = own if info.imported is not None else frame
            for step, result in self._step(inner, child, child_frame, store):
                step = Step((name, *step.where), step.command, step.stimulus, step.fired)
                if result.node is not None:
                    moved = ("S", name, own, result.node)
                    found.append((step, Result(moved, "", result.store, result.fired)))
                    continue
                after = self._exit_actions(child, child_frame, result.store)
                for reaction in self._react(region, name, result.outcome, frame, after):
                    fired = (*result.fired, *reaction.fired)
                    found.append(
                        (step, Result(reaction.node, reaction.outcome, reaction.store, fired))
                    )
        found += self._events(node, region, frame, store)
        return found

    def _step_parallel(self, node: tuple, region: Region, frame: Frame, store: Store) -> list:
        subs = [info.region for info in region.states.values()]
        found = []
        for index, (sub, inner) in enumerate(zip(subs, node[1], strict=False)):
            for step, result in self._step(inner, sub, frame, store):
                if result.node is None:
                    found.append((step, result))  # an error in one region ends them all
                    continue
                nodes = (*node[1][:index], result.node, *node[1][index + 1 :])
                if all(n[0] == "S" and n[3] == FINAL for n in nodes):
                    found.append((step, Result(None, nodes[0][1], result.store, result.fired)))
                else:
                    found.append((step, Result(("P", nodes), "", result.store, result.fired)))
        return found

    def _events(self, node: tuple, region: Region, frame: Frame, store: Store) -> list:
        """Events and time events the active state ``node[1]`` may take."""
        name = node[1]
        info = region.states[name]
        outcomes = self._declared(region, name)
        evaluator = self.evaluator(region)
        found = []
        stimuli = [
            t.stimulus
            for t in self._leaving(region, name)
            if t.stimulus and t.stimulus not in (*outcomes, *BUILT_IN)
        ]
        for stimulus in dict.fromkeys(stimuli):
            leaving = [t for t in self._leaving(region, name) if t.stimulus == stimulus]
            after = self._exit_node(node, region, frame, store)
            for index in evaluator.first_enabled([t.guard for t in leaving], frame, store):
                if index is None:
                    continue  # taken by nothing: the event is dropped
                for result in self._fire(region, leaving[index], frame, after):
                    found.append((Step((name,), "", stimulus), result))
        inner = info.imported.region if info.imported is not None else info.region
        for internal in inner.internal if inner is not None else ():
            own = node[2] if info.imported is not None else frame
            after = store
            for statement in internal.action or ():
                after = self.evaluator(inner).assign(statement, own, after)
            found.append((Step((name,), "", internal.stimulus), Result(node, "", after, ())))
        return found

    # -- reacting and entering ------------------------------------------------------------

    def _react(
        self, region: Region, source: str, outcome: str, frame: Frame, store: Store
    ) -> list[Result]:
        """``source`` ended with ``outcome``: the first transition whose guard holds fires;
        none: the region's owner ends with ``error``."""
        declared = self._declared(region, source)
        leaving = [
            t
            for t in self._leaving(region, source)
            if t.stimulus == outcome or (not t.stimulus and outcome in declared)
        ]
        found = []
        for index in self.evaluator(region).first_enabled([t.guard for t in leaving], frame, store):
            if index is None:
                found.append(Result(None, "error", store, ()))
            else:
                found += self._fire(region, leaving[index], frame, store)
        return found

    def _leaving(self, region: Region, source: str) -> list[ast.Transition]:
        """The transitions leaving ``source``, in declaration order (indexed once)."""
        if id(region) not in self._by_source:
            index: dict[str, list[ast.Transition]] = {}
            for transition in region.transitions:
                index.setdefault(transition.source, []).append(transition)
            self._by_source[id(region)] = index
        return self._by_source[id(region)].get(source, [])

    def _declared(self, region: Region, source: str) -> tuple[str, ...]:
        key = (id(region), source)
        if key not in self._outcome_names:
            info = region.states.get(source)
            self._outcome_names[key] = (info.outcomes or ()) if info is not None else ()
        return self._outcome_names[key]

    def _fire(
        self, region: Region, transition: ast.Transition, frame: Frame, store: Store
    ) -> list[Result]:
        evaluator = self.evaluator(region)
        if transition.guard is not None:
            store = evaluator.bound(transition.guard, frame, store)
        for statement in transition.action or ():
            store = evaluator.assign(statement, frame, store)
        target = transition.target
        found: list[Result] = []
        if target in region.conditions:
            found.append(Result(None, target, store, ()))
        elif target in region.pseudostates and region.pseudostates[target].kind == "choice":
            found += self._react(region, target, "", frame, store)
        elif target in region.states:
            found += self._enter_state(
                region, target, frame, store, bool(transition.target_history)
            )
        else:
            found.append(Result(None, "error", store, ()))
        return [Result(r.node, r.outcome, r.store, (transition, *r.fired)) for r in found]

    def _enter_region(self, region: Region, frame: Frame, store: Store) -> list[Result]:
        store = self._actions(region, "entry", frame, store)
        if region.orthogonal:
            return self._enter_parallel(region, frame, store)
        evaluator = self.evaluator(region)
        starts = region.start_conditions
        if starts:
            found = []
            for index in evaluator.first_enabled([c.expression for c in starts], frame, store):
                if index is None:
                    found.append(Result(None, "error", store, ()))
                    continue
                leaving = self._leaving(region, starts[index].name)
                for choice in evaluator.first_enabled([t.guard for t in leaving], frame, store):
                    if choice is None:
                        found.append(Result(None, "error", store, ()))
                    else:
                        found += self._fire(region, leaving[choice], frame, store)
            return found
        initial = next((n for n, i in region.states.items() if i.state.is_initial), None)
        if initial is None:
            return [Result(None, "error", store, ())]
        return self._enter_state(region, initial, frame, store, False)

    def _enter_parallel(self, region: Region, frame: Frame, store: Store) -> list[Result]:
        partial: list[tuple[tuple, Store, tuple]] = [((), store, ())]
        for info in region.states.values():
            grown = []
            for nodes, current, fired in partial:
                for result in self._enter_region(info.region, frame, current):
                    if result.node is None:
                        return [Result(None, "error", result.store, fired)]
                    grown.append(((*nodes, result.node), result.store, (*fired, *result.fired)))
            partial = grown
        return [Result(("P", nodes), "", s, fired) for nodes, s, fired in partial]

    def _enter_state(
        self, region: Region, name: str, frame: Frame, store: Store, history: bool
    ) -> list[Result]:
        info = region.states[name]
        if info.state.is_final:
            if _in_parallel(region):
                return [Result(("S", name, None, FINAL), "", store, ())]
            return [Result(None, name, store, ())]
        if info.imported is not None:
            child = info.imported
            own = self.frame(child, info.state.arguments, region, frame, store)
            if child.layer == "action":
                after = self._actions(child.region, "entry", own, store)
                return [Result(("S", name, own, RUN), "", after, ())]
            return self._wrap(
                region, name, own, frame, self._enter_region(child.region, own, store)
            )
        if info.region is not None and info.region.states:
            results = self._enter_region(info.region, frame, store)
            if history:  # any state it may have been left in: an over-approximation
                for other, inner in info.region.states.items():
                    if not inner.state.is_final:
                        results += self._enter_state(info.region, other, frame, store, False)
            return self._wrap(region, name, None, frame, results)
        if info.region is not None:  # a body without states: entry actions only
            store = self._actions(info.region, "entry", frame, store)
        return [Result(("S", name, None, WAIT), "", store, ())]

    def _wrap(
        self, region: Region, name: str, own: Frame | None, frame: Frame, results: list[Result]
    ) -> list[Result]:
        """Entered ``name``: its inner configurations, or its reaction when it ended at once."""
        found = []
        for result in results:
            if result.node is not None:
                found.append(Result(("S", name, own, result.node), "", result.store, result.fired))
            else:
                for reaction in self._react(region, name, result.outcome, frame, result.store):
                    fired = (*result.fired, *reaction.fired)
                    found.append(Result(reaction.node, reaction.outcome, reaction.store, fired))
        return found

    # -- exits, actions, frames ------------------------------------------------------------

    def _exit_node(self, node: tuple, region: Region, frame: Frame, store: Store) -> Store:
        """Exit actions of an active state and everything active inside it, innermost first."""
        if node[0] == "P":
            for info, inner in reversed(list(zip(region.states.values(), node[1], strict=False))):
                store = self._exit_node(inner, info.region, frame, store)
            return store
        info = region.states[node[1]]
        child = info.imported.region if info.imported is not None else info.region
        own = node[2] if info.imported is not None else frame
        if isinstance(node[3], tuple):
            store = self._exit_node(node[3], child, own, store)
        return self._exit_actions(child, own, store) if child is not None else store

    def _exit_actions(self, region: Region, frame: Frame, store: Store) -> Store:
        return self._actions(region, "exit", frame, store)

    def _actions(self, region: Region, kind: str, frame: Frame, store: Store) -> Store:
        evaluator = None
        for action in region.actions:
            if action.kind == kind:
                evaluator = evaluator or self.evaluator(region)
                for statement in action.statements:
                    store = evaluator.assign(statement, frame, store)
        return store

    def frame(
        self, child: Component, arguments: tuple, region: Region | None, frame: Frame, store: Store
    ) -> Frame:
        """The instance of ``child`` that these arguments bind, evaluated here and now."""
        names = list(child.region.parameters)
        bound = {}
        for index, argument in enumerate(arguments):
            key = argument.name or (names[index] if index < len(names) else "")
            bound[key] = argument.value
        assigned = child.assigned
        objects = self._objects(region) if region is not None else set()
        values, aliases = [], []
        for name, parameter in child.region.parameters.items():
            value = bound.get(name)
            if value is not None and isinstance(value, ast.Name):
                alias = value.name if value.name in objects else frame.object(value.name)
                if alias is not None:
                    aliases.append((name, alias))
                    continue
            if name in assigned:
                values.append((name, None))
            elif value is not None:
                values.append((name, self.evaluator(region).value(value, frame, store)))
            else:
                values.append((name, self._default(parameter)))
        return Frame(tuple(values), tuple(aliases))

    def _default(self, parameter: ast.Parameter):
        if id(parameter) not in self._defaults:
            default = parameter.default
            self._defaults[id(parameter)] = fold_value(default, parameter.type) if default else None
        return self._defaults[id(parameter)]

    def _objects(self, region: Region) -> set[str]:
        return set(self.evaluator(region).terms.scope.objects)

    def evaluator(self, region: Region) -> Evaluator:
        if id(region) not in self._evaluators:
            self._evaluators[id(region)] = Evaluator(self.typing, region)
        return self._evaluators[id(region)]

    def outcomes(self, action: Component) -> list[str]:
        """The end conditions of an action that can hold, then ``timeout`` and ``error``."""
        key = action.qualified_name
        if key not in self._outcomes:
            judge = self.evaluator(action.region).judge
            terms = self.evaluator(action.region).terms
            possible = [
                c.name
                for c in action.region.end_conditions
                if c.expression is None or not judge.never(terms.condition(c.expression))
            ]
            self._outcomes[key] = [*possible, *BUILT_IN]
        return self._outcomes[key]


def command_of(action: Component) -> str:
    """``device.command`` of an action's ``do``, as a dry-run script names it."""
    for do in action.region.actions:
        for statement in do.statements if do.kind == "do" else ():
            call = (
                statement.value
                if isinstance(statement, ast.Assignment)
                else getattr(statement, "expression", None)
            )
            function = getattr(call, "function", None)
            if isinstance(function, ast.Member) and isinstance(function.target, ast.Name):
                return f"{function.target.name}.{function.name}"
    return ""


def _in_parallel(region: Region) -> bool:
    parent = region.parent
    return (
        parent is not None
        and parent.orthogonal
        and any(info.region is region for info in parent.states.values())
    )
