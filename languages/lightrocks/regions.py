"""What the CoCos of several areas walk in a LightRocks model: the regions written in each
component's own file, their elements as written, and the source and target of every
transition with the names it may refer to."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import Analysis, analysis
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.metamodel import ast


def own_regions(a: Analysis) -> Iterator[tuple[Component, Region]]:
    """Regions written in each component's own file (inherited ones are checked at home)."""
    for component in a.models.components:
        for region in component.region.regions():
            if region.loaded is component.loaded:
                yield component, region


def region_file(region: Region) -> str:
    """The file a region is written in."""
    return region.loaded.unit.package_position.file


def source_elements(region: Region) -> tuple:
    """The elements as written (before extension merged them by name)."""
    unit = region.loaded.unit
    if region.parent is None:
        return unit.statechart.elements
    return region.parent.states[region.name].state.body or ()


def transition_ends(
    context: object,
) -> Iterator[tuple[Region, dict[str, None], dict[str, str], str, ast.Position]]:
    """Every source and target of a transition with the names of its own region (in
    declaration order, looked up in constant time) and the states of the sibling regions
    (see :func:`_sibling_regions`)."""
    for _, region in own_regions(analysis(context)):
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
