"""``run --monitor`` and ``replay`` of the task whose skill loops two levels down: the page
gets one picture per level, follows the run into the level of the active state, and lets the
user open boxes and go back along the breadcrumbs."""

from __future__ import annotations

import re
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest
from monitor.browser_page import WAIT, Page, records

from diagram.models import EXAMPLES

pytest.importorskip("starlette", reason="the monitor needs the 'monitor' extra")

AHEAD = EXAMPLES / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"
SNAP = "AssembleRailAhead/PlugTerminal1/PressOn/Arm/Snap"


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A dry run of the task with the monitor on and no page: it runs to its end."""
    trace = tmp_path_factory.mktemp("ahead") / "ahead.jsonl"
    command = [sys.executable, "-m", "lightrocks.app.cli", "run", str(AHEAD)]
    command += ["--adapter", "dryrun", "--monitor", "0", "--trace", str(trace)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=WAIT)
    assert result.returncode == 1, result.stderr  # the dry run's outcome is 'failed'
    assert result.stderr.startswith("monitor: http://127.0.0.1:"), result.stderr
    assert "outcome: failed" in result.stdout
    return trace


class LevelPage(Page):
    @property
    def level(self) -> str:
        """The key of the level in view."""
        return self.browser.find_element("css selector", "#task svg").get_attribute("data-key")


def test_the_replay_serves_one_picture_per_level(recorded: Path, launch) -> None:
    url, _, _ = launch("replay", str(recorded))
    base, _, token = url.partition("?token=")
    asked = urllib.request.Request(base + "task.svg", headers={"Authorization": f"Bearer {token}"})
    with urllib.request.urlopen(asked, timeout=60) as answer:
        bundle = answer.read().decode()
    assert '"root": "din_rail_ahead.tasks.AssembleRailAhead"' in bundle
    keys = re.findall(r'"key": "([^"]+)"', bundle)
    assert len(keys) == bundle.count('<svg class="level"') == 22
    assert {"din_rail.skills.SnapOnRail", "din_rail_ahead.tasks.PlugTerminalAhead/PressOn"} <= set(
        keys
    )


def test_the_page_follows_the_run_and_drills_down(
    recorded: Path, launch, browser, tmp_path: Path
) -> None:
    run = records(recorded)
    url, _, _ = launch("replay", str(recorded))
    page = LevelPage(browser, url)
    page.until(lambda: page.text("summary") == "outcome: failed")
    down = next(r["time"] for r in run if r.get("state") == f"{SNAP}/Down")
    slider = browser.find_element("id", "slider")
    browser.execute_script(
        "arguments[0].value = arguments[1];arguments[0].dispatchEvent(new Event('input'))",
        slider,
        down,
    )
    # both regions are active: the view follows to the level that shows them both
    page.until(lambda: page.level == "din_rail_ahead.tasks.PlugTerminalAhead/PressOn")
    assert page.text("crumbs").startswith("AssembleRailAhead › PlugTerminal1 › PressOn")
    for state in (SNAP, "AssembleRailAhead/PlugTerminal1/PressOn/Camera/LookAhead"):
        assert "current" in page.element(state).get_attribute("class")
    page.screenshot(tmp_path / "follow.png")

    page.click(page.element(SNAP))
    page.until(lambda: page.level == "din_rail.skills.SnapOnRail")
    assert not browser.find_element("id", "follow").is_selected()
    assert "current" in page.element(f"{SNAP}/Down").get_attribute("class")
    page.click(crumb(browser, "PlugTerminal1"))
    page.until(lambda: page.level == "din_rail_ahead.tasks.PlugTerminalAhead")
    press_on = page.element("AssembleRailAhead/PlugTerminal1/PressOn")
    assert {"active", "current"} <= set(press_on.get_attribute("class").split())
    browser.find_element("id", "follow").click()
    page.until(lambda: page.level == "din_rail_ahead.tasks.PlugTerminalAhead/PressOn")


def crumb(browser, name: str):
    deadline = time.monotonic() + WAIT
    while time.monotonic() < deadline:
        for link in browser.find_elements("css selector", "#crumbs a"):
            if link.text == name:
                return link
        time.sleep(0.1)
    raise AssertionError(f"no breadcrumb {name}")
