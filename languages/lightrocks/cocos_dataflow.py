"""Context conditions on data flow: races between orthogonal regions, and guards that can
hold alone but never where their transition is taken (:mod:`.behaviour.dataflow`)."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.behaviour.conditions import Conditions
from lightrocks.languages.lightrocks.behaviour.conditions import Finding as Judged
from lightrocks.languages.lightrocks.behaviour.dataflow import Context, races
from lightrocks.languages.lightrocks.behaviour.parameters import ParameterValues
from lightrocks.languages.lightrocks.cocos_behaviour import JudgedPass
from lightrocks.workbench.cocos import Code
from lightrocks.workbench.diagnostics import Severity

W = Severity.WARNING


class DataflowPass(JudgedPass):
    """Follows what the regions of every component write and test, and judges each guard
    with what is known where it is taken; guards are not judged while names or unit
    dimensions do not resolve (LR0103, LR0304)."""

    codes = (
        Code("LR0614", W, "no two orthogonal regions write one variable"),
        Code("LR0615", W, "no region writes what an orthogonal region tests"),
        Code("LR0616", W, "a guard can hold where its transition is taken"),
    )

    def _judge(self) -> Iterator[Judged]:
        a = analysis(self.context)
        resolved = not (a.typing.findings.get("LR0103") or a.typing.findings.get("LR0304"))
        values = ParameterValues(a.models) if resolved else None
        for component in a.models.components:
            for region in component.region.regions():
                if region.loaded is not component.loaded:
                    continue
                yield from races(component, region)
                if values is not None:
                    yield from Context(Conditions(a.typing, values, component, region)).findings()
