"""An application written from the documentation alone, unlike the shipped examples: a
compliant arm polishing a curved panel (a spindle spun up beside the approach in two
regions, force-controlled strokes counted per pass, a gloss inspection and a bounded redo
through a choice). It checks and verifies clean, strict, and the model checker sees its
retry loop: without the count of passes the redo is an endless retry."""

from __future__ import annotations

from pathlib import Path

from lightrocks.languages.lightrocks.behaviour.verify import verify
from lightrocks.workbench.check import check

APPLICATION = Path(__file__).with_name("applications") / "panel_polishing"
TASK = APPLICATION / "polish" / "tasks" / "PolishPanel.lr"
COUNTED = "Again -> Work [panel.passes < retries] / { panel.passes = panel.passes + 1; };"


def test_the_application_checks_clean() -> None:
    assert [str(d) for d in check([APPLICATION]).diagnostics.items] == []


def test_the_application_verifies_clean_strict() -> None:
    result = verify([APPLICATION], strict=True)
    assert [str(d) for d in result.diagnostics] == []
    assert not result.failed


def test_the_redo_without_its_count_is_an_endless_retry() -> None:
    text = TASK.read_text(encoding="utf-8")
    assert COUNTED in text
    uncounted = text.replace(COUNTED, "Again -> Work [panel.passes < retries];")
    result = verify([APPLICATION], strict=True, substituted={TASK.resolve(): uncounted})
    assert "LR0703" in {d.code for d in result.diagnostics}
    assert result.failed
