"""The acceptance of the studio's composition: the top-hat rail task (three terminals with
their error paths) composed in headless chromium from an empty task file by drag and drop
and forms only; it checks clean, is formatted, and its dry run with the shipped outcome
script ends as the shipped model's does; two steps reordered in the studio change the run.

Its screenshot is docs/studio.md's (set $STUDIO_ARTIFACTS to keep it).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from studio.charts import composed_part
from studio.studio_page import Studio, launched

pytest.importorskip("starlette", reason="the studio needs the 'monitor' extra")
pytest.importorskip("selenium", reason="the browser tests need selenium (the 'dev' extra)")

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = ROOT / "examples" / "din_rail" / "tasks" / "AssembleRail.lr"
SCRIPT = ROOT / "examples" / "din_rail" / "assembled.dryrun.json"
CHART = "din_rail.tasks.AssembleRail"


@pytest.fixture
def bare(tmp_path: Path, tmp_path_factory):
    """``lightrocks studio`` on a copy of the examples without the top-hat rail task."""
    models = shutil.copytree(ROOT / "examples", tmp_path / "examples")
    models.joinpath("din_rail", "tasks", "AssembleRail.lr").unlink()
    yield from launched(models, tmp_path, tmp_path_factory.getbasetemp() / "cache")


def lightrocks(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "lightrocks.app.cli", *args]
    return subprocess.run(command, capture_output=True, text=True, cwd=cwd, timeout=600)


def dry_run(model: Path, trace: Path) -> tuple[str, list[str]]:
    """The outcome line of the dry run with the shipped script, and the states entered."""
    done = lightrocks("run", str(model), "--adapter", "dryrun", "--script", str(SCRIPT),
                      "--trace", str(trace))  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    outcome = next(line for line in done.stdout.splitlines() if line.startswith("outcome:"))
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    return outcome, [r["state"] for r in records if r["kind"] == "enter"]


class Composer(Studio):
    """The studio's page, used by drag and drop and forms only."""

    def __init__(self, browser, url: str, models: Path) -> None:
        from selenium.common.exceptions import StaleElementReferenceException
        from selenium.webdriver.support.ui import WebDriverWait

        from studio.studio_page import WAIT

        self.browser = browser
        self.models = models
        self.wait = WebDriverWait(
            browser, WAIT, ignored_exceptions=[StaleElementReferenceException]
        )
        browser.get(url)
        self.until(lambda: browser.find_elements("css selector", "#diagram [data-path]"))

    def find(self, css: str):
        return self.browser.find_element("css selector", css)

    def type(self, element, text: str) -> None:
        element.clear()
        element.send_keys(text)

    def done(self, message: str) -> None:
        """Wait for the page to say ``message`` (a refusal's reason shows when it does not)."""
        from selenium.common.exceptions import TimeoutException

        try:
            self.until(lambda: self.text("message") == message)
        except TimeoutException:
            assert self.text("message") == message

    def drag(self, chip, target) -> None:
        from selenium.webdriver.common.action_chains import ActionChains

        ActionChains(self.browser).click_and_hold(chip).move_to_element(target).release().perform()

    def outcome(self, source: str, outcome: str, target: str) -> None:
        """Select ``source``, drag its outcome chip onto ``target``."""
        self.click(f"AssembleRail/{source}")
        label = outcome or "→ (no stimulus)"
        self.until(lambda: any(c.text == label for c in self.chips()))
        chip = next(c for c in self.chips() if c.text == label)
        self.drag(chip, self.element(f"AssembleRail/{target}"))
        self.done(f"added {source} -> {target}{' ' + outcome if outcome else ''}")

    def chips(self):
        return self.browser.find_elements("css selector", "#outcome-chips .chip")

    def checked(self, id: str, expected: str) -> None:
        """Wait for the live check of a form to say ``expected``."""
        self.until(lambda: expected in self.text(id))


@pytest.mark.slow
def test_the_top_hat_rail_task_is_composed_by_drag_and_drop_and_forms(
    bare, browser, tmp_path: Path
) -> None:
    from selenium.webdriver.support.ui import Select

    url, models = bare
    page = Composer(browser, url, models)
    page.press("new-toggle")
    page.until(lambda: page.find("#new-cell option[value='din_rail.cell.RailCell']"))
    page.type(page.find("#new-package"), "din_rail.tasks")
    page.type(page.find("#new-name"), "AssembleRail")
    Select(page.find("#new-layer")).select_by_value("task")
    Select(page.find("#new-cell")).select_by_value("din_rail.cell.RailCell")
    page.press("create")
    page.done(f"created {CHART}")
    composed = models / "din_rail" / "tasks" / "AssembleRail.lr"
    assert composed.read_text().endswith("<<task>> statechart AssembleRail { }\n")

    # parameters, the default's unit checked live by the language's typing
    for _ in range(2):
        page.press("add-parameter")
    rows = page.browser.find_elements("css selector", "#parameters tbody tr")
    given = [("Length", "across", "0 N"), ("Length", "clearance", "10 mm")]
    for row, values in zip(rows, given, strict=True):
        for cell, value in zip(row.find_elements("css selector", "input"), values, strict=True):
            page.type(cell, value)
    page.checked("parameters-check", "error LR0")
    assert "Length" in page.text("parameters-check")
    page.type(rows[0].find_elements("css selector", "input")[2], "0 mm")
    page.checked("parameters-check", "checks: nothing new")
    page.press("apply-parameters")
    page.done("set the parameters")

    for kind, name in (("start", "go"), ("end", "assembled"), ("end", "failed")):
        Select(page.find("#condition-kind")).select_by_value(kind)
        page.type(page.find("#condition-name"), name)
        page.press("add-condition")
        page.done(f"added {kind} condition {name}")

    # three terminals from the palette, their arguments in the state's form
    for number in (1, 2, 3):
        chip = page.find("#palette-list li[data-chart='din_rail.tasks.PlugTerminal']")
        page.drag(chip, page.find("#diagram svg"))
        page.done(f"added PlugTerminal{number}")
    slots = {1: "-70 mm", 2: "0 mm", 3: "70 mm"}
    for number, slot in slots.items():
        page.click(f"AssembleRail/PlugTerminal{number}")
        page.until(lambda: page.find("#arguments input[data-parameter='terminal']").is_displayed())
        given = {"terminal": f"terminal{number}", "slot": "70 N" if number == 3 else slot,
                 "across": "across", "clearance": "clearance"}  # fmt: skip
        for parameter, value in given.items():
            page.type(page.find(f"#arguments input[data-parameter='{parameter}']"), value)
        if number == 3:  # a wrong unit, said while typing; then the right one
            page.checked("arguments-check", "argument 'slot': expected Length")
            page.type(page.find("#arguments input[data-parameter='slot']"), slot)
        page.checked("arguments-check", "checks: nothing new")
        page.press("apply-arguments")
        page.done(f"set the arguments of PlugTerminal{number}")

    # transitions: from an outcome of the selected box onto its target
    page.outcome("go", "", "PlugTerminal1")
    page.outcome("PlugTerminal1", "plugged", "PlugTerminal2")
    page.outcome("PlugTerminal2", "plugged", "PlugTerminal3")
    # a box dragged onto its target, the outcome picked from the menu
    page.drag(page.element("AssembleRail/PlugTerminal3"), page.element("AssembleRail/assembled"))
    page.until(lambda: page.find("#outcome-menu").is_displayed())
    page.find("#outcome-menu li[data-outcome='plugged']").click()
    page.done("added PlugTerminal3 -> assembled plugged")
    for number in (1, 2, 3):
        page.outcome(f"PlugTerminal{number}", "failed", "failed")
    page.until(lambda: page.text("findings") == "none")
    page.screenshot(tmp_path / "studio-composed.png")

    # what the shipped task says, in its canonical text
    text = composed.read_text()
    assert composed_part(text) == composed_part(SHIPPED.read_text())
    assert lightrocks("check", str(models)).returncode == 0
    assert lightrocks("fmt", "--check", str(composed)).returncode == 0
    shipped_run = dry_run(SHIPPED, tmp_path / "shipped.jsonl")
    composed_run = dry_run(composed, tmp_path / "composed.jsonl")
    assert composed_run == shipped_run
    assert shipped_run[0].startswith("outcome: assembled after")

    # two steps reordered: the third terminal goes before the second
    page.click("AssembleRail/PlugTerminal3")
    page.press("earlier")
    page.done("moved PlugTerminal3 earlier")
    assert lightrocks("fmt", "--check", str(composed)).returncode == 0
    outcome, entered = dry_run(composed, tmp_path / "reordered.jsonl")
    assert outcome == shipped_run[0]  # the script plugs any terminal
    plugged = [s for s in entered if s.count("/") == 1]
    assert plugged == [f"AssembleRail/PlugTerminal{n}" for n in (1, 3, 2)]
    assert [s for s in shipped_run[1] if s.count("/") == 1] == [
        f"AssembleRail/PlugTerminal{n}" for n in (1, 2, 3)
    ]
