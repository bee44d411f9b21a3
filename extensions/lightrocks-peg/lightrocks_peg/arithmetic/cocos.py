"""Context conditions of ``count``: it counts an Integer."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.domain.types import UNKNOWN
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity
from lightrocks_peg.arithmetic.syntax import Count


@coco("PEG0003", Severity.ERROR, "count adds 1 to an Integer")
def counts_integers(context: object) -> Iterator[tuple]:
    a = analysis(context)
    for component in a.models.components:
        for region in component.region.regions():
            if region.loaded is not component.loaded:
                continue  # an inherited region is checked in its own file
            bodies = (region.actions, region.transitions, region.internal)
            counts = [n for n in ast.walk(bodies) if isinstance(n, Count)]
            if not counts:
                continue
            env = a.typing.environment(region)
            for count in counts:
                counted = a.typing.infer(count.target, env)
                if counted is not UNKNOWN and counted.name != "Integer":
                    yield count.position, f"count needs an Integer, not {counted}", ""


COCOS = (counts_integers,)
