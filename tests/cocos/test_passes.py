"""The pass kernel: a pass is computed once per check run and shared by whoever asks for it;
its findings are reported under the codes it declares; CoCos and passes are collected from
the modules they are written in, and every one a language's package writes is registered."""

from __future__ import annotations

import importlib
import pkgutil
import sys
from collections.abc import Iterator
from importlib.metadata import entry_points
from pathlib import Path
from types import ModuleType

import pytest

import lightrocks.workbench.check as checking
from cocos.models import BASE, materialize
from lightrocks.languages.lightrocks.analysis import Analysis, analysis
from lightrocks.languages.lightrocks.cocos_typing import TypingPass
from lightrocks.workbench.check import all_cocos, check, load, run_checks
from lightrocks.workbench.cocos import CoCo, Code, coco, cocos_in
from lightrocks.workbench.diagnostics import Severity
from lightrocks.workbench.languages import Language, languages
from lightrocks.workbench.passes import Finding, Pass, passes_in


class Counted(Pass):
    """Counts how often it is built: once per check run, however many ask."""

    built = 0
    codes = (
        Code("LR9101", Severity.WARNING, "a statechart is named"),
        Code("LR9102", Severity.ERROR, "a statechart is named twice"),
    )

    def __init__(self, context: checking.CheckContext) -> None:
        super().__init__(context)
        Counted.built += 1
        self.names = [c.name for c in analysis(context).models.components]

    def findings(self) -> Iterator[Finding]:
        for component in analysis(self.context).models.components:
            yield "LR9101", component.statechart.position, f"'{component.name}'", "a hint"


@coco("LR9103", Severity.WARNING, "asks the counted pass")
def asks_the_pass(context: checking.CheckContext) -> Iterator[tuple]:
    assert context.result(Counted).names
    return iter(())


@coco("LR9104", Severity.WARNING, "asks the counted pass too")
def asks_it_again(context: checking.CheckContext) -> Iterator[tuple]:
    assert context.result(Counted) is context.result(Counted)
    return iter(())


class Undeclared(Pass):
    codes = (Code("LR9105", Severity.ERROR, "declares one code"),)

    def findings(self) -> Iterator[Finding]:
        yield "LR9106", analysis(self.context).models.components[0].statechart.position, "", ""


def _no_files(*_: object) -> object:
    raise NotImplementedError("this language reads no files")


def _language(*passes: type[Pass], cocos: tuple[CoCo, ...] = ()) -> Language:
    return Language(
        name="counted",
        extensions=(),
        parse=_no_files,
        format=_no_files,
        declarations=lambda unit: (),
        cocos=cocos,
        passes=passes,
    )


@pytest.fixture
def models(tmp_path: Path) -> Path:
    materialize(tmp_path, BASE)
    return tmp_path


def test_a_pass_is_computed_once_per_check_run(
    models: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    counted = _language(Counted, cocos=(asks_the_pass, asks_it_again))
    monkeypatch.setattr(checking, "languages", lambda: (*languages(), counted))
    monkeypatch.setattr(Counted, "built", 0)
    first = load([models])
    run_checks(first)
    assert Counted.built == 1
    second = load([models])
    run_checks(second)
    assert Counted.built == 2
    assert second.result(Counted) is not first.result(Counted)


def test_pass_findings_are_reported_under_its_codes(
    models: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(checking, "languages", lambda: (*languages(), _language(Counted)))
    listed = {c.code: (c.severity, c.summary) for c in checking.all_cocos()}
    assert listed["LR9101"] == (Severity.WARNING, "a statechart is named")
    assert listed["LR9102"] == (Severity.ERROR, "a statechart is named twice")
    context = check([models])
    findings = [d for d in context.diagnostics.items if d.code.startswith("LR91")]
    assert {(d.code, d.severity, d.hint) for d in findings} == {
        ("LR9101", Severity.WARNING, "a hint")
    }
    assert sorted(d.message for d in findings) == sorted(
        f"'{name}'" for name in context.result(Counted).names
    )


def test_a_pass_reporting_an_undeclared_code_is_a_bug_named(
    models: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(checking, "languages", lambda: (*languages(), _language(Undeclared)))
    with pytest.raises(ValueError, match="Undeclared reports LR9106, which it does not declare"):
        run_checks(load([models]))


def test_analyses_are_asked_by_their_class(models: Path) -> None:
    context = check([models])
    assert context.result(Analysis) is analysis(context)
    assert isinstance(context.result(TypingPass), TypingPass)


def test_collected_from_the_modules_they_are_written_in() -> None:
    here = sys.modules[__name__]
    elsewhere = ModuleType("elsewhere")
    elsewhere.borrowed = asks_the_pass  # imported, not written there
    elsewhere.Borrowed = Counted
    assert cocos_in(here) == (asks_the_pass, asks_it_again)
    assert cocos_in(elsewhere) == ()
    assert passes_in(here) == (Counted, Undeclared)  # Pass itself declares no codes
    assert passes_in(elsewhere) == ()


def _registered_modules() -> Iterator[ModuleType]:
    """The module of every registered language and extension, and every module below it."""
    for group in ("lightrocks.languages", "lightrocks.language_extensions"):
        for entry in entry_points(group=group):
            module = importlib.import_module(entry.module)
            yield module
            found = pkgutil.walk_packages(getattr(module, "__path__", []), module.__name__ + ".")
            yield from (importlib.import_module(info.name) for info in found)


def test_every_coco_and_pass_a_language_writes_is_registered() -> None:
    """No CoCo or pass is left out because its module is not among those collected."""
    registered = set(all_cocos())
    for module in _registered_modules():
        for written in (*cocos_in(module), *passes_in(module)):
            codes = (written,) if isinstance(written, CoCo) else written.codes
            assert set(codes) <= registered, f"{module.__name__}: {written} is not registered"
