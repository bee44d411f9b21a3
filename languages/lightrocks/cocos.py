"""Context conditions of LightRocks components.

Each CoCo is one small check with a stable code. Graph checks (reachability, termination,
cycles of import and extension) run on networkx graphs built per region.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import networkx as nx

from lightrocks.languages.domain.types import DeviceT
from lightrocks.languages.lightrocks.analysis import Analysis, analysis
from lightrocks.languages.lightrocks.model import (
    BUILTIN_OUTCOMES,
    LAYERS,
    Component,
    Region,
    StateInfo,
)
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity, did_you_mean

Finding = tuple[ast.Position, str, str]

KNOWN_STEREOTYPES = {*LAYERS, "import", "extends", "timeout", "scene"}
MAY_USE = {"task": {"task", "skill"}, "skill": {"skill", "action"}, "action": set()}


def _own_regions(a: Analysis) -> Iterator[tuple[Component, Region]]:
    """Regions written in each component's own file (inherited ones are checked at home)."""
    for component in a.models.components:
        for region in component.region.regions():
            if region.loaded is component.loaded:
                yield component, region


def _typing(code: str, summary: str, severity: Severity = Severity.ERROR):
    """A CoCo that reports the findings of the shared typing pass for one code."""

    @coco(code, severity, summary)
    def check(context: object) -> Iterator[Finding]:
        yield from analysis(context).typing.findings.get(code, [])

    return check


unresolved_name = _typing("LR0103", "names in expressions resolve")
unresolved_type = _typing("LR0105", "types resolve")
unresolved_member = _typing("LR0106", "devices, commands, sensors and attributes resolve")
unknown_unit = _typing("LR0107", "units are known")
call_signature = _typing("LR0301", "calls match the signature: names and arity")
type_mismatch = _typing("LR0302", "values match the declared types")
not_boolean = _typing("LR0303", "guards, invariants and conditions are Boolean")
dimension_mismatch = _typing("LR0304", "unit dimensions agree")
unsafe_value = _typing("LR0305", "values lie in the safe ranges the device declares")
not_assignable = _typing("LR0306", "only environment attributes and parameters are assigned")
command_placement = _typing("LR0307", "device commands are called in do actions only")
narrowing = _typing("LR0308", "no Real value where an Integer is declared")


@coco("LR0101", Severity.ERROR, "names are unique per scope")
def unique_names(context: object) -> Iterator[Finding]:
    for _, region in _own_regions(analysis(context)):
        yield from _duplicates(_region_elements(region, ast.Parameter))
        yield from _duplicates(
            _region_elements(region, ast.Condition)
            + _region_elements(region, ast.State)
            + _region_elements(region, ast.Pseudostate)
            + _region_elements(region, ast.Region)
        )
        if region.parent is None:
            blocks = _region_elements(region, ast.EventBlock)
            yield from _duplicates([e for block in blocks for e in block.events])


def _region_elements(region: Region, kind: type) -> list:
    statechart_elements = _source_elements(region)
    flat: list = []
    for element in statechart_elements:
        if isinstance(element, ast.ParameterBlock):
            flat.extend(p for p in element.parameters if isinstance(p, kind))
        elif isinstance(element, kind):
            flat.append(element)
    return flat


def _source_elements(region: Region) -> tuple:
    """The elements as written (before extension merged them by name)."""
    unit = region.loaded.unit
    if region.parent is None:
        return unit.statechart.elements
    return region.parent.states[region.name].state.body or ()


def _duplicates(elements: list) -> Iterator[Finding]:
    seen: dict[str, ast.Position] = {}
    for element in elements:
        if element.name in seen:
            yield (
                element.position,
                f"'{element.name}' is already declared in this scope at {seen[element.name]}",
                "",
            )
        else:
            seen[element.name] = element.position


@coco("LR0108", Severity.ERROR, "the package matches the folder on the model path")
def package_matches_folder(context: object) -> Iterator[Finding]:
    a = analysis(context)
    for loaded in a.workspace.checked_units():
        possible = a.workspace.model_path.packages_of(loaded.path)
        if possible and loaded.unit.package not in possible:
            expected = possible[-1]
            shown = f"'{expected}'" if expected else "no package (the model-path root)"
            yield (
                loaded.unit.package_position,
                f"package '{loaded.unit.package}' does not match its folder: expected {shown}",
                "",
            )


@coco("LR0109", Severity.ERROR, "the statechart name matches the file name")
def name_matches_file(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        stem = Path(component.loaded.path).stem
        if component.name != stem:
            yield (
                component.statechart.position,
                f"statechart '{component.name}' must be in a file named '{component.name}.lr'",
                f"the file is '{stem}.lr'",
            )


@coco("LR0110", Severity.ERROR, "transition sources and targets resolve")
def transition_ends_resolve(context: object) -> Iterator[Finding]:
    for _, names, elsewhere, name, position in _transition_ends(context):
        if name not in names and name not in elsewhere:
            yield (position, f"unknown state or condition '{name}'", did_you_mean(name, names))


def _transition_ends(
    context: object,
) -> Iterator[tuple[Region, dict[str, None], dict[str, str], str, ast.Position]]:
    """Every source and target of a transition with the names of its own region (in
    declaration order, looked up in constant time) and the states of the sibling regions
    (see :func:`_sibling_regions`)."""
    for _, region in _own_regions(analysis(context)):
        own = dict.fromkeys([*region.states, *region.conditions, *region.pseudostates])
        elsewhere = _sibling_regions(region)
        for transition in region.transitions:
            yield region, own, elsewhere, transition.source, transition.source_position
            yield region, own, elsewhere, transition.target, transition.target_position


def _sibling_regions(region: Region) -> dict[str, str]:
    """States of the other regions of an orthogonal state, by name, to their region."""
    parent = region.parent
    if parent is None or not parent.orthogonal:
        return {}
    return {
        state: sibling.name
        for sibling in parent.states.values()
        if sibling.region is not None and sibling.region is not region
        for state in sibling.region.states
    }


@coco("LR0218", Severity.ERROR, "no transition crosses orthogonal regions")
def no_crossing(context: object) -> Iterator[Finding]:
    for region, own, elsewhere, name, position in _transition_ends(context):
        if name not in own and name in elsewhere:
            yield (
                position,
                f"'{name}' is in region '{elsewhere[name]}': a transition cannot "
                f"cross from region '{region.name}'",
                "regions meet only where their state is entered and left",
            )


BESIDE_REGIONS = (ast.State, ast.Pseudostate, ast.Transition)
IN_REGIONS = (ast.State, ast.Pseudostate, ast.Transition)
KINDS = {
    ast.Action: "an action",
    ast.Invariant: "an invariant",
    ast.InternalTransition: "an internal transition",
    ast.Condition: "a condition",
    ast.Parameter: "a parameter",
    ast.Region: "a region",
}


@coco("LR0219", Severity.ERROR, "regions hold states and transitions; nothing stands beside them")
def region_contents(context: object) -> Iterator[Finding]:
    for _, region in _own_regions(analysis(context)):
        elements = [e for e in _source_elements(region) if not isinstance(e, ast.ParameterBlock)]
        in_region = region.parent is not None and region.parent.orthogonal
        for element in elements:
            if in_region and not isinstance(element, IN_REGIONS):
                kind = KINDS.get(type(element), "this element")
                yield (
                    element.position,
                    f"{kind} cannot stand in region '{region.name}': a region holds states, "
                    "pseudostates and transitions",
                    "put it on the state that owns the regions, or into a state of the region",
                )
            elif region.orthogonal and (
                isinstance(element, BESIDE_REGIONS)
                or (isinstance(element, ast.Condition) and element.kind == "start")
            ):
                yield (
                    element.position,
                    f"'{getattr(element, 'name', None) or 'this transition'}' stands beside the "
                    f"regions of '{region.name}'",
                    "move it into one of the regions",
                )


@coco("LR0220", Severity.ERROR, "regions command different devices unless a device is concurrent")
def regions_share_no_device(context: object) -> Iterator[Finding]:
    a = analysis(context)
    for _, region in _own_regions(a):
        if not region.orthogonal:
            continue
        seen: dict[str, str] = {}  # device instance -> the first region commanding it
        for name, info in region.states.items():
            if info.region is None:
                continue
            for device, declared in sorted(_devices(a, info.region, set()).items()):
                first = seen.setdefault(device, name)
                concurrent = declared is not None and ast.stereotype(
                    declared.stereotypes, "concurrent"
                )
                if first != name and not concurrent:
                    yield (
                        info.state.position,
                        f"regions '{first}' and '{name}' both command '{device}'",
                        "give each region its own device, or declare the device type "
                        "<<concurrent>> if it takes commands of several regions at once",
                    )


def _devices(a: Analysis, region: Region, visited: set[str]) -> dict[str, ast.Device | None]:
    """Device instances the actions below ``region`` command, with their device types."""
    found: dict[str, ast.Device | None] = {}
    for inner in region.regions():
        for info in inner.states.values():
            component = info.imported
            if component is None or component.qualified_name in visited:
                continue
            visited.add(component.qualified_name)
            if component.layer == "action":
                env = a.typing.environment(component.region)
                for action in component.region.actions:
                    for statement in action.statements if action.kind == "do" else ():
                        call = getattr(statement, "value", getattr(statement, "expression", None))
                        target = getattr(getattr(call, "function", None), "target", None)
                        device = env.get(target.name) if isinstance(target, ast.Name) else None
                        if isinstance(device, DeviceT):
                            found[target.name] = device.device
            else:
                found.update(_devices(a, component.region, visited))
    return found


@coco("LR0111", Severity.WARNING, "stimuli leaving a child name one of its outcomes")
def stimulus_is_outcome(context: object) -> Iterator[Finding]:
    for component, region in _own_regions(analysis(context)):
        if component.layer is None:
            continue  # a plain chart leaves composites by events as a matter of course
        for transition in region.transitions:
            source = region.states.get(transition.source)
            if (
                source is None
                or source.outcomes is None
                or not transition.stimulus
                or transition.delay is not None
            ):
                continue
            outcomes = (*source.outcomes, *BUILTIN_OUTCOMES)
            if transition.stimulus not in outcomes:
                known = ", ".join(source.outcomes) or "it has none"
                yield (
                    transition.stimulus_position,
                    f"'{transition.stimulus}' is not an outcome of '{source.name}' "
                    f"({known}); it is taken as an external event",
                    did_you_mean(transition.stimulus, outcomes),
                )


@coco("LR0201", Severity.ERROR, "a component has exactly one layer stereotype")
def one_layer(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        layers = component.layers
        if len(layers) > 1:
            yield (layers[1].position, "a statechart has exactly one layer stereotype", "")
        elif not layers and component.base is None and _uses_lightrocks(component.region):
            yield (
                component.statechart.position,
                f"'{component.name}' uses conditions, commands or <<import>> "
                "but has no layer stereotype",
                "add <<task>>, <<skill>> or <<action>>",
            )


def _uses_lightrocks(region: Region) -> bool:
    return bool(
        region.conditions
        or any(a.kind == "do" for a in region.actions)
        or any(s.imported is not None for s in region.states.values())
    )


@coco("LR0202", Severity.ERROR, "layering: tasks use skills, skills use actions or skills")
def layering(context: object) -> Iterator[Finding]:
    for component, region in _own_regions(analysis(context)):
        layer = component.layer
        if layer not in MAY_USE:
            continue
        for info in region.states.values():
            child = info.imported.layer if info.imported is not None else None
            if layer == "action":
                yield (info.state.position, "an action has no child states", "")
            elif child is not None and child not in MAY_USE[layer]:
                yield (
                    info.state.position,
                    f"a {layer} cannot use the {child} '{info.imported.name}'",
                    f"a {layer} uses {' and '.join(f'{m}s' for m in sorted(MAY_USE[layer]))}",
                )


@coco("LR0203", Severity.ERROR, "an action has exactly one do command")
def action_has_one_command(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        if component.layer != "action":
            continue
        commands = [s for a in component.region.actions if a.kind == "do" for s in a.statements]
        if len(commands) != 1:
            where = commands[1].position if len(commands) > 1 else component.statechart.position
            yield (
                where,
                f"action '{component.name}' must have exactly one do command, "
                f"found {len(commands)}",
                "",
            )


@coco("LR0204", Severity.ERROR, "a composite has no do command")
def composite_has_no_command(context: object) -> Iterator[Finding]:
    for component, region in _own_regions(analysis(context)):
        if component.layer in ("task", "skill") and region.states:
            for action in region.actions:
                if action.kind == "do":
                    yield (action.position, "a composite runs its children, not a command", "")


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
    for _, region in _own_regions(analysis(context)):
        if region.states and not region.orthogonal and not _entries(region):
            yield (
                region.position,
                f"'{region.name}' has no initial state or start condition",
                "mark a state 'initial' or add 'start condition …;'",
            )


@coco("LR0206", Severity.ERROR, "every composite can reach an end")
def reaches_end(context: object) -> Iterator[Finding]:
    for component, region in _own_regions(analysis(context)):
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
    for _, region in _own_regions(analysis(context)):
        entries = _entries(region)
        if not entries:
            continue
        graph = _graph(region)
        reached = set(entries)
        for entry in entries:
            reached |= nx.descendants(graph, entry)
        for name, info in region.states.items():
            if name not in reached and info.state.position.file == _file(region):
                yield (info.state.position, f"state '{name}' is unreachable", "")


@coco("LR0208", Severity.ERROR, "no transition leaves a final state or an end condition")
def no_transition_from_end(context: object) -> Iterator[Finding]:
    for _, region in _own_regions(analysis(context)):
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
    for _, region in _own_regions(analysis(context)):
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
    for _, region in _own_regions(analysis(context)):
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
    """The fix where a sibling shows it: handle the outcome as the sibling does."""
    for source, transitions in leaving.items():
        for transition in transitions:
            target = transition.target
            if source != name and transition.stimulus == outcome and target not in ("", name):
                return f"add the transition '{name} -> {target} {outcome};'"
    return ""


@coco("LR0210", Severity.ERROR, "no cycle of <<import>> and <<extends>>")
def no_reference_cycle(context: object) -> Iterator[Finding]:
    a = analysis(context)
    graph = nx.DiGraph()
    where: dict[tuple[str, str], ast.Position] = {}
    for source, target, _, position in a.models.references:
        graph.add_edge(source, target)
        where.setdefault((source, target), position)
    for cycle in nx.simple_cycles(graph):
        first = cycle.index(min(cycle))  # start at the smallest name: same report every run
        cycle = cycle[first:] + cycle[:first]
        edge = (cycle[0], cycle[1 % len(cycle)])
        path = " -> ".join([*cycle, cycle[0]])
        yield (where[edge], f"cyclic <<import>>/<<extends>>: {path}", "")


@coco("LR0211", Severity.WARNING, "no two transitions fire on the same outcome")
def deterministic(context: object) -> Iterator[Finding]:
    for _, region in _own_regions(analysis(context)):
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
    for _, region in _own_regions(analysis(context)):
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
    for _, region in _own_regions(analysis(context)):
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
    for _, region in _own_regions(analysis(context)):
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
    for component, region in _own_regions(analysis(context)):
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


@coco("LR0212", Severity.WARNING, "stereotypes are known")
def known_stereotypes(context: object) -> Iterator[Finding]:
    for component, region in _own_regions(analysis(context)):
        stereotypes = list(component.statechart.stereotypes) if region.parent is None else []
        for info in region.states.values():
            stereotypes += info.state.stereotypes
        for stereotype in stereotypes:
            if stereotype.name not in KNOWN_STEREOTYPES:
                yield (
                    stereotype.position,
                    f"unknown stereotype <<{stereotype.name}>>",
                    did_you_mean(stereotype.name, KNOWN_STEREOTYPES),
                )


def _file(region: Region) -> str:
    return region.loaded.unit.package_position.file


COCOS = (
    unique_names,
    unresolved_name,
    unresolved_type,
    unresolved_member,
    unknown_unit,
    package_matches_folder,
    name_matches_file,
    transition_ends_resolve,
    stimulus_is_outcome,
    one_layer,
    layering,
    action_has_one_command,
    composite_has_no_command,
    has_entry,
    reaches_end,
    states_reachable,
    no_transition_from_end,
    outcomes_handled,
    no_reference_cycle,
    deterministic,
    known_stereotypes,
    no_transition_into_start,
    completion_needs_outcome,
    history_targets,
    choice_branches,
    declared_events,
    no_crossing,
    region_contents,
    regions_share_no_device,
    call_signature,
    type_mismatch,
    not_boolean,
    dimension_mismatch,
    unsafe_value,
    not_assignable,
    command_placement,
    narrowing,
)
