"""IEC 61131-3 textual SFC: one compilation unit (``<Top>.st``) per selected task or skill."""

from __future__ import annotations

import itertools
from collections import Counter
from pathlib import Path

import jinja2

from lightrocks.generators.outputs import chart_stems, distinct
from lightrocks.generators.selection import is_action, selected
from lightrocks.generators.sfc_iec61131.checker import check_sfc
from lightrocks.generators.sfc_iec61131.expressions import time_literal
from lightrocks.generators.sfc_iec61131.extensions import Extensions
from lightrocks.generators.sfc_iec61131.frames import FRAME_FIELDS, FUNCTIONS
from lightrocks.generators.sfc_iec61131.ir import Unit
from lightrocks.generators.sfc_iec61131.unit import UnitBuilder
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.model import Component
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.workbench.extensions import language_extensions
from lightrocks.workbench.generators import (
    GenerationError,
    GenerationRequest,
    template_environment,
    whole_number,
)

TEMPLATES = Path(__file__).parent / "templates"

INTERVAL = whole_number("interval_ms", 1, "the task cycle in milliseconds", minimum=1)


def prioritize(unit: Unit) -> None:
    """Number the branches of every selective divergence (MatIEC would run them all), in
    declaration order across the block: MatIEC tests the transitions of a network sorted by
    priority and clears a step's flag as soon as one of its transitions fires, so growing
    numbers keep the tests in declaration order, which the watch of orthogonal regions needs."""
    for block in unit.blocks:
        counts = Counter(t.source for t in block.transitions)
        numbers = itertools.count(1)
        for transition in block.transitions:
            if counts[transition.source] > 1:
                transition.priority = next(numbers)


def build_unit(top: Component, typing: Typing, extensions: Extensions | None = None) -> Unit:
    """The blocks of ``top``'s compilation unit, with their transitions prioritized; syntax
    of language extensions through ``extensions`` (without: refused)."""
    unit = UnitBuilder(top, typing, extensions).build()
    prioritize(unit)
    return unit


def environment_of(request: GenerationRequest) -> jinja2.Environment:
    """The SFC templates: the user's first, then the built-in ones, then those of language
    extensions (``sfc/<Node>.jinja``, shared with the PLCopen target)."""
    folders = [e.templates for e in language_extensions() if e.templates is not None]
    return template_environment(TEMPLATES, request.templates, folders)


def checked_text(environment: jinja2.Environment, unit: Unit, interval: str) -> str:
    """The unit as SFC text, which must pass the checker (a template can write anything)."""
    text = environment.get_template("unit.st.jinja").render(
        unit=unit,
        interval=interval,
        frames=FUNCTIONS,
        frame_fields=FRAME_FIELDS,
    )
    problems = check_sfc(text)
    if problems:
        listing = "\n".join(f"  {p}" for p in problems)
        raise GenerationError(f"generated SFC of {unit.top.name} fails the check:\n{listing}")
    return text


def interval_option(request: GenerationRequest) -> str:
    """The task cycle (option ``interval_ms``) as a TIME literal."""
    return time_literal(request.value(INTERVAL) / 1000)


def unit_files(request: GenerationRequest, suffix: str) -> dict[str, Component]:
    """The selected tasks and skills by the file of their unit: ``<Name><suffix>``, or
    ``<package.Name><suffix>`` where another one's name folds alike (generators.outputs)."""
    tops = [top for top in selected(request) if not is_action(top)]
    if not tops:
        raise GenerationError("no task or skill among the selected models")
    stems = chart_stems(tops)
    files = {f"{stems[top.qualified_name]}{suffix}": top for top in tops}
    distinct(files)
    return files


class SfcGenerator:
    name = "sfc"
    description = "IEC 61131-3 textual SFC for PLCs"
    options = (INTERVAL,)

    def generate(self, request: GenerationRequest) -> dict[str, str]:
        environment = environment_of(request)
        extensions = Extensions(environment)
        interval = interval_option(request)
        typing = analysis(request.context).typing
        files: dict[str, str] = {}
        for name, top in unit_files(request, ".st").items():
            files[name] = checked_text(environment, build_unit(top, typing, extensions), interval)
        return files


GENERATOR = SfcGenerator()
