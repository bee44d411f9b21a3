"""The library entry of ``lightrocks verify``: check, then model-check the outcome flow of
every task and skill (and of plain statecharts with an end), and give each refuted property
with the run that shows it."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.behaviour.checker import (
    MAX_CONFIGURATIONS,
    RAISE_LIMIT,
    Counterexample,
    explore,
    refute,
)
from lightrocks.languages.lightrocks.behaviour.flow import Flow
from lightrocks.languages.lightrocks.behaviour.judge import SOLVER_TURN
from lightrocks.languages.lightrocks.behaviour.liveness import Liveness
from lightrocks.languages.lightrocks.behaviour.properties import (
    REFUTED,
    UNDECIDED,
    Properties,
    PropertyLiveness,
)
from lightrocks.workbench.check import check
from lightrocks.workbench.diagnostics import Diagnostic, Severity

SEVERITY = {
    "LR0701": Severity.ERROR,
    "LR0702": Severity.ERROR,
    "LR0703": Severity.WARNING,
    "LR0704": Severity.WARNING,
    **dict.fromkeys(REFUTED.values(), Severity.ERROR),
    UNDECIDED: Severity.WARNING,
}


@dataclass
class Verification:
    """Every finding of ``check`` and of the model checker; a counterexample per refuted
    property of the outcome flow."""

    diagnostics: list[Diagnostic] = field(default_factory=list)
    counterexamples: list[tuple[Diagnostic, Counterexample]] = field(default_factory=list)
    strict: bool = False

    @property
    def failed(self) -> bool:
        """What makes ``verify`` exit with 1: an error, or with ``strict`` any warning."""
        worst = {Severity.ERROR, Severity.WARNING} if self.strict else {Severity.ERROR}
        return any(d.severity in worst for d in self.diagnostics)


def verify(
    paths: Iterable[Path],
    search_path: Iterable[Path] = (),
    strict: bool = False,
    substituted: Mapping[Path, str] | None = None,
    max_configurations: int = MAX_CONFIGURATIONS,
) -> Verification:
    """Check the models below ``paths`` (with ``search_path`` as further model-path roots);
    when that finds no error, model-check every task, skill and plain statechart with an end,
    exploring at most ``max_configurations`` configurations of each. ``substituted`` maps
    resolved paths to texts that stand in for those files (as in :func:`check`)."""
    context = check(list(paths), list(search_path), substituted=substituted)
    result = Verification(list(context.diagnostics.items), strict=strict)
    if context.diagnostics.has_errors:
        return result
    with SOLVER_TURN:
        _model_check(analysis(context), result, max_configurations)
    result.diagnostics.sort()
    return result


def _model_check(a: object, result: Verification, limit: int) -> None:
    """The refuted properties of every task, skill and plain statechart with an end."""
    liveness = Liveness()
    seen: set[tuple[str, object]] = set()
    for component in sorted(a.models.components, key=lambda c: c.qualified_name):
        if component.layer == "action" or not component.region.states:
            continue
        stated = component.region.properties
        flow = Flow(a.typing, component, PropertyLiveness(component) if stated else liveness)
        exploration = explore(flow, limit)
        if not exploration.complete:
            diagnostic = Diagnostic.at(
                component.statechart.position,
                "LR0704",
                SEVERITY["LR0704"],
                f"verification of '{component.name}' stopped at its limit of {limit:,} "
                "configurations: its properties are not proved",
                RAISE_LIMIT,
            )
            result.diagnostics.append(diagnostic)
        for refutation in refute(flow, exploration, loops=component.layer is not None):
            key = (refutation.code, refutation.position)
            if key in seen:
                continue
            seen.add(key)
            diagnostic = Diagnostic.at(
                refutation.position,
                refutation.code,
                SEVERITY[refutation.code],
                refutation.message,
                refutation.hint,
            )
            result.diagnostics.append(diagnostic)
            if refutation.counterexample is not None:
                result.counterexamples.append((diagnostic, refutation.counterexample))
        if stated:
            _properties(component, Properties(flow, exploration), result)


def _properties(component: object, properties: Properties, result: Verification) -> None:
    """The properties the chart states that its runs do not prove; each is judged where its
    chart is the root (a skill's with its parameters at their defaults)."""
    for verdict in properties.verdicts():
        diagnostic = Diagnostic.at(
            verdict.property.position,
            verdict.code,
            SEVERITY[verdict.code],
            verdict.message,
            verdict.hint,
        )
        result.diagnostics.append(diagnostic)
        if verdict.counterexample is not None:
            result.counterexamples.append((diagnostic, verdict.counterexample))
