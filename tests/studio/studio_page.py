"""The studio's page in headless chromium, for the tests of its edits and of a composition:
``lightrocks studio`` launched on a folder of models, and the page as a user sees it."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from monitor.browser_page import WAIT

WAIT = float(os.environ.get("STUDIO_WAIT", WAIT))
AHEAD = "din_rail_ahead.tasks.AssembleRailAhead"


def launched(models: Path, tmp_path: Path, cache: Path):
    """``lightrocks studio`` on ``models`` until the generator is closed: (url, models)."""
    err = tmp_path / "stderr.txt"
    env = {**os.environ, "XDG_CACHE_HOME": str(cache)}
    command = [sys.executable, "-m", "lightrocks.app.cli", "studio", str(models)]
    with err.open("w") as stderr:
        process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=stderr)
    url = ""
    while not url and process.poll() is None:
        time.sleep(0.1)
        lines = err.read_text().splitlines()
        url = next((s.removeprefix("studio: ") for s in lines if s.startswith("studio: ")), "")
    assert url, f"the studio printed no URL: {err.read_text()}"
    yield url, models
    process.kill()
    process.wait()


class Studio:
    """The studio's page as a user sees it."""

    def __init__(self, browser, url: str, models: Path) -> None:
        from selenium.common.exceptions import StaleElementReferenceException
        from selenium.webdriver.support.ui import WebDriverWait

        self.browser = browser
        self.models = models
        self.wait = WebDriverWait(
            browser, WAIT, ignored_exceptions=[StaleElementReferenceException]
        )
        browser.get(f"{url}&chart={AHEAD}")
        self.until(lambda: self.element("AssembleRailAhead/PlugTerminal3") is not None)

    def until(self, condition) -> None:
        self.wait.until(lambda _: condition())

    def element(self, path: str):
        for g in self.browser.find_elements("css selector", "#diagram [data-path]"):
            if g.get_attribute("data-path") == path:
                return g
        return None

    def click(self, path: str, kind: str = "click") -> None:
        self.until(lambda: self.element(path) is not None)
        self.browser.execute_script(
            "arguments[0].dispatchEvent(new MouseEvent(arguments[1], {bubbles: true}))",
            self.element(path),
            kind,
        )

    def press(self, button: str) -> None:
        self.browser.find_element("id", button).click()

    def text(self, id: str) -> str:
        return self.browser.find_element("id", id).text

    def file(self, chart: str = AHEAD) -> str:
        return self.models.joinpath(*chart.split(".")).with_suffix(".lr").read_text()

    def screenshot(self, path: Path) -> None:
        self.browser.save_screenshot(str(path))
        artifacts = os.environ.get("STUDIO_ARTIFACTS")
        if artifacts:
            Path(artifacts).mkdir(parents=True, exist_ok=True)
            shutil.copy(path, Path(artifacts) / path.name)
