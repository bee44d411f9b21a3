"""Context conditions on the transitions of a region (LR02xx): an entry, a reachable end and
reachable states, no transition out of an end or into a start, every outcome handled, no
transition that never fires, history targets, choices and declared events. Reachability
runs on a networkx graph built per region."""

from __future__ import annotations

from collections.abc import Iterator

import networkx as nx

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.model import BUILTIN_OUTCOMES, Region, StateInfo
from lightrocks.languages.lightrocks.regions import own_regions, region_file
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity, did_you_mean

Finding = tuple[ast.Position, str, str]


def _graph(region: Region) -> nx.DiGraph:
    graph = nx.DiGraph()
    graph.add_nodes_from(region.states)
    graph.add_nodes_from(region.conditions)
    graph.add_edges_from((t.source, t.target) for t in region.transitions)
    return graph


def _entries(region: Region) -> list[str]:
    return [s.name for s in region.start_conditions] + [
        name for name, info in region.states.items() if info.state.is_initial
    ]


def _exits(region: Region) -> list[str]:
    return [c.name for c in region.end_conditions] + [
        name for name, info in region.states.items() if info.state.is_final
    ]


@coco("LR0205", Severity.ERROR, "every composite has an entry: initial state or start condition")
def has_entry(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        if region.states and not region.orthogonal and not _entries(region):
            yield (
                region.position,
                f"'{region.name}' has no initial state or start condition",
                "mark a state 'initial' or add 'start condition …;'",
            )


@coco("LR0206", Severity.ERROR, "every composite can reach an end")
def reaches_end(context: object) -> Iterator[Finding]:
    for component, region in own_regions(analysis(context)):
        if not region.states or region.orthogonal or not _entries(region):
            continue
        exits = _exits(region)
        if not exits:
            if component.layer is not None:
                yield (
                    region.position,
                    f"'{region.name}' has no end condition or final state",
                    "add 'end condition …;'",
                )
            continue
        graph = _graph(region)
        reached = set().union(*(nx.descendants(graph, e) | {e} for e in _entries(region)))
        if not reached.intersection(exits):
            yield (region.position, f"no end condition of '{region.name}' is reachable", "")


@coco("LR0207", Severity.ERROR, "all states are reachable")
def states_reachable(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        entries = _entries(region)
        if not entries:
            continue
        graph = _graph(region)
        reached = set(entries)
        for entry in entries:
            reached |= nx.descendants(graph, entry)
        for name, info in region.states.items():
            if name not in reached and info.state.position.file == region_file(region):
                yield (info.state.position, f"state '{name}' is unreachable", "")


@coco("LR0208", Severity.ERROR, "no transition leaves a final state or an end condition")
def no_transition_from_end(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        for transition in region.transitions:
            condition = region.conditions.get(transition.source)
            state = region.states.get(transition.source)
            pseudostate = region.pseudostates.get(transition.source)
            if (
                (condition is not None and condition.kind == "end")
                or (state is not None and state.state.is_final)
                or (pseudostate is not None and pseudostate.kind != "choice")
            ):
                yield (
                    transition.source_position,
                    f"a transition cannot leave '{transition.source}': it is an end",
                    "",
                )


@coco("LR0213", Severity.ERROR, "no transition enters a start condition")
def no_transition_into_start(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        for transition in region.transitions:
            condition = region.conditions.get(transition.target)
            if condition is not None and condition.kind == "start":
                yield (
                    transition.target_position,
                    f"'{transition.target}' is a start condition: it can only be a source",
                    "",
                )


@coco("LR0209", Severity.WARNING, "every outcome of a child is handled")
def outcomes_handled(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        if region.orthogonal:
            continue  # its regions complete together, never one by one
        leaving: dict[str, list[ast.Transition]] = {}
        for transition in region.transitions:
            leaving.setdefault(transition.source, []).append(transition)
        for name, info in region.states.items():
            outcomes = info.outcomes
            if outcomes is None or info.state.is_final:
                continue
            transitions = leaving.get(name, [])
            handled = {t.stimulus for t in transitions}
            if any(not t.stimulus for t in transitions):
                outcomes = ()  # a completion transition takes every declared outcome
            for outcome in (*outcomes, *_builtin_outcomes(info, leaving)):
                if outcome not in handled:
                    yield (
                        info.state.position,
                        f"outcome '{outcome}' of '{name}' is not handled: it ends "
                        f"'{region.name}' with 'error'",
                        _handler_hint(name, outcome, leaving),
                    )


def _builtin_outcomes(info: StateInfo, leaving: dict[str, list[ast.Transition]]) -> list[str]:
    """The built-in outcomes a child handles as it handles declared ones: ``timeout`` where
    the statechart it imports sets its own budget (``<<timeout>>``: a budget written down is
    there to be reached), and ``error`` where the region handles the ``error`` of another
    child (the region deals with errors, so one left out is an oversight). Elsewhere both go
    to the parent as ``error``, by design: a device's or the default budget is a safety
    net, and an error ends what it interrupts."""
    found = []
    if info.imported is not None and info.imported.budget is not None:
        found.append("timeout")
    if any(t.stimulus == "error" for s, ts in leaving.items() if s != info.name for t in ts):
        found.append("error")
    return found


def _handler_hint(name: str, outcome: str, leaving: dict[str, list[ast.Transition]]) -> str:
    """The fix where the siblings show it, only where it is right for the outcome: the place
    most siblings send ``outcome`` to without a guard (a guarded handling is by case), none
    through a history state, and for ``timeout`` or ``error`` (a fault, not a result to
    retry on) a place that does not lead back to the child."""
    targets: list[str] = []
    for source, transitions in leaving.items():
        for transition in transitions:
            if source == name or transition.stimulus != outcome:
                continue
            if transition.target_history:
                return ""  # resumed where it was: no answer to copy
            if transition.guard is None:
                targets.append(transition.target)
    if not targets:
        return ""
    target = max(dict.fromkeys(targets), key=targets.count)
    if target in ("", name) or (outcome in BUILTIN_OUTCOMES and _leads_back(target, name, leaving)):
        return ""
    return f"add the transition '{name} -> {target} {outcome};'"


def _leads_back(target: str, name: str, leaving: dict[str, list[ast.Transition]]) -> bool:
    """From ``target`` the region can come back to ``name``: the handling retries the work."""
    graph = nx.DiGraph((s, t.target) for s, ts in leaving.items() for t in ts)
    return target in graph and name in graph and nx.has_path(graph, target, name)


@coco("LR0211", Severity.WARNING, "no two transitions fire on the same outcome")
def deterministic(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        seen: dict[tuple[str, str], ast.Transition] = {}
        for transition in region.transitions:
            if transition.guard is not None:
                continue
            key = (transition.source, transition.stimulus)
            outcome = _is_outcome(region, transition)
            earlier = seen.get(key) or (seen.get((transition.source, "")) if outcome else None)
            if earlier is not None:
                kind = "outcome" if outcome else "event" if transition.stimulus else "completion"
                yield (
                    transition.position,
                    f"never fires: the transition at {earlier.position} takes the same "
                    f"{kind} first",
                    "",
                )
            else:
                seen[key] = transition


def _is_outcome(region: Region, transition: ast.Transition) -> bool:
    """The stimulus names a declared outcome of the source; otherwise it is an event."""
    source = region.states.get(transition.source)
    outcomes = source.outcomes if source is not None else None
    return bool(outcomes) and transition.stimulus in outcomes


@coco("LR0214", Severity.ERROR, "a transition without stimulus leaves a state that completes")
def completion_needs_outcome(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        for transition in region.transitions:
            source = region.states.get(transition.source)
            if (
                transition.stimulus
                or source is None
                or source.state.is_final
                or source.outcomes is not None
                or any(s.name == "import" for s in source.state.stereotypes)
            ):
                continue
            yield (
                transition.position,
                f"never fires: '{source.name}' has no final state or end condition, "
                "so it never completes",
                "name the event that leaves it",
            )


@coco("LR0215", Severity.ERROR, "a history target names a history pseudostate of its state")
def history_targets(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        for transition in region.transitions:
            if not transition.target_history:
                continue
            target = region.states.get(transition.target)
            inner = target.region if target is not None else None
            histories = [
                name
                for name, p in (inner.pseudostates.items() if inner is not None else ())
                if p.kind != "choice"
            ]
            if transition.target_history not in histories:
                yield (
                    transition.target_position,
                    f"'{transition.target_history}' is no history pseudostate of "
                    f"'{transition.target}'",
                    did_you_mean(transition.target_history, histories),
                )


@coco("LR0216", Severity.ERROR, "a choice is left by transitions without stimulus")
def choice_branches(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        for name, pseudostate in region.pseudostates.items():
            if pseudostate.kind != "choice":
                continue
            leaving = [t for t in region.transitions if t.source == name]
            if not leaving:
                yield (pseudostate.position, f"choice '{name}' has no branch", "")
            for transition in leaving:
                if transition.stimulus:
                    yield (
                        transition.stimulus_position,
                        f"a branch of choice '{name}' has no stimulus: guards decide at once",
                        "",
                    )


@coco("LR0217", Severity.ERROR, "a statechart that declares events uses declared events only")
def declared_events(context: object) -> Iterator[Finding]:
    for component, region in own_regions(analysis(context)):
        declared = component.region.events
        if declared is None:
            continue
        stimuli = [
            (t.stimulus, t.stimulus_position)
            for t in region.transitions
            if t.stimulus
            and t.delay is None
            and not _is_outcome(region, t)
            and not _is_builtin(region, t)
        ]
        stimuli += [(t.stimulus, t.stimulus_position) for t in region.internal if t.delay is None]
        for name, position in stimuli:
            if name not in declared:
                yield (
                    position,
                    f"'{name}' is no declared event ({', '.join(declared) or 'none declared'})",
                    did_you_mean(name, list(declared)),
                )


def _is_builtin(region: Region, transition: ast.Transition) -> bool:
    source = region.states.get(transition.source)
    return transition.stimulus in BUILTIN_OUTCOMES and (
        source is None or source.outcomes is not None
    )
