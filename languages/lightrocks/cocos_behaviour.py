"""Context conditions on behaviour: guards, start and end conditions judged by the SMT
solver (:mod:`.behaviour.conditions`). One pass over every region serves all codes."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.behaviour.conditions import Conditions, Finding
from lightrocks.languages.lightrocks.behaviour.judge import SOLVER_TURN
from lightrocks.languages.lightrocks.behaviour.parameters import ParameterValues
from lightrocks.languages.lightrocks.behaviour.plausibility import Plausibility, degree_findings
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity


def condition_findings(context: object) -> dict[str, list[Finding]]:
    """Every finding on conditions of this run, by code, computed once."""
    with SOLVER_TURN:
        return _condition_findings(context)


def _condition_findings(context: object) -> dict[str, list[Finding]]:
    cached = context.cache.get("behaviour-conditions")
    if cached is not None:
        return cached
    a = analysis(context)
    values = ParameterValues(a.models)
    found: dict[str, list[Finding]] = defaultdict(list)
    if not a.typing.findings.get("LR0103") and not a.typing.findings.get("LR0304"):
        own_files = {c.loaded.unit.package_position.file for c in a.models.components}
        for component in a.models.components:
            for region in component.region.regions():
                if region.loaded is component.loaded:
                    for finding in Conditions(a.typing, values, component, region).findings():
                        found[finding.code].append(finding)
            if component.layer == "action":
                for finding in Plausibility(a.typing, component).findings():
                    found[finding.code].append(finding)
        for file, expressions in a.typing.inferred.items():
            if file in own_files:
                for finding in degree_findings(expressions):
                    found[finding.code].append(finding)
    context.cache["behaviour-conditions"] = found
    return found


def _conditions(code: str, severity: Severity, summary: str):
    @coco(code, severity, summary)
    def check(context: object) -> Iterator[tuple[ast.Position, str, str]]:
        for finding in condition_findings(context).get(code, []):
            yield finding.position, finding.message, finding.hint

    return check


never_holds = _conditions("LR0601", Severity.WARNING, "a guard or condition can hold")
always_holds = _conditions("LR0602", Severity.WARNING, "a guard or condition does not always hold")
holds_at_start = _conditions(
    "LR0603", Severity.WARNING, "an end condition does not already hold when its command starts"
)
shadowed = _conditions("LR0604", Severity.WARNING, "no transition or condition is shadowed")
overlapping = _conditions(
    "LR0605", Severity.WARNING, "guards of transitions on one stimulus exclude each other"
)
exact_measurement = _conditions(
    "LR0606", Severity.WARNING, "measured values are compared with a tolerance, not with =="
)

too_short = _conditions(
    "LR0607", Severity.WARNING, "a time budget leaves the commanded motion the time it takes"
)
implausible_gain = _conditions(
    "LR0608", Severity.WARNING, "stiffness and damping are of the device's typical magnitude"
)
pi_degrees = _conditions("LR0609", Severity.WARNING, "degrees are not written as multiples of π")
impossible_sign = _conditions(
    "LR0610", Severity.WARNING, "a force end condition can hold against the commanded motion"
)

BEHAVIOUR_COCOS = (
    never_holds,
    always_holds,
    holds_at_start,
    shadowed,
    overlapping,
    exact_measurement,
    too_short,
    implausible_gain,
    pi_degrees,
    impossible_sign,
)
