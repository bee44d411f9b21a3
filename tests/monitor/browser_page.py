"""The monitor's page in headless chromium, for the tests of the monitor, the studio and the
diagram: the ``launch`` and ``browser`` fixtures, the page as a user sees it, a trace's records.

chromium and chromedriver are found on PATH or through $CHROMIUM and $CHROMEDRIVER
(Debian: ``apt-get install chromium chromium-driver``)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest
from judges import missing

CHROMIUM = os.environ.get("CHROMIUM", shutil.which("chromium") or "")
CHROMEDRIVER = os.environ.get("CHROMEDRIVER", shutil.which("chromedriver") or "")
WAIT = 300.0
"""Seconds a page may take to show what is expected (a limit, not a measurement)."""


@pytest.fixture
def launch(tmp_path: Path, tmp_path_factory):
    """Start ``lightrocks`` with a monitor on a free port: (url, trace, process)."""
    processes: list[subprocess.Popen] = []
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path_factory.getbasetemp() / "cache")}

    def start(*arguments: str) -> tuple[str, Path, subprocess.Popen]:
        trace = tmp_path / f"run{len(processes)}.jsonl"
        err = tmp_path / f"stderr{len(processes)}.txt"
        command = [sys.executable, "-m", "lightrocks.app.cli", *arguments]
        command += ["--monitor", "0"]
        if arguments[0] == "run":
            command += ["--trace", str(trace)]
        with err.open("w") as stderr:
            process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=stderr)
        processes.append(process)
        url = ""
        while not url and process.poll() is None:
            time.sleep(0.1)
            lines = err.read_text().splitlines()
            url = next(
                (s.removeprefix("monitor: ") for s in lines if s.startswith("monitor: ")), ""
            )
        assert url, f"the monitor printed no URL: {err.read_text()}"
        return url, trace, process

    yield start
    for process in processes:
        process.kill()
        process.wait()


@pytest.fixture
def browser():
    if not (CHROMIUM and CHROMEDRIVER):
        missing(
            "chromium and chromedriver", "`make judges` (apt-get install chromium chromium-driver)"
        )
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,1000"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})  # CSP reports land here
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    yield driver
    driver.quit()


class Page:
    """The monitor page as a user sees it."""

    def __init__(self, browser, url: str) -> None:
        from selenium.webdriver.support.ui import WebDriverWait

        self.browser = browser
        self.wait = WebDriverWait(browser, WAIT)
        browser.get(url)
        self.until(lambda: self.browser.find_elements("css selector", "#task g.node"))

    def until(self, condition) -> None:
        self.wait.until(lambda _: condition())

    def text(self, id: str) -> str:
        return self.browser.find_element("id", id).text

    @property
    def active(self) -> str:
        return self.browser.find_element("id", "task").get_attribute("data-active")

    def press(self, button: str) -> None:
        self.browser.find_element("id", button).click()

    def element(self, path: str):
        """What shows the state ``path`` on the level in view: its box, or the level's frame."""
        return next(
            g
            for g in self.browser.find_elements("css selector", "#task [data-path]")
            if g.get_attribute("data-path") == path
        )

    def click(self, element, kind: str = "click") -> None:
        """A click on an SVG group (Selenium's own click needs a visible rectangle); a
        ``contextmenu`` click toggles a breakpoint."""
        self.browser.execute_script(
            "arguments[0].dispatchEvent(new MouseEvent(arguments[1], {bubbles: true}))",
            element,
            kind,
        )

    def screenshot(self, path: Path) -> Path:
        self.browser.save_screenshot(str(path))
        artifacts = os.environ.get("MONITOR_ARTIFACTS")
        if artifacts:
            Path(artifacts).mkdir(parents=True, exist_ok=True)
            shutil.copy(path, Path(artifacts) / path.name)
        return path


def records(trace: Path) -> list[dict]:
    return [json.loads(line) for line in trace.read_text().splitlines()]
