"""The live monitor in headless chromium: the highlighted state follows the run; pause,
step, a breakpoint and resume act on the run; requests without the token are refused."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

pytest.importorskip("starlette", reason="the monitor needs the 'monitor' extra")
pytest.importorskip("selenium", reason="the browser tests need selenium (the 'dev' extra)")

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"
CHROMIUM = os.environ.get("CHROMIUM", shutil.which("chromium") or "")
CHROMEDRIVER = os.environ.get("CHROMEDRIVER", shutil.which("chromedriver") or "")
WAIT = 120.0
"""Seconds a page may take to show what is expected (a limit, not a measurement)."""


@pytest.fixture
def monitored(tmp_path: Path, tmp_path_factory):
    """A paused run of the screwing task under the monitor: (url, trace, process)."""
    trace = tmp_path / "run.jsonl"
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path_factory.getbasetemp() / "cache")}
    command = [sys.executable, "-m", "lightrocks.workbench.app.cli", "run", str(SCREW_TASK)]
    command += ["--adapter", os.environ.get("MONITOR_ADAPTER", "dryrun"), "--trace", str(trace)]
    command += ["--monitor", "0", "--paused"]
    err = tmp_path / "stderr.txt"
    with err.open("w") as stderr:
        process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=stderr)
    url = ""
    while not url and process.poll() is None:
        time.sleep(0.1)
        lines = err.read_text().splitlines()
        url = next((s.removeprefix("monitor: ") for s in lines if s.startswith("monitor: ")), "")
    assert url, f"the monitor printed no URL: {err.read_text()}"
    yield url, trace, process
    process.kill()
    process.wait()


@pytest.fixture
def browser():
    if not (CHROMIUM and CHROMEDRIVER):
        pytest.skip("chromium and chromedriver are needed (apt-get install chromium-driver)")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,1000"):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    yield driver
    driver.quit()


def test_requests_without_the_token_are_refused(monitored) -> None:
    url, _, _ = monitored
    base = url.split("?")[0]
    for path in ("", "task.svg", "control/resume"):
        method = "POST" if path.startswith("control") else "GET"
        request = urllib.request.Request(base + path, method=method)
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(request, timeout=30)
        assert refused.value.code == 403
    wrong = urllib.request.Request(f"{base}control/resume?token=wrong", method="POST")
    with pytest.raises(urllib.error.HTTPError):
        urllib.request.urlopen(wrong, timeout=30)


def test_pause_step_breakpoint_resume(monitored, browser, tmp_path: Path) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    url, trace, process = monitored
    wait = WebDriverWait(browser, WAIT)
    browser.get(url)
    state = browser.find_element(By.ID, "state")
    wait.until(lambda _: state.text.startswith("paused"))
    wait.until(lambda b: b.find_elements(By.CSS_SELECTOR, "#task g.node"))
    task = browser.find_element(By.ID, "task")
    wait.until(lambda _: task.get_attribute("data-active") == "ScrewTask")
    assert state.text == "paused", "the run went on before Start"

    browser.find_element(By.ID, "step").click()
    wait.until(lambda _: state.text == "paused at ScrewTask/go->ScrewTask/FindScrew")
    assert task.get_attribute("data-active") == "ScrewTask"

    browser.find_element(By.ID, "step").click()
    wait.until(lambda _: task.get_attribute("data-active") == "ScrewTask/FindScrew")
    wait.until(lambda _: state.text == "paused at ScrewTask/FindScrew")

    drive_in = next(
        g
        for g in browser.find_elements(By.CSS_SELECTOR, "#task g.cluster")
        if g.find_element(By.TAG_NAME, "title").get_attribute("textContent")
        == "cluster_ScrewTask/DriveIn"
    )
    browser.execute_script(
        "arguments[0].dispatchEvent(new MouseEvent('click', {bubbles: true}))", drive_in
    )
    wait.until(lambda _: "breakpoint" in drive_in.get_attribute("class"))

    browser.find_element(By.ID, "resume").click()
    wait.until(lambda _: state.text == "paused at ScrewTask/DriveIn")
    wait.until(lambda _: task.get_attribute("data-active") == "ScrewTask/DriveIn")
    assert "active" in drive_in.get_attribute("class")
    shot = tmp_path / "monitor.png"
    browser.save_screenshot(str(shot))
    assert_not_blank(shot)
    log = browser.find_element(By.ID, "log").text.splitlines()
    entered = [line for line in log if '"kind":"enter"' in line]
    assert '"state":"ScrewTask/DriveIn"' in entered[-1], "the run went past the breakpoint"
    assert process.poll() is None, "the run ended while paused"

    browser.find_element(By.ID, "resume").click()
    summary = browser.find_element(By.ID, "summary")
    wait.until(lambda _: summary.text.startswith("outcome: "))
    assert summary.text == "outcome: screwed"
    assert process.wait(timeout=WAIT) == 0
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    assert [r["state"] for r in records if r["kind"] == "enter"].count("ScrewTask/DriveIn") == 1
    assert records[-1]["kind"] == "finished" and records[-1]["outcome"] == "screwed"


def assert_not_blank(png: Path) -> None:
    from matplotlib.image import imread

    pixels = imread(png)[..., :3]
    assert pixels.shape[0] > 500 and pixels.shape[1] > 800
    assert pixels.std() > 0.05, "the screenshot is blank"
    highlighted = (abs(pixels - [1.0, 0.953, 0.769]).max(axis=2) < 0.03).sum()
    assert highlighted > 100, "no highlighted state in the screenshot"
    artifacts = os.environ.get("MONITOR_ARTIFACTS")
    if artifacts:
        Path(artifacts).mkdir(parents=True, exist_ok=True)
        shutil.copy(png, Path(artifacts) / png.name)
