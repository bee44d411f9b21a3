"""The findings of the typing pass (:mod:`.typing`): names, types, members and units that do
not resolve (LR0103, LR0105–LR0107) and typing, units and safe ranges (LR0301–LR0308). One
pass over every component types each expression once and finds them all."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.workbench.cocos import Code
from lightrocks.workbench.diagnostics import Severity
from lightrocks.workbench.passes import Finding, Pass

E = Severity.ERROR


class TypingPass(Pass):
    """Reports what the typing of this run's components found, under the code it names."""

    codes = (
        Code("LR0103", E, "names in expressions resolve"),
        Code("LR0105", E, "types resolve"),
        Code("LR0106", E, "devices, commands, sensors and attributes resolve"),
        Code("LR0107", E, "units are known"),
        Code("LR0301", E, "calls match the signature: names and arity"),
        Code("LR0302", E, "values match the declared types"),
        Code("LR0303", E, "guards, invariants and conditions are Boolean"),
        Code("LR0304", E, "unit dimensions agree"),
        Code("LR0305", E, "values lie in the safe ranges the device declares"),
        Code("LR0306", E, "only environment attributes and parameters are assigned"),
        Code("LR0307", E, "device commands are called in do actions only"),
        Code("LR0308", E, "no Real value where an Integer is declared"),
    )

    def findings(self) -> Iterator[Finding]:
        for code, found in analysis(self.context).typing.findings.items():
            for position, message, hint in found:
                yield code, position, message, hint
