"""Context conditions on properties (``property name: formula;``): what ``lightrocks verify``
cannot prove or refute because it does not say which outcome or state it means, or stands
where no run of its own is checked. Names of values, types and units in the predicates are
the typing pass's (LR0103, LR0303, LR0304)."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.properties import state_names
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity, did_you_mean

Finding = tuple[ast.Position, str, str]


@coco("LR0717", Severity.ERROR, "a property names an outcome and states of its own statechart")
def property_names(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        region = component.region
        outcomes = region.outcomes
        counts = state_names(region)
        env = analysis(context).typing.environment(region)
        for own in _own(component, region.properties):
            if own.kind == "ensures" and own.outcome not in outcomes:
                yield (
                    own.outcome_position,
                    f"'{own.outcome}' is no outcome of '{component.name}': a contract "
                    "holds where the run ends with an end condition or a final state",
                    did_you_mean(own.outcome, outcomes) or "name one of " + ", ".join(outcomes),
                )
            for predicate in own.expressions:
                for node in ast.walk(predicate):
                    if not isinstance(node, ast.Name) or node.name in env:
                        continue
                    if counts.get(node.name, 0) > 1 and node.name not in outcomes:
                        yield (
                            node.position,
                            f"{counts[node.name]} states of '{component.name}' are named "
                            f"'{node.name}': the property cannot tell which one it means",
                            "rename one of them",
                        )


@coco("LR0718", Severity.ERROR, "properties stand at the top of a composite, once by name")
def property_places(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        top = component.region
        seen: dict[str, ast.Property] = {}
        for own in _own(component, top.properties):
            if component.layer == "action":
                yield (
                    own.position,
                    f"property '{own.name}' of the action '{component.name}': verify checks "
                    "the runs of tasks, skills and plain statecharts, not of one command",
                    "state it in a skill that uses the action",
                )
            elif own.name in seen:
                yield (
                    own.position,
                    f"a second property named '{own.name}' (the first at "
                    f"{seen[own.name].position.line}:{seen[own.name].position.column})",
                    "give each property a name of its own",
                )
            seen.setdefault(own.name, own)
        for region in top.regions()[1:]:
            for own in _own(component, region.properties):
                yield (
                    own.position,
                    f"property '{own.name}' inside '{region.name}': a property speaks of "
                    f"the whole statechart and stands at the top of '{component.name}'",
                    "move it to the statechart's body",
                )


def _own(component, properties: list[ast.Property]) -> list[ast.Property]:
    """The properties written in the component's own file (an extended one's are checked
    where they are written)."""
    file = component.loaded.unit.package_position.file
    return [p for p in properties if p.position.file == file]
