"""Context conditions on behaviour: guards, start and end conditions judged by the SMT
solver (:mod:`.behaviour.conditions`), and the plausibility of what actions command. One
pass over every region finds the findings of all codes."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.behaviour.conditions import Conditions
from lightrocks.languages.lightrocks.behaviour.conditions import Finding as Judged
from lightrocks.languages.lightrocks.behaviour.intervals import (
    Durations,
    nested_budgets,
    zero_budget,
)
from lightrocks.languages.lightrocks.behaviour.judge import SOLVER_TURN
from lightrocks.languages.lightrocks.behaviour.parameters import ParameterValues
from lightrocks.languages.lightrocks.behaviour.plausibility import Plausibility, degree_findings
from lightrocks.metamodel import ast
from lightrocks.workbench.check import CheckContext
from lightrocks.workbench.cocos import Code
from lightrocks.workbench.diagnostics import Severity
from lightrocks.workbench.passes import Finding, Pass

W = Severity.WARNING


class JudgedPass(Pass):
    """A pass whose findings the solver judges once, when the pass is made, one check at a
    time (:data:`SOLVER_TURN`); a subclass says what it judges in :meth:`_judge`."""

    def __init__(self, context: CheckContext) -> None:
        super().__init__(context)
        with SOLVER_TURN:
            self.judged = list(self._judge())

    def _judge(self) -> Iterator[Judged]:
        raise NotImplementedError

    def findings(self) -> Iterator[Finding]:
        for judged in self.judged:
            yield judged.code, judged.position, judged.message, judged.hint


class BehaviourPass(JudgedPass):
    """Judges the conditions of every region and the commands of every action of the run;
    nothing is judged while names or unit dimensions do not resolve (LR0103, LR0304)."""

    codes = (
        Code("LR0601", W, "a guard or condition can hold"),
        Code("LR0602", W, "a guard or condition does not always hold"),
        Code("LR0603", W, "an end condition does not already hold when its command starts"),
        Code("LR0604", W, "no transition or condition is shadowed"),
        Code("LR0605", W, "guards of transitions on one stimulus exclude each other"),
        Code("LR0606", W, "measured values are compared with a tolerance, not with =="),
        Code("LR0607", W, "a time budget leaves the commanded motion the time it takes"),
        Code("LR0608", W, "stiffness and damping are of the device's typical magnitude"),
        Code("LR0609", W, "degrees are not written as multiples of π"),
        Code("LR0610", W, "a force end condition can hold against the commanded motion"),
        Code("LR0611", W, "a duration is positive"),
        Code("LR0612", W, "a wait or a child's budget is shorter than the budget enclosing it"),
        Code("LR0613", W, "an action's end condition is not implied by its start condition"),
    )

    def _judge(self) -> Iterator[Judged]:
        a = analysis(self.context)
        if a.typing.findings.get("LR0103") or a.typing.findings.get("LR0304"):
            return
        values = ParameterValues(a.models)
        own_files = {c.loaded.unit.package_position.file for c in a.models.components}
        for component in a.models.components:
            for region in component.region.regions():
                if region.loaded is component.loaded:
                    conditions = Conditions(a.typing, values, component, region)
                    yield from conditions.findings()
                    yield from conditions.implied_by_start()
                    yield from Durations(conditions).findings()
                    yield from nested_budgets(conditions)
            own = ast.stereotype(component.statechart.stereotypes, "timeout")
            spent = zero_budget(own, component.time_budget) if own is not None else None
            if spent is not None:
                yield spent
            if component.layer == "action":
                yield from Plausibility(a.typing, component).findings()
        for file, expressions in a.typing.inferred.items():
            if file in own_files:
                yield from degree_findings(expressions)
