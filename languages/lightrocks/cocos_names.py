"""Context conditions on names and references (LR01xx): names unique per scope, packages and
statecharts where their files are, transition ends that resolve, and stimuli that name an
outcome of the state they leave. The names the typing pass resolves are checked in
:mod:`.cocos_typing`."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.model import BUILTIN_OUTCOMES, Region
from lightrocks.languages.lightrocks.regions import own_regions, source_elements, transition_ends
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity, did_you_mean

Finding = tuple[ast.Position, str, str]


@coco("LR0101", Severity.ERROR, "names are unique per scope")
def unique_names(context: object) -> Iterator[Finding]:
    for _, region in own_regions(analysis(context)):
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
    statechart_elements = source_elements(region)
    flat: list = []
    for element in statechart_elements:
        if isinstance(element, ast.ParameterBlock):
            flat.extend(p for p in element.parameters if isinstance(p, kind))
        elif isinstance(element, kind):
            flat.append(element)
    return flat


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
    for _, names, elsewhere, name, position in transition_ends(context):
        if name not in names and name not in elsewhere:
            yield (position, f"unknown state or condition '{name}'", did_you_mean(name, names))


@coco("LR0111", Severity.WARNING, "stimuli leaving a child name one of its outcomes")
def stimulus_is_outcome(context: object) -> Iterator[Finding]:
    for component, region in own_regions(analysis(context)):
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
