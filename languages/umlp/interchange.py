"""Conversion between UML/P statecharts as MontiCore writes them (``.sc``) and LightRocks
(``.lr``), for every construct the two languages share; docs/interchange.md lists what maps
to what.

``.sc → .lr`` translates the Java of guards, actions and invariants into LightRocks
expressions and statements where LightRocks has the construct (names, member access, calls,
the operators both share, literals, assignments, ``x++`` and ``x += e``), and refuses the
rest with a finding at its position (LR2120): a chart whose actions are all expressible
runs in the Python runtime. A call of a method of the class the chart describes converts to
a call, with a warning (LR2124): the LightRocks check reports it until it is replaced.
Variables the chart assigns or tests but does not declare (UML/P takes them from the class
the chart describes) become parameters of the types their uses show (LR2123). ``.lr → .sc``
takes plain statecharts: a LightRocks component (layers, ``<<import>>``, start and end
conditions) or a construct MontiCore's statecharts lack (regions, choice, history, time
events) is refused (LR2121).

Findings: LR2120 (error) Java code without LightRocks counterpart, or LightRocks code
without Java counterpart; LR2121 (error) a construct the target language lacks; LR2122
(warning) something dropped that the target cannot say and that does not change what the
chart does; LR2123 (info) a parameter declared for an undeclared variable; LR2124 (warning)
a call of a method LightRocks does not have.

The conversion is split by direction: :mod:`languages.umlp.chart_to_lr` and
:mod:`languages.umlp.java_to_lr` (with :mod:`languages.umlp.undeclared`) read UML/P,
:mod:`languages.umlp.chart_to_sc` and :mod:`languages.umlp.lr_to_java` write it;
:mod:`languages.umlp.literals` and :mod:`languages.umlp.refusal` serve both. This module
holds the two conversions, registered as ``sc-to-lr`` and ``lr-to-sc`` through the
``lightrocks.conversions`` entry point (:mod:`workbench.conversions`).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from lightrocks.languages.umlp.chart_to_lr import sc_to_lr
from lightrocks.languages.umlp.chart_to_sc import lr_to_sc
from lightrocks.languages.umlp.printer import print_sc
from lightrocks.workbench.conversions import Conversion, Converted
from lightrocks.workbench.diagnostics import Diagnostic, Severity


def _has_errors(findings: Sequence[Diagnostic]) -> bool:
    return any(f.severity is Severity.ERROR for f in findings)


def convert_sc_to_lr(path: Path, text: str, shown: str) -> Converted:
    """``A.sc`` to the text of ``<chart name>.lr`` (``None`` when refused)."""
    from lightrocks.languages.lightrocks.printer import print_statechart
    from lightrocks.languages.umlp.syntax import parse_sc

    unit = parse_sc(text, shown)
    name = unit.statechart.name or path.stem
    result, findings = sc_to_lr(unit, name)
    if _has_errors(findings):
        return Converted(f"{name}.lr", None, findings, result)
    return Converted(f"{name}.lr", print_statechart(result), findings, result)


def convert_lr_to_sc(path: Path, text: str, shown: str) -> Converted:
    """A plain ``A.lr`` to the text of ``A.sc`` (``None`` when refused)."""
    from lightrocks.languages.lightrocks.syntax import parse_statechart

    unit = parse_statechart(text, shown)
    result, findings = lr_to_sc(unit)
    name = f"{unit.statechart.name or path.stem}.sc"
    if _has_errors(findings):
        return Converted(name, None, findings, result)
    return Converted(name, print_sc(result), findings, result)


SC_TO_LR = Conversion(".sc", "lr", "UML/P statecharts (MontiCore) to LightRocks", convert_sc_to_lr)
LR_TO_SC = Conversion(".lr", "sc", "plain LightRocks statecharts to UML/P", convert_lr_to_sc)
