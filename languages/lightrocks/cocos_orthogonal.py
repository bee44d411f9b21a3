"""Context conditions on orthogonal regions (LR0218–LR0220): no transition crosses from one
region into another, a region holds states and transitions and nothing stands beside the
regions, and two regions command the same device only if it takes concurrent commands."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.domain.types import DeviceT
from lightrocks.languages.lightrocks.analysis import Analysis, analysis
from lightrocks.languages.lightrocks.model import Region
from lightrocks.languages.lightrocks.regions import own_regions, source_elements, transition_ends
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity

Finding = tuple[ast.Position, str, str]


@coco("LR0218", Severity.ERROR, "no transition crosses orthogonal regions")
def no_crossing(context: object) -> Iterator[Finding]:
    for region, own, elsewhere, name, position in transition_ends(context):
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
    for _, region in own_regions(analysis(context)):
        elements = [e for e in source_elements(region) if not isinstance(e, ast.ParameterBlock)]
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
    for _, region in own_regions(a):
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
