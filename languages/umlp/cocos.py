"""The context conditions of MontiCore's statechart language, 0xCC100 to 0xCC114, as
LightRocks findings LR2100 to LR2114 (the last digits are MontiCore's), and the two
findings of MontiCore's type check that its statechart tests expect (0xFD118) as LR2115
and LR2116.

| LightRocks | MontiCore | CoCo class of MontiCore |
|---|---|---|
| LR2100 | 0xCC100 | UniqueStates |
| LR2101 | 0xCC101 | InvariantValid |
| LR2102 | 0xCC102 | AtLeastOneInitialState |
| LR2103 | 0xCC103 | TransitionSourceTargetExists (source) |
| LR2104 | 0xCC104 | TransitionSourceTargetExists (target) |
| LR2105 | 0xCC105 | CapitalStateNames |
| LR2106 | 0xCC106 | SCFileExtension |
| LR2107 | 0xCC107 | PackageCorrespondsToFolders |
| LR2108 | 0xCC108 | SCNameIsArtifactName |
| LR2109 | 0xCC109 | NonCapitalParamNames |
| LR2110 | 0xCC110 | NonCapitalEventNames |
| LR2111 | 0xCC111 | TransitionPreconditionsAreBoolean |
| LR2112 | 0xCC112 | AnteBlocksOnlyForInitialStates |
| LR2114 | 0xCC114 | MaxOneInitialState |
| LR2115 | 0xFD118 | (type check) a type stands where a value belongs |
| LR2116 | 0xFD118 | (type check) a name the chart does not declare |

MontiCore has no 0xCC113. Severities are MontiCore's (``Log.warn`` is a warning); the
type-checked ones judge a type only when it is known (see :mod:`languages.umlp.typing`).
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.printer import expression
from lightrocks.languages.umlp.typing import (
    is_boolean,
    is_known,
    type_of,
    type_references,
)
from lightrocks.metamodel.ast import Position
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity, did_you_mean

Finding = tuple[Position, str, str]

MONTICORE_CODES = {
    "LR2100": "0xCC100",
    "LR2101": "0xCC101",
    "LR2102": "0xCC102",
    "LR2103": "0xCC103",
    "LR2104": "0xCC104",
    "LR2105": "0xCC105",
    "LR2106": "0xCC106",
    "LR2107": "0xCC107",
    "LR2108": "0xCC108",
    "LR2109": "0xCC109",
    "LR2110": "0xCC110",
    "LR2111": "0xCC111",
    "LR2112": "0xCC112",
    "LR2114": "0xCC114",
    "LR2115": "0xFD118",
    "LR2116": "0xFD118",
}
"""The MontiCore finding each LightRocks code stands for."""


def _artifacts(context: object) -> Iterator[tuple[Path, n.SCArtifact]]:
    for loaded in context.workspace.checked_units():
        if isinstance(loaded.unit, n.SCArtifact):
            yield loaded.path, loaded.unit


def _elements(elements: tuple[n.SCElement, ...] | None) -> Iterator[n.SCElement]:
    """Every element at and below ``elements``, in source order."""
    for element in elements or ():
        yield element
        if isinstance(element, n.SCState):
            yield from _elements(element.body)


def _top_states(chart: n.SCStatechart) -> list[n.SCState]:
    return [e for e in chart.elements if isinstance(e, n.SCState)]


def _where(unit: n.SCArtifact) -> Position:
    return Position(unit.file, 1, 1)


@coco("LR2100", Severity.ERROR, "state names are unique in a statechart (0xCC100)")
def unique_states(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        seen: dict[str, n.SCState] = {}
        for state in n.states(unit.statechart.elements):
            first = seen.setdefault(state.name, state)
            if first is not state:
                yield (
                    state.position,
                    f"state names must be unique, but {state.name} is also declared at "
                    f"{first.position.line}:{first.position.column}",
                    "",
                )


def _invariants(unit: n.SCArtifact) -> Iterator[n.SCState]:
    for state in n.states(unit.statechart.elements):
        if state.invariant is not None:
            yield state


@coco("LR2101", Severity.ERROR, "a state invariant is Boolean (0xCC101)")
def invariant_valid(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        for state in _invariants(unit):
            kind = type_of(state.invariant)
            if is_known(kind) and not is_boolean(kind):
                message = f"invariant of {state.name} is of type {kind}, not boolean"
                yield state.position, message, ""


@coco("LR2102", Severity.ERROR, "a statechart has an initial state on its top level (0xCC102)")
def at_least_one_initial_state(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        chart = unit.statechart
        if not any(state.initial for state in _top_states(chart)):
            yield chart.position, "statecharts need at least one initial state", ""


def _transitions(unit: n.SCArtifact) -> Iterator[n.SCTransition]:
    for element in _elements(unit.statechart.elements):
        if isinstance(element, n.SCTransition):
            yield element


@coco("LR2103", Severity.ERROR, "the source of a transition is a state (0xCC103)")
def transition_source_exists(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        names = [s.name for s in n.states(unit.statechart.elements)]
        for transition in _transitions(unit):
            if transition.source not in names:
                yield (
                    transition.source_position,
                    f"source state {transition.source} of the transition is missing",
                    did_you_mean(transition.source, names),
                )


@coco("LR2104", Severity.ERROR, "the target of a transition is a state (0xCC104)")
def transition_target_exists(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        names = [s.name for s in n.states(unit.statechart.elements)]
        for transition in _transitions(unit):
            if transition.target not in names:
                yield (
                    transition.target_position,
                    f"target state {transition.target} of the transition is missing",
                    did_you_mean(transition.target, names),
                )


@coco("LR2105", Severity.WARNING, "state names start with a capital letter (0xCC105)")
def capital_state_names(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        for state in n.states(unit.statechart.elements):
            if state.name[:1].islower():
                hint = f"did you mean '{state.name[0].upper()}{state.name[1:]}'?"
                yield state.position, f"state {state.name} should start with a capital letter", hint


@coco("LR2106", Severity.WARNING, "a UML/P statechart is in a file ending in .sc (0xCC106)")
def sc_file_extension(context: object) -> Iterator[Finding]:
    for path, unit in _artifacts(context):
        if path.suffix != ".sc":
            found = path.suffix.lstrip(".") or "none"
            yield _where(unit), f"file extension is '{found}', but should be 'sc'", ""


@coco("LR2107", Severity.ERROR, "the package corresponds to the folders of the file (0xCC107)")
def package_corresponds_to_folders(context: object) -> Iterator[Finding]:
    for path, unit in _artifacts(context):
        if not unit.package:
            continue
        parts = tuple(unit.package.split("."))
        folders = path.parent.parts
        if folders[len(folders) - len(parts) :] != parts:
            yield (
                unit.package_position,
                f"package name '{unit.package}' does not correspond to the file path '{unit.file}'",
                f"move the file to a folder {'/'.join(parts)}/ or declare the package "
                f"'{'.'.join(folders[-len(parts) :]) if folders else ''}'",
            )


@coco("LR2108", Severity.WARNING, "the statechart's name is the file's name (0xCC108)")
def sc_name_is_artifact_name(context: object) -> Iterator[Finding]:
    for path, unit in _artifacts(context):
        chart = unit.statechart
        base = path.stem
        if chart.name and chart.name != base:
            yield (
                chart.position,
                f"the statechart name {chart.name} does not match the artifact name {base}",
                "",
            )


def _event_definitions(unit: n.SCArtifact) -> Iterator[n.SCFuncEventDef]:
    for element in unit.statechart.elements:
        if isinstance(element, n.SCFuncEventDef):
            yield element


@coco("LR2109", Severity.WARNING, "event parameter names start with a lower-case letter (0xCC109)")
def non_capital_param_names(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        for definition in _event_definitions(unit):
            for parameter in definition.parameters:
                if not parameter.name[:1].islower():
                    yield (
                        parameter.position,
                        f"the parameter name {parameter.name} should start with a lower-case "
                        "letter",
                        "",
                    )


@coco("LR2110", Severity.WARNING, "event names start with a lower-case letter (0xCC110)")
def non_capital_event_names(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        for definition in _event_definitions(unit):
            if not definition.name[:1].islower():
                yield (
                    definition.position,
                    f"the event name {definition.name} should start with a lower-case letter",
                    "",
                )


def _guarded(unit: n.SCArtifact) -> Iterator[n.SCTransition | n.SCInternTransition]:
    for element in _elements(unit.statechart.elements):
        if isinstance(element, n.SCTransition | n.SCInternTransition) and element.pre:
            yield element


@coco("LR2111", Severity.ERROR, "the guard of a transition is Boolean (0xCC111)")
def transition_preconditions_are_boolean(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        for transition in _guarded(unit):
            kind = type_of(transition.pre)
            if is_known(kind) and not is_boolean(kind):
                yield (
                    transition.pre.position,
                    f"guard expressions must be boolean; [{expression(transition.pre)}] is of "
                    f"type '{kind}'",
                    "",
                )


@coco("LR2112", Severity.ERROR, "only initial states have an ante block (0xCC112)")
def ante_blocks_only_for_initial_states(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        for state in n.states(unit.statechart.elements):
            if state.ante is not None and not state.initial:
                yield (
                    state.position,
                    "initialization actions may only be specified for initial states, "
                    f"but '{state.name}' is not initial",
                    "",
                )


@coco("LR2114", Severity.ERROR, "at most one initial state on the top level (0xCC114)")
def max_one_initial_state(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        initial = [s for s in _top_states(unit.statechart) if s.initial]
        for state in initial[1:]:
            names = ", ".join(s.name for s in initial)
            yield (
                state.position,
                "statecharts must not have more than one initial state; following states are "
                f"currently initial: {names}",
                "",
            )


def _checked_expressions(unit: n.SCArtifact) -> Iterator[n.JExpression]:
    """The guards and invariants: the Java expressions MontiCore's CoCos type."""
    for element in _elements(unit.statechart.elements):
        if isinstance(element, n.SCState) and element.invariant is not None:
            yield element.invariant
        elif isinstance(element, n.SCTransition | n.SCInternTransition) and element.pre:
            yield element.pre


@coco("LR2115", Severity.ERROR, "a guard or invariant uses no type as a value (0xFD118)")
def no_type_as_value(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        for checked in _checked_expressions(unit):
            for name in type_references(checked):
                yield name.position, f"'{name.name}' is a type, not a value", ""


@coco(
    "LR2116",
    Severity.WARNING,
    "a name of a guard or invariant is declared where the chart can see it (0xFD118)",
)
def names_from_context(context: object) -> Iterator[Finding]:
    for _, unit in _artifacts(context):
        for checked in _checked_expressions(unit):
            found: list[n.JName] = []
            type_of(checked, found.append)
            for name in found:
                yield (
                    name.position,
                    f"'{name.name}' is not declared in the statechart: its type is unknown, "
                    "so this condition is not type-checked",
                    "UML/P takes it from the class the chart describes, which is not read here",
                )
