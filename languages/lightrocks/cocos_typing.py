"""Context conditions that report the findings of the shared typing pass
(:mod:`.typing`), one CoCo a code: names, types, members and units that do not resolve
(LR0103, LR0105–LR0107) and typing, units and safe ranges (LR0301–LR0308). The pass runs
once for all of them."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import CoCo, coco
from lightrocks.workbench.diagnostics import Severity

Finding = tuple[ast.Position, str, str]


def _typing(code: str, summary: str, severity: Severity = Severity.ERROR) -> CoCo:
    """A CoCo that reports the findings of the shared typing pass for one code."""

    @coco(code, severity, summary)
    def check(context: object) -> Iterator[Finding]:
        yield from analysis(context).typing.findings.get(code, [])

    return check


unresolved_name = _typing("LR0103", "names in expressions resolve")
unresolved_type = _typing("LR0105", "types resolve")
unresolved_member = _typing("LR0106", "devices, commands, sensors and attributes resolve")
unknown_unit = _typing("LR0107", "units are known")
call_signature = _typing("LR0301", "calls match the signature: names and arity")
type_mismatch = _typing("LR0302", "values match the declared types")
not_boolean = _typing("LR0303", "guards, invariants and conditions are Boolean")
dimension_mismatch = _typing("LR0304", "unit dimensions agree")
unsafe_value = _typing("LR0305", "values lie in the safe ranges the device declares")
not_assignable = _typing("LR0306", "only environment attributes and parameters are assigned")
command_placement = _typing("LR0307", "device commands are called in do actions only")
narrowing = _typing("LR0308", "no Real value where an Integer is declared")
