"""Context conditions that keep a model from meaning something its author did not write:
typed stereotype values, actions that can end, guards in their place, and safe ranges on
every path a constant takes to a device command (defaults, bindings)."""

from __future__ import annotations

import math
import re
from collections.abc import Iterator

from lightrocks.languages.domain.ranges import Range
from lightrocks.languages.lightrocks.analysis import Analysis, analysis
from lightrocks.languages.lightrocks.ranges import Flows
from lightrocks.languages.lightrocks.regions import own_regions, region_file
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import seconds
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity

Finding = tuple[ast.Position, str, str]

SCENE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _stereotypes(a: Analysis) -> Iterator[ast.Stereotype]:
    """Every stereotype of every loaded unit: statecharts, their states, devices and cells."""
    for loaded in a.workspace.checked_units():
        unit = loaded.unit
        if isinstance(unit, ast.StatechartUnit):
            yield from unit.statechart.stereotypes
            yield from _state_stereotypes(unit.statechart.elements)
        else:
            for declaration in unit.declarations:
                yield from getattr(declaration, "stereotypes", ())


def _state_stereotypes(elements: tuple) -> Iterator[ast.Stereotype]:
    for element in elements:
        if isinstance(element, ast.State):
            yield from element.stereotypes
            yield from _state_stereotypes(element.body or ())


@coco("LR0501", Severity.ERROR, "a timeout is a duration with a time unit, such as 5 s")
def timeout_is_duration(context: object) -> Iterator[Finding]:
    for stereotype in _stereotypes(analysis(context)):
        if stereotype.name != "timeout":
            continue
        duration = seconds(stereotype.value)
        if duration is None:
            yield (
                stereotype.position,
                f"timeout '{stereotype.value}' is not a duration",
                'write a number with a time unit, e.g. <<timeout="8 s">>',
            )
        elif not math.isfinite(duration):
            yield (
                stereotype.position,
                f"timeout '{stereotype.value}' is beyond the largest number a Real holds "
                "(about 1.8e308 in SI units)",
                'write a duration a run can wait, e.g. <<timeout="8 s">>',
            )


@coco("LR0502", Severity.ERROR, "a scene is named, not given as a path")
def scene_is_name(context: object) -> Iterator[Finding]:
    for stereotype in _stereotypes(analysis(context)):
        if stereotype.name == "scene" and not SCENE_NAME.fullmatch(stereotype.value or ""):
            yield (
                stereotype.position,
                f"scene '{stereotype.value}' is not a scene name",
                'name a scene the adapters know, e.g. <<scene="screwing">>',
            )


@coco("LR0503", Severity.ERROR, "an elemental action declares an end condition")
def action_can_end(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        if component.layer == "action" and not component.region.end_conditions:
            yield (
                component.statechart.position,
                f"action '{component.name}' has no end condition: its command never ends it",
                "declare one, e.g. 'end condition done: <sensor condition>;'",
            )


@coco("LR0504", Severity.WARNING, "a condition after the stimulus follows an action")
def guard_in_place(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
        for transition in region.transitions:
            if transition.postcondition is not None and transition.action is None:
                yield (
                    transition.postcondition.position,
                    "a [condition] after the stimulus is a postcondition, not a guard",
                    f"for a guard write it before the stimulus: "
                    f"{transition.source} -> {transition.target} [...] {transition.stimulus};",
                )


# -- safe ranges through parameters ------------------------------------------------------


@coco(
    "LR0505",
    Severity.ERROR,
    "constants reaching a command through parameter defaults and bindings are in range",
)
def safe_through_parameters(context: object) -> Iterator[Finding]:
    a = analysis(context)
    flows = Flows(a.typing)
    for component, region in own_regions(a):
        for parameter in region.parameters.values():
            if parameter.default is not None and parameter.position.file == region_file(region):
                for safe in flows.of(component).get(parameter.name, ()):
                    yield from _breach(parameter.default, safe, f"default of '{parameter.name}'")
        for called, name, value in flows.bindings(region):
            for safe in flows.of(called).get(name, ()):
                yield from _breach(value, safe, f"'{name}' of {called.name}")


def _breach(value: ast.Expression, safe: Range, what: str) -> Iterator[Finding]:
    breach = safe.breach(value)
    if breach is not None:
        yield value.position, f"{what} reaches {breach}", ""
