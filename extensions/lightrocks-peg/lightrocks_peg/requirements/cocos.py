"""Context conditions of requirements: unique names, and a verifying outcome that exists."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity, did_you_mean
from lightrocks_peg.requirements.syntax import Requirement


def _requirements(context: object) -> Iterator[tuple[object, list[Requirement]]]:
    """Each region written in its own file with the requirements declared in it."""
    for component in analysis(context).models.components:
        for region in component.region.regions():
            own = [
                r
                for r in region.extensions
                if isinstance(r, Requirement) and r.position.file == region.position.file
            ]
            if own:
                yield region, own


@coco("PEG0001", Severity.ERROR, "requirement names are unique per statechart or state")
def unique_requirements(context: object) -> Iterator[tuple]:
    for _, requirements in _requirements(context):
        seen: set[str] = set()
        for requirement in requirements:
            if requirement.name in seen:
                yield requirement.position, f"requirement '{requirement.name}' again", ""
            seen.add(requirement.name)


@coco("PEG0002", Severity.ERROR, "a requirement is verified by an outcome of its region")
def verified_by_outcome(context: object) -> Iterator[tuple]:
    for region, requirements in _requirements(context):
        for requirement in requirements:
            if requirement.outcome and requirement.outcome not in region.outcomes:
                yield (
                    requirement.position,
                    f"'{requirement.outcome}' is no outcome of {region.name}",
                    did_you_mean(requirement.outcome, list(region.outcomes)),
                )


COCOS = (unique_requirements, verified_by_outcome)
