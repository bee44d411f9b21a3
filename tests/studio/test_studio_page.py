"""``lightrocks studio`` in headless chromium: a task's diagram edited by clicks (a state moved
along the chain, a state added from the palette, a transition, a deletion), the findings of
check shown on the diagram, a file changed on disk reloaded; and what the server refuses.

The screenshots of docs/studio.md are taken here: set $STUDIO_ARTIFACTS to a folder to keep
them.
"""

from __future__ import annotations

import json
import os
import shutil
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from studio.studio_page import AHEAD, Studio, launched

pytest.importorskip("starlette", reason="the studio needs the 'monitor' extra")
pytest.importorskip("selenium", reason="the browser tests need selenium (the 'dev' extra)")

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def studio(tmp_path: Path, tmp_path_factory):
    """``lightrocks studio`` on a copy of the examples: (url, the copy's folder)."""
    models = shutil.copytree(ROOT / "examples", tmp_path / "examples")
    yield from launched(models, tmp_path, tmp_path_factory.getbasetemp() / "cache")


def test_a_task_is_edited_on_its_diagram(studio, browser, tmp_path: Path) -> None:
    from selenium.webdriver.support.ui import Select

    page = Studio(browser, *studio)
    assert "token" not in browser.current_url  # a strict cookie carries it from here on
    page.screenshot(tmp_path / "studio.png")

    page.click("AssembleRailAhead/PlugTerminal3")
    page.press("earlier")
    page.until(lambda: page.text("message") == "moved PlugTerminal3 earlier")
    assert "PlugTerminal1 -> PlugTerminal3 plugged;" in page.file()
    assert "PlugTerminal3 -> PlugTerminal2 plugged;\n  PlugTerminal2 -> assembled" in page.file()

    Select(browser.find_element("id", "palette")).select_by_value("din_rail.skills.Retreat")
    browser.find_element("id", "name").clear()
    browser.find_element("id", "name").send_keys("Away")
    page.press("add-state")
    page.until(lambda: page.text("message") == "added Away")
    assert '<<import="Retreat">> state Away;' in page.file()
    assert "import din_rail.skills.Retreat;" in page.file()

    page.click("AssembleRailAhead/Away")
    page.click("AssembleRailAhead/failed")
    page.until(lambda: page.text("ends") == "from Away to failed")
    browser.find_element("id", "stimulus").send_keys("retreated")
    page.press("add-transition")
    page.until(lambda: page.text("message") == "added Away -> failed retreated")
    assert "Away -> failed retreated;" in page.file()

    page.until(lambda: "LR0207" in page.text("findings"))  # nothing leads to Away
    away = page.element("AssembleRailAhead/Away")
    assert {"error", "warning"} & set(away.get_attribute("class").split())  # marked
    page.click("AssembleRailAhead/PlugTerminal1")  # select something else, then the finding
    next(
        item
        for item in browser.find_elements("css selector", "#findings li")
        if "LR0207" in item.text
    ).click()
    page.until(lambda: "selected" in page.element("AssembleRailAhead/Away").get_attribute("class"))
    page.screenshot(tmp_path / "studio-findings.png")

    page.press("delete")
    page.until(lambda: page.text("message") == "deleted Away")
    assert "Away" not in page.file()
    assert page.text("findings") == "none"

    page.click("AssembleRailAhead/PlugTerminal2", "dblclick")
    page.until(lambda: page.element("AssembleRailAhead/PlugTerminal2/PressOn") is not None)
    assert page.text("crumbs").startswith("AssembleRailAhead › PlugTerminal2")
    page.screenshot(tmp_path / "studio-drilled.png")


def test_the_studio_and_an_editor_change_the_chart_at_once_and_no_edit_is_lost(
    studio, browser
) -> None:
    """A form being typed in stays through a reload of a change on disk and is applied to
    the changed file; an edit made on a version the page never saw (a change on disk it was
    not told of) is refused and applied again on what is on disk."""
    page = Studio(browser, *studio)
    path = page.models / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"
    page.click("AssembleRailAhead/PlugTerminal2")
    slot = 'input[data-parameter="slot"]'
    page.until(lambda: browser.find_element("css selector", slot).is_displayed())
    browser.find_element("css selector", slot).clear()
    browser.find_element("css selector", slot).send_keys("5 mm")
    path.write_text(path.read_text().replace("  PlugTerminal3 -> failed failed;\n", ""))
    page.until(lambda: page.text("message").startswith("reloaded:"))
    page.until(
        lambda: page.element("AssembleRailAhead/PlugTerminal3->AssembleRailAhead/failed") is None
    )
    assert browser.find_element("css selector", slot).get_attribute("value") == "5 mm"
    page.press("apply-arguments")
    page.until(lambda: page.text("message") == "set the arguments of PlugTerminal2")
    text = page.file()
    assert "slot = 5 mm," in text and "PlugTerminal3 -> failed failed;" not in text

    # an editor's change the page is not told of: same size, same modification time
    status = path.stat()
    unseen = path.with_name(".unseen")
    unseen.write_text(text.replace("slot = 70 mm", "slot = 75 mm"))
    os.utime(unseen, ns=(status.st_atime_ns, status.st_mtime_ns))
    os.replace(unseen, path)  # at no moment does the file look changed
    page.click("AssembleRailAhead/PlugTerminal3")
    page.press("earlier")
    page.until(lambda: page.text("message").startswith("refused: AssembleRailAhead.lr changed"))
    assert "slot = 75 mm" in page.file() and "PlugTerminal1 -> PlugTerminal3" not in page.file()
    page.press("again")
    page.until(lambda: page.text("message") == "moved PlugTerminal3 earlier")
    assert "slot = 75 mm" in page.file() and "slot = 5 mm" in page.file()
    assert "PlugTerminal2 -> PlugTerminal3 plugged" not in page.file()
    assert "PlugTerminal1 -> PlugTerminal3 plugged" in page.file()

    page.press("undo")
    page.until(lambda: page.text("message") == "undone: move PlugTerminal3")
    assert "PlugTerminal2 -> PlugTerminal3 plugged" in page.file()
    assert "slot = 75 mm" in page.file()

    path.write_text(path.read_text()[:200])  # an editor leaves it half-written
    page.until(lambda: "din_rail_ahead.tasks.AssembleRailAhead is gone" in page.text("message"))
    assert AHEAD not in browser.find_element("id", "chart").text


def request(
    url: str, path: str, body: dict | None = None, chart: str = "", **headers: str
) -> tuple[int, str]:
    """A request of the page's kind to the studio at ``url`` (which carries the token)."""
    base, _, query = url.partition("?")
    query += f"&chart={chart}" if chart else ""
    data = json.dumps(body).encode() if body is not None else None
    call = urllib.request.Request(f"{base.rstrip('/')}/{path}?{query}", data, headers)
    try:
        with urllib.request.urlopen(call, timeout=60) as answer:
            return answer.status, answer.read().decode()
    except urllib.error.HTTPError as error:
        return error.code, error.read().decode()


def test_stale_edits_strangers_and_other_sites_are_refused(studio) -> None:
    url, models = studio
    path = models / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"
    status, state = request(url, "state", chart=AHEAD)
    assert status == 200
    old = json.loads(state)["version"]
    path.write_text(path.read_text().replace("  PlugTerminal3 -> failed failed;\n", ""))
    changed = path.read_text()
    move = {"chart": AHEAD, "version": old, "level": AHEAD, "op": "move"}
    status, answer = request(url, "edit", {**move, "state": "PlugTerminal3", "steps": -1})
    assert status == 409 and "changed on disk" in answer
    assert path.read_text() == changed

    base = url.split("?")[0]
    assert request(base + "?token=wrong", "charts")[0] == 403
    port = base.rstrip("/").rpartition(":")[2]
    assert request(url, "charts", Host=f"rebound.example:{port}")[0] == 403
    fresh = json.loads(request(url, "state", chart=AHEAD)[1])["version"]
    other = {**move, "version": fresh, "state": "PlugTerminal3", "steps": -1}
    assert request(url, "edit", other, Origin="http://rebound.example")[0] == 403
    assert path.read_text() == changed


def test_a_dry_run_is_started_stepped_and_watched_from_the_studio(
    studio, browser, tmp_path: Path
) -> None:
    """The run is the monitor's (its stream and controls below run/), on the studio's own
    diagram: paused at the start, stepped to the first terminal, which is highlighted,
    resumed to the shipped outcome; a second run is aborted."""
    from selenium.webdriver.support.ui import Select

    page = Studio(browser, *studio)
    Select(browser.find_element("id", "chart")).select_by_value("din_rail.tasks.AssembleRail")
    page.until(lambda: page.element("AssembleRail/PlugTerminal2") is not None)
    Select(browser.find_element("id", "run-adapter")).select_by_value("dryrun")
    script = "examples/din_rail/assembled.dryrun.json"
    page.until(lambda: browser.find_elements("css selector", f"#run-script [value='{script}']"))
    Select(browser.find_element("id", "run-script")).select_by_value(script)
    browser.find_element("id", "run-paused").click()
    page.press("run-start")
    page.until(lambda: page.text("run-status").startswith("paused"))
    page.press("run-step")
    page.until(lambda: "go->AssembleRail/PlugTerminal1" in page.text("run-status"))
    page.press("run-step")
    active = lambda: browser.find_element("id", "diagram").get_attribute("data-active")  # noqa: E731
    page.until(lambda: active() == "AssembleRail/PlugTerminal1")
    assert "current" in page.element("AssembleRail/PlugTerminal1").get_attribute("class")
    browser.find_element("id", "run-follow").click()  # stay on the task's level
    Select(browser.find_element("id", "chart")).select_by_value("din_rail.tasks.AssembleRail")
    page.until(lambda: page.element("AssembleRail/PlugTerminal2") is not None)
    page.click("AssembleRail/PlugTerminal2")
    page.press("run-break")
    page.until(
        lambda: "breakpoint" in page.element("AssembleRail/PlugTerminal2").get_attribute("class")
    )
    page.screenshot(tmp_path / "studio-run.png")
    page.press("run-resume")
    page.until(lambda: page.text("run-status") == "paused at AssembleRail/PlugTerminal2")
    page.until(
        lambda: "current" in page.element("AssembleRail/PlugTerminal2").get_attribute("class")
    )
    page.press("run-resume")
    page.until(lambda: page.text("run-status") == "outcome: assembled")
    assert "finished assembled" in page.text("run-log")
    assert browser.find_element("id", "run-monitor").get_attribute("href").endswith("/run/")

    page.press("run-start")  # paused again: the box stays ticked
    page.until(lambda: page.text("run-status").startswith("paused"))
    page.press("run-abort")
    page.until(lambda: page.text("run-status") == "outcome: preempted")
    assert "aborted" in page.text("run-log")


@pytest.mark.slow
def test_a_simulation_started_from_the_studio_shows_the_cell_live(
    studio, browser, tmp_path: Path
) -> None:
    """MuJoCo from the page: frames of the simulated cell (its offscreen renderer, as
    ``--video`` draws them) shown beside the diagram while it runs; aborted safely."""
    from selenium.webdriver.support.ui import Select

    page = Studio(browser, *studio)
    Select(browser.find_element("id", "chart")).select_by_value("din_rail.tasks.AssembleRail")
    page.until(lambda: page.element("AssembleRail/PlugTerminal2") is not None)
    page.until(lambda: browser.find_elements("css selector", "#run-adapter [value='mujoco']"))
    Select(browser.find_element("id", "run-adapter")).select_by_value("mujoco")
    page.press("run-start")
    shown = "return document.getElementById('run-view').dataset.frame ?? null"  # the newest
    frame = lambda: browser.execute_script(shown)  # noqa: E731
    page.until(lambda: frame() is not None)
    first = frame()
    width = "return document.getElementById('run-view').naturalWidth"
    assert browser.execute_script(width) == 480
    page.until(lambda: frame() != first)  # the next frame came
    active = lambda: browser.find_element("id", "diagram").get_attribute("data-active")  # noqa: E731
    page.until(lambda: active().startswith("AssembleRail/PlugTerminal1/"))  # followed down
    page.until(lambda: page.browser.find_elements("css selector", "#diagram g.current"))
    page.screenshot(tmp_path / "studio-simulation.png")
    page.press("run-abort")
    page.until(lambda: page.text("run-status") == "outcome: preempted")
